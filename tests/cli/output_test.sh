#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The command line and its outputs: --version; every usage error exits 2; output paths are checked
# before the run; a failed write leaves the previous report intact and no temporary file behind;
# recorded inputs that are not regular files are refused at once; progress lines reach a
# non-terminal stderr and a closing line names the files written.
# Usage: output_test.sh MIRAGE_BINARY EXAMPLES_DIR WORK_DIR
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
ok() { echo "ok   $*"; }

# --version prints the name and version and exits 0.
if out=$("$mirage" --version) && [[ $out == "mirage "[0-9]* ]]; then ok "--version: $out"; else fail "--version: '$out'"; fi

# Every usage error exits 2 (CLI11 alone would give 104-114).
expect_usage_error() {
  local name=$1
  shift
  "$mirage" "$@" >"$work/usage.out" 2>"$work/usage.err"
  local status=$?
  if [[ $status -eq 2 && -s $work/usage.err ]]; then ok "usage error $name: exit 2"; else fail "usage error $name: exit $status"; fi
}
expect_usage_error "no subcommand"
expect_usage_error "no scenario" run
expect_usage_error "unknown option" run "$examples/seminar_room.yaml" --bogus
expect_usage_error "unknown subcommand" fly
expect_usage_error "runs not a number" run "$examples/seminar_room.yaml" --runs many
expect_usage_error "negative seed" run "$examples/seminar_room.yaml" --seed -1
expect_usage_error "seed not a number" run "$examples/seminar_room.yaml" --seed 1x
expect_usage_error "seed above 2^64 - 1" run "$examples/seminar_room.yaml" --seed 18446744073709551616
expect_usage_error "simulate without --out" simulate "$examples/seminar_room.yaml"
expect_usage_error "simulate negative seed" simulate "$examples/seminar_room.yaml" --out "$work/sim" --seed -3
if "$mirage" --help >/dev/null 2>&1; then ok "--help: exit 0"; else fail "--help: not exit 0"; fi

# Output paths are checked before the run: an unwritable --json fails at once, before any CSV.
start=$(date +%s%N)
"$mirage" run "$examples/seminar_room.yaml" --csv "$work/early_csv" --json /proc/mirage/report.json >/dev/null 2>"$work/early.err"
status=$?
elapsed_ms=$((($(date +%s%N) - start) / 1000000))
if [[ $status -eq 2 ]] && grep -q -- "--json /proc/mirage/report.json" "$work/early.err" && [[ ! -e $work/early_csv/tracks.csv ]] &&
  [[ $elapsed_ms -lt 5000 ]]; then
  ok "unwritable --json refused before the run (${elapsed_ms} ms)"
else
  fail "unwritable --json: exit $status after ${elapsed_ms} ms: $(cat "$work/early.err")"
fi
"$mirage" run "$examples/seminar_room.yaml" --csv "$examples/seminar_room.yaml" >/dev/null 2>"$work/csvfile.err"
status=$?
if [[ $status -eq 2 ]] && grep -q "not a directory" "$work/csvfile.err"; then ok "--csv naming a file refused"; else fail "--csv naming a file: exit $status"; fi

# A failed write leaves the previous report as it was and no temporary file: SIGXFSZ ignored,
# a 1 KiB file-size limit makes the report's write fail half-way (EFBIG).
"$mirage" run "$examples/seminar_room.yaml" --runs 1 --quiet --json "$work/atomic/report.json" || fail "first report"
cp "$work/atomic/report.json" "$work/atomic/previous.json"
(
  trap '' XFSZ
  ulimit -f 1
  exec "$mirage" run "$examples/seminar_room.yaml" --runs 2 --quiet --json "$work/atomic/report.json"
) 2>"$work/atomic.err"
status=$?
leftovers=$(find "$work/atomic" -name '*.tmp-*' | wc -l)
if [[ $status -eq 2 ]] && grep -q "report.json: write failed" "$work/atomic.err" &&
  cmp -s "$work/atomic/report.json" "$work/atomic/previous.json" && [[ $leftovers -eq 0 ]]; then
  ok "a failed write keeps the previous report and leaves no temporary file"
else
  fail "failed write: exit $status, leftovers $leftovers: $(cat "$work/atomic.err")"
fi

# Recorded inputs that are not regular files are refused (a link to /dev/zero once grew to 8 GB).
rec=$work/devzero
"$mirage" simulate "$examples/seminar_room_ranges.yaml" --out "$rec" --quiet || fail "simulate for the /dev/zero case"
rm -f "$rec/ranges.csv"
ln -s /dev/zero "$rec/ranges.csv"
timeout 20 "$mirage" run "$rec/scenario.yaml" --quiet 2>"$work/devzero.err"
status=$?
if [[ $status -eq 2 ]] && grep -q "ranges.csv: not a regular file" "$work/devzero.err"; then
  ok "ranges.csv linked to /dev/zero refused"
else
  fail "ranges.csv linked to /dev/zero: exit $status: $(head -c 300 "$work/devzero.err")"
fi

# Progress on a non-terminal stderr, and the closing line naming every file written.
"$mirage" run "$examples/seminar_room.yaml" --runs 1 --json "$work/p/report.json" --csv "$work/p/csv" \
  >/dev/null 2>"$work/progress.err"
# The jobs: per trajectory (2) the posterior bound and the one run.
if grep -q "^mirage: 4/4 jobs done" "$work/progress.err" &&
  grep -q "^mirage: wrote $work/p/report.json, $work/p/csv/tracks.csv, $work/p/csv/runs.csv" "$work/progress.err"; then
  ok "progress and closing lines on a non-terminal stderr"
else
  fail "progress / closing lines: $(cat "$work/progress.err")"
fi
# --quiet prints nothing at all on success.
"$mirage" run "$examples/seminar_room.yaml" --runs 1 --quiet --csv "$work/q" >"$work/quiet.out" 2>"$work/quiet.err"
if [[ ! -s $work/quiet.out && ! -s $work/quiet.err ]]; then ok "--quiet is silent"; else fail "--quiet printed something"; fi

echo "$failures failure(s)"
[[ $failures -eq 0 ]]
