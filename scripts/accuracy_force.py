"""The blocked tip force predicted from bending alone, against published measurements.

usage: python3 scripts/accuracy_force.py [--plot FILE]   (needs the built package: source devel/setup.bash)

For each segment of Marchese, Katzschmann & Rus 2015 (data/marchese2015_*_bending.csv and *_blocked_force.csv), as
drawn (config/marchese2015_*_drawing.yaml, docs/DRAWING.md's rule), `--wall-law auto` is fitted to the bending data
alone (pneumatic_finger.calibrate, the code of finger_calibrate: it chooses the law, the keys and the comparison by
the bends held out), and the file it writes predicts the blocked tip force (FingerModel.blocked_tip_force,
docs/MODEL.md "Force") at every pressure of the force data, which no fit saw. Prints the Markdown of docs/FORCE.md
("Measured against predicted") and draws the plot (default docs/force_blocked.png). About a minute.
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
# The goal: within 15 % of the measured force, or within 0.05 N where the force is small.
RELATIVE, ABSOLUTE_N = 0.15, 0.05

SEGMENTS = ["ribbed", "cylindrical"]


def read_rows(path):
    lines = [line for line in open(ROOT / path) if not line.startswith("#")]
    return sorted(csv.DictReader(lines), key=lambda r: float(r["gauge_pa"]))


def fit_bending(seg):
    """--wall-law auto on the bends of @p seg as drawn; returns its law, keys and values, its largest bend error
    (deg), its warnings, and the file it wrote (in @p tmp)."""
    config = str(ROOT / f"config/marchese2015_{seg}_drawing.yaml")
    data = str(ROOT / f"data/marchese2015_{seg}_bending.csv")
    out = pathlib.Path(tempfile.mkdtemp()) / f"{seg}_auto.yaml"
    r = pf.calibrate(data=data, config=config, wall_law="auto", output=str(out))
    res = r["residuals"]
    bend = np.nanmax(np.abs(res["model_tip_angle_rad"] - res["measured_tip_angle_rad"])) * 180 / math.pi
    return r["wall_law"], r["fitted"], bend, r["warnings"], str(out)


def study(seg):
    law, fitted, bend_error, warnings, written = fit_bending(seg)
    model = pf.FingerModel(config=written)
    rows = read_rows(f"data/marchese2015_{seg}_blocked_force.csv")
    pressure = np.array([float(r["gauge_pa"]) for r in rows])
    measured = np.array([float(r["blocked_tip_force_n"]) for r in rows])
    predicted = model.blocked_tip_force(pressure)
    within = np.abs(predicted - measured) <= np.maximum(RELATIVE * measured, ABSOLUTE_N)
    return {"seg": seg, "law": law, "overrides": fitted, "bend_error": bend_error, "warnings": warnings,
            "contact": model.contact_gauge_pa, "pressure": pressure, "measured": measured, "predicted": predicted,
            "within": within}


def summary(r):
    err = r["predicted"] - r["measured"]
    miss = ~r["within"]
    worst = int(np.argmax(np.abs(err)))
    # A pressure where the model predicts no force (below the walls' touch) is not counted as met by the 0.05 N floor:
    # there the model says nothing, whatever the measured force.
    pressing = r["predicted"] > 0
    silent = ~pressing
    met = int((r["within"] & pressing).sum())
    below = (f"; below the touch {int(silent.sum())} predicted 0 N against up to {r['measured'][silent].max():.3f} N"
             if silent.any() else "")
    return (f"| {r['seg']} | {r['law']} | {r['bend_error']:.2f} | {r['contact'] / 1e3:.1f} | "
            f"{met} of {int(pressing.sum())} where it predicts a force{below} | "
            f"{', '.join(f'{p / 1e3:.1f}' for p in r['pressure'][miss]) or 'none'} | "
            f"{err[worst]:+.3f} at {r['pressure'][worst] / 1e3:.1f} kPa |")


def rows_table(r):
    out = [f"**{r['seg']}** ({r['law']} law: " + ", ".join(f"{k} = {v:.4g}" for k, v in r["overrides"].items()
                                                            if isinstance(v, float)) + ")", "",
           "| gauge (kPa) | measured (N) | predicted (N) | error (N) | error (%) | within the goal |",
           "|---|---|---|---|---|---|"]
    for p, m, f, ok in zip(r["pressure"], r["measured"], r["predicted"], r["within"]):
        pct = f"{100 * (f - m) / m:+.0f}" if m > 0 else "-"
        out.append(f"| {p / 1e3:.1f} | {m:.3f} | {f:.3f} | {f - m:+.3f} | {pct} | {'yes' if ok else 'no'} |")
    return out


def plot(results, path):
    fig, axes = plt.subplots(1, len(results), figsize=(5.2 * len(results), 4.0))
    for ax, r in zip(axes, results):
        ax.plot(r["pressure"] / 1e3, r["measured"], "o", label="measured (Marchese et al. 2015)")
        ax.plot(r["pressure"] / 1e3, r["predicted"], "-", label=f"predicted, {r['law']} law, auto on the bends")
        band = np.maximum(RELATIVE * r["measured"], ABSOLUTE_N)
        ax.fill_between(r["pressure"] / 1e3, r["measured"] - band, r["measured"] + band, alpha=0.15,
                        label="goal: 15 % or 0.05 N")
        ax.axvline(r["contact"] / 1e3, color="grey", lw=0.8, ls=":", label="the walls touch (the fitted gap)")
        ax.set_title(f"{r['seg']} segment: blocked tip force")
        ax.set_xlabel("gauge pressure (kPa)")
        ax.set_ylabel("tip force (N)")
        ax.legend(fontsize=7, loc="upper left")
    save(fig, path)


def main():
    args = plot_arguments(__doc__, ROOT / "docs/force_blocked.png")
    results = [study(s) for s in SEGMENTS]
    print("| segment | law (by bending) | bending fit: largest error (deg) | walls touch at (kPa) | "
          "force within the goal | pressures outside it (kPa) | largest error (N) |")  # outside: by the goal alone
    print("|---|---|---|---|---|---|---|")
    for r in results:
        print(summary(r))
    for r in results:
        print()
        for w in r["warnings"]:
            print(f"- {r['seg']}, bending fit: {w}")
        print()
        print("\n".join(rows_table(r)))
    plot(results, args.plot)


if __name__ == "__main__":
    main()
