#!/usr/bin/env bash
# Runs one mpcal command line and checks how it ended.
#   expect.sh EXIT REGEX [--absent PATH]... [--workdir DIR] -- COMMAND ARGS...
# Passes when COMMAND exits with EXIT, its stdout+stderr match the extended
# regular expression REGEX, and no --absent PATH exists afterwards (an output
# file that must not be left behind). For errors it also checks the contract:
# exactly one line on stderr, starting "mpcal: error: ".
set -u
expected_exit=$1; regex=$2; shift 2
absent=(); workdir=""
while [ $# -gt 0 ] && [ "$1" != "--" ]; do
  case $1 in
    --absent) absent+=("$2"); shift 2 ;;
    --workdir) workdir=$2; shift 2 ;;
    *) echo "expect.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
shift
[ -n "$workdir" ] && { mkdir -p "$workdir" && cd "$workdir" || exit 2; }
for f in "${absent[@]}"; do rm -f "$f"; done
out=$(mktemp); err=$(mktemp)
trap 'rm -f "$out" "$err"' EXIT
"$@" </dev/null >"$out" 2>"$err"
code=$?
fail=0
if [ "$code" -ne "$expected_exit" ]; then
  echo "FAIL: exit $code, expected $expected_exit"; fail=1
fi
if ! cat "$out" "$err" | grep -Eq -- "$regex"; then
  echo "FAIL: output does not match /$regex/"; fail=1
fi
if [ "$expected_exit" -ne 0 ]; then
  if ! head -n1 "$err" | grep -q '^mpcal: error: '; then
    echo "FAIL: stderr does not start with 'mpcal: error: '"; fail=1
  fi
  if [ "$(grep -c '' "$err")" -ne 1 ]; then
    echo "FAIL: stderr has $(grep -c '' "$err") lines, expected one"; fail=1
  fi
fi
for f in "${absent[@]}"; do
  if [ -e "$f" ]; then echo "FAIL: $f was left behind"; fail=1; fi
done
if [ $fail -ne 0 ]; then
  echo "--- command: $*"; echo "--- stdout:"; cat "$out"; echo "--- stderr:"; cat "$err"
fi
exit $fail
