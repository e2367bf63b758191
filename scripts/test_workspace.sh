#!/usr/bin/env bash
# The package as users build it: a fresh catkin workspace in a temporary folder, with a copy of the repository's
# tracked files under src/pneumatic_finger, built with catkin_make (libraries, nodes, tools, tests), then its unit
# tests run from the workspace's devel space. Writes its JUnit results under build/test_results/workspace/.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
export PATH="/usr/bin:/bin:$PATH"
WS=$(mktemp -d)
trap 'rm -rf "$WS"' EXIT
mkdir -p "$WS/src/pneumatic_finger"
# The repository's files as a clone has them plus any new file not ignored (never build/).
(cd "$ROOT" && git ls-files -z --cached --others --exclude-standard | xargs -0 cp --parents -t "$WS/src/pneumatic_finger")
catkin_make -C "$WS" -DPYTHON_EXECUTABLE=/usr/bin/python3 -DPython3_EXECUTABLE=/usr/bin/python3 -j"$(nproc)" \
  all tests >"$ROOT/build/workspace.log" 2>&1 || { tail -40 "$ROOT/build/workspace.log"; exit 1; }
mkdir -p "$ROOT/build/test_results/workspace"
status=0
for t in test_core test_tools test_concurrency test_no_allocation; do
  "$WS/devel/lib/pneumatic_finger/$t" --gtest_output="xml:$ROOT/build/test_results/workspace/gtest-${t}_workspace.xml" \
    >"$ROOT/build/workspace_$t.log" 2>&1 || { status=1; tail -30 "$ROOT/build/workspace_$t.log"; }
  grep -E "^\[  (PASSED|FAILED) " "$ROOT/build/workspace_$t.log" | sed "s/^/catkin workspace $t: /" || true
done
exit $status
