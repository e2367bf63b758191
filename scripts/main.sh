#!/usr/bin/env bash
# The main job: install what is missing, build, and show the paper's actuator over its validated pressure range.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
bash "$ROOT/scripts/setup.sh"
bash "$ROOT/scripts/build.sh"
"$ROOT/build/devel/lib/pneumatic_finger/finger_model" --sweep-pa 0:196133:9 | awk -F, '
  NR == 1 { printf "%9s %7s %9s %9s %10s %10s %10s %9s %9s\n", "gauge_Pa", "kg/cm2", "stretch", "bulge_mm",
            "theta_deg", "joint1_deg", "joint2_deg", "tip_x_mm", "tip_y_mm"; next }
  { d = 180 / 3.141592653589793
    printf "%9.0f %7.3f %9.6f %9.5f %10.4f %10.4f %10.4f %9.3f %9.3f\n", $1, $1 / 98066.5, $2, $3 * 1e3, $4 * d,
           $5 * d, $6 * d, $(NF - 1) * 1e3, $NF * 1e3 }'
