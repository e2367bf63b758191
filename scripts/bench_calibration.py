"""Every calibration of docs/CALIBRATE.md and docs/ACCURACY.md, timed side by side with another commit's engine.

usage: python3 scripts/bench_calibration.py [--base REV] [--timeout S] [--only NAME] [--doc FILE]
  (needs the built package: source devel/setup.bash)

Each calibration is pneumatic_finger.calibrate (the code of finger_calibrate) as a user runs it: with leave-one-out,
the CLI's default. It runs in a fresh interpreter, once with REV's build (default 5ec0fca, the last commit of the
nested one-dimensional searches; built in a scratch clone, as scripts/bench_compare.sh does) and once with this
tree's, both on this tree's data and parameter files, so that both engines solve the same problem. Printed for each:
the wall time of each, and the objective each reached (the largest |error| for minimax, the sum of squares for least
squares; lower is better). A run past --timeout seconds (default 900) is reported as "> S". --doc FILE writes the
table into FILE's measured block (scripts/measured_block.py's markers); with --only, just those rows (a new one after
the others), the rest as they were. --base-from-doc FILE takes REV's cells from FILE's table instead of running REV's
engine again (its code does not change; its slowest rows take minutes): for a rerun of this tree's side alone;
a row that FILE lacks gets "not run" there.
"""
import argparse
import json
import os
import pathlib
import platform
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
MU, GAP, JM, SHARE = "shear_modulus_pa", "chamber_gap_m", "wall_locking_jm", "base_wall_share"
DEAD, SKIN = "dead_volume_m3", "chamber_growth_ratio"
TABLE1, RIBBED, CYLINDRICAL = "data/sierra2022_table1.csv", "data/marchese2015_ribbed_bending.csv", \
    "data/marchese2015_cylindrical_bending.csv"
RIBBED_START, CYLINDRICAL_START = "config/marchese2015_ribbed.yaml", "config/marchese2015_cylindrical.yaml"
EPFL, EPFL_START = "data/epfl_ecoflex30_c7_bending.csv", "config/epfl_ecoflex30_c7_coupon.yaml"

# name, page, pf.calibrate's arguments (paths relative to the package).
CALIBRATIONS = [
    ("Table 1, every joint (the shipped fit)", "CALIBRATE", {}),
    ("Table 1, joints 2..7 average, s0 = 0", "ACCURACY", {"overrides": {SHARE: 0.0}, "compare": "average"}),
    ("Table 1, tip angle", "ACCURACY", {"compare": "tip_angle"}),
    ("Table 1, the paper's average column", "ACCURACY", {"average_column": "paper_avg_rad"}),
    ("Table 1, least squares", "ACCURACY", {"objective": "least_squares"}),
    ("Table 1, --wall-law auto", "ACCURACY", {"compare": "average", "wall_law": "auto", "keys": [MU, GAP]}),
    ("Table 1, --wall-law auto alone", "CALIBRATE", {"wall_law": "auto"}),
    ("ribbed, --wall-law auto", "ACCURACY", {"data": RIBBED, "config": RIBBED_START, "compare": "tip_angle",
                                            "wall_law": "auto"}),
    ("ribbed, thick wall, mu c J_m", "ACCURACY", {"data": RIBBED, "config": RIBBED_START, "compare": "tip_angle",
                                                 "wall_law": "thick", "keys": [MU, GAP, JM]}),
    ("ribbed by volume, bends (mu c)", "CALIBRATE", {
        "data": RIBBED, "config": RIBBED_START, "overrides": {DEAD: 1.28e-4, JM: 1.16}, "drive": "volume",
        "compare": "tip_angle", "keys": [MU, GAP]}),
    ("ribbed by volume, the gas", "CALIBRATE", {
        "data": RIBBED, "config": RIBBED_START, "overrides": {DEAD: 1.28e-4, JM: 1.16}, "drive": "volume",
        "compare": "gauge_pa", "keys": [DEAD], "objective": "least_squares"}),
    ("ribbed by volume, gap and gas together", "CALIBRATE", {
        "data": RIBBED, "config": RIBBED_START, "overrides": {DEAD: 1.28e-4, JM: 1.16}, "drive": "volume",
        "compare": "tip_angle+gauge_pa", "keys": [GAP, DEAD], "objective": "least_squares"}),
    ("ribbed by volume, membrane mu c gas", "ACCURACY", {
        "data": RIBBED, "config": RIBBED_START, "overrides": {DEAD: 1.28e-4, JM: 1.16}, "drive": "volume",
        "compare": "tip_angle+gauge_pa", "keys": [MU, GAP, DEAD], "objective": "least_squares"}),
    ("cylindrical, --wall-law auto", "ACCURACY", {"data": CYLINDRICAL, "config": CYLINDRICAL_START,
                                                 "compare": "tip_angle", "wall_law": "auto"}),
    ("cylindrical by volume, paper law", "CALIBRATE", {
        "data": CYLINDRICAL, "config": CYLINDRICAL_START, "wall_law": "paper", "drive": "volume",
        "compare": "tip_angle", "overrides": {DEAD: 1.35e-4, "wall_critical_height_m": 0.0014}, "keys": [MU, GAP]}),
    ("cylindrical by volume, thick inner face, mu c gas", "CALIBRATE", {
        "data": CYLINDRICAL, "config": CYLINDRICAL_START, "wall_law": "thick", "drive": "volume",
        "overrides": {DEAD: 1.35e-4, "wall_flexion_face": "inner", JM: 0.0}, "compare": "tip_angle+gauge_pa",
        "keys": [MU, GAP, DEAD], "objective": "least_squares"}),
    ("cylindrical by volume, thick inner face, four keys: mu c gas skin", "CALIBRATE", {
        "data": CYLINDRICAL, "config": CYLINDRICAL_START, "wall_law": "thick", "drive": "volume",
        "overrides": {DEAD: 1.35e-4, "wall_flexion_face": "inner", JM: 0.0},
        "compare": "tip_angle+gauge_pa", "keys": [MU, GAP, DEAD, SKIN], "objective": "least_squares"}),
    # The shipped fit (config/epfl_ecoflex30_c7.yaml); 5ec0fca reads no chord_angle_rad column, and refuses both.
    ("EPFL 7 chambers, its ramp, four keys: mu J_m kappa c (chord_angle)", "ACCURACY", {
        "data": EPFL, "config": EPFL_START, "compare": "chord_angle", "keys": [MU, JM, "wall_bulge_share", GAP]}),
    ("EPFL 7 chambers, its ramp, --wall-law auto alone", "CALIBRATE", {
        "data": EPFL, "config": EPFL_START, "wall_law": "auto"}),
    ("EPFL 7 chambers, its ramp and its blocked force, --wall-law auto", "ACCURACY", {
        "data": [EPFL, "data/epfl_ecoflex30_c7_blocked_force.csv"], "config": EPFL_START, "wall_law": "auto"}),
    ("ribbed as drawn, --wall-law auto", "ACCURACY", {
        "data": RIBBED, "config": "config/marchese2015_ribbed_drawing.yaml", "wall_law": "auto"}),
    # Its bend leaps: auto compares the pressure that holds each bend and the bend at its pressure, and keeps the
    # better prediction (5ec0fca's engine has neither the first nor the choice).
    ("cylindrical as drawn, --wall-law auto", "ACCURACY", {
        "data": CYLINDRICAL, "config": "config/marchese2015_cylindrical_drawing.yaml", "wall_law": "auto"}),
    ("ribbed as drawn, by volume, --wall-law auto alone", "CALIBRATE", {
        "data": RIBBED, "config": "config/marchese2015_ribbed_drawing.yaml", "wall_law": "auto", "drive": "volume"}),
]

RUN = """
import json, sys, time
import pneumatic_finger.core as pf
spec = json.loads(sys.argv[1])
start = time.perf_counter()
try:
    fit = pf.calibrate(**spec)
except ValueError as e:
    print(json.dumps({"refused": str(e).splitlines()[0]}))
    sys.exit(0)
print(json.dumps({"seconds": time.perf_counter() - start, "objective": fit["objective_value"],
                  "wall_law": fit["wall_law"], "fitted": fit["fitted"]}))
"""


def base_build(rev):
    """REV's build in the scratch clone scripts/bench_compare.sh uses (built there when missing)."""
    short = subprocess.check_output(["git", "-C", str(ROOT), "rev-parse", "--short", rev], text=True).strip()
    base = pathlib.Path(os.environ.get("TMPDIR", "/tmp")) / "pneumatic_finger_bench_compare" / short
    if not (base / "devel" / "lib" / "pneumatic_finger" / "finger_bench").exists():
        subprocess.run(["rm", "-rf", str(base)], check=True)
        subprocess.run(["git", "clone", "-q", str(ROOT), str(base)], check=True)
        subprocess.run(["git", "-C", str(base), "checkout", "-q", rev], check=True)
        subprocess.run(["bash", str(base / "scripts" / "build.sh")], check=True, stdout=subprocess.DEVNULL)
    return base / "devel" / "lib" / "python3" / "dist-packages"


def run(python_path, spec, timeout):
    """One calibration in a fresh interpreter with @p python_path first: its result, or None past the timeout."""
    def path(v):
        return [str(ROOT / p) for p in v] if isinstance(v, list) else str(ROOT / v)
    args = {k: (path(v) if k in ("data", "config") else v) for k, v in spec.items()}
    # The build's own libraries first: devel/setup.bash puts this tree's on the library path.
    lib = pathlib.Path(python_path).parent.parent
    env = dict(os.environ, PYTHONPATH=f"{python_path}:{os.environ.get('PYTHONPATH', '')}",
               LD_LIBRARY_PATH=f"{lib}:{os.environ.get('LD_LIBRARY_PATH', '')}")
    try:
        out = subprocess.run([sys.executable, "-c", RUN, json.dumps(args)], env=env, capture_output=True, text=True,
                             timeout=timeout, check=True).stdout
    except subprocess.TimeoutExpired:
        return None
    return json.loads(out.strip().splitlines()[-1])


def cell_time(result, timeout):
    if result is not None and "cells" in result:
        return result["cells"][0]
    if result is None:
        return f"> {timeout:g}"
    return "refused" if "refused" in result else f"{result['seconds']:.2f}"


def cell_objective(result):
    if result is not None and "cells" in result:
        return result["cells"][1]
    return "" if result is None or "refused" in result else f"{result['objective']:.6g}"


def table(rows, rev, timeout):
    lines = [f"| calibration (page) | {rev}: s | now: s | {rev}: objective | now: objective |",
             "|---|---:|---:|---:|---:|"]
    for name, page, base, now in rows:
        lines.append(f"| {name} ({page}) | {cell_time(base, timeout)} | {cell_time(now, timeout)} | "
                     f"{cell_objective(base)} | {cell_objective(now)} |")
    return "\n".join(lines)


def write_doc(path, text, command, only=False):
    """Replaces FILE's measured block (scripts/measured_block.py's markers) with @p text; with @p only, just the rows
    of @p text's calibrations, the others as they were."""
    begin, end = f"<!-- measured by {command}: begin -->", "<!-- measured: end -->"
    page = pathlib.Path(path).read_text()
    head, rest = page.split(begin, 1)
    block, tail = rest.split(end, 1)
    if only:
        fresh = {line.split(" | ")[0]: line for line in text.splitlines()[2:] if line.startswith("| ")}
        kept = [fresh.pop(line.split(" | ")[0], line) for line in block.strip("\n").splitlines()]
        rows_end = max(i for i, line in enumerate(kept) if line.startswith("| ")) + 1
        text = "\n".join(kept[:rows_end] + list(fresh.values()) + kept[rows_end:])
    pathlib.Path(path).write_text(f"{head}{begin}\n{text}\n{end}{tail}")


def doc_base_cells(path):
    """REV's cells (time, objective) of each row of FILE's measured table, by the row's first cell."""
    cells = {}
    for line in pathlib.Path(path).read_text().splitlines():
        parts = [c.strip() for c in line.strip().strip("|").split("|")]
        if line.startswith("| ") and len(parts) == 5 and parts[1] not in ("", "---:") and not parts[0].startswith("calib"):
            cells[parts[0]] = {"cells": (parts[1], parts[3])}
    return cells


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--base", default="5ec0fca")
    parser.add_argument("--timeout", type=float, default=900.0)
    parser.add_argument("--only", default="", help="run only the calibrations whose name contains this")
    parser.add_argument("--doc", default="")
    parser.add_argument("--base-from-doc", default="", help="REV's cells from this page's table, not run again")
    a = parser.parse_args()
    cached = doc_base_cells(a.base_from_doc) if a.base_from_doc else None
    base_path = None if cached is not None else base_build(a.base)
    tree_path = ROOT / "devel" / "lib" / "python3" / "dist-packages"
    rows = []
    for name, page, spec in CALIBRATIONS:
        if a.only not in name:
            continue
        if cached is not None and f"{name} ({page})" not in cached:  # a new row: REV's engine was not run on it
            print(f"--base-from-doc: no row '{name} ({page})' in {a.base_from_doc}: {a.base}'s cells 'not run'")
            cached[f"{name} ({page})"] = {"cells": ("not run", "")}
        base = cached[f"{name} ({page})"] if cached is not None else run(base_path, spec, a.timeout)
        now = run(tree_path, spec, a.timeout)
        rows.append((name, page, base, now))
        print(f"{name}: {a.base} {cell_time(base, a.timeout)} s {cell_objective(base)} | now "
              f"{cell_time(now, a.timeout)} s {cell_objective(now)}", flush=True)
    text = table(rows, a.base, a.timeout)
    text += f"\n\nMachine: {platform.node()}, {os.cpu_count()} cores, {platform.processor() or platform.machine()}."
    print(text)
    if a.doc:
        write_doc(a.doc, text, "python3 scripts/bench_calibration.py", only=bool(a.only))


if __name__ == "__main__":
    main()
