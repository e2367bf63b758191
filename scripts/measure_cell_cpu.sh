#!/usr/bin/env bash
# CPU share of every node of the pick-and-place cell, measured headless over SECONDS (default 24: two cycles),
# from /proc/<pid>/stat (user + system time), and writes the result into README.md's block for this command.
# usage: bash scripts/measure_cell_cpu.sh [SECONDS]
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
SECONDS_TO_RUN="${1:-24}"
source "$ROOT/scripts/ros_env.sh"
port=$ROS_PORT
roslaunch --port "$port" pneumatic_finger pick_and_place_cell.launch rviz:=false >"$ROOT/build/measure_cell.log" 2>&1 &
launch=$!
trap 'kill $launch 2>/dev/null; wait 2>/dev/null' EXIT
sleep 5  # start-up
ticks() { awk '{print $14 + $15}' "/proc/$1/stat" 2>/dev/null || echo 0; }
declare -A pid start
for name in finger_node pressure_regulator cell_sequencer robot_state_publisher; do
  for p in $(pgrep -f "lib/.*/$name( |$)" || true); do pid["$name/$p"]=$p; start["$name/$p"]=$(ticks "$p"); done
done
sleep "$SECONDS_TO_RUN"
hz=$(getconf CLK_TCK)
{
echo "node CPU share over ${SECONDS_TO_RUN} s of the running cell ($(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p')):"
for key in $(printf '%s\n' "${!pid[@]}" | sort); do
  used=$(( $(ticks "${pid[$key]}") - ${start[$key]} ))
  awk -v n="${key%/*}" -v u="$used" -v hz="$hz" -v s="$SECONDS_TO_RUN" 'BEGIN { printf "  %-24s %5.2f %% of one core\n", n, 100 * u / hz / s }'
done
} | tee /dev/stderr | /usr/bin/python3 "$ROOT/scripts/readme_block.py" "$ROOT/README.md" "bash scripts/measure_cell_cpu.sh"
