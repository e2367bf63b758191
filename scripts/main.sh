#!/usr/bin/env bash
# The main job: install what is missing, build, and run the pick-and-place cell (three soft fingers on an arm).
# With a display, rviz shows it; without one, the cell runs headless and its log says what happens.
# usage: bash scripts/main.sh [LOOPS [ARG:=VALUE...]]   (LOOPS pick-and-place cycles, default 3; 0 runs until Ctrl-C;
#        then any of the launch file's arguments, e.g. physics:=mujoco: MuJoCo moves the part, docs/SIMULATION.md)
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
LOOPS="${1:-3}"
shift || true
bash "$ROOT/scripts/setup.sh"
bash "$ROOT/scripts/build.sh"
source "$ROOT/scripts/ros_env.sh"
port=$ROS_PORT
if [ -n "${DISPLAY:-}" ]; then
  rviz=true
  echo "main: starting the cell with rviz on $DISPLAY ($LOOPS cycles of 12 s)"
else
  rviz=false
  cat <<MSG
main: no display: running the cell headless ($LOOPS cycles of 12 s); the log below shows each phase.
      To watch it, run this command on a machine with a display (rviz opens), or render a picture of it
      mid-grasp with:  bash scripts/screenshot_cell.sh /tmp/cell.png   (Xvfb; with no argument it rewrites the
      README's picture, docs/cell_rviz.png)
      While it runs, from another shell:  source devel/setup.bash && ROS_MASTER_URI=$ROS_MASTER_URI \\
        rostopic echo /finger_a/finger_state/tip_angle_rad
MSG
fi
exec roslaunch --port "$port" pneumatic_finger pick_and_place_cell.launch rviz:="$rviz" loop_count:="$LOOPS" "$@"
