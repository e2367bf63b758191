#!/usr/bin/python3
"""Draws docs/fill_backbones.png, the paper's Figure 12 for this finger: the backbone at each time step while a
constant air flow fills it (`finger_model`'s time mode gives the pressure of each step; `pneumatic_finger.core` gives
the backbone at it).

    source devel/setup.bash; /usr/bin/python3 scripts/plot_fill.py [--flow-lpm 0.5] [--duration-s 1.0] [--step-s 0.1]
"""
import argparse
import csv
import io
import os
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--flow-lpm", default="0.5")
    parser.add_argument("--duration-s", default="1.0")
    parser.add_argument("--step-s", default="0.1")
    parser.add_argument("--output", default=os.path.join(ROOT, "docs", "fill_backbones.png"))
    args = parser.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import pneumatic_finger.core as pf

    exe = os.path.join(ROOT, "devel", "lib", "pneumatic_finger", "finger_model")
    out = subprocess.run([exe, "--flow-lpm", args.flow_lpm, "--duration-s", args.duration_s, "--step-s", args.step_s],
                         check=True, capture_output=True, text=True).stdout
    rows = list(csv.DictReader(io.StringIO(out)))
    times = [float(r["time_s"]) for r in rows]
    pressures = [float(r["gauge_pa"]) for r in rows]
    backbones = pf.FingerModel().evaluate(pressures)["backbone_m"]

    fig, ax = plt.subplots(figsize=(7, 6))
    colors = plt.get_cmap("plasma")
    for i, (t, p) in enumerate(zip(times, pressures)):
        b = backbones[i] * 1e3
        c = colors(i / max(1, len(times) - 1))
        ax.plot(b[:, 0], b[:, 1], "-o", color=c, markersize=3, linewidth=1.5,
                label=f"t = {t:.1f} s, {p / 98066.5:.2f} kg/cm²")
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm), along the unbent finger")
    ax.set_ylabel("y (mm), toward the strain-limited side")
    ax.set_title(f"Backbone while {args.flow_lpm} L/min fills the finger (eq 4, ideal spring)")
    ax.legend(fontsize=7, loc="upper left")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.output, dpi=110)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
