#!/usr/bin/python3
"""Draws docs/grasp_joint_angles.png: the joint angles against pressure for one obstacle, beside the free finger's,
and the volume the supply has pushed in (the walls the disk holds take no more).

Both curves come from `finger_model` (the same CSV the README documents), so the plot shows what the tool prints:
    /usr/bin/python3 scripts/plot_grasp.py [--disk X,Y,R] [--output PATH]
"""
import argparse
import csv
import io
import os
import subprocess
import sys

from page_support import finish_axes

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run_model(extra):
    exe = os.path.join(ROOT, "devel", "lib", "pneumatic_finger", "finger_model")
    out = subprocess.run([exe, "--sweep-pa", "0:294199.5:600"] + extra, check=True, capture_output=True, text=True)
    rows = list(csv.DictReader(io.StringIO(out.stdout)))
    joints = sorted((k for k in rows[0] if k.startswith("joint_")), key=lambda k: int(k.split("_")[1]))
    shape = {j: [float(r[j]) for r in rows] for j in joints}
    return [float(r["gauge_pa"]) for r in rows], shape, [float(r["supplied_volume_m3"]) for r in rows]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--disk", default="0.06,0.03,0.012", help="X,Y,R of the obstacle disk (m, finger plane)")
    parser.add_argument("--output", default=os.path.join(ROOT, "docs", "grasp_joint_angles.png"))
    args = parser.parse_args()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    p, free, free_volume = run_model([])
    _, held, held_volume = run_model(["--obstacle-disk", args.disk])
    fig, (ax, ax_volume) = plt.subplots(1, 2, figsize=(12, 4.8), gridspec_kw={"width_ratios": [3, 2]})
    colors = plt.get_cmap("viridis")
    for i, joint in enumerate(free):
        c = colors(i / max(1, len(free) - 1))
        ax.plot([x / 1e3 for x in p], free[joint], "--", color=c, linewidth=1, alpha=0.6)
        ax.plot([x / 1e3 for x in p], held[joint], "-", color=c, linewidth=2, label=joint.replace("_rad", ""))
    # The first touch: the first pressure at which a joint departs from its free curve.
    touch = next((p[k] for k in range(len(p)) if any(held[j][k] != free[j][k] for j in free)), None)
    if touch is not None:
        ax.axvline(touch / 1e3, color="grey", linestyle=":")
        ax.annotate(f"segment touches the disk: joints freeze\n(joints 2..7 coincide until then: identical chambers)",
                    (touch / 1e3, 0.02), xytext=(8, 0), textcoords="offset points", fontsize=8)
    ax.set_xlabel("gauge pressure (kPa)")
    ax.set_ylabel("joint angle (rad)")
    x, y, r = (float(v) * 1e3 for v in args.disk.split(","))
    finish_axes(ax, f"Joint angles with a {r:g} mm disk at ({x:g}, {y:g}) mm (solid) and free (dashed)",
                legend_columns=2)
    ax_volume.plot([v * 1e6 for v in free_volume], [x / 1e3 for x in p], "--", color="k", label="free")
    ax_volume.plot([v * 1e6 for v in held_volume], [x / 1e3 for x in p], "-", color="C3", linewidth=2,
                   label="on the disk: held walls take no more")
    ax_volume.set_xlabel("supplied volume (mL)")
    ax_volume.set_ylabel("gauge pressure (kPa)")
    finish_axes(ax_volume, "Driven by volume: the pressure it makes")
    fig.tight_layout()
    fig.savefig(args.output, dpi=110)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    sys.exit(main())
