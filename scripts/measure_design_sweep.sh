#!/usr/bin/env bash
# A million designs: times finger_design on a 1,000 x 1,000 grid at one pressure (the whole command: the lean sweep,
# the CSV, the heat map), and the sweep call alone from Python, then writes both into docs/DESIGN.md's measured block.
# usage: bash scripts/measure_design_sweep.sh     (after scripts/build.sh)
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
export PATH="/usr/bin:/bin:$PATH"
set +u  # ROS's setup scripts read unset variables
source "$ROOT/devel/setup.bash"
set -u
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
command=(python3 "$ROOT/scripts/finger_design" --vary chamber_height_m=0.008:0.016:1000
         --vary chamber_gap_m=20e-6:200e-6:1000 --quantity tip_angle_rad@196133 --csv "$out/designs.csv"
         --png "$out/designs.png")
start=$(date +%s.%N)
"${command[@]}"
end=$(date +%s.%N)
alone=$(python3 - <<'PY'
import time, numpy, pneumatic_finger.core as pf
grid = numpy.stack(numpy.meshgrid(numpy.linspace(0.008, 0.016, 1000), numpy.linspace(20e-6, 200e-6, 1000),
                                  indexing="ij"), axis=-1).reshape(-1, 2)
model = pf.FingerModel()
start = time.perf_counter()
model.sweep_designs(["chamber_height_m", "chamber_gap_m"], grid, 196133.0, outputs=["tip_angle_rad"])
print(f"{time.perf_counter() - start:.2f}")
PY
)
{
  echo "machine: $(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p'), Debian 12"
  echo "finger_design --vary chamber_height_m=0.008:0.016:1000 --vary chamber_gap_m=20e-6:200e-6:1000 \\"
  echo "    --quantity tip_angle_rad@196133 --csv designs.csv --png designs.png"
  echo "designs: $(($(wc -l < "$out/designs.csv") - 1)) (CSV rows), the whole command: $(python3 -c "print(f'{$end - $start:.1f}')") s"
  echo "of which the sweep itself (FingerModel.sweep_designs, one model per design, in C++): $alone s"
} | python3 "$ROOT/scripts/measured_block.py" "$ROOT/docs/DESIGN.md" "bash scripts/measure_design_sweep.sh"
