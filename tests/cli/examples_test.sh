#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Every example runs as-is (briefly: one run per trajectory, or per variant of a coop grid) and writes its outputs (STYLE.md
# Sec. 8): exit 0, a JSON report with position_error_m, CSV files and a non-empty picture.
# Usage: examples_test.sh MIRAGE_BINARY EXAMPLES_DIR OUTPUT_DIR
set -u

if [[ $# -ne 3 ]]; then
  echo "usage: $0 MIRAGE_BINARY EXAMPLES_DIR OUTPUT_DIR" >&2
  exit 2
fi
mirage=$1
examples=$2
out=$3
mkdir -p "$out"
failures=0
count=0

shopt -s nullglob
files=("$examples"/*.yaml "$examples"/*/scenario.yaml)  # */scenario.yaml: recordings
if [[ ${#files[@]} -eq 0 ]]; then
  echo "FAIL: no examples in $examples"
  exit 1
fi
for file in "${files[@]}"; do
  name=$(basename "$file" .yaml)
  [[ $name == scenario ]] && name=$(basename "$(dirname "$file")")
  count=$((count + 1))
  rm -rf "$out/$name.json" "$out/${name}_csv" "$out/$name.png" "$out/$name.png.json"
  start=$(date +%s.%N)
  "$mirage" run "$file" --runs 1 --json "$out/$name.json" --csv "$out/${name}_csv" --plot "$out/$name.png" \
    >"$out/$name.stdout" 2>"$out/$name.stderr"
  status=$?
  seconds=$(awk -v s="$start" -v e="$(date +%s.%N)" 'BEGIN { printf "%.1f", e - s }')
  problem=""
  if [[ $status -ne 0 ]]; then
    problem="exit status $status: $(head -c 500 "$out/$name.stderr")"
  elif ! grep -q '"position_error_m"' "$out/$name.json" 2>/dev/null; then
    problem="$out/$name.json has no position_error_m"
  elif [[ ! -s $out/${name}_csv/tracks.csv || ! -s $out/${name}_csv/runs.csv ]]; then
    problem="the CSV files (tracks.csv, runs.csv) are missing in $out/${name}_csv"
  elif grep -q '^grid:' "$file" &&
    [[ ! -s $out/${name}_csv/variants.csv || ! -s $out/${name}_csv/error_by_step.csv ]]; then
    problem="a grid's CSV files (variants.csv, error_by_step.csv) are missing in $out/${name}_csv"
  elif [[ ! -s $out/$name.png ]]; then
    problem="$out/$name.png is missing or empty"
  fi
  if [[ -n $problem ]]; then
    failures=$((failures + 1))
    echo "FAIL $name: $problem"
  else
    echo "ok   $name (${seconds} s)"
  fi
done

echo "$((count - failures)) of $count examples passed"
[[ $failures -eq 0 ]] || exit 1
