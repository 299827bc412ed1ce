#!/usr/bin/env bash
# Whole-process speed of `mpcal calibrate` of accelerometer + gyroscope on
# imu_tk's Xsens recording (two files of 51 175 rows merged by row;
# target: under 0.1 s), as a ratio to its floor: reading and parsing both
# files with fast_float (bench/parse_floor.cc). The floor and the commands
# run side by side, interleaved, REPETITIONS times (default 11) after a
# warm-up. Wall time: the median per run. CPU time (user + sys of the
# process, from getrusage through bash's `time`, 1 ms per run): the mean
# over the runs, so that a floor of a few ms is resolved.
#
#   bench/gyro_speed_bench.sh BUILD_DIR [REPETITIONS]
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
reps=${2:-11}
here=$(cd "$(dirname "$0")" && pwd)
mpcal=$build/mpcal
floor=$build/bench/mpcal_parse_floor
data=$here/../tests/data/real/xsens-multiposition
for exe in "$mpcal" "$floor"; do
  [ -x "$exe" ] || { echo "gyro_speed_bench: $exe not built (make build)" >&2; exit 1; }
done
work=$(mktemp -d "${TMPDIR:-/tmp}/mpcal_gyro_speed.XXXXXX")
trap 'rm -rf "$work"' EXIT
TIMEFORMAT='%3U %3S'

# run NAME CMD...: appends "wall_us cpu_us" to $work/NAME.
run() {
  local name=$1; shift
  local t0 t1 status=0
  t0=$EPOCHREALTIME
  { time "$@" >/dev/null 2>"$work/stderr"; } 2>"$work/cpu" || status=$?
  t1=$EPOCHREALTIME
  if ((status != 0)); then cat "$work/stderr" >&2; exit 1; fi
  echo "$((${t1//[.,]/} - ${t0//[.,]/})) $(awk '{printf "%d", ($1 + $2) * 1e6}' "$work/cpu")" \
    >>"$work/$name"
}
median() { sort -n -k1,1 "$work/$1" | awk '{v[NR]=$1} END {print v[int((NR+1)/2)]}'; }
mean_cpu() { awk '{s+=$2} END {printf "%d", s/NR}' "$work/$1"; }

imu=("$mpcal" calibrate "$data/xsens_acc.mat" --gyro-log "$data/xsens_gyro.mat"
  --units counts --gyro-units counts --gravity 9.81744)
run warmup "$floor" "$data/xsens_acc.mat"
run warmup "${imu[@]}"
for _ in $(seq "$reps"); do
  run floor_acc "$floor" "$data/xsens_acc.mat"
  run floor_gyro "$floor" "$data/xsens_gyro.mat"
  run imu "${imu[@]}"
  run accel "$mpcal" calibrate "$data/xsens_acc.mat" --units counts --gravity 9.81744
done
# The target is on the wall time of an idle machine; on a shared one the CPU
# time is the figure that depends less on the other jobs: both are printed,
# each with its ratio to the floor measured the same way.
awk -v fw="$(($(median floor_acc) + $(median floor_gyro)))" \
  -v fc="$(($(mean_cpu floor_acc) + $(mean_cpu floor_gyro)))" \
  -v iw="$(median imu)" -v ic="$(mean_cpu imu)" \
  -v aw="$(median accel)" -v ac="$(mean_cpu accel)" -v n="$reps" \
  -v fa="$(median floor_acc)" -v fac="$(mean_cpu floor_acc)" \
  -v gw="$(median floor_gyro)" -v gc="$(mean_cpu floor_gyro)" 'BEGIN {
  printf "xsens calibrate accelerometer + gyroscope (%d runs): wall %.3f s = %.1f x the parse floor of both files (%.3f s); CPU %.3f s = %.1f x the floor CPU (%.4f s)\n",
    n, iw / 1e6, iw / fw, fw / 1e6, ic / 1e6, ic / fc, fc / 1e6
  printf "accelerometer alone: wall %.3f s = %.1f x the parse floor of its file (%.3f s); CPU %.3f s = %.1f x the floor CPU (%.4f s)\n",
    aw / 1e6, aw / fa, fa / 1e6, ac / 1e6, ac / fac, fac / 1e6
  printf "the gyroscope'"'"'s share (both sensors - accelerometer alone): wall %.3f s, CPU %.3f s, of which its file'"'"'s parse floor wall %.3f s, CPU %.4f s\n",
    (iw - aw) / 1e6, (ic - ac) / 1e6, gw / 1e6, gc / 1e6
  printf "target < 0.1 s: wall %s, CPU %s\n", (iw < 1e5 ? "MET" : "NOT MET"), (ic < 1e5 ? "MET" : "NOT MET")
}'
