#!/bin/sh
# record_tcp.sh MPCAL PYTHON DIR: the same session from a TCP server on
# the loopback (a python3 server feeding it at 50 times its pace).
. "$(dirname "$0")/record_session.sh"
"$py" "$here/record_pace.py" sim.csv --speed 50 --serve port.txt &
server=$!
i=0
while [ ! -s port.txt ] && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
"$mpcal" record "tcp:127.0.0.1:$(cat port.txt)" -o s.csv --calibrate c.json >out.txt
wait $server || true
grep -q '^done: every parameter within its target; ' out.txt || fail "not done: $(tail -3 out.txt)"
same_as_calibrate
