#!/usr/bin/env bash
# The cell's cost, side by side in one run: CPU share of every process (from /proc/<pid>/stat, user + system time)
# and the latency through the gripper (scripts/cell_latency.py), for three ways to run it:
#   nodes, finger_tf:=false    separate processes; robot_state_publisher publishes every frame (the default)
#   nodes, finger_tf:=true     separate processes; each finger_node broadcasts its own frames
#   nodelet, finger_tf:=false  the regulator and the three fingers as nodelets in one manager
# Each runs headless for SECONDS (default 24: two cycles). Writes the result into docs/CELL.md's generated block.
# usage: bash scripts/measure_cell.sh [SECONDS]
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
SECONDS_TO_RUN="${1:-24}"
source "$ROOT/scripts/ros_env.sh"
hz=$(getconf CLK_TCK)
ticks() { awk '{print $14 + $15}' "/proc/$1/stat" 2>/dev/null || echo 0; }
measure() {  # measure NODELET FINGER_TF
  local port
  port=$(/usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("localhost", 0)); print(s.getsockname()[1])')
  export ROS_MASTER_URI="http://localhost:$port"
  roslaunch --port "$port" pneumatic_finger pick_and_place_cell.launch rviz:=false nodelet:="$1" finger_tf:="$2" \
    >"$ROOT/build/measure_cell_$1_$2.log" 2>&1 &
  local launch=$!
  sleep 6  # start-up
  declare -A pid start
  for name in finger_node pressure_regulator cell_sequencer robot_state_publisher "nodelet manager"; do
    for p in $(pgrep -f "/$name( |$)" || true); do pid["${name// /_}/$p"]=$p; start["${name// /_}/$p"]=$(ticks "$p"); done
  done
  local latency
  latency=$(/usr/bin/python3 "$ROOT/scripts/cell_latency.py" "$SECONDS_TO_RUN" 2>/dev/null || echo "latency: failed")
  local total=0 used
  echo "$([ "$1" = true ] && echo "nodelet (one manager)" || echo "nodes (one process each)"), finger_tf:=$2"
  for key in $(printf '%s\n' "${!pid[@]}" | sort); do
    used=$(( $(ticks "${pid[$key]}") - ${start[$key]} ))
    total=$(( total + used ))
    awk -v n="${key%/*}" -v u="$used" -v hz="$hz" -v s="$SECONDS_TO_RUN" 'BEGIN { printf "  %-24s %5.2f %% of one core\n", n, 100 * u / hz / s }'
  done
  awk -v u="$total" -v hz="$hz" -v s="$SECONDS_TO_RUN" 'BEGIN { printf "  %-24s %5.2f %% of one core\n", "all of the above", 100 * u / hz / s }'
  echo "  regulator publish -> finger A joint_states at a subscriber: $latency"
  kill -INT $launch 2>/dev/null || true
  wait $launch 2>/dev/null || true
}
out="$ROOT/build/measure_cell.txt"
{
  echo "over ${SECONDS_TO_RUN} s of the running cell, each way ($(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p')):"
  measure false false
  measure false true
  measure true false
} >"$out"
# The verdicts, computed from the figures above (the totals and the p50 latencies), never typed by hand.
/usr/bin/python3 - "$out" >>"$out" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
parts = re.split(r"\n(?=nod)", text)[1:]
figures = {}
for part in parts:
    name = part.splitlines()[0]
    total = float(re.search(r"all of the above\s+([\d.]+)", part).group(1))
    p50 = re.search(r"p50 (\d+) us", part)
    figures[name] = (total, float(p50.group(1)) if p50 else float("nan"))
(a, (ca, la)), (b, (cb, lb)), (n, (cn, ln)) = figures.items()
print("verdicts (computed by the script from the lines above):")
print(f"  nodelet against separate nodes: CPU {cn:.2f} % against {ca:.2f} % ({'less' if cn < ca else 'more'}),"
      f" p50 latency {ln:.0f} us against {la:.0f} us ({'lower' if ln < la else 'higher'})")
print(f"  robot_state_publisher against the finger nodes publishing the frames: CPU {ca:.2f} % against {cb:.2f} %,"
      f" p50 latency {la:.0f} us against {lb:.0f} us")
PY
cat "$out" >&2
/usr/bin/python3 "$ROOT/scripts/measured_block.py" "$ROOT/docs/CELL.md" "bash scripts/measure_cell.sh" <"$out"
