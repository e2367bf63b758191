"""Every wall law on every data set: fit, leave-one-out, and a fit to half the points predicting the other half.

usage: python3 scripts/accuracy_laws.py [--plot FILE]   (needs the built package: source devel/setup.bash)

For the paper's Table 1 (data/sierra2022_table1.csv, the joints 2..7 average) and the two segments of Marchese,
Katzschmann & Rus 2015 (data/marchese2015_*_bending.csv, the bend angle of the whole segment, taken as the tip angle),
each law is fitted with the package's calibration (pneumatic_finger.calibrate, the code of finger_calibrate), minimax:
 - on every row, with each row also predicted by a fit to the others (leave-one-out, what `--wall-law auto` compares);
 - on the rows of even index (pressures sorted), predicting the rows of odd index, which the fit never saw.
Prints a Markdown table (docs/ACCURACY.md, "Other actuators" is its output) and draws the plot (default
docs/accuracy_laws.png). Takes seconds (docs/CALIBRATE.md, "The solver").
"""
import csv
import math
import pathlib
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pneumatic_finger.core as pf  # noqa: E402
from page_support import plot_arguments, save  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent
DEG = 180 / math.pi
MU, GAP, JM, SHARE = "shear_modulus_pa", "chamber_gap_m", "wall_locking_jm", "base_wall_share"

# Each data set: its file, what is compared, its parameter file, and per law the start (overrides) and the keys of the
# full fit and of the half fit. Table 1's four rows allow two keys (leave-one-out needs two rows more than keys), and
# its halves of two rows one: mu alone, with no gap (c = 0, which assumes nothing of the data) for both laws. The
# paper law cannot take the segments' lever (b > L), so it starts from its uniform wall, b = L/2, as --wall-law auto
# does. The thick wall is fitted as --wall-law auto fits it on the segments, Neo-Hookean (two keys; the files' J_m is
# 0) and Gent (three, J_m fitted too), auto keeping whichever predicts better. It bends each segment by the face its
# parameter file maps (wall_flexion_face: the ribbed segment's outer, the cylindrical's inner); the cylindrical segment
# shows the outer face too, as a variant.
SETS = [
    {"name": "Table 1 (the paper's finger)", "data": "data/sierra2022_table1.csv", "config": "config/finger.yaml",
     "compare": "average", "column": "avg", "laws": {
         "paper": {"start": {}, "keys": [MU, GAP], "half_keys": [MU], "half_start": {GAP: 0.0}},
         "membrane": {"start": {"wall_law": "membrane", MU: 2e4}, "keys": [MU, GAP], "half_keys": [MU],
                      "half_start": {GAP: 0.0}},
         "thick": {"start": {"wall_law": "thick", MU: 2e4}, "keys": [MU, GAP], "half_keys": [MU],
                   "half_start": {GAP: 0.0}}}},
    {"name": "Marchese 2015 ribbed segment", "data": "data/marchese2015_ribbed_bending.csv",
     "config": "config/marchese2015_ribbed.yaml", "compare": "tip_angle", "column": "bend_angle_rad", "laws": {
         "paper": {"start": {"wall_law": "paper", "wall_critical_height_m": 0.00155}, "keys": [MU, GAP]},
         "membrane, Neo-Hookean": {"start": {JM: 0.0}, "keys": [MU, GAP], "variant": True},
         "membrane": {"start": {}, "keys": [MU, GAP, JM]},
         "thick, Neo-Hookean": {"start": {"wall_law": "thick", JM: 0.0}, "keys": [MU, GAP]},
         "thick": {"start": {"wall_law": "thick"}, "keys": [MU, GAP, JM]}}},
    {"name": "Marchese 2015 cylindrical segment", "data": "data/marchese2015_cylindrical_bending.csv",
     "config": "config/marchese2015_cylindrical.yaml", "compare": "tip_angle", "column": "bend_angle_rad", "laws": {
         "paper": {"start": {"wall_law": "paper", "wall_critical_height_m": 0.0014}, "keys": [MU, GAP]},
         "membrane, Neo-Hookean": {"start": {JM: 0.0}, "keys": [MU, GAP], "variant": True},
         "membrane": {"start": {}, "keys": [MU, GAP, JM]},
         "thick, Neo-Hookean": {"start": {"wall_law": "thick", JM: 0.0}, "keys": [MU, GAP]},
         "thick": {"start": {"wall_law": "thick"}, "keys": [MU, GAP, JM]},
         "thick, Neo-Hookean, outer face": {"start": {"wall_law": "thick", JM: 0.0, "wall_flexion_face": "outer"},
                                            "keys": [MU, GAP], "variant": True}}},
]


def read_rows(path):
    lines = [line for line in open(ROOT / path) if not line.startswith("#")]
    return sorted(csv.DictReader(lines), key=lambda r: float(r["gauge_pa"]))


def measured(row, column):
    if column == "avg":
        return float(np.mean([float(row[f"joint_{k}_rad"]) for k in range(2, 8)]))
    return float(row[column])


def write_rows(rows, directory, name):
    path = pathlib.Path(directory) / name
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    return str(path)


def predict(config, overrides, pressures, column):
    """The model's compared quantity at each pressure (NaN where it has no shape: beyond the limit point)."""
    out = pf.FingerModel(str(ROOT / config), overrides).evaluate(np.asarray(pressures, dtype=float))
    # In pressure order, as a ramp: a wall past its limit point is on its far branch ("snapped through"), a shape too;
    # so is a curl past a full turn ("meets itself"): the model's shape, said to pass through the finger.
    shaped = np.isin(out["status"], [pf.STATUS.index(s) for s in ("ok", "vacuum", "snapped through", "meets itself")])
    value = out["joint_angle_rad"][:, 1:].mean(axis=1) if column == "avg" else out["tip_angle_rad"]
    return np.where(shaped, value, np.nan)


def errors(model, measure):
    e = np.asarray(model) - np.asarray(measure)
    if np.any(np.isnan(e)):
        return math.inf, math.inf
    return float(np.max(np.abs(e))) * DEG, float(np.sqrt(np.mean(e * e))) * DEG


def fit(data_path, s, law, keys, start, loo):
    r = pf.calibrate(data_path, keys, "minimax", str(ROOT / s["config"]), start, compare=s["compare"],
                     leave_one_out=loo)
    return {**start, **r["fitted"]}, r


def model_of(r, column, key):
    return list(r[key]["model_avg_rad" if column == "avg" else "model_tip_angle_rad"])


def study(s, tmp):
    rows = read_rows(s["data"])
    pressures = [float(r["gauge_pa"]) for r in rows]
    truth = [measured(r, s["column"]) for r in rows]
    even, odd = rows[0::2], rows[1::2]
    out = {"rows": rows, "p": pressures, "truth": truth, "laws": {}}
    for law, spec in s["laws"].items():
        overrides, full = fit(str(ROOT / s["data"]), s, law, spec["keys"], spec["start"], True)
        half_start = {**spec["start"], **spec.get("half_start", {})}
        half_overrides, half = fit(write_rows(even, tmp, "even.csv"), s, law, spec.get("half_keys", spec["keys"]),
                                   half_start, False)
        held = predict(s["config"], half_overrides, [float(r["gauge_pa"]) for r in odd], s["column"])
        out["laws"][law] = {
            "keys": spec["keys"], "half_keys": spec.get("half_keys", spec["keys"]), "fitted": full["fitted"],
            "fit": errors(model_of(full, s["column"], "residuals"), truth),
            "loo": errors(model_of(full, s["column"], "leave_one_out"), truth),
            "half_fit": errors(model_of(half, s["column"], "residuals"), truth[0::2]),
            "held_out": errors(held, truth[1::2]), "half_overrides": half_overrides, "overrides": overrides,
            "held_errors": np.degrees(np.asarray(held) - np.asarray(truth[1::2])), "variant": spec.get("variant"),
            "warnings": full["warnings"]}
    # What --wall-law auto keeps: of the laws with their default keys, the smaller largest leave-one-out error.
    out["auto"] = min((k for k in out["laws"] if not out["laws"][k]["variant"]), key=lambda k: out["laws"][k]["loo"][0])
    return out


def pair_bound(r):
    """Half the largest spread of bends measured at one pressure: what any law driven by pressure alone must miss."""
    by_pressure = {}
    for p, t in zip(r["p"], r["truth"]):
        by_pressure.setdefault(p, []).append(t)
    spreads = [(max(v) - min(v), p) for p, v in by_pressure.items() if len(v) > 1]
    return max(spreads) if spreads else None


def cell(pair):
    return "no shape past the limit point" if math.isinf(pair[0]) else f"{pair[0]:.2f} / {pair[1]:.2f}"


def table(results):
    print("| data set | law | keys fitted (all rows / half) | fit: largest / rms (deg) | leave-one-out: largest / rms "
          "(deg) | half fit | other half predicted: largest / rms (deg) |")
    print("|---|---|---|---|---|---|---|")
    for s, r in zip(SETS, results):
        for law, v in r["laws"].items():
            mark = " (auto)" if law == r["auto"] else ""
            print(f"| {s['name']} | {law}{mark} | {len(v['keys'])} / {len(v['half_keys'])} | {cell(v['fit'])} | "
                  f"{cell(v['loo'])} | {cell(v['half_fit'])} | {cell(v['held_out'])} |")
    print()
    for s, r in zip(SETS, results):
        for law, v in r["laws"].items():
            fitted = ", ".join(f"{k} = {x:.4g}" for k, x in v["fitted"].items())
            held = ", ".join(f"{p / 1e3:.1f} kPa {e:+.2f}" for p, e in zip(r["p"][1::2], v["held_errors"]))
            print(f"- {s['name']}, {law}: {fitted}. Held-out errors (deg): {held}")
            for w in v["warnings"]:
                print(f"  - warning: {w}")
        bound = pair_bound(r)
        if bound:
            print(f"- {s['name']}: two bends {bound[0] * DEG:.2f} deg apart at {bound[1] / 1e3:.1f} kPa: a law driven by "
                  f"pressure alone misses one of them by at least {bound[0] * DEG / 2:.2f} deg")


def plot(results, path):
    fig, axes = plt.subplots(1, len(SETS), figsize=(5.2 * len(SETS), 5.6))
    colors = {"paper": "tab:blue", "membrane": "tab:red", "membrane, Neo-Hookean": "tab:orange", "thick": "tab:green",
              "thick, Neo-Hookean": "tab:cyan", "thick, Neo-Hookean, outer face": "tab:olive"}
    for ax, s, r in zip(axes, SETS, results):
        p = np.array(r["p"]) / 1e3
        truth = np.degrees(r["truth"])
        ax.plot(p[0::2], truth[0::2], "ko", label="measured, fitted half")
        ax.plot(p[1::2], truth[1::2], "o", mfc="white", mec="k", label="measured, held out")
        grid = np.linspace(0, max(r["p"]) * 1.02, 300)
        for law, v in r["laws"].items():
            curve = np.degrees(predict(s["config"], v["half_overrides"], grid, s["column"]))
            ax.plot(grid / 1e3, curve, color=colors[law],
                    label=f"{law}: fit to half; held out {cell(v['held_out']).split(' /')[0]} deg")
        ax.set_title(s["name"], fontsize=10)
        ax.set_xlabel("gauge pressure (kPa)")
        ax.set_ylabel("joints 2..7 average (deg)" if s["column"] == "avg" else "bend angle of the segment (deg)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14))  # below: the points stay in sight
    save(fig, path)


def main():
    args = plot_arguments(__doc__, ROOT / "docs/accuracy_laws.png")
    with tempfile.TemporaryDirectory() as tmp:
        results = [study(s, tmp) for s in SETS]
    table(results)
    plot(results, args.plot)


if __name__ == "__main__":
    main()
