#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Bad scenario files make `mirage run` fail with one line "mirage: error: FILE:LINE: KEY: ..." and
# exit status 2, that of bad input (README.md, STYLE.md Sec. 9).
# Usage: bad_input_test.sh MIRAGE_BINARY BAD_DIR
# Each BAD_DIR/*.yaml states what it expects in its header comments:
#   # expect: <text the message must contain, usually the key path>
#   # line: <n>      (optional: the message must contain "<file>:<n>:")
set -u

if [[ $# -ne 2 ]]; then
  echo "usage: $0 MIRAGE_BINARY BAD_DIR" >&2
  exit 2
fi
mirage=$1
bad_dir=$2
failures=0
cases=0
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# check NAME FILE EXPECT LINE: runs mirage on FILE and checks status and stderr.
check() {
  local name=$1 file=$2 expect=$3 line=$4
  local status
  cases=$((cases + 1))
  "$mirage" run "$file" --quiet >"$work/stdout" 2>"$work/stderr"
  status=$?
  local err
  err=$(cat "$work/stderr")
  local base
  base=$(basename "$file")
  local problem=""
  if [[ $status -ne 2 ]]; then
    problem="exit status $status, expected 2 (bad input)"
  elif [[ $(wc -l <"$work/stderr") -ne 1 ]]; then
    problem="stderr has $(wc -l <"$work/stderr") lines, expected 1"
  elif [[ $err != "mirage: error: "* ]]; then
    problem="stderr does not start with 'mirage: error:'"
  elif [[ $err != *"$base"* ]]; then
    problem="stderr does not name the file $base"
  elif [[ $err != *"$expect"* ]]; then
    problem="stderr does not contain '$expect'"
  elif [[ -n $line && $err != *"$base:$line:"* ]]; then
    problem="stderr does not contain '$base:$line:'"
  elif [[ -s $work/stdout ]]; then
    problem="--quiet printed to stdout"
  fi
  if [[ -n $problem ]]; then
    failures=$((failures + 1))
    echo "FAIL $name: $problem (exit $status)"
    echo "     stderr: $err"
  else
    echo "ok   $name (exit $status): $err"
  fi
}

shopt -s nullglob
files=("$bad_dir"/*.yaml)
if [[ ${#files[@]} -eq 0 ]]; then
  echo "FAIL: no bad scenario files in $bad_dir"
  exit 1
fi
for file in "${files[@]}"; do
  expect=$(sed -n 's/^# expect: //p' "$file" | head -n 1)
  line=$(sed -n 's/^# line: \([0-9][0-9]*\)$/\1/p' "$file" | head -n 1)
  if [[ -z $expect ]]; then
    failures=$((failures + 1))
    echo "FAIL $(basename "$file"): no '# expect:' comment"
    continue
  fi
  check "$(basename "$file" .yaml)" "$file" "$expect" "$line"
done

# A scenario file that does not exist.
check missing_file "$work/does_not_exist.yaml" "file not found" ""

echo "$((cases - failures)) of $cases bad-input cases passed"
[[ $failures -eq 0 ]] || exit 1
