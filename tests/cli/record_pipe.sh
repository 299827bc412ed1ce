#!/bin/sh
# record_pipe.sh MPCAL PYTHON DIR: a session piped into `mpcal record -`
# at 50 times the sensor's pace ends by itself once the positions are
# enough, one line per event, and its calibration is calibrate's.
. "$(dirname "$0")/record_session.sh"
"$py" "$here/record_pace.py" sim.csv --speed 50 |
  "$mpcal" record - -o s.csv --calibrate c.json >out.txt 2>err.txt
cat out.txt
grep -q '^captured 1: ' out.txt || fail "no capture line"
grep -q '^next: .* down; ' out.txt || fail "no next-target line"
grep -q '^done: every parameter within its target (' out.txt || fail "no done line"
grep -q '^done: every parameter within its target; .* positions captured; session written to s.csv$' out.txt ||
  fail "no end line"
grep -q '^wrote c.json$' out.txt || fail "no calibration written"
test ! -s err.txt || fail "stderr: $(cat err.txt)"
# It ended by itself: the session holds fewer lines than the whole log.
test "$(wc -l <s.csv)" -lt "$(wc -l <sim.csv)" || fail "read to the end of the stream"
same_as_calibrate
