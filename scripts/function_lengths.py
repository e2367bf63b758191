"""Function lengths of the C++ sources, from Universal Ctags' start and end lines (ctags --fields=+ne), and file
lengths: the house rules of this repository (a function under 60 lines, a file under 500).

    usage: python3 scripts/function_lengths.py [--max-function 60] [--max-file 500] [--top N]
Exits 1 when a function or a file is over its limit, and lists them.
"""
import argparse
import pathlib
import shutil
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
FOLDERS = ["src", "include"]


def sources():
    return sorted(p for folder in FOLDERS for p in (ROOT / folder).rglob("*") if p.suffix in (".cpp", ".hpp"))


def functions(files):
    ctags = shutil.which("ctags-universal") or "ctags"  # Debian's universal-ctags; plain ctags may be another
    out = subprocess.run([ctags, "-x", "--_xformat=%N\t%F\t%n\t%e\t%K", "--fields=+ne", "--kinds-C++=f",
                          "--language-force=C++", *map(str, files)], capture_output=True, text=True, check=True).stdout
    for line in out.splitlines():
        name, path, start, end, _ = line.split("\t")
        if end:
            yield int(end) - int(start) + 1, pathlib.Path(path).relative_to(ROOT), int(start), name


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--max-function", type=int, default=60)
    parser.add_argument("--max-file", type=int, default=500)
    parser.add_argument("--top", type=int, default=10)
    args = parser.parse_args()
    files = sources()
    found = sorted(functions(files), reverse=True)
    long_files = [(len(p.read_text().splitlines()), p.relative_to(ROOT)) for p in files]
    long_files = sorted((n, p) for n, p in long_files if n > args.max_file)
    print(f"longest functions of {len(found)} in src/ and include/:")
    for length, path, start, name in found[:args.top]:
        print(f"  {length:4d}  {path}:{start}  {name}")
    over = [f for f in found if f[0] > args.max_function]
    print(f"functions over {args.max_function} lines: {len(over)}; files over {args.max_file} lines: {len(long_files)}")
    for n, p in long_files:
        print(f"  {n:4d}  {p}")
    sys.exit(1 if over or long_files else 0)


if __name__ == "__main__":
    main()
