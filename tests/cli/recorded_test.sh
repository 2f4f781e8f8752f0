#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# `mirage simulate` and recorded input (issue 4): a run written by `mirage simulate` and read back
# by `mirage run DIR/scenario.yaml` gives exactly the track of the same simulated run (MINT on
# CIRs and SLAM on range-level draws); without truth.csv the report has no error block but still
# the trajectory and the map; bad recorded files stop the run with "FILE:LINE:" and exit 2.
# Acoustic stamps (issue 26 item 9): the replay of mics.csv/toa.csv gives every row of the
# simulated run's track (estimate, truth, error) bit for bit; bad stamp files exit 2 with FILE:LINE.
# UWB TDOA: the same for anchors.csv/tdoa.csv, and the filter starts itself without truth.csv.
# Usage: recorded_test.sh MIRAGE_BINARY EXAMPLES_DIR WORK_DIR
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

# same_track SCENARIO: simulate trajectory_1 run 0, replay it, compare with `mirage run --runs 1`.
same_track() {
  local scenario=$1 name
  name=$(basename "$scenario" .yaml)
  if ! "$mirage" simulate "$examples/$scenario" --out "$work/$name" --quiet; then
    fail "$name: mirage simulate failed"
    return
  fi
  "$mirage" run "$work/$name/scenario.yaml" --quiet --csv "$work/$name/replay" || fail "$name: replay failed"
  "$mirage" run "$examples/$scenario" --runs 1 --quiet --csv "$work/$name/direct" || fail "$name: direct run failed"
  # Columns 7, 8: x_est_m, y_est_m. The replay is one run named "recorded".
  if ! diff <(awk -F, 'NR > 1 { print $7, $8 }' "$work/$name/replay/tracks.csv") \
            <(awk -F, 'NR > 1 && $1 == "trajectory_1" { print $7, $8 }' "$work/$name/direct/tracks.csv") >/dev/null; then
    fail "$name: the replayed track differs from the simulated run's track"
  else
    echo "ok   $name: replay of the recording == simulated run ($(($(wc -l <"$work/$name/replay/tracks.csv") - 1)) steps)"
  fi
}
same_track seminar_room.yaml
same_track seminar_room_ranges.yaml

# SLAM on recorded ranges without truth: no error block, a trajectory and a map.
slam=$work/slam_no_truth
"$mirage" simulate "$examples/seminar_room_ranges.yaml" --out "$slam" --quiet
sed -i -e '/^  truth: truth.csv/d' "$slam/scenario.yaml"
printf '  start_m: [%s]\n' "$(awk -F, 'NR == 2 { print $2 ", " $3 }' "$slam/truth.csv")" >>"$slam/scenario.yaml"
# Another method's name replaces the recording's method: map (MINT's options) as a whole.
printf 'extends: scenario.yaml\nmethod: {name: slam}\n' >"$slam/slam.yaml"
if ! "$mirage" run "$slam/slam.yaml" --quiet --json "$slam/report.json" --csv "$slam/csv"; then
  fail "slam without truth: run failed"
elif ! python3 - "$slam/report.json" "$slam/csv" <<'PY'
import csv, json, sys
j = json.load(open(sys.argv[1]))
assert j["position_error_m"] is None, j["position_error_m"]
assert j["diverged_runs"] is None
assert j["recorded_data"]["truth"] is None
rows = list(csv.DictReader(open(sys.argv[2] + "/tracks.csv")))
assert len(rows) == j["steps"] > 100 and rows[0]["error_m"] == "" and rows[0]["x_est_m"] != ""
assert len(list(csv.DictReader(open(sys.argv[2] + "/map.csv")))) >= 2  # at least the two anchors
PY
then
  fail "slam without truth: report or CSV not as expected"
else
  echo "ok   slam without truth: no error block, track and map written"
fi

# bad NAME FILE SED_EXPR EXPECT: corrupt one file of a copy of the recording, expect FILE:LINE.
base=$work/seminar_room_ranges
bad() {
  local name=$1 file=$2 expr=$3 expect=$4 dir=$work/bad_$1 status err
  cp -r "$base" "$dir"
  sed -i "$expr" "$dir/$file"
  "$mirage" run "$dir/scenario.yaml" --quiet >"$dir/stdout" 2>"$dir/stderr"
  status=$?
  err=$(cat "$dir/stderr")
  if [[ $status -ne 2 ]]; then
    fail "$name: exit $status, expected 2 ($err)"
  elif [[ $(wc -l <"$dir/stderr") -ne 1 || $err != "mirage: error: "*"$expect"* ]]; then
    fail "$name: message '$err' lacks '$expect'"
  else
    echo "ok   $name: $err"
  fi
}
bad missing_field ranges.csv '5s/,[^,]*,[^,]*$//' "ranges.csv:5: expected 4 fields"
bad unknown_anchor ranges.csv '7s/,A[12],/,A9,/' "ranges.csv:7: anchor_id 'A9': unknown anchor"
bad time_backwards ranges.csv '40s/^[^,]*,/0,/' "ranges.csv:40: t_s '0': time goes backwards"
bad negative_range ranges.csv '9s/^\([^,]*,[^,]*\),/\1,-/' "ranges.csv:9: range_m '-"
bad nan_range ranges.csv '11s/^\([^,]*,[^,]*\),[^,]*,/\1,NaN,/' "ranges.csv:11: range_m 'NaN': must be finite"
bad anchor_outside anchors.csv '2s/.*/A1,9.5,7/' "anchors.csv: anchor 'A1' at [9.5, 7] m is outside"
bad truth_short truth.csv '100,$d' "truth.csv: covers t_s in"

# Acoustic stamps: simulate, replay, compare every column but the run's name (t_s, truth,
# estimate, covariance, error) with `mirage run --runs 1`.
acoustic_scenario=$(dirname "$0")/data/acoustic_short.yaml
acoustic=$work/acoustic_short
if ! "$mirage" simulate "$acoustic_scenario" --out "$acoustic" --quiet; then
  fail "acoustic: mirage simulate failed"
else
  "$mirage" run "$acoustic/scenario.yaml" --quiet --csv "$acoustic/replay" --json "$acoustic/replay.json" ||
    fail "acoustic: replay failed"
  "$mirage" run "$acoustic_scenario" --runs 1 --quiet --csv "$acoustic/direct" --json "$acoustic/direct.json" ||
    fail "acoustic: direct run failed"
  # The JSON has the errors in full precision, and the method's effective options (derived from
  # the physical keys the replay scenario states).
  python3 - "$acoustic/replay.json" "$acoustic/direct.json" <<'PY' || fail "acoustic: the replay's report differs"
import json, sys
replay, direct = (json.load(open(p)) for p in sys.argv[1:])
for key in ("position_error_m", "final_error_m", "steps", "acoustic"):
    assert replay[key] == direct[key], (key, replay[key], direct[key])
assert replay["recorded_data"]["toa"].endswith("toa.csv"), replay["recorded_data"]
PY
  # The posterior bound (peb_m) is the simulation's: a recording has none.
  peb=$(head -1 "$acoustic/direct/tracks.csv" | tr , '\n' | grep -n '^peb_m$' | cut -d: -f1)
  replay_rows=$(cut -d, --complement -f1,"$peb" "$acoustic/replay/tracks.csv" | tail -n +2)
  direct_rows=$(cut -d, --complement -f1,"$peb" "$acoustic/direct/tracks.csv" | tail -n +2)
  if [[ -z $replay_rows || $replay_rows != "$direct_rows" ]]; then
    fail "acoustic: the replayed track differs from the simulated run's track"
  elif [[ $(awk -F, 'NR > 1 && $NF != "" { n++ } END { print n + 0 }' "$acoustic/replay/tracks.csv") -eq 0 ]]; then
    fail "acoustic: the replay has no errors (truth missing)"
  else
    echo "ok   acoustic: replay of mics.csv/toa.csv == simulated run ($(wc -l <<<"$replay_rows") steps)"
  fi
fi
# The inertial input has no recorded form: refused, not dropped.
# The acoustic filter on the recording without truth starts itself (the fix over all stamps in the
# floor plan, confirmed by the next emission) and tracks: its positions stay within the plan.
if [[ -f $acoustic/scenario.yaml ]]; then
  mkdir -p "$work/acoustic_no_truth"
  cp "$acoustic"/mics.csv "$acoustic"/toa.csv "$work/acoustic_no_truth/"
  sed -e '/^  truth: truth.csv/d' "$acoustic/scenario.yaml" >"$work/acoustic_no_truth/scenario.yaml"
  if ! "$mirage" run "$work/acoustic_no_truth/scenario.yaml" --quiet --json "$work/acoustic_no_truth/report.json" \
    --csv "$work/acoustic_no_truth/csv"; then
    fail "acoustic without truth: run failed"
  elif ! python3 - "$work/acoustic_no_truth/report.json" "$work/acoustic_no_truth/csv" "$acoustic/truth.csv" <<'PY'
import csv, json, math, sys
j = json.load(open(sys.argv[1]))
assert j["position_error_m"] is None and j["recorded_data"]["truth"] is None
run = j["health"]["runs"][0]
assert run["started"] and run["epochs_before_start"] <= 3, run
assert run["steps_outside_plan"] == 0, run
# The track itself (not judged by the report) against the truth the run did not see.
truth = [(float(r["t_s"]), float(r["x_m"]), float(r["y_m"])) for r in csv.DictReader(open(sys.argv[3]))]
rows = list(csv.DictReader(open(sys.argv[2] + "/tracks.csv")))
errors = []
for r in rows:  # the truth sample of the same emission (tracks.csv rounds t_s to the millisecond)
    t, x, y = min(truth, key=lambda q: abs(q[0] - float(r["t_s"])))
    assert abs(t - float(r["t_s"])) < 0.002, (t, r["t_s"])
    errors.append(math.hypot(float(r["x_est_m"]) - x, float(r["y_est_m"]) - y))
assert len(errors) == len(rows) >= 35 and sorted(errors)[len(errors) // 2] < 0.05, (len(errors), sorted(errors)[len(errors) // 2])
PY
  then
    fail "acoustic without truth: did not start itself or track"
  else
    echo "ok   acoustic without truth: started itself and tracked"
  fi
fi

printf 'extends: %s\nmethod: {inertial: true}\n' "$(realpath "$acoustic_scenario")" >"$work/acoustic_inertial.yaml"
"$mirage" simulate "$work/acoustic_inertial.yaml" --out "$work/acoustic_inertial" --quiet 2>"$work/acoustic_inertial.err"
status=$?
if [[ $status -ne 2 || $(cat "$work/acoustic_inertial.err") != *"method.inertial: the inertial records have no recorded-data form"* ]]; then
  fail "acoustic inertial: exit $status, '$(cat "$work/acoustic_inertial.err")'"
elif [[ -e $work/acoustic_inertial/toa.csv ]]; then
  fail "acoustic inertial: refused but wrote toa.csv"
else
  echo "ok   acoustic inertial: $(cat "$work/acoustic_inertial.err")"
fi

base=$acoustic
bad mics_missing_z mics.csv '3s/,[^,]*$//' "mics.csv:3: expected 4 fields"
bad mics_duplicate mics.csv '3s/^M2,/M1,/' "mics.csv:3: receiver_id 'M1': duplicate microphone id"
bad toa_unknown_mic toa.csv '6s/,M[0-9],/,M9,/' "toa.csv:6: receiver_id 'M9': unknown microphone"
bad toa_backwards toa.csv '30s/^[^,]*,/0,/' "toa.csv:30: t_s '0': time goes backwards"
bad toa_not_a_number toa.csv '8s/,[^,]*$/,0.5s/' "toa.csv:8: toa_s '0.5s': not a number"
bad toa_nan toa.csv '9s/,[^,]*$/,nan/' "toa.csv:9: toa_s 'nan': must be finite"

# UWB TDOA (issue 26 item 9): simulate, replay tdoa.csv, compare every column but the run's name;
# the replay without truth starts itself; a grid that varies the measurements cannot be written.
tdoa_scenario=$(dirname "$0")/data/uwb_tdoa_short.yaml
tdoa=$work/uwb_tdoa_short
if ! "$mirage" simulate "$tdoa_scenario" --out "$tdoa" --quiet; then
  fail "tdoa: mirage simulate failed"
else
  "$mirage" run "$tdoa/scenario.yaml" --quiet --csv "$tdoa/replay" --json "$tdoa/replay.json" || fail "tdoa: replay failed"
  "$mirage" run "$tdoa_scenario" --quiet --csv "$tdoa/direct" --json "$tdoa/direct.json" || fail "tdoa: direct run failed"
  python3 - "$tdoa/replay.json" "$tdoa/direct.json" <<'PY' || fail "tdoa: the replay's report differs"
import json, sys
replay, direct = (json.load(open(p)) for p in sys.argv[1:])
for key in ("position_error_m", "final_error_m", "steps", "tdoa_ekf"):
    assert replay[key] == direct[key], (key, replay[key], direct[key])
assert replay["recorded_data"]["tdoa"].endswith("tdoa.csv"), replay["recorded_data"]
PY
  replay_rows=$(cut -d, -f2- "$tdoa/replay/tracks.csv" | tail -n +2)
  direct_rows=$(cut -d, -f2- "$tdoa/direct/tracks.csv" | tail -n +2)
  if [[ -z $replay_rows || $replay_rows != "$direct_rows" ]]; then
    fail "tdoa: the replayed track differs from the simulated run's track"
  else
    echo "ok   tdoa: replay of anchors.csv/tdoa.csv == simulated run ($(wc -l <<<"$replay_rows") steps)"
  fi
  grep -v '^  truth:' "$tdoa/scenario.yaml" >"$tdoa/no_truth.yaml"
  if ! "$mirage" run "$tdoa/no_truth.yaml" --quiet --csv "$tdoa/no_truth"; then
    fail "tdoa without truth: run failed"
  elif ! python3 - "$tdoa/no_truth/tracks.csv" "$tdoa/replay/tracks.csv" <<'PY'
import csv, math, statistics, sys
own = {r["t_s"]: r for r in csv.DictReader(open(sys.argv[1]))}
truth = [r for r in csv.DictReader(open(sys.argv[2])) if r["t_s"] in own]
assert len(truth) > 1000, len(truth)
errors = [math.dist([float(own[r["t_s"]][k]) for k in ("x_est_m", "y_est_m", "z_est_m")],
                    [float(r[k]) for k in ("x_true_m", "y_true_m", "z_true_m")]) for r in truth]
# Self-started, then as good as the run started at the truth: 0.15 m noise, NLOS behind the box.
assert statistics.median(errors) < 0.5, statistics.median(errors)
PY
  then
    fail "tdoa without truth: the self-started track is not near the truth"
  else
    echo "ok   tdoa without truth: started itself from the first differences and tracked the truth"
  fi
fi
printf 'extends: %s\ngrid:\n  - {measurements.sigma_m: [0.1, 0.2]}\n' "$(realpath "$tdoa_scenario")" >"$work/tdoa_grid.yaml"
"$mirage" simulate "$work/tdoa_grid.yaml" --out "$work/tdoa_grid" --quiet 2>"$work/tdoa_grid.err"
status=$?
if [[ $status -ne 2 || $(cat "$work/tdoa_grid.err") != *"the grid varies measurements.sigma_m"* ]]; then
  fail "tdoa grid: exit $status, '$(cat "$work/tdoa_grid.err")'"
else
  echo "ok   tdoa grid: $(cat "$work/tdoa_grid.err")"
fi

base=$tdoa
bad tdoa_unknown_anchor tdoa.csv '6s/,A[0-7],/,A9,/' "tdoa.csv:6: id_i 'A9': unknown anchor"
bad tdoa_backwards tdoa.csv '30s/^[^,]*,/0,/' "tdoa.csv:30: t_s '0': time goes backwards"
bad tdoa_nan tdoa.csv '9s/,[^,]*$/,nan/' "tdoa.csv:9: tdoa_m 'nan': must be finite"
bad tdoa_anchor_without_z anchors.csv '3s/,[^,]*$//' "anchors.csv:3: expected 4 fields"

[[ $failures -eq 0 ]] || exit 1
echo "all recorded-data cases passed"
