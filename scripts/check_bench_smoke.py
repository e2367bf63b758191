"""Checks a finger_bench JSON report (smoke mode): every benchmark ran, and all its numbers are finite. With --sim,
the same for a sim_bench report (the physics engine's steps).

usage: python3 scripts/check_bench_smoke.py [--sim] REPORT.json
"""
import json
import math
import sys

sim = sys.argv[1] == "--sim"
report = json.load(open(sys.argv[-1]))
runs = report["benchmarks"]
bad = [(r["name"], k) for r in runs for k, v in r.items() if isinstance(v, float) and not math.isfinite(v)]
names = {r["name"] for r in runs}
expected = {f"{v}/{s}" for v in ("robust", "table", "paper", "eigen_companion", "gsl_complex")
            for s in ("validated", "hard")} | {"robust_pair/validated"} | {f"robust_stage/{i}" for i in range(1, 6)} | {f"latency/{i}" for i in range(4)} | {f"contact/{i}" for i in range(4)} \
    | {"membrane/validated", "membrane/volume", "thick/validated"} \
    | {f"{law}/{kind}" for law in ("membrane", "thick") for kind in ("newton", "build", "build_newton")} \
    | {f"{b}/{p}" for b in ("batch", "batch_backbone") for p in ("scalar", "generic", "avx2", "avx512")}
if sim:
    expected = {"sim/cell_step", "sim/step", "sim/step_with_springs"}
names = {n.split("/min_time")[0] for n in names}  # a benchmark with its own minimum time carries it in its name
missing = expected - names
# Only the batch paths of an instruction set the CPU lacks may be skipped.
skipped = [r["name"] for r in runs if r.get("error_occurred")
           and not (r["name"].split("/")[-1] in ("avx2", "avx512") and "lacks" in r.get("error_message", ""))]
if bad or missing or skipped:
    print(f"bench smoke: FAILED: non-finite {bad}, missing {sorted(missing)}, failed {skipped}")
    sys.exit(1)
print(f"bench smoke: ok ({len(runs)} benchmarks, all numbers finite)")
