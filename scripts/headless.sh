# Sourced (after scripts/ros_env.sh) by the scripts that render rviz without a screen: starts Xvfb on a display
# derived from this ROS port (so that parallel runs do not collide), and on exit stops every process whose pid the
# script appended to `pids`.
port=$ROS_PORT
display=":$((port % 400 + 100))"
pids=()
cleanup() { for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done; wait 2>/dev/null || true; }
trap cleanup EXIT
Xvfb "$display" -screen 0 1200x800x24 -nolisten tcp >/dev/null 2>&1 & pids+=($!)
