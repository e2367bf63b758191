"""Every fit an accuracy script makes, by this tree's calibration engine and by another commit's: which objective is lower.

usage: python3 scripts/compare_fits.py SCRIPT [--base REV]     (source devel/setup.bash first)
  e.g. python3 scripts/compare_fits.py scripts/accuracy_volume.py

Runs SCRIPT twice, in fresh interpreters, with pneumatic_finger.calibrate logged (each call's objective): once with
REV's build (default 5ec0fca, the nested one-dimensional searches; built as scripts/bench_calibration.py builds it)
and once with this tree's. The calls are paired in order. A script that feeds one fit's keys into the next makes
later calls differ slightly in their start; the calibration does not depend on its start, so each pair is still the
same problem up to those digits. Prints each pair whose objectives differ by more than 1e-6 relative, and the count of
pairs lower, equal and higher with this tree.
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
def logged(*a, **k):
    r = real(*a, **k)
    log.write(json.dumps({"objective": r["objective_value"], "keys": list(r["fitted"]),
                          "compare": r["compared"]}) + "\\n")
    return r
pf.calibrate = logged
sys.path.insert(0, str(__import__("pathlib").Path(script).resolve().parent))
sys.argv = [script]
with contextlib.redirect_stdout(io.StringIO()):
    runpy.run_path(script, run_name="__main__")
log.close()
"""


def fits(python_path, script, log):
    lib = pathlib.Path(python_path).parent.parent
    env = dict(os.environ, PYTHONPATH=f"{python_path}:{os.environ.get('PYTHONPATH', '')}",
               LD_LIBRARY_PATH=f"{lib}:{os.environ.get('LD_LIBRARY_PATH', '')}")
    subprocess.run([sys.executable, "-c", LOGGED, str(log), str(script)], env=env, check=True,
                   stderr=subprocess.DEVNULL)
    return [json.loads(line) for line in open(log)]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("script")
    parser.add_argument("--base", default="5ec0fca")
    a = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        base = fits(base_build(a.base), a.script, pathlib.Path(tmp) / "base.jsonl")
        tree = fits(ROOT / "devel" / "lib" / "python3" / "dist-packages", a.script, pathlib.Path(tmp) / "tree.jsonl")
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
