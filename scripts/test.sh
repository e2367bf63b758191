#!/usr/bin/env bash
# Every test: install what is missing, build (a catkin workspace), lint, run gtest/rostest, the sanitized unit tests
# and the install space, and exit non-zero on any failure.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
bash "$ROOT/scripts/setup.sh"
bash "$ROOT/scripts/build.sh"
export PATH="/usr/bin:/bin:$PATH"

echo "lint: catkin_lint"
# catkin_lint checks that the folder is named after the package; the clone's folder name is not ours to choose.
# The link lives outside the tree: inside it, rospack would crawl the package into itself.
lint_dir=$(mktemp -d)
ln -s "$ROOT" "$lint_dir/pneumatic_finger"
catkin_lint -W2 --strict "$lint_dir/pneumatic_finger"
rm -rf "$lint_dir"
echo "lint: layers (no ROS header in core, description, tools)"
/usr/bin/python3 "$ROOT/scripts/check_layers.py" --self-test
/usr/bin/python3 "$ROOT/scripts/check_layers.py" "$ROOT"
echo "lint: house rules (no function over 60 lines, no file over 500, in src/ and include/)"
/usr/bin/python3 "$ROOT/scripts/function_lengths.py" --top 3

# The benchmark in smoke mode: it must run and its numbers must be finite (timings are never tests).
"$ROOT/devel/lib/pneumatic_finger/finger_bench" --benchmark_min_time=0.002 --benchmark_format=json \
  >"$ROOT/build/bench_smoke.json" 2>/dev/null
/usr/bin/python3 "$ROOT/scripts/check_bench_smoke.py" "$ROOT/build/bench_smoke.json"
"$ROOT/devel/lib/pneumatic_finger/sim_bench" --benchmark_min_time=0.002 --benchmark_format=json \
  >"$ROOT/build/sim_bench_smoke.json" 2>/dev/null
/usr/bin/python3 "$ROOT/scripts/check_bench_smoke.py" --sim "$ROOT/build/sim_bench_smoke.json"

# Each run gets its own ROS master port and ROS_HOME under build/, so two runs never collide.
source "$ROOT/scripts/ros_env.sh"
rm -rf "$ROOT/build/test_results"
# `make run_tests` exits 0 even when tests fail: the verdict is catkin_test_results'.
make -C "$ROOT/build" run_tests >"$ROOT/build/run_tests.log" 2>&1 || true
grep -E "^\[  (FAILED|PASSED) |tests? from .* ran|FAILURE|ERROR" "$ROOT/build/run_tests.log" || true
# The unit tests again under AddressSanitizer and UndefinedBehaviorSanitizer (a second build); their results join
# the others in build/test_results.
sanitized_status=0
bash "$ROOT/scripts/test_sanitized.sh" || sanitized_status=1
# The package built as users build it, in a fresh catkin workspace (catkin_make), and its unit tests there.
workspace_status=0
bash "$ROOT/scripts/test_workspace.sh" || workspace_status=1
# The install space: make install into build/.install, then the tools and the node run from there alone.
install_status=0
bash "$ROOT/scripts/test_install.sh" || install_status=1

set +e
catkin_test_results "$ROOT/build/test_results" >/dev/null 2>&1
catkin_status=$?
/usr/bin/python3 "$ROOT/scripts/count_results.py" "$ROOT/build/test_results"
count_status=$?
set -e
for stage in catkin_status count_status sanitized_status install_status workspace_status; do
  [ "${!stage}" -eq 0 ] || echo "test: FAILED: ${stage%_status}"
done
[ $catkin_status -eq 0 ] && [ $count_status -eq 0 ] && [ $sanitized_status -eq 0 ] && [ $install_status -eq 0 ] && [ $workspace_status -eq 0 ]
