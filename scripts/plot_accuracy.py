"""Plots the measured finger against the calibrated model, before and after joint 1's parameter: docs/accuracy.png.

usage: python3 scripts/plot_accuracy.py [BUILD_DIR]   (BUILD_DIR defaults to the repository, where scripts/build.sh
                                                       puts devel/)

Left: joint angles against pressure. Right: the finger's backbone at the four measured pressures, measured (its
joint angles laid along the model's segments, eq 38) and modelled. "After" is the shipped config/finger.yaml; "before"
is the same with base_wall_share = 0 (the paper's reading of joint 1, and the shipped fit until joint 1 had its own
parameter). Every model number comes from the package's finger_model tool; the measurements from
data/sierra2022_table1.csv.
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
BUILD = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT
KGCM2 = 98066.5
DEG = 180 / math.pi
N = 7
BASE_M, SEGMENT_M = 0.015, 0.010  # Z0 and Z of config/finger.yaml

rows = [r for r in csv.DictReader(line for line in open(ROOT / "data/sierra2022_table1.csv") if not line.startswith("#"))]


def finger_model(*args):
    out = subprocess.run([str(BUILD / "devel/lib/pneumatic_finger/finger_model"), *args], check=True,
                         capture_output=True, text=True).stdout
    return list(csv.DictReader(io.StringIO(out)))


def backbone(joints):
    """O_0..O_{N+1} from joint angles (eq 38), in mm."""
    x, y, angle = [0.0, BASE_M], [0.0, 0.0], 0.0
    for q in joints:
        angle += q
        x.append(x[-1] + SEGMENT_M * math.cos(angle))
        y.append(y[-1] + SEGMENT_M * math.sin(angle))
    return [v * 1e3 for v in x], [v * 1e3 for v in y]


sweep = f"0:{2.5 * KGCM2}:251"
after, before = finger_model("--sweep-pa", sweep), finger_model("--sweep-pa", sweep, "--set", "base_wall_share=0")
p_model = [float(r["gauge_pa"]) / KGCM2 for r in after]

fig, (ax, bx) = plt.subplots(1, 2, figsize=(13, 5.4), dpi=110, gridspec_kw={"width_ratios": [1, 1.05]})
ax.plot(p_model, [float(r["joint_2_rad"]) * DEG for r in after], color="C0", lw=2, label="model, joints 2..7")
ax.plot(p_model, [float(r["joint_1_rad"]) * DEG for r in after], color="C1", lw=2,
        label="model, joint 1, after (base face s₀ = 0.31)")
ax.plot(p_model, [float(r["joint_1_rad"]) * DEG for r in before], color="C1", lw=1.2, ls="--",
        label="model, joint 1, before (s₀ = 0: half of the others)")
for i, r in enumerate(rows):
    p = float(r["pressure_kgcm2"])
    joints = [float(r[f"joint_{k}_rad"]) * DEG for k in range(2, 8)]
    ax.scatter([p] * 6, joints, s=14, color="C0", alpha=0.45, label="measured, joints 2..7" if i == 0 else None)
    ax.scatter([p], [sum(joints) / 6], s=70, marker="D", color="C0", edgecolor="k", zorder=3,
               label="measured, average of joints 2..7" if i == 0 else None)
    ax.scatter([p], [float(r["joint_1_rad"]) * DEG], s=45, marker="s", color="C1", edgecolor="k", zorder=3,
               label="measured, joint 1" if i == 0 else None)
ax.set_xlabel("gauge pressure (kg/cm²)")
ax.set_ylabel("joint angle (°)")
ax.set_title("Joint angles: Table 1 of Sierra & Ordoñez-Avila (2022) against the model", fontsize=10)
ax.grid(alpha=0.3)
ax.set_xlim(0, 2.5)
ax.set_ylim(bottom=0)
ax.legend(fontsize=8, loc="upper left")

for i, r in enumerate(rows):
    gauge = r["gauge_pa"]
    colour = f"C{i + 2}"
    mx, my = backbone([float(r[f"joint_{k}_rad"]) for k in range(1, N + 1)])
    m_after = finger_model("--gauge-pa", gauge)[0]
    m_before = finger_model("--gauge-pa", gauge, "--set", "base_wall_share=0")[0]
    ax_x, ax_y = backbone([float(m_after[f"joint_{k}_rad"]) for k in range(1, N + 1)])
    bx_x, bx_y = backbone([float(m_before[f"joint_{k}_rad"]) for k in range(1, N + 1)])
    label = f"{float(r['pressure_kgcm2']):.1f} kg/cm²"
    bx.plot(mx, my, "o", color=colour, ms=5, label=f"{label}: measured (joints on the model's segments)")
    bx.plot(ax_x, ax_y, "-", color=colour, lw=2)
    bx.plot(bx_x, bx_y, "--", color=colour, lw=1)
    err_after = math.hypot(ax_x[-1] - mx[-1], ax_y[-1] - my[-1])
    err_before = math.hypot(bx_x[-1] - mx[-1], bx_y[-1] - my[-1])
    bx.annotate(f"tip off by {err_after:.1f} mm\n(before {err_before:.1f} mm)", (mx[-1], my[-1]), fontsize=7,
                textcoords="offset points", xytext=(8, -4), color=colour)
bx.plot([], [], "-", color="grey", lw=2, label="model, after")
bx.plot([], [], "--", color="grey", lw=1, label="model, before")
bx.set_aspect("equal")
bx.set_xlabel("x along the unbent finger (mm)")
bx.set_ylabel("y toward the strain-limited side (mm)")
bx.set_title("The whole finger at the measured pressures: backbone O₀..O₈", fontsize=10)
bx.grid(alpha=0.3)
bx.set_xlim(-2, 102)
bx.set_ylim(-2, 48)
bx.legend(fontsize=7, loc="upper left")
fig.tight_layout()
out = ROOT / "docs/accuracy.png"
fig.savefig(out)
print(f"wrote {out}")
