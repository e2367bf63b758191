#!/usr/bin/env bash
# Builds the package as its users do: a catkin workspace (build/ws, whose src/ links to this repository) built with
# catkin_make, with the build space in build/ and the devel space in build/devel. Also builds the tests and the
# benchmarks. The install space is build/install (scripts/test_install.sh installs into it and runs from it).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# catkin must see Debian's python3 (with catkin_pkg), not a pyenv/conda/venv one earlier on PATH.
export PATH="/usr/bin:/bin:$PATH"
WS="$ROOT/build/ws"
mkdir -p "$WS/src"
ln -sfn "$ROOT" "$WS/src/pneumatic_finger"
touch "$ROOT/build/CATKIN_IGNORE"  # rospack must not look for packages in the build folder itself
catkin_make -C "$WS" --build "$ROOT/build" -DCATKIN_DEVEL_PREFIX="$ROOT/build/devel" \
  -DCMAKE_INSTALL_PREFIX="$ROOT/build/install" -DCMAKE_BUILD_TYPE=Release \
  -DPYTHON_EXECUTABLE=/usr/bin/python3 -DPython3_EXECUTABLE=/usr/bin/python3 -Dpneumatic_finger_BENCHMARKS=ON \
  -j"$(nproc)" all tests >"$ROOT/build.log" 2>&1 || { tail -60 "$ROOT/build.log"; exit 1; }
echo "build: ok (catkin workspace build/ws; log in build.log)"
