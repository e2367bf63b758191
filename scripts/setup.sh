#!/usr/bin/env bash
# Installs the Debian packages this package needs (the system dependencies declared in package.xml, by their
# Debian names; there is no rosdep index here). Does nothing when all are present. Needs root (or sudo) to install.
set -euo pipefail

# Extra packages can be asked for by name (scripts/fuzz.sh asks for clang): bash scripts/setup.sh [PACKAGE]...
PACKAGES=("$@"

  # build: catkin, compiler, core library (package.xml: catkin, eigen, yaml-cpp)
  build-essential cmake catkin python3-catkin-pkg libeigen3-dev libyaml-cpp-dev
  # the ROS node (package.xml: roscpp, message_generation/runtime, std/sensor/geometry/diagnostic msgs,
  # diagnostic_updater, tf2, tf2_ros, tf2_msgs, urdfdom) and its tools (rostest, roslaunch, check_urdf, rviz)
  libroscpp-dev ros-message-generation ros-message-runtime libstd-msgs-dev ros-std-msgs python3-std-msgs
  libsensor-msgs-dev ros-sensor-msgs python3-sensor-msgs libgeometry-msgs-dev ros-geometry-msgs
  python3-geometry-msgs libdiagnostic-msgs-dev ros-diagnostic-msgs python3-diagnostic-msgs
  libdiagnostic-updater-dev libtf2-dev libtf2-msgs-dev ros-tf2-msgs python3-tf2-msgs libtf2-ros-dev python3-tf2-ros
  liburdfdom-dev liburdfdom-tools librostest-dev python3-rostest python3-roslaunch python3-rosmaster
  python3-rostopic python3-rosnode python3-rosparam python3-rosservice rosbash ros-robot-state-publisher
  python3-rosbag
  libvisualization-msgs-dev ros-visualization-msgs python3-visualization-msgs rviz xvfb imagemagick
  # the tools' argument parser (package.xml: cli11)
  libcli11-dev
  # the calibration room's solver (package.xml: libceres-dev)
  libceres-dev
  # its minimax solver (package.xml: libnlopt-cxx-dev)
  libnlopt-cxx-dev
  # the cell sequencer's forward kinematics (package.xml: kdl_parser)
  libkdl-parser-dev liborocos-kdl-dev
  # nodelets (package.xml: nodelet, pluginlib)
  libnodeletlib-dev libnodelet-dev libnodeletlib-tools pluginlib-dev
  # live parameters (package.xml: dynamic_reconfigure)
  libdynamic-reconfigure-config-init-mutex-dev python3-dynamic-reconfigure
  # the grasp: the object message, the gripper action, the drag handle, and the tests' independent 3D geometry
  # (package.xml: shape_msgs, actionlib, actionlib_msgs, interactive_markers; test_depend geometric_shapes)
  libshape-msgs-dev ros-shape-msgs python3-shape-msgs libactionlib-dev libactionlib-msgs-dev ros-actionlib-msgs
  python3-actionlib-msgs python3-actionlib libgeometric-shapes-dev libinteractive-markers-dev
  # the Python API (package.xml: pybind11-dev, python3-numpy, python3-rospkg; test_depend python3-pytest)
  pybind11-dev python3-dev python3-numpy python3-rospkg python3-pytest
  # benchmarks (package.xml: benchmark, gsl)
  libbenchmark-dev libgsl-dev pkg-config
  # tests (package.xml: gtest; test_depend) and the docs' plots
  libgtest-dev googletest python3-matplotlib
  # the simulator that checks the descriptions (package.xml: test_depend libmujoco-dev), and its viewer and tools
  # (mujoco-simulate, mujoco-compile, mujoco-testspeed), which docs/SIMULATION.md uses
  libmujoco-dev libmujoco-samples
  # lint (checked by scripts/test.sh): catkin_lint, and Universal Ctags for the function lengths
  catkin-lint universal-ctags
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} Debian packages present"
  exit 0
fi
echo "setup: installing ${#missing[@]} Debian packages: ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup: error: not root and no sudo; run as root" >&2; exit 1; }
  SUDO="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
