#!/bin/sh
# record_interrupt.sh MPCAL PYTHON DIR: Ctrl-C (SIGINT) in the middle of a
# session leaves a complete log, which detect reads without a warning about
# a cut line, and the positions captured before it.
. "$(dirname "$0")/record_session.sh"
mkfifo fifo
"$py" "$here/record_pace.py" sim.csv --speed 10 >fifo &
feeder=$!
"$mpcal" record - -o s.csv <fifo >out.txt 2>err.txt &
rec=$!
i=0
while ! grep -q '^captured 4: ' out.txt && [ $i -lt 300 ]; do sleep 0.1; i=$((i + 1)); done
kill -INT $rec
wait $rec || fail "record exit $?: $(cat err.txt)"
kill $feeder 2>/dev/null || true
grep -q '^stopped (Ctrl-C); ' out.txt || fail "no stop line: $(tail -2 out.txt)"
"$mpcal" detect s.csv >detect.txt 2>detect_err.txt || true
if grep -qi 'warning' detect_err.txt; then fail "detect warns: $(cat detect_err.txt)"; fi
# The positions captured before Ctrl-C are in the file.
grep -Eq '([4-9]|[1-9][0-9]) static positions' detect.txt || fail "positions: $(head -3 detect.txt)"
