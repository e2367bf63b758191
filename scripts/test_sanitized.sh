#!/usr/bin/env bash
# The unit tests again under sanitizers, each in a build of its own inside build/ (which rosrun and rospack skip); any
# sanitizer report fails the test binary. Called by scripts/test.sh after scripts/setup.sh.
#  - AddressSanitizer and UndefinedBehaviorSanitizer: test_core and test_tools (the tools built likewise), in
#    build/sanitized/;
#  - ThreadSanitizer: test_concurrency (one model shared by threads, each with its own workspace; a calibration, whose
#    scan, local solves and folds run on every core), in build/tsan/.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
export PATH="/usr/bin:/bin:$PATH"
mkdir -p "$ROOT/build/test_results/sanitized"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
export TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1
status=0

# sanitize NAME "FLAGS" TEST: configures build/NAME with FLAGS, builds TEST and runs it into the test results.
sanitize() {
  local name=$1 flags=$2 test=$3 B="$ROOT/build/$1"
  mkdir -p "$B"
  touch "$B/CATKIN_IGNORE"
  cmake -S "$ROOT" -B "$B" -DCATKIN_DEVEL_PREFIX="$B/devel" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DPYTHON_EXECUTABLE=/usr/bin/python3 -DPython3_EXECUTABLE=/usr/bin/python3 \
    -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" -DCMAKE_SHARED_LINKER_FLAGS="$flags" \
    >"$ROOT/build/$name.log" 2>&1 || { cat "$ROOT/build/$name.log"; return 1; }
  make -C "$B" -j"$(nproc)" "$test" >>"$ROOT/build/$name.log" 2>&1 || { tail -50 "$ROOT/build/$name.log"; return 1; }
  # The sanitized libraries, not the main build's (a sourced devel space puts those on LD_LIBRARY_PATH first).
  LD_LIBRARY_PATH="$B/devel/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" "$B/devel/lib/pneumatic_finger/$test" \
    --gtest_output="xml:$ROOT/build/test_results/sanitized/gtest-${test}_$name.xml" >"$B/$test.log" 2>&1 \
    || { tail -40 "$B/$test.log"; return 1; }
  grep -E "^\[  (PASSED|FAILED) " "$B/$test.log" | sed "s/^/$name $test: /" || true
}

# test_no_allocation is left out: it replaces malloc, as the sanitizers do.
asan="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
sanitize sanitized "$asan" test_core || status=1
sanitize sanitized "$asan" test_tools || status=1  # the tools themselves, built with the sanitizers
sanitize tsan "-fsanitize=thread -fno-omit-frame-pointer" test_concurrency || status=1
exit $status
