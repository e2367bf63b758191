"""The volume input on the two Marchese 2015 segments: pressure-driven keys against keys fitted to the volume.

usage: python3 scripts/accuracy_volume.py [--plot docs/accuracy_volume.png]   (needs the built package:
source devel/setup.bash)

Each segment (data/marchese2015_*_bending.csv: pressure, supplied volume and bend, filled in volume steps) is split by
volume: the rows of even index are fitted, the odd ones held out. Every fit is the package's calibration
(pneumatic_finger.calibrate, as finger_calibrate), with the membrane law's three keys (shear_modulus_pa,
chamber_gap_m, wall_locking_jm):
 1. "keys from pressure": the keys fitted to the bends against pressure (drive="pressure", minimax); then the drive's
    gas, dead_volume_m3, fitted to the pressures against volume with those keys (drive="volume", compare="gauge_pa",
    least squares);
 2. "keys from volume": the keys fitted to the bends against volume (drive="volume"), with that gas, by the
    objective (minimax or least squares) whose leave-one-out within the fitted rows is smaller (the held-out half
    plays no part in the choice);
 3. "bends and pressures together": from the keys from volume, shear_modulus_pa, chamber_gap_m and the gas refitted
    to the bends and the pressures against volume at once (compare="tip_angle+gauge_pa", least squares: the tip
    angle's error in rad beside the pressure's relative error).
Each is then driven by the measured volume of every row (evaluate_volume) and reported for the fitted and the
held-out half: the bend error (deg) and the pressure error (%), and the two bends the ribbed segment has at one
pressure. It also prints what the chambers' growth holds at the last row. Takes about six and a half minutes (the
leave-one-out of two three-key fits per segment). Its output is
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
KEYS = ["shear_modulus_pa", "chamber_gap_m", "wall_locking_jm"]
BOTH_KEYS = ["shear_modulus_pa", "chamber_gap_m", "dead_volume_m3"]
WAYS = ("keys from pressure", "keys from volume", "bends and pressures together")
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


def fits(name, even):
    """The two sets of keys (pressure, volume) and the gas, each fitted to the even rows; for the keys from volume,
    the objective whose leave-one-out within the even rows is smaller, and both objectives' leave-one-out."""
    config = str(ROOT / f"config/marchese2015_{name}.yaml")
    by_pressure = pf.calibrate(table(even), KEYS, "minimax", config, compare="tip_angle", drive="pressure")["fitted"]
    gas = pf.calibrate(table(even), ["dead_volume_m3"], "least_squares", config, by_pressure, compare="gauge_pa",
                       drive="volume")["fitted"]
    candidates = {objective: pf.calibrate(table(even), KEYS, objective, config, {**by_pressure, **gas},
                                          compare="tip_angle", drive="volume", leave_one_out=True)
                  for objective in ("minimax", "least_squares")}
    loo = {objective: largest_loo_deg(fit) for objective, fit in candidates.items()}
    chosen = min(loo, key=loo.get)
    by_volume = {**candidates[chosen]["fitted"], **gas}
    both = pf.calibrate(table(even), BOTH_KEYS, "least_squares", config, by_volume, compare="tip_angle+gauge_pa",
                        drive="volume")["fitted"]
    return config, {**by_pressure, **gas}, by_volume, {**by_volume, **both}, loo, chosen


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


def report(title, name, curves):
    rows = rows_of(name)
    even, odd = rows[0::2], rows[1::2]
    config, by_pressure, by_volume, both, loo, chosen = fits(name, even)
    print(f"- {title} ({len(even)} rows fitted, {len(odd)} held out; 3 keys fitted to bends, then 1 to pressures; "
          f"together: 3 to both):")
    print("  keys from volume, objective by leave-one-out within the fitted rows: " +
          ", ".join(f"{k} {v:.2f} deg" for k, v in loo.items()) + f" -> {chosen}")
    for label, keys in zip(WAYS, (by_pressure, by_volume, both)):
        print(f"  {label}: " + ", ".join(f"{k} = {keys[k]:.4g}" for k in KEYS + ["dead_volume_m3"]))
        model = pf.FingerModel(config, keys)
        for half, part in (("fitted half", even), ("held-out half", odd)):
            print(summary(f"{label}, {half}, driven by volume", *errors(model, part)))
        twins = same_pressure_rows(model, rows)
        if twins:
            print(f"  - {label}, the two bends at one pressure: {twins}")
        v = np.linspace(0, column(rows, "supplied_volume_m3").max(), 200)
        curves[(name, label)] = (v, model.evaluate_volume(v, outputs=["tip_angle_rad", "gauge_pa"]))
    print(chamber_share(config, by_pressure, rows[-1]))


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
            for label, style in zip(WAYS, ("--", "-", ":")):
                v, out = curves[(name, label)]
                model_key = "tip_angle_rad" if key == "bend_angle_rad" else "gauge_pa"
                ax.plot(v * 1e6, out[model_key] * scale, style, label=f"model driven by volume, {label}")
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
    curves = {}
    for title, name in SETS:
        report(title, name, curves)
    if args.plot:
        plot(args.plot, curves)


if __name__ == "__main__":
    main()
