#!/usr/bin/env bash
# Design to spec, timed: finger_design --target on the shipped EPFL file, the whole command, for a snap target (a
# 5-chamber sibling, its wall free), for three targets at once (snap, bend and blocked force, three sizes free), for a
# three-target Pareto front and for the lowest pressure that holds a part, then writes them into docs/DESIGN.md's
# measured block.
# usage: bash scripts/measure_design_target.sh     (after scripts/build.sh)
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
export PATH="/usr/bin:/bin:$PATH"
set +u  # ROS's setup scripts read unset variables
source "$ROOT/devel/setup.bash"
set -u
cd "$ROOT"
one=(python3 scripts/finger_design --config config/epfl_ecoflex30_c7.yaml --target snap_gauge_pa=40000
     --free drawing/wall_thickness_m --chamber-count 5)
three=(python3 scripts/finger_design --config config/epfl_ecoflex30_c7.yaml --target snap_gauge_pa=40000
       --target tip_angle_rad@30000=0.3 --target blocked_tip_force_n@45000=1.0 --free drawing/wall_thickness_m
       --free drawing/cavity_height_m --free drawing/roof_thickness_m --chamber-count 4:8)
front=(python3 scripts/finger_design --config config/epfl_ecoflex30_c7.yaml --target snap_gauge_pa=40000
       --target tip_angle_rad@30000=0.6 --target blocked_tip_force_n@45000=0.5 --free drawing/wall_thickness_m
       --free drawing/cavity_height_m --chamber-count 4:8 --pareto 6)
grip=(python3 scripts/finger_design --config config/epfl_ecoflex30_c7.yaml --target grip_gauge_pa=min
      --part mass_kg=0.02,diameter_m=0.03,lift_mps2=2 --free drawing/wall_thickness_m --chamber-count 4:9)
time_of() {
  local start end
  start=$(date +%s.%N)
  "$@" >/dev/null
  end=$(date +%s.%N)
  echo "$end - $start" | bc -l | xargs printf "%.2f"
}
{
  echo "machine: $(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p'), Debian 12"
  echo "${one[*]:1}: $(time_of "${one[@]}") s (the whole command: Python, the model's file, the search)"
  echo "${three[*]:1}: $(time_of "${three[@]}") s"
  echo "${front[*]:1}: $(time_of "${front[@]}") s (a three-target Pareto front)"
  echo "${grip[*]:1}: $(time_of "${grip[@]}") s (the lowest pressure that holds a part)"
} | python3 scripts/measured_block.py docs/DESIGN.md "bash scripts/measure_design_target.sh"
