"""An actuator described as drawn (docs/ACCURACY.md): each shipped drawing's prediction against its measurements.

usage: python3 scripts/accuracy_drawn.py      (the package's Python API on PYTHONPATH: source devel/setup.bash)

Prints a Markdown table, the same on every run (update_docs.py puts it into docs/ACCURACY.md). For each actuator and
each way of getting its material, from the parameter file as shipped:
- the snap: the model's limit point (limit_gauge_pa) against the measured one, the pressure midway across the largest
  rise of the bend between two neighbouring rows of the ramp;
- the bends along the ramp, evaluated as one path in order (the model follows its snap), below and above the measured
  snap: the largest and the rms error in degrees. The ramp's bends were zeroed where it starts, so the model's are
  taken from the same pressure. Rows where the model gives no shape (beyond its limit point) or meets itself count as
  misses, and are named;
- the stepwise loading's bends (not zeroed), the same way.
"""
import math
import pathlib
import warnings

import numpy

import pneumatic_finger.core as pf

ROOT = pathlib.Path(__file__).resolve().parent.parent
DEG = 180.0 / math.pi
CASES = [
    ("EPFL Ecoflex 00-30, 7 chambers", "zero-shot: drawing + coupon", "config/epfl_ecoflex30_c7_coupon.yaml",
     "data/epfl_ecoflex30_c7_bending.csv", "data/epfl_ecoflex30_c7_bending_stepwise.csv"),
    ("EPFL Ecoflex 00-30, 7 chambers", "fitted on its ramp (mu, c; gauge_at_tip_angle)",
     "config/epfl_ecoflex30_c7.yaml", "data/epfl_ecoflex30_c7_bending.csv",
     "data/epfl_ecoflex30_c7_bending_stepwise.csv"),
]


def table(path):
    """A data file's first two columns (gauge_pa and the bend), below its comments and its header."""
    rows = [line.split(",")[:2] for line in (ROOT / path).read_text().splitlines() if line and not line.startswith("#")]
    return numpy.array(rows[1:], dtype=float)


def measured_snap(ramp):
    """The pressure midway across the largest rise of the bend between neighbouring rows (Pa)."""
    rise = numpy.diff(ramp[:, 1])
    k = int(numpy.argmax(rise))
    return 0.5 * (ramp[k, 0] + ramp[k + 1, 0])


def errors(model, rows, zero_pa=None):
    """Model - measured bend (rad) along @p rows as one path; NaN where the model gives no usable shape."""
    pressures = rows[:, 0] if zero_pa is None else numpy.concatenate(([zero_pa], rows[:, 0]))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        state = model.path().evaluate(pressures, outputs=["tip_angle_rad", "status"])
    angle = state["tip_angle_rad"].astype(float)
    usable = numpy.array([pf.STATUS[s] in ("ok", "snapped through", "clamped to max_gauge_pa") for s in state["status"]])
    angle[~usable] = math.nan
    if zero_pa is not None:
        angle = angle[1:] - angle[0]
    return angle - rows[:, 1]


def summary(e):
    good = e[~numpy.isnan(e)]
    if good.size == 0:
        return "no usable row"
    text = f"{numpy.max(numpy.abs(good)) * DEG:.1f} / {math.sqrt(numpy.mean(good * good)) * DEG:.1f}"
    misses = int(numpy.isnan(e).sum())
    return text + (f" ({misses} of {e.size} rows with no usable shape)" if misses else "")


def main():
    print("| actuator | material | snap: model / measured (kPa) | ramp bends below the snap: largest / rms (deg) "
          "| above it | stepwise: largest / rms (deg) |")
    print("|---|---|---|---|---|---|")
    for name, how, config, ramp_file, step_file in CASES:
        model = pf.FingerModel(config=str(ROOT / config))
        ramp, steps = table(ramp_file), table(step_file)
        snap = measured_snap(ramp)
        limit = model.limit_gauge_pa
        e = errors(model, ramp, zero_pa=ramp[0, 0])
        below, above = ramp[:, 0] < snap, ramp[:, 0] > snap
        print(f"| {name} | {how} | {limit / 1e3:.1f} / {snap / 1e3:.2f} ({100 * (limit / snap - 1):+.0f} %) "
              f"| {summary(e[below])} | {summary(e[above])} | {summary(errors(model, steps))} |")


if __name__ == "__main__":
    main()
