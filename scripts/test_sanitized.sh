#!/usr/bin/env bash
# The unit tests again, built with AddressSanitizer and UndefinedBehaviorSanitizer (a second build in
# build/sanitized/); any sanitizer report fails the test binary. Called by scripts/test.sh after scripts/setup.sh.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
B="$ROOT/build/sanitized"  # inside build/, which rosrun and rospack skip
export PATH="/usr/bin:/bin:$PATH"
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
mkdir -p "$B"
touch "$B/CATKIN_IGNORE"
cmake -S "$ROOT" -B "$B" -DCATKIN_DEVEL_PREFIX="$B/devel" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DPYTHON_EXECUTABLE=/usr/bin/python3 -DPython3_EXECUTABLE=/usr/bin/python3 \
  -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" -DCMAKE_SHARED_LINKER_FLAGS="$flags" \
  >"$ROOT/build/sanitized.log" 2>&1 || { cat "$ROOT/build/sanitized.log"; exit 1; }
make -C "$B" -j"$(nproc)" test_core >>"$ROOT/build/sanitized.log" 2>&1 \
  || { tail -50 "$ROOT/build/sanitized.log"; exit 1; }
mkdir -p "$ROOT/build/test_results/sanitized"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
# The sanitized libraries, not the main build's (a sourced devel space puts those on LD_LIBRARY_PATH first).
export LD_LIBRARY_PATH="$B/devel/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
status=0
# test_no_allocation is left out: it replaces malloc, as the sanitizers do.
for t in test_core; do
  "$B/devel/lib/pneumatic_finger/$t" --gtest_output="xml:$ROOT/build/test_results/sanitized/gtest-${t}_sanitized.xml" \
    >"$B/$t.log" 2>&1 || { status=1; tail -40 "$B/$t.log"; }
  grep -E "^\[  (PASSED|FAILED) " "$B/$t.log" | sed "s/^/sanitized $t: /" || true
done
exit $status
