# Sourced by the scripts that start ROS nodes: Debian's python first on PATH, the package's devel space, and a ROS
# master on a free port of its own with ROS_HOME under build/, so that two runs never share a master.
# Sets ROOT (the repository) and ROS_PORT.
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PATH="/usr/bin:/bin:$PATH"
set +u  # catkin's setup scripts read unset variables
# shellcheck disable=SC1091
source "$ROOT/devel/setup.bash"
set -u
ROS_PORT=$(/usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("localhost", 0)); print(s.getsockname()[1])')
export ROS_HOSTNAME=localhost ROS_MASTER_URI="http://localhost:$ROS_PORT" ROS_HOME="$ROOT/build/ros_home"
