"""The volume input on the two Marchese 2015 segments, with every wall law: keys fitted to the bends against
pressure, against volume, and to bends and pressures together.

usage: python3 scripts/accuracy_volume.py [--plot docs/accuracy_volume.png]   (needs the built package:
source devel/setup.bash)

Each segment (data/marchese2015_*_bending.csv: pressure, supplied volume and bend, filled in volume steps) is split by
volume: the rows of even index are fitted, the odd ones held out. Every fit is the package's calibration
(pneumatic_finger.calibrate, as finger_calibrate), with each law's keys (LAWS below: the membrane's Gent wall with
three, shear_modulus_pa, chamber_gap_m and wall_locking_jm; the thick wall, Neo-Hookean, bent by the face its
segment's parameter file maps (wall_flexion_face: outer for the ribbed segment's row of channels, inner for the
cylindrical's one channel), and the paper law with the first two):
 1. "keys from pressure": the keys fitted to the bends against pressure (drive="pressure", minimax); then the drive's
    gas, dead_volume_m3, fitted to the pressures against volume with those keys (drive="volume", compare="gauge_pa",
    least squares);
 2. "keys from volume": the keys fitted to the bends against volume (drive="volume"), with that gas, by the
    objective (minimax or least squares) whose leave-one-out within the fitted rows is smaller (the held-out half
    plays no part in the choice);
 3. "bends and pressures together": from the keys from volume, shear_modulus_pa, chamber_gap_m and the gas refitted
    to the bends and the pressures against volume at once (compare="tip_angle+gauge_pa", least squares: the tip
    angle's error in rad beside the pressure's relative error);
 4. "with the skin": the same three keys refitted at each skin share chamber_growth_ratio of SKIN_RATIOS (a chamber
    growing r_V times what its walls give, docs/MODEL.md "Volume"), keeping the share whose fit leaves the smaller
    objective on the fitted rows.
Each is then driven by the measured volume of every row (evaluate_volume) and reported for the fitted and the
held-out half: the bend error (deg) and the pressure error (%), and the two bends the ribbed segment has at one
pressure; for the membrane law, also what the chambers' growth holds at the last row. A closing table sets the
held-out half side by side: driven by pressure (the keys from pressure), driven by volume (the keys from volume),
the keys fitted to both, and with the skin. Took about fifteen minutes with the old engine (the leave-one-out of the fits by volume,
and a fit per skin share). Its output is
docs/ACCURACY.md's "Volume as the input"; --plot draws bend and pressure against volume for both segments.
"""
import argparse
import csv
import math
import pathlib

import numpy as np

import pneumatic_finger.core as pf

ROOT = pathlib.Path(__file__).resolve().parent.parent
DEG = 180 / math.pi
MU, GAP, JM = "shear_modulus_pa", "chamber_gap_m", "wall_locking_jm"
BOTH_KEYS = [MU, GAP, "dead_volume_m3"]
# Each law's start (overrides of the segment's file) and the keys fitted to the bends, as scripts/accuracy_laws.py
# fits them by pressure: the membrane's Gent wall with three keys; the thick wall Neo-Hookean with two (its Gent
# fits take too long for this page); the paper law from its uniform wall, b = L/2 of each segment.
LAWS = {"membrane": {"start": {}, "keys": [MU, GAP, JM]},
        "thick, Neo-Hookean": {"start": {"wall_law": "thick", JM: 0.0}, "keys": [MU, GAP]},
        "paper": {"start": {"ribbed": {"wall_law": "paper", "wall_critical_height_m": 0.00155},
                            "cylindrical": {"wall_law": "paper", "wall_critical_height_m": 0.0014}}, "keys": [MU, GAP]}}
WAYS = ("keys from pressure", "keys from volume", "bends and pressures together", "with the skin")
# The skin's shares tried by the fourth way (chamber_growth_ratio): from the walls' growth alone to 32 times it.
SKIN_RATIOS = (1, 2, 4, 6, 8, 12, 16, 32)
SETS = [("Marchese 2015 ribbed segment", "ribbed"), ("Marchese 2015 cylindrical segment", "cylindrical")]
COLUMNS = ["gauge_pa", "supplied_volume_m3", "bend_angle_rad"]


def rows_of(name):
    lines = [line for line in open(ROOT / f"data/marchese2015_{name}_bending.csv") if not line.startswith("#")]
    return sorted(csv.DictReader(lines), key=lambda r: float(r["supplied_volume_m3"]))


def column(rows, key):
    return np.array([float(r[key]) for r in rows])


def table(rows):
    return {k: column(rows, k) for k in COLUMNS}


def largest_loo_deg(fit):
    loo = fit["leave_one_out"]
    return float(np.nanmax(np.abs(loo["model_tip_angle_rad"] - loo["measured_tip_angle_rad"]))) * DEG


def start_of(name, law):
    start = LAWS[law]["start"]
    return dict(start[name]) if name in start else dict(start)


def fits(name, even, law):
    """The three sets of keys of @p law (from pressure, from volume, together), each fitted to the even rows with the
    gas fitted to the pressures against volume; for the keys from volume, the objective whose leave-one-out within
    the even rows is smaller, and both objectives' leave-one-out."""
    config, keys, start = str(ROOT / f"config/marchese2015_{name}.yaml"), LAWS[law]["keys"], start_of(name, law)
    by_pressure = {**start, **pf.calibrate(table(even), keys, "minimax", config, start, compare="tip_angle",
                                           drive="pressure", leave_one_out=False)["fitted"]}
    gas = pf.calibrate(table(even), ["dead_volume_m3"], "least_squares", config, by_pressure, compare="gauge_pa",
                       drive="volume", leave_one_out=False)["fitted"]
    candidates = {objective: pf.calibrate(table(even), keys, objective, config, {**by_pressure, **gas},
                                          compare="tip_angle", drive="volume", leave_one_out=True)
                  for objective in ("minimax", "least_squares")}
    loo = {objective: largest_loo_deg(fit) for objective, fit in candidates.items()}
    chosen = min(loo, key=loo.get)
    by_volume = {**by_pressure, **candidates[chosen]["fitted"], **gas}
    both = pf.calibrate(table(even), BOTH_KEYS, "least_squares", config, by_volume, compare="tip_angle+gauge_pa",
                        drive="volume", leave_one_out=False)["fitted"]
    ways = ({**by_pressure, **gas}, by_volume, {**by_volume, **both}, with_skin(config, even, by_volume))
    return config, ways, loo, chosen


def best_skin_share(config, even, start, keys, compare, report=None):
    """@p keys fitted by volume (least squares, @p compare) at each skin share r_V of SKIN_RATIOS, from @p start; the
    keys of the share whose fit leaves the smaller objective on the fitted rows (the held-out half plays no part).
    @p report(ratio, objective), if given, hears each share's."""
    best = None
    for ratio in SKIN_RATIOS:
        at = {**start, "chamber_growth_ratio": float(ratio)}
        fit = pf.calibrate(table(even), keys, "least_squares", config, at, compare=compare, drive="volume",
                           leave_one_out=False)
        if report:
            report(ratio, fit["objective_value"])
        if best is None or fit["objective_value"] < best[0]:
            best = (fit["objective_value"], {**at, **fit["fitted"]})
    return best[1]


def with_skin(config, even, by_volume):
    """The keys of "together" refitted at each skin share (best_skin_share)."""
    return best_skin_share(config, even, by_volume, BOTH_KEYS, "tip_angle+gauge_pa")


def errors(model, part):
    """Bend error (deg) and pressure error (%) of @p model driven by each row's measured volume."""
    out = model.evaluate_volume(column(part, "supplied_volume_m3"), outputs=["tip_angle_rad", "gauge_pa"])
    bend = (out["tip_angle_rad"] - column(part, "bend_angle_rad")) * DEG
    p = column(part, "gauge_pa")
    rel = np.where(p > 0, (out["gauge_pa"] - p) / np.where(p > 0, p, 1) * 100, 0.0)
    return bend, rel


def summary(label, bend, rel):
    return (f"  - {label}: bend error largest {np.nanmax(np.abs(bend)):.2f} deg (rms {math.sqrt(np.nanmean(bend ** 2)):.2f});"
            f" pressure error largest {np.nanmax(np.abs(rel)):.1f} % (rms {math.sqrt(np.nanmean(rel ** 2)):.1f});"
            f" rows without a shape: {int(np.sum(np.isnan(bend)))}")


def same_pressure_rows(model, rows):
    """The rows that share a measured pressure with another: measured and model bend (deg), by volume."""
    p = column(rows, "gauge_pa")
    twins = [r for r in rows if np.sum(p == float(r["gauge_pa"])) > 1]
    if not twins:
        return ""
    bend, _ = errors(model, twins)
    return "; ".join(f"{float(r['supplied_volume_m3']) * 1e6:.1f} mL at {float(r['gauge_pa']) / 1e3:.1f} kPa: measured "
                     f"{float(r['bend_angle_rad']) * DEG:.2f} deg, error {e:+.2f}" for r, e in zip(twins, bend))


def gas_uptake_m3(dead_m3, gauge_pa, atmospheric_pa):
    """The volume the drive's gas takes at @p gauge_pa: its isothermal compression (docs/MODEL.md, "Volume")."""
    return dead_m3 * gauge_pa / (atmospheric_pa + gauge_pa)


def chamber_share(config, keys, last):
    """What the chambers must take at the last row, against what the model's chambers grow."""
    model = pf.FingerModel(config, keys)
    p, v = float(last["gauge_pa"]), float(last["supplied_volume_m3"])
    gas = gas_uptake_m3(keys["dead_volume_m3"], p, model.parameters["atmospheric_pressure_pa"])
    growth = pf.FingerModel(config, {**keys, "dead_volume_m3": 0.0}).supplied_volume(p)
    return (f"  - at the last row ({p / 1e3:.1f} kPa, {v * 1e6:.1f} mL supplied), keys from pressure: the gas takes "
            f"{gas * 1e6:.1f} mL, which leaves {max(v - gas, 0) * 1e6:.1f} mL for the chambers; the model's chambers "
            f"grow by {growth * 1e6:.2f} mL there")


def pressure_driven(model, part):
    """The bend error (deg) of @p model driven by each row's measured pressure."""
    out = model.evaluate(column(part, "gauge_pa"), outputs=["tip_angle_rad"])
    return (out["tip_angle_rad"] - column(part, "bend_angle_rad")) * DEG


def largest_rms(x):
    """Largest / rms of the rows with a shape, and how many have none (past a limit the law does not follow)."""
    shapeless = int(np.sum(np.isnan(x)))
    return (f"{np.nanmax(np.abs(x)):.2f} / {math.sqrt(np.nanmean(x ** 2)):.2f}" +
            (f" ({shapeless} without a shape)" if shapeless else ""))


def report(title, name, law, curves, summary_rows):
    rows = rows_of(name)
    even, odd = rows[0::2], rows[1::2]
    config, ways, loo, chosen = fits(name, even, law)
    keys = LAWS[law]["keys"]
    print(f"- {title}, {law} ({len(even)} rows fitted, {len(odd)} held out; {len(keys)} keys fitted to bends, then 1 "
          f"to pressures; together: 3 to both; with the skin: 3 to both at each of {len(SKIN_RATIOS)} skin shares):")
    print("  keys from volume, objective by leave-one-out within the fitted rows: " +
          ", ".join(f"{k} {v:.2f} deg" for k, v in loo.items()) + f" -> {chosen}")
    held = {}
    for label, fitted in zip(WAYS, ways):
        shown = [k for k in dict.fromkeys(keys + BOTH_KEYS + ["chamber_growth_ratio"]) if k in fitted]
        print(f"  {label}: " + ", ".join(f"{k} = {fitted[k]:.4g}" for k in shown))
        model = pf.FingerModel(config, fitted)
        for half, part in (("fitted half", even), ("held-out half", odd)):
            print(summary(f"{label}, {half}, driven by volume", *errors(model, part)))
        held[label] = errors(model, odd)
        twins = same_pressure_rows(model, rows)
        if twins:
            print(f"  - {label}, the two bends at one pressure: {twins}")
        v = np.linspace(0, column(rows, "supplied_volume_m3").max(), 200)
        curves[(name, law, label)] = (v, model.evaluate_volume(v, outputs=["tip_angle_rad", "gauge_pa"]))
    if law == "membrane":
        print(chamber_share(config, ways[0], rows[-1]))
    by_pressure_bends = pressure_driven(pf.FingerModel(config, ways[0]), odd)
    summary_rows.append(f"| {title.replace('Marchese 2015 ', '')} | {law} | {len(keys)} | "
                        f"{largest_rms(by_pressure_bends)} | {len(keys)} + 1 | {largest_rms(held['keys from volume'][0])} | "
                        f"{np.nanmax(np.abs(held['keys from volume'][1])):.1f} | "
                        f"{largest_rms(held['bends and pressures together'][0])} | "
                        f"{np.nanmax(np.abs(held['bends and pressures together'][1])):.1f} | "
                        f"{ways[3]['chamber_growth_ratio']:g} | {largest_rms(held['with the skin'][0])} | "
                        f"{np.nanmax(np.abs(held['with the skin'][1])):.1f} |")


def plot(path, curves):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 2, figsize=(10, 7), sharex="col")
    for col, (title, name) in enumerate(SETS):
        rows = rows_of(name)
        for row, (key, scale, unit) in enumerate((("bend_angle_rad", DEG, "bend (deg)"), ("gauge_pa", 1e-3, "pressure (kPa)"))):
            ax = axes[row][col]
            for part, marker, label in ((rows[0::2], "o", "measured, fitted"), (rows[1::2], "s", "measured, held out")):
                ax.plot(column(part, "supplied_volume_m3") * 1e6, column(part, key) * scale, marker, mfc="none",
                        color="k", label=label)
            model_key = "tip_angle_rad" if key == "bend_angle_rad" else "gauge_pa"
            for label, style in zip(WAYS, ("--", "-", ":")):  # the membrane law, every way
                v, out = curves[(name, "membrane", label)]
                ax.plot(v * 1e6, out[model_key] * scale, style, color="C0",
                        label=f"membrane law driven by volume, {label}")
            for law, color in zip([law for law in LAWS if law != "membrane"], ("C1", "C2")):
                v, out = curves[(name, law, "keys from volume")]
                ax.plot(v * 1e6, out[model_key] * scale, "-", color=color, lw=1,
                        label=f"{law} law driven by volume, keys from volume")
            for law, color in zip(LAWS, ("C0", "C1", "C2")):
                v, out = curves[(name, law, "with the skin")]
                ax.plot(v * 1e6, out[model_key] * scale, "-.", color=color, lw=1.5,
                        label=f"{law} law driven by volume, with the skin")
            top = np.max(column(rows, key)) * scale
            ax.set_ylim(-0.05 * top, 1.6 * top)  # a law may bend, or press, far past the data
            ax.set_ylabel(unit)
            ax.grid(alpha=0.3)
            if row == 0:
                ax.set_title(title)
            else:
                ax.set_xlabel("supplied volume (mL)")
    axes[0][0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--plot", help="write the figure here (PNG)")
    args = parser.parse_args()
    curves, summary_rows = {}, []
    for title, name in SETS:
        for law in LAWS:
            report(title, name, law, curves, summary_rows)
    print()
    print("| segment | law | keys, pressure in | held out, pressure in: bend largest / rms (deg) | keys, volume in | "
          "held out, volume in: bend largest / rms (deg) | pressure largest (%) | together (3 keys): bend (deg) | "
          "together: pressure (%) | with the skin: r_V | with the skin (3 keys + r_V): bend (deg) | "
          "with the skin: pressure (%) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    print("\n".join(summary_rows))
    if args.plot:
        plot(args.plot, curves)


if __name__ == "__main__":
    main()
