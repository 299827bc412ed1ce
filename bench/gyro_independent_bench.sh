#!/usr/bin/env bash
# The gyroscope on sessions that mpcal's simulator did not make
# (bench/independent/gen_imu_session.py: full attitude, hand turns, tremor,
# lever arm, Earth rate, bias random walk), scored by
# bench/independent/gyro_study.py against the truth: RMS of
# z = (estimate − truth)/reported 1σ over the 9 entries of M (bar 0.8-1.25),
# and RMS of (estimate − truth)/Cramér-Rao bound, the bound computed in
# Python from the generator's own truth and noise figures
# (bench/independent/gyro_bound.py). Two studies of 50 sessions: with the
# hand's tremor (z judged; the bound shown), and without it (z and the bound
# judged: the bound then holds every disturbance of the session). About
# five minutes each on two idle cores.
#
#   bench/gyro_independent_bench.sh BUILD_DIR [SESSIONS]
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
sessions=${2:-50}
here=$(cd "$(dirname "$0")" && pwd)
mpcal=$build/mpcal
[ -x "$mpcal" ] || { echo "gyro_independent_bench: $mpcal not built (make build)" >&2; exit 1; }
status=0
echo "-- with the hand's tremor"
python3 "$here/independent/gyro_study.py" "$mpcal" --sessions "$sessions" || status=1
echo "-- without tremor"
python3 "$here/independent/gyro_study.py" "$mpcal" --sessions "$sessions" --tremor 0 || status=1
exit $status
