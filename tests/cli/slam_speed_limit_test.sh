#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The SLAM tracker's walker speed limit (method.max_speed_mps) on the run that needed it: seminar
# room, seed 30, trajectory 2, run 19, replayed from `mirage simulate`. The track-loss recovery
# restarts that track 1 m off at step 164 (pillar's shadow). With the limit the track stays within
# the recovery's reach (max_jump_m, 3 m) and is restarted right (not diverged); without it, it
# takes clutter at up to 3.5 m/s and ends 19.6 m off (diverged), which this test also checks, so
# that it notices when the run stops exercising the limit.
# Usage: slam_speed_limit_test.sh MIRAGE_BINARY EXAMPLES_DIR WORK_DIR
set -u

if [[ $# -ne 3 ]]; then
  echo "usage: $0 MIRAGE_BINARY EXAMPLES_DIR WORK_DIR" >&2
  exit 2
fi
mirage=$1
examples=$2
work=$3
rm -rf "$work"
mkdir -p "$work"
failures=0
fail() {
  failures=$((failures + 1))
  echo "FAIL $*"
}

if ! "$mirage" simulate "$examples/seminar_room_slam.yaml" --seed 30 --trajectory trajectory_2 --run 19 \
    --out "$work/run" --quiet; then
  echo "FAIL mirage simulate failed"
  exit 1
fi
printf 'extends: scenario.yaml\nmethod: {max_speed_mps: 0}\n' >"$work/run/no_limit.yaml"

# json_number FILE KEY: the first value of "KEY": in the report (the trajectory's, as it has one).
json_number() {
  grep -o "\"$2\": *[-0-9.e+]*" "$1" | head -1 | sed 's/.*: *//'
}

"$mirage" run "$work/run/scenario.yaml" --quiet --json "$work/limit.json" || fail "run with the limit failed"
"$mirage" run "$work/run/no_limit.yaml" --quiet --json "$work/no_limit.json" || fail "run without the limit failed"

diverged=$(json_number "$work/limit.json" diverged_runs)
max_m=$(json_number "$work/limit.json" max)
if [[ "$diverged" == 0 ]] && awk -v m="$max_m" 'BEGIN { exit !(m < 3.0) }'; then
  echo "ok   with the speed limit: not diverged, max error $max_m m (< 3 m, the recovery's reach)"
else
  fail "with the speed limit: diverged_runs $diverged, max error $max_m m (expected 0 and < 3 m)"
fi

diverged=$(json_number "$work/no_limit.json" diverged_runs)
max_m=$(json_number "$work/no_limit.json" max)
if [[ "$diverged" == 1 ]]; then
  echo "ok   without it (max_speed_mps: 0) the run diverges (max error $max_m m), so it exercises the limit"
else
  fail "without the speed limit the run no longer diverges (diverged_runs $diverged, max error $max_m m):" \
       "it no longer exercises the limit; pick another run"
fi

if [[ $failures -gt 0 ]]; then
  echo "$failures failure(s)"
  exit 1
fi
