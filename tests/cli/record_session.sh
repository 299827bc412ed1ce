# Sourced by the record_*.sh tests: `mpcal` is $1, python3 is $2, the
# scratch directory $3; makes it, enters it, and writes sim.csv, a simulated
# 26-position session (2.4 min of log, 100 Hz) that the tests feed at the
# sensor's pace, sped up.
set -eu
mpcal=$1
py=$2
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$3"
mkdir -p "$3"
cd "$3"
"$mpcal" simulate static --preset colibri --seed 5 --dwell 4 --turn 1.5 --rest 4 \
  -o sim.csv >/dev/null
fail() {
  echo "FAIL: $*" >&2
  exit 1
}
# The calibration at the end equals `calibrate` on the written session.
same_as_calibrate() {
  "$mpcal" calibrate s.csv -o c2.json >/dev/null
  "$py" "$here/same_numbers.py" c.json c2.json || fail "record --calibrate differs from calibrate"
}
