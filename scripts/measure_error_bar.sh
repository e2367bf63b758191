#!/usr/bin/env bash
# The error bar's coverage, as the test ErrorBarCoverage checks it: for each objective and input, the spread of
# (fitted - truth) / stated sd over 100 noise seeds (it must lie between 0.8 and 1.25), into docs/CALIBRATE.md's
# measured block ("How sure is the fit?"). The seeds are fixed: every run prints the same spreads.
# usage: bash scripts/measure_error_bar.sh     (after scripts/build.sh and make tests)
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
cd "$ROOT"
"$ROOT/devel/lib/pneumatic_finger/test_core" --gtest_filter='ErrorBarCoverage*' | grep spread |
  python3 scripts/measured_block.py docs/CALIBRATE.md "bash scripts/measure_error_bar.sh"
