#!/usr/bin/env bash
# Installs the Debian packages this package needs (the system dependencies declared in package.xml, by their
# Debian names; there is no rosdep index here). Does nothing when all are present. Needs root (or sudo) to install.
set -euo pipefail

PACKAGES=(
  # build: catkin, compiler, core library (package.xml: catkin, eigen, yaml-cpp)
  build-essential cmake catkin python3-catkin-pkg libeigen3-dev libyaml-cpp-dev
  # benchmarks (package.xml: benchmark, gsl)
  libbenchmark-dev libgsl-dev pkg-config
  # tests (package.xml: gtest; test_depend) and the docs' plots
  libgtest-dev googletest python3-matplotlib
  # lint (checked by scripts/test.sh)
  catkin-lint
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
