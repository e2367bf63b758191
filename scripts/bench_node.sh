#!/usr/bin/env bash
# The node benchmark: finger_node at RATE Hz of pressure messages, side by side with robot_state_publisher fed joint
# states for the same chain at the same rate; latency (p50, p99, max) and CPU share, as Markdown tables.
# usage: bash scripts/bench_node.sh [RATE_HZ] [SECONDS]     (after scripts/build.sh; defaults 1000 Hz, 10 s)
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
RATE="${1:-1000}"
SECS="${2:-10}"
source "$ROOT/scripts/ros_env.sh"
port=$ROS_PORT
urdf="$ROOT/build/bench_rsp.urdf"
"$ROOT/devel/lib/pneumatic_finger/finger_urdf" --prefix rsp_ --parent rsp_mount -o "$urdf"
roslaunch --port "$port" "$ROOT/bench/node_bench.launch" rsp_urdf:="$urdf" >"$ROOT/build/bench_node.log" 2>&1 &
launch=$!
trap 'kill $launch 2>/dev/null; wait 2>/dev/null' EXIT
for _ in $(seq 1 100); do
  finger_pid=$(pgrep -f "finger_node __name:=bench_finger_node" | head -1 || true)
  rsp_pid=$(pgrep -f "robot_state_publisher __name:=robot_state_publisher" | head -1 || true)
  [ -n "$finger_pid" ] && [ -n "$rsp_pid" ] && break
  sleep 0.1
done
sleep 2
"$ROOT/devel/lib/pneumatic_finger/node_bench" _rate_hz:="$RATE" _seconds:="$SECS" \
  _finger_pid:="${finger_pid:-0}" _rsp_pid:="${rsp_pid:-0}" _config:="$ROOT/config/finger.yaml"
echo "(machine: $(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p'), $(grep -m1 MHz /proc/cpuinfo | sed 's/.*: //') MHz)"
