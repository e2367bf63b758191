"""An actuator described as drawn (docs/ACCURACY.md): each shipped drawing's prediction against its measurements.

usage: python3 scripts/accuracy_drawn.py      (the package's Python API on PYTHONPATH: source devel/setup.bash)

Prints a Markdown table, the same on every run (update_docs.py puts it into docs/ACCURACY.md). For each actuator and
each way of getting its material, from the parameter file as shipped:
- the snap: the model's (snap_gauge_pa: its limit point where its wall folds, else where its bend rises fastest)
  against the measured one, the pressure midway across the largest rise of the bend between two neighbouring rows of
  the ramp;
- the bends along the ramp, evaluated as one path in order (the model follows its snap), below and above the measured
  snap: the largest and the rms error in degrees. The ramp's bends were zeroed where it starts, so the model's are
  taken from the same pressure. Rows where the model gives no shape (beyond its limit point) or meets itself count as
  misses, and are named;
- the stepwise loading's bends (not zeroed), the same way;
- the blocked tip force along the blocked test's pressures: where it jumps (the model's: its snap) and the largest
  error below and above the measured jump.

--plot PNG draws the first table's models against the ramp, the stepwise loading and the blocked force instead.
--fits prints the second table instead: each actuator as drawn, calibrated on its own bends (pf.calibrate, the code
of finger_calibrate, with leave-one-out), and the material of one Marchese segment carried to the other's drawing.

--solid [--plot PNG] prints the third: the EPFL drawing as a solid by finite elements (the table
data/fem_epfl_ecoflex30_c7_cell.csv that scripts/fem_cell.py wrote) beside the thick wall law, each with the coupon's
modulus and with one modulus fitted on the ramp's bends up to 20 kPa, the rest predicted, as far as the solid
reaches. --walls prints the fourth: the same drawing with other walls between cavities, solid against law.
--skins prints the fifth: the solid with other roofs and side walls, each with a modulus fitted as --solid fits it,
against the ramp up to and across the measured snap.
"""
import math
import pathlib
import sys
import warnings

import numpy

import pneumatic_finger.core as pf

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import fem_cell  # noqa: E402  (the solid cell's geometry, for the beam beside it)

ROOT = pathlib.Path(__file__).resolve().parent.parent
DEG = 180.0 / math.pi
# The EPFL source measured its bends as chords (base to tip; its data files say how): the model's are compared alike.
CHORD = "chord_angle_rad"
CASES = [
    ("EPFL Ecoflex 00-30, 7 chambers", "zero-shot: drawing + coupon", "config/epfl_ecoflex30_c7_coupon.yaml",
     "data/epfl_ecoflex30_c7_bending.csv", "data/epfl_ecoflex30_c7_bending_stepwise.csv"),
    ("EPFL Ecoflex 00-30, 7 chambers", "fitted on its ramp (mu, J_m, kappa, c; chord_angle)",
     "config/epfl_ecoflex30_c7.yaml", "data/epfl_ecoflex30_c7_bending.csv",
     "data/epfl_ecoflex30_c7_bending_stepwise.csv"),
]
BLOCKED = "data/epfl_ecoflex30_c7_blocked_force.csv"
# name, drawing, bends, wall law ("auto": --wall-law auto; None: the file's), and the calibration's other arguments
# (none: the tool's defaults). The EPFL actuator's are the shipped fit's (config/epfl_ecoflex30_c7.yaml's command,
# docs/ACCURACY.md).
EPFL_FIT = {"keys": "shear_modulus_pa,wall_locking_jm,wall_bulge_share,chamber_gap_m", "compare": "chord_angle"}
DRAWN = [
    ("Marchese ribbed, 13 channels", "config/marchese2015_ribbed_drawing.yaml", "data/marchese2015_ribbed_bending.csv",
     "auto", {}),
    ("Marchese cylindrical, 1 channel", "config/marchese2015_cylindrical_drawing.yaml",
     "data/marchese2015_cylindrical_bending.csv", "auto", {}),
    ("EPFL Ecoflex 00-30, 7 chambers", "config/epfl_ecoflex30_c7_coupon.yaml", "data/epfl_ecoflex30_c7_bending.csv",
     None, EPFL_FIT),
    ("EPFL Ecoflex 00-30, 7 chambers, auto alone", "config/epfl_ecoflex30_c7_coupon.yaml",
     "data/epfl_ecoflex30_c7_bending.csv", "auto", {}),
    ("EPFL Ecoflex 00-30, 7 chambers, auto on its bends and its blocked force", "config/epfl_ecoflex30_c7_coupon.yaml",
     ["data/epfl_ecoflex30_c7_bending.csv", BLOCKED], "auto", {}),
]
MATERIAL = ("wall_law", "shear_modulus_pa", "wall_locking_jm")
# --solid: the finite-element cell of the drawing (scripts/fem_cell.py with this file's coupon modulus), and the ramp's
# first part, on which one modulus is fitted for the rest to be predicted
SOLID = "data/fem_epfl_ecoflex30_c7_cell.csv"
SOLID_CONFIG = "config/epfl_ecoflex30_c7_coupon.yaml"
RAMP_START_PA = 10e3  # where the source zeroed the ramp's bends
FIT_TOP_PA = 20e3
STEEP_FROM_PA = 30e3  # about where the ramp's bend starts to steepen toward its snap (a round figure, read off it)
SOLID_NAME = "the solid cell (fem_cell.py)"
# --skins: the same cell with the skins around the cavities changed (fem_cell.py --set drawing/...)
SKINS = [("as drawn (roof and side walls 7 mm, the defaults)", SOLID),
         ("roof 3 mm", "data/fem_epfl_ecoflex30_c7_roof_3mm.csv"),
         ("roof 10 mm", "data/fem_epfl_ecoflex30_c7_roof_10mm.csv"),
         ("side walls 2 mm (body 12 mm wide)", "data/fem_epfl_ecoflex30_c7_body_12mm.csv")]
# the same cell with a thicker roof (fem_cell.py --set drawing/roof_thickness_m=0.010), and where the two are compared
ROOF, ROOF_M, ROOF_AT_PA = "data/fem_epfl_ecoflex30_c7_roof_10mm.csv", 0.010, 12e3
# --walls: the same cell with other walls between cavities (fem_cell.py --set drawing/wall_thickness_m=...), compared
# with the law up to a pressure every one of them reaches
WALLS = [(3, "data/fem_epfl_ecoflex30_c7_wall_3mm.csv"), (5, "data/fem_epfl_ecoflex30_c7_wall_5mm.csv"), (7, SOLID),
         (10, "data/fem_epfl_ecoflex30_c7_wall_10mm.csv")]
WALLS_TOP_PA = 12e3
SYMBOL = {"shear_modulus_pa": "mu", "chamber_gap_m": "c", "wall_locking_jm": "J_m", "base_wall_share": "s0",
          "wall_bulge_share": "kappa"}


def table(path, value=None):
    """A data file's gauge_pa and @p value columns, by their header's names, below its comments. @p value None: the
    bend as the file measured it, its chord_angle_rad (base to tip) or else its bend_angle_rad (the tip's direction)."""
    lines = [line.split(",") for line in (ROOT / path).read_text().splitlines() if line and not line.startswith("#")]
    if value is None:
        value = "chord_angle_rad" if "chord_angle_rad" in lines[0] else "bend_angle_rad"
    columns = [lines[0].index("gauge_pa"), lines[0].index(value)]
    return numpy.array([[row[c] for c in columns] for row in lines[1:]], dtype=float)


def measured_snap(ramp):
    """The pressure midway across the largest rise of the second column between neighbouring rows (Pa)."""
    rise = numpy.diff(ramp[:, 1])
    k = int(numpy.argmax(rise))
    return 0.5 * (ramp[k, 0] + ramp[k + 1, 0])


def path_bends(model, pressures, crossing=False, angle_name=CHORD):
    """The model's bend (rad; its chord angle, base to tip, or with @p angle_name "tip_angle_rad" its tip's
    direction) along @p pressures as one path; NaN where it gives no usable shape (with @p crossing, a shape that
    meets itself keeps its bend: the model's answer, only its backbone passes through itself)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        state = model.path().evaluate(pressures, outputs=[angle_name, "status"])
    angle = state[angle_name].astype(float)
    kept = ("ok", "snapped through", "clamped to max_gauge_pa") + (("meets itself",) if crossing else ())
    usable = numpy.array([pf.STATUS[s] in kept for s in state["status"]])
    angle[~usable] = math.nan
    return angle


def errors(model, rows, zero_pa=None, crossing=False, angle_name=CHORD):
    """Model - measured bend (rad) along @p rows as one path; NaN where the model gives no usable shape."""
    pressures = rows[:, 0] if zero_pa is None else numpy.concatenate(([zero_pa], rows[:, 0]))
    angle = path_bends(model, pressures, crossing, angle_name)
    if zero_pa is not None:
        angle = angle[1:] - angle[0]
    return angle - rows[:, 1]


def bend_cell(model, rows, mask, zero_pa=None):
    """summary() of the bend errors along @p rows, of those in @p mask, a shape that meets itself counted with its
    bend, and said so."""
    usable = errors(model, rows, zero_pa)[mask]
    every = errors(model, rows, zero_pa, crossing=True)[mask]
    crossing = int((numpy.isnan(usable) & ~numpy.isnan(every)).sum())
    return summary(every) + (f" ({crossing} of {every.size} rows meet themselves)" if crossing else "")


def summary(e, miss="with no usable shape"):
    good = e[~numpy.isnan(e)]
    if good.size == 0:
        return "no usable row" if miss == "with no usable shape" else f"none: every row {miss}"
    text = f"{numpy.max(numpy.abs(good)) * DEG:.1f} / {math.sqrt(numpy.mean(good * good)) * DEG:.1f}"
    misses = int(numpy.isnan(e).sum())
    return text + (f" ({misses} of {e.size} rows {miss})" if misses else "")


def force_summary(model, blocked):
    """Where the blocked force jumps, model / measured (kPa), and the largest error below and above the measured jump."""
    jump = measured_snap(blocked)
    force = model.blocked_tip_force(blocked[:, 0])
    e = force - blocked[:, 1]
    below, above = blocked[:, 0] < jump, blocked[:, 0] > jump
    return (f"{model.snap_gauge_pa / 1e3:.1f} / {jump / 1e3:.1f}; "
            f"{numpy.max(numpy.abs(e[below])):.2f} / {numpy.max(numpy.abs(e[above])):.2f} N")


def snap_table():
    print("| actuator | material | snap: model / measured (kPa) | ramp bends below the snap: largest / rms (deg) "
          "| above it | stepwise: largest / rms (deg) | blocked force: jump model / measured (kPa); largest error "
          "below / above it |")
    print("|---|---|---|---|---|---|---|")
    for name, how, config, ramp_file, step_file in CASES:
        model = pf.FingerModel(config=str(ROOT / config))
        ramp, steps = table(ramp_file), table(step_file)
        snap = measured_snap(ramp)
        limit = model.snap_gauge_pa
        below, above = ramp[:, 0] < snap, ramp[:, 0] > snap
        every = numpy.ones(len(steps), dtype=bool)
        print(f"| {name} | {how} | {limit / 1e3:.1f} / {snap / 1e3:.2f} ({100 * (limit / snap - 1):+.1f} %) "
              f"| {bend_cell(model, ramp, below, ramp[0, 0])} | {bend_cell(model, ramp, above, ramp[0, 0])} "
              f"| {bend_cell(model, steps, every)} "
              f"| {force_summary(model, table(BLOCKED, 'blocked_tip_force_n'))} |")
    print()
    print(zero_shot_sentence(*CASES[0][2:4]))
    print()
    print(fitted_sentences(CASES[-1][2]))
    print()
    print(ramp_against_steps(*CASES[-1][2:]))
    print()
    print(steps_by_pressure(*CASES[-1][2:]))


def zero_shot_sentence(config, ramp_file):
    """A sentence: the zero-shot model's bends on the ramp below its own snap, where it has not yet ballooned."""
    model = pf.FingerModel(config=str(ROOT / config))
    ramp = table(ramp_file)
    own = ramp[:, 0] < model.snap_gauge_pa
    e = errors(model, ramp, zero_pa=ramp[0, 0])[own]
    return (f"Below its own snap ({model.snap_gauge_pa / 1e3:.1f} kPa; {int(own.sum())} of the ramp's rows), the "
            f"zero-shot model's bends are off by {summary(e)} deg (largest / rms); past it its chambers balloon "
            f"until the finger meets itself, hundreds of degrees past the measured bends (the table).")


def fitted_sentences(config):
    """The fitted file's wall: the lock J_m at which it would fold (a limit point), and where its walls first touch."""
    model = pf.FingerModel(config=str(ROOT / config))
    jm = model.parameters["wall_locking_jm"]

    def folds(x):
        return math.isfinite(pf.FingerModel(config=str(ROOT / config), overrides={"wall_locking_jm": x}).limit_gauge_pa)

    lo, hi = jm, 2.0 * jm
    while not folds(hi):
        lo, hi = hi, 2.0 * hi
    while hi - lo > 1e-3 * hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if folds(mid) else (mid, hi)
    return (f"The fitted wall's lock is J_m = {jm:.1f}; from J_m = {hi:.1f} on, the same wall would fold (a limit point)"
            f". Its limit_gauge_pa is {model.limit_gauge_pa}, and its walls first touch at "
            f"{model.contact_gauge_pa / 1e3:.1f} kPa.")


def ramp_against_steps(config, ramp_file, step_file):
    """A sentence: the two loadings' own disagreement. The ramp, zeroed where it starts, is put on the stepwise
    loading's absolute scale by the fitted model's bend there, and read at the stepwise pressures by interpolation."""
    ramp, steps = table(ramp_file), table(step_file)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        start = float(pf.FingerModel(config=str(ROOT / config)).evaluate(ramp[0, 0])[CHORD])
    inside = steps[:, 0] <= ramp[-1, 0]
    gap = numpy.interp(steps[inside, 0], ramp[:, 0], ramp[:, 1]) + start - steps[inside, 1]
    k = int(numpy.argmax(numpy.abs(gap)))
    return (f"The two loadings differ from each other: the ramp, read at the stepwise pressures (and put on their "
            f"absolute scale by the fitted model's {start * DEG:.1f} deg at {ramp[0, 0] / 1e3:.0f} kPa, where the ramp "
            f"was zeroed), bends up to {abs(gap[k]) * DEG:.1f} deg {'more' if gap[k] > 0 else 'less'} than the "
            f"stepwise loading (at {steps[inside][k, 0] / 1e3:.0f} kPa; {math.sqrt(numpy.mean(gap * gap)) * DEG:.1f} deg "
            f"rms).")


def pressure_at_bends(model, bends):
    """The pressure (Pa) at which the model's path first reaches each of @p bends (chord angles, rad): its chords on a
    grid of 0.05 kPa to 60 kPa, inverted by interpolation along their running maximum."""
    grid = numpy.linspace(0.0, 60e3, 1201)
    chord = numpy.maximum.accumulate(numpy.nan_to_num(path_bends(model, grid, crossing=True), nan=-math.inf))
    return numpy.interp(bends, chord, grid)


def steps_by_pressure(config, ramp_file, step_file):
    """A sentence: the stepwise loading read by the pressure at which each of its bends is reached (well posed on a
    leap), for the fitted model and for the ramp itself (its bends, put on the absolute scale as ramp_against_steps
    does, inverted by interpolation along their running maximum)."""
    ramp, steps = table(ramp_file), table(step_file)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = pf.FingerModel(config=str(ROOT / config))
        start = float(model.evaluate(ramp[0, 0])[CHORD])
        bends = numpy.maximum.accumulate(ramp[:, 1] + start)
        inside = (steps[:, 1] >= bends[0]) & (steps[:, 1] <= bends[-1])
        held = pressure_at_bends(model, steps[inside, 1])
    ramp_held = numpy.interp(steps[inside, 1], bends, ramp[:, 0])
    model_gap, ramp_gap, apart = held - steps[inside, 0], ramp_held - steps[inside, 0], held - ramp_held

    def span(x):
        return f"{numpy.min(x) / 1e3:+.1f} to {numpy.max(x) / 1e3:+.1f} kPa"
    return (f"Read by the pressure at which each stepwise bend is reached ("
            f"{int(inside.sum())} of {len(steps)} steps, the ones within the ramp's bends), the fitted model needs "
            f"{span(model_gap)} from the steps' pressures, and the ramp itself {span(ramp_gap)}: the model is within "
            f"{numpy.max(numpy.abs(apart)) / 1e3:.2f} kPa of the ramp at every one of these bends.")


def bend_errors(residuals):
    """Model - measured bend (rad) of a calibration's rows that measured one (rows of blocked force alone are left
    out): the tip angle, or the chord where that was measured."""
    tip = residuals["model_tip_angle_rad"] - residuals["measured_tip_angle_rad"]
    chord = residuals["model_chord_angle_rad"] - residuals["measured_chord_angle_rad"]
    shaped = ~(numpy.isnan(residuals["measured_tip_angle_rad"]) & numpy.isnan(residuals["measured_chord_angle_rad"]))
    return numpy.where(numpy.isnan(residuals["measured_tip_angle_rad"]), chord, tip)[shaped]


def force_cell(residuals):
    """The blocked force's largest error (N) where the calibration fitted it too, else nothing."""
    e = residuals["model_blocked_tip_force_n"] - residuals["measured_blocked_tip_force_n"]
    e = e[~numpy.isnan(residuals["measured_blocked_tip_force_n"])]
    return f"; force {numpy.max(numpy.abs(e)):.2f} N" if e.size else ""


def fitted_value(key, value):
    """A fitted key as the table shows it: mu in kPa, c in mm, the rest as they are."""
    if key == "shear_modulus_pa":
        return f"mu {value / 1e3:.1f} kPa"
    if key == "chamber_gap_m":
        return f"c {value * 1e3:.3f} mm"
    return f"{SYMBOL.get(key, key)} {value:.3g}"


def fitted(config, data, law, how):
    paths = [str(ROOT / d) for d in data] if isinstance(data, list) else str(ROOT / data)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return pf.calibrate(data=paths, config=str(ROOT / config), wall_law=law, **how)


def transferred(fit, config, data):
    """The bends of the actuator drawn in @p config with the material of @p fit, along its own measured pressures."""
    overrides = {key: fit["fitted"].get(key, fit["material"][key]) for key in MATERIAL}
    overrides["wall_law"] = fit["wall_law"]  # the law the calibration kept
    model = pf.FingerModel(config=str(ROOT / config), overrides=overrides)
    rows = table(data)
    return errors(model, rows, angle_name="tip_angle_rad")


def fits_table():
    print("| actuator, as drawn | how | wall law; compared | bends: largest / rms (deg) | leave-one-out: largest / rms (deg) |")
    print("|---|---|---|---|---|")
    results = {}
    for name, config, data, law, how in DRAWN:
        fit = fitted(config, data, law, how)
        model = pf.FingerModel(config=str(ROOT / config))
        fit["material"] = {key: model.parameters[key] for key in MATERIAL}
        results[name] = fit
        keys = ", ".join(fitted_value(k, v) for k, v in fit["fitted"].items())
        what = "its bends and its blocked force" if isinstance(data, list) else "its bends"
        how = f"fitted on {what} ({keys}{'; --wall-law auto' if law == 'auto' else ''})"
        print(f"| {name} | {how} | {fit['wall_law']}; {fit['compared']} | "
              f"{summary(bend_errors(fit['residuals']))}{force_cell(fit['residuals'])} "
              f"| {summary(bend_errors(fit['leave_one_out']))}{force_cell(fit['leave_one_out'])} |")
    for source, target in ((0, 1), (1, 0)):
        name, config, data, _, _ = DRAWN[target]
        fit = results[DRAWN[source][0]]
        e = transferred(fit, config, data)
        print(f"| {name} | the material fitted on the {DRAWN[source][0].split(',')[0].split()[-1]} segment "
              f"({fit['wall_law']}), on this drawing | {fit['wall_law']}; tip_angle | {summary(e)} | - |")


def chord_of_tip_angle(tip_angle_rad):
    """The chord angle (rad) of the drawn finger (SOLID_CONFIG) bent to @p tip_angle_rad: the law's shape there, whose
    chambers bend alike as the solid cell's do. From the law filled by volume (one shape per tip angle, past its
    limit point too), interpolated."""
    model = pf.FingerModel(config=str(ROOT / SOLID_CONFIG))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        volume = numpy.linspace(0.0, model.volume_for_tip_angle(2.5), 2001)
        state = model.evaluate_volume(volume, outputs=["tip_angle_rad", CHORD])
    return numpy.interp(tip_angle_rad, state["tip_angle_rad"], state[CHORD])


def solid_bends(solid, coupon_mu_pa, mu_pa, pressures):
    """The solid cell's chord angles (base to tip) at @p pressures with shear modulus @p mu_pa, zeroed at the ramp's
    start (rad); NaN beyond its reach. Neo-Hookean, its bend at P with mu is its bend at P mu0/mu with its own mu0.
    The cell gives the tip's direction; chord_of_tip_angle puts it on the drawn finger's backbone."""
    k = coupon_mu_pa / mu_pa
    scaled = numpy.asarray(pressures) * k
    bend = chord_of_tip_angle(numpy.interp(scaled, solid[:, 0], solid[:, 1]))
    bend[scaled > solid[-1, 0]] = math.nan
    return bend - chord_of_tip_angle(numpy.interp(RAMP_START_PA * k, solid[:, 0], solid[:, 1]))


def thick_bends(config, mu_pa, pressures):
    """The wall law's bends along @p pressures as one path, zeroed at the ramp's start (rad); NaN with no shape."""
    model = pf.FingerModel(config=str(ROOT / config), overrides={"shear_modulus_pa": mu_pa})
    rows = numpy.column_stack([pressures, numpy.zeros(len(pressures))])
    return errors(model, rows, zero_pa=RAMP_START_PA)


def best_mu(bends, rows):
    """The shear modulus (Pa, on a 0.1 kPa grid from 10 to 80 kPa) whose bends have the least rms error on @p rows."""
    def rms(mu):
        e = bends(mu, rows[:, 0]) - rows[:, 1]
        return math.inf if numpy.isnan(e).any() else float(numpy.mean(e * e))
    return min(numpy.arange(10e3, 80e3 + 1, 100.0), key=rms)


def solid_table():
    """The drawn cell as a solid (fem_cell.py) and as the thick wall law, each with the coupon's modulus and with a
    modulus fitted on the ramp's first part, against the ramp: the fitted rows, the rows after them up to the measured
    snap, and those above it as far as the solid reaches; and where each has its limit point."""
    ramp = table("data/epfl_ecoflex30_c7_bending.csv")
    solid = table(SOLID)
    coupon = pf.FingerModel(config=str(ROOT / SOLID_CONFIG)).parameters["shear_modulus_pa"]
    fit_rows = ramp[ramp[:, 0] <= FIT_TOP_PA]
    curves = {SOLID_NAME: lambda mu, p: solid_bends(solid, coupon, mu, p),
              "the thick wall law": lambda mu, p: thick_bends(SOLID_CONFIG, mu, p)}
    fitted_mu = {name: best_mu(bends, fit_rows) for name, bends in curves.items()}
    snap = measured_snap(ramp)
    reach = solid[-1, 0] * min(fitted_mu.values()) / coupon
    p = ramp[:, 0]
    parts = (ramp[(p > FIT_TOP_PA) & (p <= STEEP_FROM_PA)], ramp[(p > STEEP_FROM_PA) & (p < snap)],
             ramp[(p > snap) & (p <= reach)])
    print(f"| model of the drawn actuator | mu (kPa) | bends {RAMP_START_PA / 1e3:.0f} to {FIT_TOP_PA / 1e3:.0f} kPa: "
          f"largest / rms (deg) | {FIT_TOP_PA / 1e3:.0f} to {STEEP_FROM_PA / 1e3:.0f} kPa | {STEEP_FROM_PA / 1e3:.0f} "
          f"kPa to the snap ({snap / 1e3:.2f}) | the snap to {reach / 1e3:.1f} kPa | limit point (kPa) |")
    print("|---|---|---|---|---|---|---|")
    for name, bends in curves.items():
        for how, mu in (("the coupon's", coupon), (f"fitted on the bends to {FIT_TOP_PA / 1e3:.0f} kPa",
                                                     fitted_mu[name])):
            miss = "beyond its solver's reach" if name == SOLID_NAME else "with no usable shape"
            cells = [summary(bends(mu, rows[:, 0]) - rows[:, 1], miss) for rows in (fit_rows,) + parts]
            print(f"| {name} | {mu / 1e3:.1f}, {how} | {' | '.join(cells)} | {limit_point(name, solid, coupon, mu)} |")
    print()
    print(solid_sentences(ramp, solid, coupon, fitted_mu[SOLID_NAME]))
    print()
    print(law_sentences(ramp, solid, coupon, curves, fitted_mu))
    return ramp, solid, coupon, curves, fitted_mu


def solid_sentences(ramp, solid, coupon_mu_pa, fitted_mu_pa):
    """What the solid says in numbers: how much more it bends than the actuator with the coupon's modulus, to its
    solver's stop; the factor on the modulus; and how much less a thicker roof makes it bend, against that factor."""
    top = solid[-1, 0]
    measured = numpy.interp(top, ramp[:, 0], ramp[:, 1]) - numpy.interp(RAMP_START_PA, ramp[:, 0], ramp[:, 1])
    ratio = solid_bends(solid, coupon_mu_pa, coupon_mu_pa, numpy.array([top]))[0] / measured
    roof = table(ROOF)
    drawn = numpy.interp(ROOF_AT_PA, solid[:, 0], solid[:, 1])
    thicker = numpy.interp(ROOF_AT_PA, roof[:, 0], roof[:, 1]) / drawn
    stiffer = numpy.interp(ROOF_AT_PA * coupon_mu_pa / fitted_mu_pa, solid[:, 0], solid[:, 1]) / drawn
    return (f"With the coupon's modulus the solid bends {ratio:.2f} times as much as the actuator from "
            f"{RAMP_START_PA / 1e3:.0f} to {top / 1e3:.1f} kPa (its solver's stop). The fitted modulus is "
            f"{fitted_mu_pa / coupon_mu_pa:.2f} times the coupon's: a law exact for this solid, given the coupon, puts "
            f"every pressure at {coupon_mu_pa / fitted_mu_pa:.2f} of the actuator's. A roof of "
            f"{ROOF_M * 1e3:.0f} mm instead of the default (`{ROOF}`) makes the solid bend {100 * (1 - thicker):.0f} % "
            f"less at {ROOF_AT_PA / 1e3:.0f} kPa; the fitted modulus, {100 * (1 - stiffer):.0f} % less.")


def law_sentences(ramp, solid, coupon_mu_pa, curves, fitted_mu):
    """The thick wall law against the solid, each at its fitted modulus: how far apart their bends are, as far as the
    solid reaches, and the law's limit point at the solid's modulus and at its own."""
    law, solid_mu = fitted_mu["the thick wall law"], fitted_mu[SOLID_NAME]
    p = numpy.linspace(RAMP_START_PA, solid[-1, 0] * solid_mu / coupon_mu_pa, 200)
    apart = numpy.nanmax(numpy.abs(curves["the thick wall law"](law, p) - curves[SOLID_NAME](solid_mu, p)))
    snap = measured_snap(ramp)

    def limit(mu):
        return f"{law_limit_pa(mu) / 1e3:.1f} kPa ({100 * (law_limit_pa(mu) / snap - 1):+.0f} %)"
    return (f"Fitted the same way, the thick wall law takes {law / 1e3:.1f} kPa, {law / solid_mu:.2f} times the "
            f"solid's, and its bends then stay within {apart * DEG:.2f}° of the solid's as far as the solid reaches "
            f"({p[-1] / 1e3:.1f} kPa). Its limit point is {limit(solid_mu)} at the solid's modulus and {limit(law)} "
            "at its own.")


def law_limit_pa(mu_pa):
    """The thick wall law's limit point on the drawing of --solid with shear modulus @p mu_pa (Pa)."""
    return pf.FingerModel(config=str(ROOT / SOLID_CONFIG), overrides={"shear_modulus_pa": mu_pa}).limit_gauge_pa


def limit_point(name, solid, coupon_mu_pa, mu_pa):
    """The thick wall law's limit point at @p mu_pa (kPa), or, for the solid cell, how far its ramp shows none."""
    if name != SOLID_NAME:
        return f"{law_limit_pa(mu_pa) / 1e3:.1f}"
    return f"none below {solid[-1, 0] * mu_pa / coupon_mu_pa / 1e3:.1f}, its solver's stop"


def skins_table():
    """The solid cell with the drawing's skins changed (the roof, the side walls through the body's width), each
    with the modulus that gives it the ramp's bends to 20 kPa: what it then predicts before and across the snap."""
    ramp = table("data/epfl_ecoflex30_c7_bending.csv")
    coupon = pf.FingerModel(config=str(ROOT / SOLID_CONFIG)).parameters["shear_modulus_pa"]
    snap = measured_snap(ramp)
    p = ramp[:, 0]
    before = ramp[(p > FIT_TOP_PA) & (p <= STEEP_FROM_PA)]
    at = ramp[p < snap][-1:, 0]  # the ramp's last row below the snap
    print(f"| the drawing's skins | mu fitted on the bends to {FIT_TOP_PA / 1e3:.0f} kPa (x the coupon's) "
          f"| bends {FIT_TOP_PA / 1e3:.0f} to {STEEP_FROM_PA / 1e3:.0f} kPa: largest / rms (deg) "
          f"| bend at {at[0] / 1e3:.1f} kPa: solid / measured (deg) | the solid's stop at that modulus (kPa) |")
    print("|---|---|---|---|---|")
    for name, path in SKINS:
        solid = table(path)
        bends = lambda mu, q, solid=solid: solid_bends(solid, coupon, mu, q)  # noqa: E731
        mu = best_mu(bends, ramp[ramp[:, 0] <= FIT_TOP_PA])
        measured = numpy.interp(at, ramp[:, 0], ramp[:, 1])[0]
        there = bends(mu, at)[0]
        there = "beyond its solver's reach" if math.isnan(there) else f"{there * DEG:.1f}"
        miss = "beyond its solver's reach"
        first = summary(bends(mu, before[:, 0]) - before[:, 1], miss)
        print(f"| {name} | {mu / 1e3:.1f} ({mu / coupon:.2f}) | {first} | {there} / {measured * DEG:.1f} "
              f"| {solid[-1, 0] * mu / coupon / 1e3:.1f} |")


def modulus_factor(solid, wall_m):
    """The factor on the coupon's modulus at which the thick wall law, on the drawing with @p wall_m, bends as the
    solid cell does at its pressures (least squares; a 0.2 % grid from 0.5 to 5), and the rms left (rad)."""
    model = pf.FingerModel(config=str(ROOT / SOLID_CONFIG), overrides={"drawing/wall_thickness_m": wall_m})
    coupon = model.parameters["shear_modulus_pa"]

    def rms(k):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            law = pf.FingerModel(config=str(ROOT / SOLID_CONFIG),
                                 overrides={"drawing/wall_thickness_m": wall_m, "shear_modulus_pa": coupon * k})
            bend = law.path().evaluate(solid[:, 0], outputs=["tip_angle_rad"])["tip_angle_rad"]
        return math.sqrt(numpy.mean((bend - solid[:, 1]) ** 2))
    factor = min(numpy.exp(numpy.linspace(math.log(0.5), math.log(5.0), 1152)), key=rms)
    return factor, rms(factor), model


def beam_bend(model, gauge_pa):
    """One chamber's bend (rad) by small-strain beam theory: the pressure's moment on the cavity's face, P h w (h/2),
    over the pitch Z, against the section through the cavity about the strain-limiting layer, E = 3 mu (the floor on
    the layer, as fem_cell.py meshes it)."""
    p = model.parameters
    h, w, top = p["chamber_height_m"], p["chamber_width_m"], p["wall_critical_height_m"]
    width = 2 * fem_cell.Cell(p["drawing"], 1.0).Y * 1e-3  # the body's width as the cell has it (mm to m)
    second_moment = (width * top ** 3 - w * h ** 3) / 3
    return gauge_pa * h * w * (h / 2) * p["segment_length_m"] / (3 * p["shear_modulus_pa"] * second_moment)


def walls_table():
    """The thick wall law against the solid cell for the EPFL drawing with other walls between cavities, each with
    the coupon's modulus: the factor on the modulus that makes the law bend as the solid does."""
    print(f"| wall between cavities (mm) | solid's bend at {WALLS_TOP_PA / 1e3:.0f} kPa (deg) | the law's (deg) "
          "| the law bends as the solid at (x the modulus) | rms left (deg) | the law's limit point (kPa) "
          "| the solid's first step over the beam's |")
    print("|---|---|---|---|---|---|---|")
    for wall_mm, path in WALLS:
        solid = table(path)
        solid = solid[(solid[:, 0] > 0) & (solid[:, 0] <= WALLS_TOP_PA)]
        factor, left, model = modulus_factor(solid, wall_mm * 1e-3)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            law = model.path().evaluate([WALLS_TOP_PA], outputs=["tip_angle_rad"])["tip_angle_rad"][0]
        first = table(path, "chamber_bend_rad")[1]  # the ramp's first step, near rest
        print(f"| {wall_mm:g} | {solid[-1, 1] * DEG:.2f} | {law * DEG:.2f} | {factor:.2f} | {left * DEG:.3f} "
              f"| {model.limit_gauge_pa / 1e3:.1f} | {first[1] / beam_bend(model, first[0]):.2f} |")


def plot_solid(path, ramp, solid, coupon, curves, fitted_mu):
    """The ramp and the four curves of solid_table, whole (left) and before the snap (right)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.8))
    p = numpy.linspace(RAMP_START_PA, ramp[-1, 0], 400)
    for ax, top in zip(axes, (120, 30)):
        ax.plot(ramp[:, 0] / 1e3, ramp[:, 1] * DEG, "k.", ms=4, label="measured ramp (zeroed at 10 kPa)")
        for (name, bends), color, width in zip(curves.items(), ("C0", "C3"), (4, 1.5)):
            for mu, style, how in ((coupon, "--", "the coupon's"), (fitted_mu[name], "-", "fitted to 20 kPa")):
                ax.plot(p / 1e3, bends(mu, p) * DEG, style, color=color, lw=width, alpha=0.6 if width > 2 else 1,
                        label=f"{name}, mu {mu / 1e3:.1f} kPa ({how})")
        ax.axvline(FIT_TOP_PA / 1e3, color="0.6", lw=0.8)
        ax.set(xlabel="gauge pressure (kPa)", ylabel="chord angle, base to tip (deg)", ylim=(-2 * top / 120, top))
    axes[1].set_xlim(RAMP_START_PA / 1e3, measured_snap(ramp) / 1e3)
    axes[0].set_title("the whole ramp")
    axes[1].set_title("up to the measured snap (each solid curve ends where its solver stops)", fontsize=10)
    axes[0].legend(fontsize=7.5, loc="upper left")
    fig.suptitle("EPFL Ecoflex 00-30 PneuNet, 7 chambers, as drawn: the solid cell and the thick wall law")
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def plot_snap(path):
    """The first table's models against the ramp, the stepwise loading (left) and the blocked force (right)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    ramp, steps = table(CASES[0][3]), table(CASES[0][4])
    blocked = table(BLOCKED, "blocked_tip_force_n")
    fig, (bend_ax, force_ax) = plt.subplots(1, 2, figsize=(11, 4.6))
    bend_ax.plot(ramp[:, 0] / 1e3, ramp[:, 1] * DEG, "k.", ms=4, label="measured: slow ramp (zeroed at 10 kPa)")
    bend_ax.plot(steps[:, 0] / 1e3, steps[:, 1] * DEG, "ks", mfc="none", ms=6, label="measured: stepwise")
    force_ax.plot(blocked[:, 0] / 1e3, blocked[:, 1], "k.", ms=5, label="measured")
    p = numpy.linspace(ramp[0, 0], ramp[-1, 0], 600)
    for (_, how, config, _, _), color in zip(CASES, ("C3", "C0")):
        model = pf.FingerModel(config=str(ROOT / config))
        bend = path_bends(model, p)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            force = model.blocked_tip_force(blocked[:, 0])
        bend_ax.plot(p / 1e3, (bend - bend[0]) * DEG, color=color, label=f"model, {how}")
        force_ax.plot(blocked[:, 0] / 1e3, force, color=color, label=f"model, {how}")
        for ax in (bend_ax, force_ax):
            ax.axvline(model.snap_gauge_pa / 1e3, color=color, lw=0.8, ls=":")
    bend_ax.axvline(measured_snap(ramp) / 1e3, color="k", lw=0.8, ls=":")
    bend_ax.set(xlabel="gauge pressure (kPa)", ylabel="chord angle, base to tip (deg)", ylim=(-5, 130),
                title="bend (dotted: each snap; the model's from snap_gauge_pa)")
    force_ax.set(xlabel="gauge pressure (kPa)", ylabel="blocked tip force (N)", ylim=(-0.05, 1.5),
                 title="blocked tip force")
    bend_ax.legend(fontsize=7.5, loc="upper left")
    force_ax.legend(fontsize=7.5, loc="upper left")
    fig.suptitle("EPFL Ecoflex 00-30 PneuNet, 7 chambers: zero-shot (drawing + coupon) and fitted on its ramp")
    fig.tight_layout()
    fig.savefig(path, dpi=100)


def main():
    if "--plot" in sys.argv[1:] and len(sys.argv) == 3:
        plot_snap(sys.argv[2])
    elif "--fits" in sys.argv[1:]:
        fits_table()
    elif "--skins" in sys.argv[1:]:
        skins_table()
    elif "--walls" in sys.argv[1:]:
        walls_table()
    elif "--solid" in sys.argv[1:]:
        curves = solid_table()
        if "--plot" in sys.argv[1:]:
            plot_solid(sys.argv[sys.argv.index("--plot") + 1], *curves)
    else:
        snap_table()


if __name__ == "__main__":
    main()
