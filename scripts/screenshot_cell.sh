#!/usr/bin/env bash
# Renders the pick-and-place cell in rviz under Xvfb mid-grasp (the gripper closed on the object, lifting it) to
# docs/cell_rviz.png.   usage: bash scripts/screenshot_cell.sh [OUTPUT.png] [PHASE] [RVIZ_CONFIG] [ARG:=VALUE...]
# (after scripts/build.sh; the last, the launch file's arguments). The close-up of the grasp: bash
# scripts/screenshot_cell.sh docs/grasp_closeup.png lift rviz/grasp_closeup.rviz; with MuJoCo's fingers beside the
# twin's: bash scripts/screenshot_cell.sh docs/cell_physics.png lift rviz/cell_physics_closeup.rviz physics:=mujoco
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
OUT="${1:-$ROOT/docs/cell_rviz.png}"
PHASE="${2:-lift}"
CONFIG="${3:-$ROOT/rviz/pick_and_place_cell.rviz}"
shift 3 2>/dev/null || shift $#
source "$ROOT/scripts/ros_env.sh"
source "$ROOT/scripts/headless.sh"  # Xvfb on $display; every pid in $pids is stopped on exit
DISPLAY="$display" roslaunch --port "$port" pneumatic_finger pick_and_place_cell.launch rviz:=true rviz_config:="$(realpath "$CONFIG")" "$@" \
  >"$ROOT/build/screenshot_cell.log" 2>&1 & pids+=($!)
sleep 8   # rviz start-up
# Wait for the phase in the next cycle (rviz has then drawn the whole scene at least once).
for _ in $(seq 1 120); do
  phase=$(timeout 2 rostopic echo -n 1 /cell/phase 2>/dev/null | sed -n 's/^data: "*\([^"]*\)"*$/\1/p' || true)
  [ "$phase" = "$PHASE" ] && break
  sleep 0.25
done
sleep 0.5
DISPLAY="$display" import -window root "$OUT"
echo "wrote $OUT (phase: ${phase:-unknown})"
