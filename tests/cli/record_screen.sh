#!/bin/sh
# record_screen.sh MPCAL PYTHON DIR: the live screen on a terminal (tmux):
# while the session arrives it shows the direction to hold next and the
# positions captured; at the end, the calibration's verdict. Then `q` on a
# terminal whose keyboard is not the source stops a session early.
. "$(dirname "$0")/record_session.sh"
socket="mpcal-record-$$"
t() { tmux -L "$socket" "$@"; }
trap 't kill-server 2>/dev/null || true' EXIT
t new-session -d -x 110 -y 40 \
  "'$py' '$here/record_pace.py' sim.csv --speed 10 | '$mpcal' record - -o s.csv --calibrate c.json; echo END; sleep 60"
seen_next=no
seen_count=no
i=0
while [ $i -lt 600 ]; do
  t capture-pane -p >pane.txt
  grep -q '\[>\]' pane.txt && grep -q 'turn so that the .* points down' pane.txt && seen_next=yes
  grep -Eq 'positions captured: [1-9]' pane.txt && seen_count=yes
  grep -q '^END' pane.txt && break
  sleep 0.1
  i=$((i + 1))
done
cat pane.txt
test $seen_next = yes || fail "the next direction was never shown"
test $seen_count = yes || fail "no captured count was shown"
grep -q 'done: every parameter within its target' pane.txt || fail "not done"
grep -Eq '^(good|look at|do not use) ' pane.txt || grep -Eq 'verdict|good' pane.txt || fail "no verdict"
same_as_calibrate

# q: the source a TCP stream, the keyboard the terminal's.
rm -f port.txt s.csv
"$py" "$here/record_pace.py" sim.csv --speed 5 --serve port.txt &
i=0
while [ ! -s port.txt ] && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
t new-session -d -s q -x 110 -y 40 \
  "'$mpcal' record tcp:127.0.0.1:$(cat port.txt) -o s.csv; echo END; sleep 60"
i=0
while ! t capture-pane -p -t q | grep -Eq 'positions captured: [2-9]' && [ $i -lt 300 ]; do
  sleep 0.1
  i=$((i + 1))
done
t send-keys -t q q
i=0
while ! t capture-pane -p -t q | grep -q '^END' && [ $i -lt 100 ]; do sleep 0.1; i=$((i + 1)); done
t capture-pane -p -t q >pane_q.txt
cat pane_q.txt
grep -q '^stopped (q); ' pane_q.txt || fail "q did not stop it"
"$mpcal" detect s.csv >/dev/null 2>detect_err.txt || true
if grep -qi 'warning' detect_err.txt; then fail "detect warns: $(cat detect_err.txt)"; fi
