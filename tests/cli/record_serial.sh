#!/bin/sh
# record_serial.sh MPCAL PYTHON DIR: the session through a pseudo-terminal
# pair (socat) standing in for a serial port, starting with a sensor's boot
# text and a line cut in half: both skipped, the rest recorded and
# calibrated as calibrate calibrates the written file.
. "$(dirname "$0")/record_session.sh"
socat pty,raw,echo=0,link=sensor pty,raw,echo=0,link=port &
pair=$!
trap 'kill $pair 2>/dev/null || true' EXIT
i=0
while { [ ! -e sensor ] || [ ! -e port ]; } && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
"$mpcal" record port --baud 115200 -o s.csv --calibrate c.json >out.txt &
rec=$!
sleep 0.5
"$py" "$here/record_pace.py" sim.csv --speed 50 --device sensor --boot &
feeder=$!
wait $rec || fail "record failed: $(tail -3 out.txt)"
kill $feeder 2>/dev/null || true
grep -q '^done: every parameter within its target; ' out.txt || fail "not done: $(tail -3 out.txt)"
# The boot text is not in the session file; its first line is a data line.
if grep -q 'ets Jun\|rst:\|IMU ready' s.csv; then fail "boot text in the session"; fi
same_as_calibrate
