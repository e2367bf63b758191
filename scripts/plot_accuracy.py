"""Plots measured joint angles against the calibrated model: docs/accuracy.png.

usage: python3 scripts/plot_accuracy.py [BUILD_DIR]   (BUILD_DIR defaults to build/)

The model curve comes from the package's own finger_model tool (default, calibrated parameters), the measurements
and the paper's model column from data/sierra2022_table1.csv.
"""
import csv
import io
import math
import pathlib
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent
BUILD = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "build"
KGCM2 = 98066.5
DEG = 180 / math.pi

rows = [r for r in csv.DictReader(line for line in open(ROOT / "data/sierra2022_table1.csv") if not line.startswith("#"))]
model_csv = subprocess.run([str(BUILD / "devel/lib/pneumatic_finger/finger_model"), "--sweep-pa", f"0:{2.5 * KGCM2}:251"],
                           check=True, capture_output=True, text=True).stdout
model = list(csv.DictReader(io.StringIO(model_csv)))

fig, ax = plt.subplots(figsize=(8, 5.2), dpi=110)
p_model = [float(r["gauge_pa"]) / KGCM2 for r in model]
ax.plot(p_model, [float(r["joint_2_rad"]) * DEG for r in model], color="C0", lw=2,
        label="model, joints 2..7 (calibrated: minimax over the averages)")
ax.plot(p_model, [float(r["joint_1_rad"]) * DEG for r in model], color="C1", lw=1.5, ls="--",
        label="model, joint 1 (one active wall)")
for i, r in enumerate(rows):
    p = float(r["pressure_kgcm2"])
    joints = [float(r[f"joint_{k}_rad"]) * DEG for k in range(2, 8)]
    ax.scatter([p] * 6, joints, s=14, color="C0", alpha=0.45, label="measured, joints 2..7" if i == 0 else None)
    ax.scatter([p], [sum(joints) / 6], s=70, marker="D", color="C0", edgecolor="k", zorder=3,
               label="measured, average of joints 2..7" if i == 0 else None)
    ax.scatter([p], [float(r["joint_1_rad"]) * DEG], s=40, marker="s", color="C1", edgecolor="k", zorder=3,
               label="measured, joint 1" if i == 0 else None)
    ax.scatter([p], [float(r["paper_model_rad"]) * DEG], s=80, marker="x", color="C3", zorder=3,
               label="the paper's model column" if i == 0 else None)
ax.set_xlabel("gauge pressure (kg/cm²)")
ax.set_ylabel("joint angle (°)")
ax.set_title("Seven-chamber finger: measured joint angles (Sierra & Ordoñez-Avila 2022, Table 1) vs model")
ax.title.set_fontsize(10)
ax.grid(alpha=0.3)
ax.set_xlim(0, 2.5)
ax.set_ylim(bottom=0)
ax.legend(fontsize=8, loc="upper left")
fig.tight_layout()
out = ROOT / "docs/accuracy.png"
fig.savefig(out)
print(f"wrote {out}")
