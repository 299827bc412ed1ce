#!/usr/bin/env bash
# Whole-process speed and memory of `mpcal noise` on an 8-hour
# still recording at 400 Hz (11.5 M rows of accelerometer and gyroscope,
# about 1 GB of text), as a ratio to the parse floor measured in the same
# run (bench/parse_floor.cc: read the file and parse every number with
# fast_float, nothing more), with the peak RSS of each beside the size of
# the samples themselves (7 doubles a row).
#
#   bench/noise_bench.sh BUILD_DIR [REPETITIONS] [HOURS] [RATE_HZ] [BASELINE_MPCAL]
#
# Each figure is the median of REPETITIONS runs (default 3), each command in
# turn in every round, after a warm-up that puts the file in the page cache.
# Wall time on these shared 2-core machines moves with the other load; the
# CPU time (user + sys) much less: both are printed, as ratios to the floor.
# BASELINE_MPCAL: another mpcal executable (an older build) run in the same
# rounds on the same file, for a before / after comparison.
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
reps=${2:-3}
hours=${3:-8}
rate=${4:-400}
baseline=${5:-}
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

# Each mpcal runs straight after a floor run, so that both find the same
# state of memory: fresh memory costs this virtual machine more when the
# host has taken back what the run before freed (the floor frees nothing),
# up to a second of kernel time for the 615 MB of samples; a baseline run
# straight after the new one would find it warm.
run warmup "$floor" "$log"
for _ in $(seq "$reps"); do
  run floor "$floor" "$log"
  run noise "$mpcal" noise "$log" --json "$work/noise.json" --kalibr "$work/imu.yaml"
  if [ -n "$baseline" ]; then
    run floor "$floor" "$log"
    run baseline "$baseline" noise "$log" --json "$work/noise0.json" --kalibr "$work/imu0.yaml"
  fi
done

# row LABEL NAME: one line of the table, as ratios to the floor.
row() {
  awk -v label="$1" -v f="$(median floor 1)" -v fc="$(median floor 3)" \
      -v t="$(median "$2" 1)" -v c="$(median "$2" 3)" -v m="$(median "$2" 2)" 'BEGIN {
    printf "%-34s %8.2f %7.2f %8.2f %7.2f %9.0f\n", label, t / 1e6, t / f, c / 1e3, c / fc, m / 1024
  }'
}
awk -v rows="$rows" -v bytes="$bytes" -v reps="$reps" -v hours="$hours" -v rate="$rate" 'BEGIN {
  printf "still record: %g h at %g Hz, %d rows (accelerometer and gyroscope), %.0f MB; median of %d runs\n",
    hours, rate, rows, bytes / 1e6, reps
  printf "%-34s %8s %7s %8s %7s %9s\n", "", "wall (s)", "ratio", "CPU (s)", "ratio", "peak (MB)"
}'
row "floor: read + fast_float" floor
[ -n "$baseline" ] && row "baseline: $(basename "$baseline") noise" baseline
row "mpcal noise --json --kalibr" noise
awk -v rows="$rows" -v f="$(median floor 1)" -v n="$(median noise 1)" \
    -v fc="$(median floor 3)" -v nc="$(median noise 3)" 'BEGIN {
  printf "samples themselves: %.0f MB (7 doubles a row)\n", rows * 56 / 1048576
  printf "target: wall < 10 s and within 1.5x of the floor (wall %.2f s, ratio %.2f; CPU ratio %.2f)\n",
    n / 1e6, n / f, nc / fc
  printf "%s\n", (n / f <= 1.5 && n < 10e6) ? "PASS" : "FAIL (ratio or time above target)"
}'
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
