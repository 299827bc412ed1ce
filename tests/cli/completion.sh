#!/usr/bin/env bash
# Checks the bash completion the build wrote, by calling its function as
# bash does on TAB: COMP_WORDS and COMP_CWORD set, COMPREPLY read.
#   completion.sh MPCAL COMPLETION_SCRIPT
set -u
mpcal=$1
# shellcheck source=/dev/null
source "$2"
fail=0

# The candidates for the words given, the last being the one completed,
# sorted, on one line.
candidates() {
  COMP_WORDS=("$@")
  COMP_CWORD=$((${#COMP_WORDS[@]} - 1))
  COMPREPLY=()
  _mpcal
  printf '%s\n' "${COMPREPLY[@]}" | sed '/^$/d' | sort | tr '\n' ' ' | sed 's/ $//'
}
expect() {
  local want=$1; shift
  local got
  got=$(candidates "$@")
  if [ "$got" != "$want" ]; then
    echo "FAIL: '$*<TAB>' gave '$got', expected '$want'"; fail=1
  fi
}

expect "calibrate" mpcal cal
expect "--units" mpcal calibrate --un
expect "counts g mps2" mpcal calibrate --units ""
expect "counts g mps2" mpcal calibrate --units =
expect "g" mpcal calibrate --units = g
expect "bias-scale-6 shin-el-sheimy-9" mpcal calibrate session.csv --units g --model ""
expect "--model" mpcal calibrate --units=g --mod
expect "--model" mpcal calibrate --units = g --mod
expect "" mpcal calibrate --gravity ""
expect "static" mpcal simulate st
expect "--truth" mpcal simulate static --tru
expect "--json" mpcal noise still.csv --js

# Every subcommand --help lists, in the same set.
want=$("$mpcal" --help | awk '/^Subcommands:/ {s = 1; next} s && /^  [a-z]/ {print $1}' | sort | tr '\n' ' ' | sed 's/ $//')
expect "$want" mpcal ""
# Every flag of calibrate's --help option column.
want=$("$mpcal" calibrate --help | grep -E '^  +-' | awk '{print $1}' | tr ',' '\n' | sort -u | tr '\n' ' ' | sed 's/ $//')
expect "$want" mpcal calibrate -

# File names after a path flag and for the input.
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
touch "$scratch/session.csv" "$scratch/settings.json"
cd "$scratch" || exit 2
expect "session.csv settings.json" mpcal calibrate -o ""
expect "session.csv" mpcal calibrate ses
expect "settings.json" mpcal calibrate session.csv --gyro-log set
[ $fail -eq 0 ] && echo "completion checked"
exit $fail
