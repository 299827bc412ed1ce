#!/usr/bin/env bash
# Whole-process speed and memory of `mpcal noise` (issue 18) on an 8-hour
# still recording at 400 Hz (11.5 M rows of accelerometer and gyroscope,
# about 1 GB of text), as a ratio to the parse floor measured in the same
# run (bench/parse_floor.cc: read the file and parse every number with
# fast_float, nothing more), with the peak RSS of each beside the size of
# the samples themselves (7 doubles a row).
#
#   bench/noise_bench.sh BUILD_DIR [REPETITIONS] [HOURS] [RATE_HZ]
#
# Each figure is the median of REPETITIONS runs (default 5), each command in
# turn in every round, after a warm-up that puts the file in the page cache.
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
reps=${2:-5}
hours=${3:-8}
rate=${4:-400}
mpcal=$build/mpcal
floor=$build/bench/mpcal_parse_floor
for exe in "$mpcal" "$floor"; do
  [ -x "$exe" ] || { echo "noise_bench: $exe not built (make build)" >&2; exit 1; }
done
work=$(mktemp -d "${TMPDIR:-/tmp}/mpcal_noise_bench.XXXXXX")
trap 'rm -rf "$work"' EXIT
log=$work/still.csv

echo "generating the record (mpcal simulate noise --hours $hours --rate $rate) ..."
"$mpcal" simulate noise --hours "$hours" --rate "$rate" --seed 1 -o "$log" \
  --truth "$work/truth.json" >/dev/null
rows=$(($(grep -c '' "$log") - 1))
bytes=$(stat -c %s "$log")

# run NAME CMD...: one timed run; appends "µs peak_kB cpu_ms" to $work/NAME.
run() {
  local name=$1; shift
  local t0 t1 peak cpu
  t0=$(date +%s%N)
  /usr/bin/time -v -o "$work/rss" "$@" >/dev/null 2>"$work/stderr" ||
    { cat "$work/stderr" >&2; exit 1; }
  t1=$(date +%s%N)
  peak=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$work/rss")
  cpu=$(awk -F': ' '/User time/ {u=$2} /System time/ {s=$2} END {printf "%d", (u + s) * 1000}' \
    "$work/rss")
  echo "$(( (t1 - t0) / 1000 )) $peak $cpu" >>"$work/$name"
}
median() {
  sort -n -k"$2","$2" "$work/$1" | awk -v c="$2" '{v[NR]=$c} END {print v[int((NR+1)/2)]}'
}

run warmup "$floor" "$log"
for _ in $(seq "$reps"); do
  run floor "$floor" "$log"
  run noise "$mpcal" noise "$log" --json "$work/noise.json" --kalibr "$work/imu.yaml"
done

f_us=$(median floor 1); n_us=$(median noise 1)
f_cpu=$(median floor 3); n_cpu=$(median noise 3)
awk -v rows="$rows" -v bytes="$bytes" -v reps="$reps" -v f="$f_us" -v n="$n_us" \
    -v fc="$f_cpu" -v nc="$n_cpu" -v fm="$(median floor 2)" -v nm="$(median noise 2)" 'BEGIN {
  printf "still record: %d rows (accelerometer and gyroscope), %.0f MB; median of %d runs\n",
    rows, bytes / 1e6, reps
  printf "%-32s %9s %8s %10s %14s\n", "", "time (s)", "ratio", "CPU ratio", "peak RSS (MB)"
  printf "%-32s %9.2f %8.2f %10.2f %14.0f\n", "floor: read + fast_float", f / 1e6, 1, 1, fm / 1024
  printf "%-32s %9.2f %8.2f %10.2f %14.0f   target: ratio <= 1.5, < 10 s\n",
    "mpcal noise --json --kalibr", n / 1e6, n / f, nc / fc, nm / 1024
  printf "samples themselves: %.0f MB (7 doubles a row)\n", rows * 56 / 1048576
  ok = (n / f <= 1.5 && n < 10e6)
  printf "%s\n", ok ? "PASS" : "FAIL (ratio or time above target)"
}'
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
