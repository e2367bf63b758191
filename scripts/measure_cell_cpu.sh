#!/usr/bin/env bash
# CPU share of every node of the pick-and-place cell, both frame authorities in turn (finger_tf:=false, the default:
# robot_state_publisher publishes every frame; finger_tf:=true: each finger_node broadcasts its own), measured
# headless over SECONDS each (default 24: two cycles) from /proc/<pid>/stat (user + system time). Writes the result
# into README.md's block for this command.   usage: bash scripts/measure_cell_cpu.sh [SECONDS]
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
SECONDS_TO_RUN="${1:-24}"
source "$ROOT/scripts/ros_env.sh"
hz=$(getconf CLK_TCK)
ticks() { awk '{print $14 + $15}' "/proc/$1/stat" 2>/dev/null || echo 0; }
measure() {  # measure FINGER_TF: prints one line per node and the total
  local port
  port=$(/usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("localhost", 0)); print(s.getsockname()[1])')
  ROS_MASTER_URI="http://localhost:$port" roslaunch --port "$port" pneumatic_finger pick_and_place_cell.launch \
    rviz:=false finger_tf:="$1" >"$ROOT/build/measure_cell_$1.log" 2>&1 &
  local launch=$!
  sleep 6  # start-up
  declare -A pid start
  for name in finger_node pressure_regulator cell_sequencer robot_state_publisher; do
    for p in $(pgrep -f "/$name( |$)" || true); do pid["$name/$p"]=$p; start["$name/$p"]=$(ticks "$p"); done
  done
  sleep "$SECONDS_TO_RUN"
  local total=0 used
  echo "finger_tf:=$1 ($([ "$1" = true ] && echo "each finger_node broadcasts its frames" || echo "robot_state_publisher publishes every frame"))"
  for key in $(printf '%s\n' "${!pid[@]}" | sort); do
    used=$(( $(ticks "${pid[$key]}") - ${start[$key]} ))
    total=$(( total + used ))
    awk -v n="${key%/*}" -v u="$used" -v hz="$hz" -v s="$SECONDS_TO_RUN" 'BEGIN { printf "  %-24s %5.2f %% of one core\n", n, 100 * u / hz / s }'
  done
  awk -v u="$total" -v hz="$hz" -v s="$SECONDS_TO_RUN" 'BEGIN { printf "  %-24s %5.2f %% of one core\n", "all of the above", 100 * u / hz / s }'
  kill -INT $launch 2>/dev/null || true
  wait $launch 2>/dev/null || true
}
{
  echo "node CPU share over ${SECONDS_TO_RUN} s of the running cell, each way ($(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p')):"
  measure false
  measure true
} | tee /dev/stderr | /usr/bin/python3 "$ROOT/scripts/readme_block.py" "$ROOT/README.md" "bash scripts/measure_cell_cpu.sh"
