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
- the stepwise loading's bends (not zeroed), the same way;
- the blocked tip force along the blocked test's pressures: where it jumps (the model's: its limit point) and the
  largest error below and above the measured jump.

--fits prints the second table instead: each actuator as drawn, calibrated on its own bends (pf.calibrate, the code
of finger_calibrate, with leave-one-out), and the material of one Marchese segment carried to the other's drawing.
"""
import math
import pathlib
import sys
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
BLOCKED = "data/epfl_ecoflex30_c7_blocked_force.csv"
# name, drawing, bends, wall law (None: --wall-law auto)
DRAWN = [
    ("Marchese ribbed, 13 channels", "config/marchese2015_ribbed_drawing.yaml", "data/marchese2015_ribbed_bending.csv",
     "auto"),
    ("Marchese cylindrical, 1 channel", "config/marchese2015_cylindrical_drawing.yaml",
     "data/marchese2015_cylindrical_bending.csv", "auto"),
    ("EPFL Ecoflex 00-30, 7 chambers", "config/epfl_ecoflex30_c7_coupon.yaml", "data/epfl_ecoflex30_c7_bending.csv",
     None),
]
MATERIAL = ("wall_law", "shear_modulus_pa", "wall_locking_jm")
SYMBOL = {"shear_modulus_pa": "mu", "chamber_gap_m": "c", "wall_locking_jm": "J_m", "base_wall_share": "s0"}


def table(path, value="bend_angle_rad"):
    """A data file's gauge_pa and @p value columns, by their header's names, below its comments."""
    lines = [line.split(",") for line in (ROOT / path).read_text().splitlines() if line and not line.startswith("#")]
    columns = [lines[0].index("gauge_pa"), lines[0].index(value)]
    return numpy.array([[row[c] for c in columns] for row in lines[1:]], dtype=float)


def measured_snap(ramp):
    """The pressure midway across the largest rise of the second column between neighbouring rows (Pa)."""
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


def force_summary(model, blocked):
    """Where the blocked force jumps, model / measured (kPa), and the largest error below and above the measured jump."""
    jump = measured_snap(blocked)
    force = model.blocked_tip_force(blocked[:, 0])
    e = force - blocked[:, 1]
    below, above = blocked[:, 0] < jump, blocked[:, 0] > jump
    return (f"{model.limit_gauge_pa / 1e3:.1f} / {jump / 1e3:.1f}; {numpy.max(numpy.abs(e[below])):.2f} / "
            f"{numpy.max(numpy.abs(e[above])):.2f} N")


def snap_table():
    print("| actuator | material | snap: model / measured (kPa) | ramp bends below the snap: largest / rms (deg) "
          "| above it | stepwise: largest / rms (deg) | blocked force: jump model / measured (kPa); largest error "
          "below / above it |")
    print("|---|---|---|---|---|---|---|")
    for name, how, config, ramp_file, step_file in CASES:
        model = pf.FingerModel(config=str(ROOT / config))
        ramp, steps = table(ramp_file), table(step_file)
        snap = measured_snap(ramp)
        limit = model.limit_gauge_pa
        e = errors(model, ramp, zero_pa=ramp[0, 0])
        below, above = ramp[:, 0] < snap, ramp[:, 0] > snap
        print(f"| {name} | {how} | {limit / 1e3:.1f} / {snap / 1e3:.2f} ({100 * (limit / snap - 1):+.0f} %) "
              f"| {summary(e[below])} | {summary(e[above])} | {summary(errors(model, steps))} "
              f"| {force_summary(model, table(BLOCKED, 'blocked_force_n'))} |")


def bend_errors(residuals):
    """Model - measured tip angle (rad) of a calibration's rows."""
    return residuals["model_tip_angle_rad"] - residuals["measured_tip_angle_rad"]


def fitted_value(key, value):
    """A fitted key as the table shows it: mu in kPa, c in mm, the rest as they are."""
    if key == "shear_modulus_pa":
        return f"mu {value / 1e3:.1f} kPa"
    if key == "chamber_gap_m":
        return f"c {value * 1e3:.3f} mm"
    return f"{SYMBOL.get(key, key)} {value:.3g}"


def fitted(config, data, law):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return pf.calibrate(data=str(ROOT / data), config=str(ROOT / config), wall_law=law)


def transferred(fit, config, data):
    """The bends of the actuator drawn in @p config with the material of @p fit, along its own measured pressures."""
    overrides = {key: fit["fitted"].get(key, fit["material"][key]) for key in MATERIAL}
    overrides["wall_law"] = fit["wall_law"]  # the law the calibration kept
    model = pf.FingerModel(config=str(ROOT / config), overrides=overrides)
    rows = table(data)
    return errors(model, rows)


def fits_table():
    print("| actuator, as drawn | how | wall law; compared | bends: largest / rms (deg) | leave-one-out: largest / rms (deg) |")
    print("|---|---|---|---|---|")
    results = {}
    for name, config, data, law in DRAWN:
        fit = fitted(config, data, law)
        model = pf.FingerModel(config=str(ROOT / config))
        fit["material"] = {key: model.parameters[key] for key in MATERIAL}
        results[name] = fit
        keys = ", ".join(fitted_value(k, v) for k, v in fit["fitted"].items())
        how = f"fitted on its bends ({keys}{'; --wall-law auto' if law == 'auto' else ''})"
        print(f"| {name} | {how} | {fit['wall_law']}; {fit['compared']} | {summary(bend_errors(fit['residuals']))} "
              f"| {summary(bend_errors(fit['leave_one_out']))} |")
    for source, target in ((0, 1), (1, 0)):
        name, config, data, _ = DRAWN[target]
        fit = results[DRAWN[source][0]]
        e = transferred(fit, config, data)
        print(f"| {name} | the material fitted on the {DRAWN[source][0].split(',')[0].split()[-1]} segment "
              f"({fit['wall_law']}), on this drawing | {fit['wall_law']}; tip_angle | {summary(e)} | - |")


def main():
    fits_table() if "--fits" in sys.argv[1:] else snap_table()


if __name__ == "__main__":
    main()
