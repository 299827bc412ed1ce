#!/usr/bin/env bash
# Whole-process speed of `mpcal calibrate` of accelerometer + gyroscope on
# imu_tk's Xsens recording (two files of 51 175 rows merged by row; issue 17
# target: under 0.1 s), as a ratio to its floor: reading and parsing both
# files with fast_float (bench/parse_floor.cc). Median of REPETITIONS runs
# (default 11) after a warm-up; CPU time (user + sys) beside the wall time.
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

# run NAME CMD...: appends "wall_us cpu_ms" to $work/NAME.
run() {
  local name=$1; shift
  local t0 t1
  t0=$(date +%s%N)
  /usr/bin/time -f '%U %S' -o "$work/cpu" "$@" >/dev/null 2>"$work/stderr" ||
    { cat "$work/stderr" >&2; exit 1; }
  t1=$(date +%s%N)
  echo "$(( (t1 - t0) / 1000 )) $(awk '{printf "%d", ($1 + $2) * 1000}' "$work/cpu")" >>"$work/$name"
}
median() { sort -n -k"$2","$2" "$work/$1" | awk -v c="$2" '{v[NR]=$c} END {print v[int((NR+1)/2)]}'; }

run warmup "$floor" "$data/xsens_acc.mat"
for _ in $(seq "$reps"); do
  run floor_acc "$floor" "$data/xsens_acc.mat"
  run floor_gyro "$floor" "$data/xsens_gyro.mat"
  run imu "$mpcal" calibrate "$data/xsens_acc.mat" --gyro-log "$data/xsens_gyro.mat" \
    --units counts --gyro-units counts --gravity 9.81744
  run accel "$mpcal" calibrate "$data/xsens_acc.mat" --units counts --gravity 9.81744
done
floor_us=$(( $(median floor_acc 1) + $(median floor_gyro 1) ))
floor_cpu=$(( $(median floor_acc 2) + $(median floor_gyro 2) ))
imu_us=$(median imu 1)
acc_us=$(median accel 1)
# The target is on the wall time of an idle machine; on a shared one the CPU
# time (user + sys, ms resolution) is the figure that does not depend on the
# other jobs, so both are printed with their ratio to the floor.
awk -v f="$floor_us" -v fc="$floor_cpu" -v i="$imu_us" -v a="$acc_us" -v ic="$(median imu 2)" \
  -v ac="$(median accel 2)" 'BEGIN {
  printf "xsens calibrate accelerometer + gyroscope: wall %.3f s, %.1f x the parse floor of both files (%.3f s); CPU %.3f s, %.1f x the floor CPU (%.3f s); accelerometer alone wall %.3f s, CPU %.3f s; target < 0.1 s: wall %s, CPU %s\n",
    i / 1e6, i / f, f / 1e6, ic / 1e3, (fc > 0 ? ic / fc : 0), fc / 1e3, a / 1e6, ac / 1e3,
    (i < 1e5 ? "MET" : "NOT MET"), (ic < 100 ? "MET" : "NOT MET")
}'
