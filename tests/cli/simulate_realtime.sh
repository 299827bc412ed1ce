#!/usr/bin/env bash
# `simulate static --realtime`: the same log as without it, written at the
# sensor's pace (never ahead of it), and a reader that quits ends it
# quietly with exit status 0.
#   simulate_realtime.sh MPCAL WORKDIR
set -euo pipefail
mpcal=$1
mkdir -p "$2" && cd "$2"
session=(simulate static --preset mti-g --seed 3 --positions 6 --dwell 2 --turn 1 --rest 1)

"$mpcal" "${session[@]}" -o whole.csv >/dev/null
start=$(date +%s.%N)
"$mpcal" "${session[@]}" --speed 10 -o - >paced.csv 2>summary.txt
end=$(date +%s.%N)
cmp whole.csv paced.csv || { echo "FAIL: the paced log differs from the file"; exit 1; }
grep -q "Wrote the log to standard output" summary.txt ||
  { echo "FAIL: no summary on stderr"; cat summary.txt; exit 1; }
# The log spans its last time stamp; at 10x it cannot have taken less.
span=$(tail -n 1 whole.csv | cut -d, -f1)
awk -v s="$start" -v e="$end" -v span="$span" 'BEGIN {
  took = e - s; least = span / 10
  if (took < least) { printf "FAIL: %.2f s, ahead of the pace (%.2f s)\n", took, least; exit 1 }
}'

# The reader quits after 20 lines: simulate stops, quietly, with status 0.
set +e
"$mpcal" "${session[@]}" --realtime --speed 50 -o - 2>quit_err.txt | head -n 20 >head.txt
status=${PIPESTATUS[0]}
set -e
[ "$status" -eq 0 ] || { echo "FAIL: exit $status when the reader quit"; exit 1; }
[ ! -s quit_err.txt ] || { echo "FAIL: it spoke when the reader quit:"; cat quit_err.txt; exit 1; }
[ "$(wc -l <head.txt)" -eq 20 ] || { echo "FAIL: the reader got $(wc -l <head.txt) lines"; exit 1; }
head -n 20 whole.csv | cmp - head.txt || { echo "FAIL: the first lines differ"; exit 1; }
echo "simulate --realtime: same log, at its pace, quiet when the reader quits"
