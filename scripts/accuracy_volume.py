"""The volume input on the two Marchese 2015 segments: the pressure-driven fit, then the volume's own prediction.

usage: python3 scripts/accuracy_volume.py   (needs the built package: source devel/setup.bash)

For each segment (data/marchese2015_*_bending.csv: pressure, supplied volume and bend, filled in volume steps), on the
rows of even index (by volume) it:
 1. fits the membrane law's keys (shear_modulus_pa, chamber_gap_m, wall_locking_jm) to the bends against pressure,
    with the package's calibration (pneumatic_finger.calibrate, minimax);
 2. fits dead_volume_m3 to the supplied volumes, by least squares, where the model has a shape at the measured
    pressure: V_s - growth(P) = V_g P/(P_o + P) is linear in V_g;
then drives the model by the measured volume of every row (evaluate_volume) and reports, for the fitted half and the
held-out half (odd index), the bend error (deg) and the pressure error (%). It also prints what the chambers' growth
can hold: the model's growth at the last row against the measured volume less the fitted gas's compression. Takes
about two minutes (two three-key fits). Its output is docs/ACCURACY.md's "Volume as the input".
"""
import csv
import math
import pathlib
import tempfile

import numpy as np

import pneumatic_finger.core as pf

ROOT = pathlib.Path(__file__).resolve().parent.parent
DEG = 180 / math.pi
KEYS = ["shear_modulus_pa", "chamber_gap_m", "wall_locking_jm"]
SETS = [("Marchese 2015 ribbed segment", "ribbed"), ("Marchese 2015 cylindrical segment", "cylindrical")]


def rows_of(name):
    lines = [line for line in open(ROOT / f"data/marchese2015_{name}_bending.csv") if not line.startswith("#")]
    return sorted(csv.DictReader(lines), key=lambda r: float(r["supplied_volume_m3"]))


def column(rows, key):
    return np.array([float(r[key]) for r in rows])


def fit_half(name, even, tmp):
    path = pathlib.Path(tmp) / f"{name}_even.csv"
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(even[0].keys()))
        w.writeheader()
        w.writerows(even)
    config = str(ROOT / f"config/marchese2015_{name}.yaml")
    fit = pf.calibrate(str(path), KEYS, "minimax", config, {}, compare="tip_angle", leave_one_out=False)
    return config, fit["fitted"]


def dead_volume(model, p, v, p_o):
    growth = np.array([model.supplied_volume(x) for x in p])
    x = p / (p_o + p)
    ok = ~np.isnan(growth)
    return max(float(np.sum(x[ok] * (v[ok] - growth[ok])) / np.sum(x[ok] * x[ok])), 0.0), growth


def report(title, name, tmp):
    rows = rows_of(name)
    even, odd = rows[0::2], rows[1::2]
    config, fitted = fit_half(name, even, tmp)
    plain = pf.FingerModel(config, fitted)
    p_o = plain.parameters["atmospheric_pressure_pa"]
    v_g, _ = dead_volume(plain, column(even, "gauge_pa"), column(even, "supplied_volume_m3"), p_o)
    model = pf.FingerModel(config, {**fitted, "dead_volume_m3": v_g})
    print(f"- {title}: fitted to the bends of the even rows against pressure: "
          + ", ".join(f"{k} = {fitted[k]:.4g}" for k in KEYS) + f"; dead_volume_m3 = {v_g:.4g} (least squares)")
    for label, part in (("fitted half", even), ("held-out half", odd)):
        v = column(part, "supplied_volume_m3")
        out = model.evaluate_volume(v, outputs=["tip_angle_rad", "gauge_pa", "status"])
        bend = (out["tip_angle_rad"] - column(part, "bend_angle_rad")) * DEG
        p = column(part, "gauge_pa")
        rel = np.where(p > 0, (out["gauge_pa"] - p) / np.where(p > 0, p, 1) * 100, 0.0)
        print(f"  - {label}, driven by volume: bend error largest {np.nanmax(np.abs(bend)):.2f} deg "
              f"(rms {math.sqrt(np.nanmean(bend ** 2)):.2f}); pressure error largest {np.nanmax(np.abs(rel)):.1f} % "
              f"(rms {math.sqrt(np.nanmean(rel ** 2)):.1f}); rows without a shape: {int(np.sum(np.isnan(bend)))}")
    last = rows[-1]
    p_last, v_last = float(last["gauge_pa"]), float(last["supplied_volume_m3"])
    gas = v_g * p_last / (p_o + p_last)
    growth = plain.supplied_volume(p_last)
    rest = plain.parameters["chamber_count"] * np.mean(plain.parameters["chamber_height_m"]) * np.mean(
        plain.parameters["chamber_thickness_m"]) * np.mean(plain.parameters["chamber_width_m"])
    print(f"  - at the last row ({p_last / 1e3:.1f} kPa, {v_last * 1e6:.1f} mL supplied): the fitted gas takes "
          f"{gas * 1e6:.1f} mL, which leaves {max(v_last - gas, 0) * 1e6:.1f} mL for the chambers; the model's "
          f"chambers grow by {growth * 1e6 if not math.isnan(growth) else float('nan'):.2f} mL there (rest volume "
          f"{rest * 1e6:.2f} mL)")


def main():
    with tempfile.TemporaryDirectory() as tmp:
        for title, name in SETS:
            report(title, name, tmp)


if __name__ == "__main__":
    main()
