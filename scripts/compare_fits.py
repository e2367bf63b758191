"""Every fit an accuracy script makes, by this tree's calibration engine and by another commit's: which objective is lower.

usage: python3 scripts/compare_fits.py SCRIPT [--base REV]     (source devel/setup.bash first)
  e.g. python3 scripts/compare_fits.py scripts/accuracy_volume.py

Runs SCRIPT with this tree's build, in a fresh interpreter, with pneumatic_finger.calibrate logged (each call's
arguments and objective), then replays every logged call, with the same arguments, on REV's build (default 5ec0fca,
the nested one-dimensional searches; built as scripts/bench_calibration.py builds it). Each pair is therefore one
problem: a script that feeds one fit's keys into the next (a gas fitted before the keys) would otherwise hand the
two engines slightly different problems. Prints each pair whose objectives differ by more than 1e-6 relative, and
the count of pairs lower, equal and higher with this tree.
"""
import argparse
import json
import os
import pathlib
import subprocess
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from bench_calibration import ROOT, base_build  # noqa: E402

LOGGED = """
import contextlib, io, json, runpy, sys
import pneumatic_finger.core as pf
log, script = open(sys.argv[1], "w"), sys.argv[2]
real = pf.calibrate
def plain(x):
    if isinstance(x, dict):
        return {k: plain(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [plain(v) for v in x]
    return x.tolist() if hasattr(x, "tolist") else x
def logged(*a, **k):
    r = real(*a, **k)
    log.write(json.dumps({"objective": r["objective_value"], "keys": list(r["fitted"]),
                          "compare": r["compared"], "args": plain(list(a)), "kwargs": plain(k)}) + "\\n")
    return r
pf.calibrate = logged
sys.path.insert(0, str(__import__("pathlib").Path(script).resolve().parent))
sys.argv = [script]
with contextlib.redirect_stdout(io.StringIO()):
    runpy.run_path(script, run_name="__main__")
log.close()
"""


REPLAY = """
import json, sys
import numpy
import pneumatic_finger.core as pf
out = open(sys.argv[2], "w")
for line in open(sys.argv[1]):
    call = json.loads(line)
    a = [{k: numpy.array(v) for k, v in x.items()} if i == 0 and isinstance(x, dict) else x
         for i, x in enumerate(call["args"])]
    k = dict(call["kwargs"])
    if isinstance(k.get("data"), dict):
        k["data"] = {c: numpy.array(v) for c, v in k["data"].items()}
    r = pf.calibrate(*a, **k)
    out.write(json.dumps({"objective": r["objective_value"]}) + "\\n")
out.close()
"""


def environment(python_path):
    lib = pathlib.Path(python_path).parent.parent
    return dict(os.environ, PYTHONPATH=f"{python_path}:{os.environ.get('PYTHONPATH', '')}",
                LD_LIBRARY_PATH=f"{lib}:{os.environ.get('LD_LIBRARY_PATH', '')}")


def fits(python_path, script, log):
    subprocess.run([sys.executable, "-c", LOGGED, str(log), str(script)], env=environment(python_path), check=True,
                   stderr=subprocess.DEVNULL)
    return [json.loads(line) for line in open(log)]


def replayed(python_path, calls, log):
    subprocess.run([sys.executable, "-c", REPLAY, str(calls), str(log)], env=environment(python_path), check=True,
                   stderr=subprocess.DEVNULL)
    return [json.loads(line) for line in open(log)]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("script")
    parser.add_argument("--base", default="5ec0fca")
    a = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        tree = fits(ROOT / "devel" / "lib" / "python3" / "dist-packages", a.script, pathlib.Path(tmp) / "tree.jsonl")
        base = replayed(base_build(a.base), pathlib.Path(tmp) / "tree.jsonl", pathlib.Path(tmp) / "base.jsonl")
    counts = {"lower": 0, "equal": 0, "higher": 0}
    for i, (b, t) in enumerate(zip(base, tree)):
        ob, ot = b["objective"], t["objective"]
        kind = "higher" if ot > ob * (1 + 1e-6) else "lower" if ot < ob * (1 - 1e-6) else "equal"
        counts[kind] += 1
        if kind != "equal":
            print(f"fit {i + 1} ({', '.join(t['keys'])}; {t['compare']}): {a.base} {ob:.6g}, now {ot:.6g} ({kind})")
    print(f"{len(tree)} fits: {counts['lower']} lower, {counts['equal']} equal, {counts['higher']} higher than "
          f"{a.base}'s")


if __name__ == "__main__":
    main()
