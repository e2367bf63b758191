#!/usr/bin/env bash
# finger_bench side by side: the working tree's build against another commit's, in one run, rounds interleaved (this
# VM's speed drifts, so a figure is only comparable to one measured beside it). Builds REV in a scratch clone.
# usage: bash scripts/bench_compare.sh REV [ROUNDS] [FILTER]
#   prints, per round and per benchmark, REV's and this tree's real time (ns), then the medians
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
rev=${1:?usage: bench_compare.sh REV [ROUNDS] [FILTER]}
rounds=${2:-3}
filter=${3:-'^(robust/validated|table/validated|batch/avx512|contact/1)$'}
export PATH="/usr/bin:/bin:$PATH"
# Outside the package: roslaunch and rostest search the package directory for launch and test files, and would find
# the clone's copies too.
base="${TMPDIR:-/tmp}/pneumatic_finger_bench_compare/$(git -C "$ROOT" rev-parse --short "$rev")"
if [ ! -x "$base/devel/lib/pneumatic_finger/finger_bench" ]; then
  rm -rf "$base" && git clone -q "$ROOT" "$base" && git -C "$base" checkout -q "$rev"
  bash "$base/scripts/build.sh" >/dev/null
fi
# JSON, not CSV: Google Benchmark's CSV reporter aborts when the benchmarks of one run have different counters
# (membrane/volume beside robust/validated).
run() {
  "$1" --benchmark_filter="$filter" --benchmark_min_time=0.3 --benchmark_format=json 2>/dev/null |
    python3 -c 'import json, sys
for b in json.load(sys.stdin)["benchmarks"]:
    print(sys.argv[2], sys.argv[1], b["name"], "%.1f" % b["real_time"])' "$2" "$3"
}
{
  for round in $(seq "$rounds"); do
    run "$base/devel/lib/pneumatic_finger/finger_bench" "$rev" "$round"
    run "$ROOT/devel/lib/pneumatic_finger/finger_bench" "tree" "$round"
  done
} | tee /dev/stderr | python3 -c '
import collections, statistics, sys
times = collections.defaultdict(list)
for line in sys.stdin:
    _, who, name, ns = line.split()
    times[(name, who)].append(float(ns))
names = sorted({n for n, _ in times})
whos = sorted({w for _, w in times}, key=lambda w: w == "tree")
print("median ns:", " | ".join(whos))
for n in names:
    print(f"{n}: " + " | ".join(f"{statistics.median(times[(n, w)]):.1f}" for w in whos))
'
