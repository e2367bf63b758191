#!/usr/bin/env bash
# A long run of the pick-and-place cell, measured (scripts/soak_cell.py): memory and CPU of every process, latency,
# grasps and warnings per cycle, at the shortest cycle time the schedule accepts. Writes docs/SOAK.md and
# docs/soak.png. Exits non-zero when a cycle did not complete, a grasp missed or memory grew after warm-up.
# usage: bash scripts/soak_cell.sh CYCLES [OPTION...]   e.g. 1000 (about 45 minutes)
#        bash scripts/soak_cell.sh HOURSh [OPTION...]   e.g. 8h: as many cycles as that many hours hold (2.5 s each)
# OPTION: soak_cell.py's (--cycle-time S, --object-mass KG, --doc PAGE: default docs/SOAK.md), e.g.
#        bash scripts/soak_cell.sh 110 --cycle-time 4 --object-mass 0.01 --doc docs/SOAK_4S.md
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
arg=${1:?usage: soak_cell.sh CYCLES or HOURSh}
if [[ "$arg" =~ ^([0-9.]+)h$ ]]; then
  cycles=$(/usr/bin/python3 -c "print(max(1, int(float('${BASH_REMATCH[1]}') * 3600 / 2.5)))")
elif [[ "$arg" =~ ^[0-9]+$ ]]; then
  cycles=$arg
else
  echo "soak_cell: '$arg' is neither CYCLES (a whole number) nor HOURS (e.g. 8h)" >&2
  exit 2
fi
set +u
source "$ROOT/scripts/ros_env.sh"
set -u
shift
case " $* " in *" --doc "*) exec /usr/bin/python3 "$ROOT/scripts/soak_cell.py" "$cycles" "$@" ;; esac
exec /usr/bin/python3 "$ROOT/scripts/soak_cell.py" "$cycles" --doc "$ROOT/docs/SOAK.md" "$@"
