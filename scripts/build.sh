#!/usr/bin/env bash
# Configures and builds the package (its tests and benchmarks too) into build/, devel space devel/ (outside build/:
# rosrun ignores every executable under a package's build/ folder), install
# space build/.install (a dot folder: roslaunch and rosrun search the package folder, but skip dot folders).
# scripts/test_workspace.sh also builds it the way users do, in a catkin workspace.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# catkin must see Debian's python3 (with catkin_pkg), not a pyenv/conda/venv one earlier on PATH.
export PATH="/usr/bin:/bin:$PATH"
cmake -S "$ROOT" -B "$ROOT/build" -DCATKIN_DEVEL_PREFIX="$ROOT/devel" \
  -DCMAKE_INSTALL_PREFIX="$ROOT/build/.install" -Dpneumatic_finger_BENCHMARKS=ON \
  -DPYTHON_EXECUTABLE=/usr/bin/python3 -DPython3_EXECUTABLE=/usr/bin/python3 >"$ROOT/build.log" 2>&1 \
  || { cat "$ROOT/build.log"; exit 1; }
touch "$ROOT/build/CATKIN_IGNORE" "$ROOT/devel/CATKIN_IGNORE"  # rospack and catkin_lint must not look in build/ or devel/
make -C "$ROOT/build" -j"$(nproc)" all tests >>"$ROOT/build.log" 2>&1 || { tail -50 "$ROOT/build.log"; exit 1; }
echo "build: ok (log in build.log)"
