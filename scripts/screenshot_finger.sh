#!/usr/bin/env bash
# Renders one finger in rviz under Xvfb, bent by a published pressure, to OUTPUT.png (default build/finger_rviz.png;
# docs/finger_rviz.png, the README's picture, is this script's output at 196133 Pa: pass it to regenerate that).
# usage: bash scripts/screenshot_finger.sh [GAUGE_PA] [OUTPUT.png]     (after scripts/build.sh)
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
GAUGE="${1:-196133}"
OUT="${2:-$ROOT/build/finger_rviz.png}"
source "$ROOT/scripts/ros_env.sh"
source "$ROOT/scripts/headless.sh"  # Xvfb on $display; every pid in $pids is stopped on exit
DISPLAY="$display" roslaunch --port "$port" pneumatic_finger finger.launch rviz:=true >"$ROOT/build/screenshot.log" 2>&1 & pids+=($!)
sleep 6
absolute=$(/usr/bin/python3 -c "print($GAUGE + 101325)")
rostopic pub -r 5 /pressure sensor_msgs/FluidPressure "{header: {stamp: now}, fluid_pressure: $absolute}" >/dev/null 2>&1 & pids+=($!)
sleep 12
DISPLAY="$display" import -window root "$OUT"
echo "wrote $OUT (gauge $GAUGE Pa)"
