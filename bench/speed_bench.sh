#!/usr/bin/env bash
# Whole-process speed of `mpcal calibrate` and `mpcal apply` on a long log,
# each as a ratio to its floor measured in the same run:
#   calibrate : floor = read the file + parse every number with fast_float
#   apply     : floor = the same + write every number back with std::to_chars
# plus peak memory (RSS) beside the file's size, and calibrate on the real
# 51 k-row Xsens recording of imu_tk (target: under 0.1 s; its peak memory
# beside its samples' own size, rows x 4 doubles, and imu_tk's 12.7 MB for
# the same calibration, which it must not exceed). Also the ratio
# of CPU time (user + sys): mpcal reads with two threads, so on an idle
# machine its time ratio is below its CPU ratio; on a loaded one they meet.
#
#   bench/speed_bench.sh BUILD_DIR [REPETITIONS]
#
# The session: 1 kHz, 26 positions, 60 s each (1.7 M rows, ~110 MB),
# from `mpcal simulate static`. Each figure is the median of REPETITIONS
# runs (default 11: these machines are shared and noisy) after one warm-up
# that puts the file in the page cache.
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
reps=${2:-11}
here=$(cd "$(dirname "$0")" && pwd)
mpcal=$build/mpcal
floor=$build/bench/mpcal_parse_floor
xsens=$here/../tests/data/real/xsens-multiposition/xsens_acc.mat

for exe in "$mpcal" "$floor"; do
  [ -x "$exe" ] || { echo "speed_bench: $exe not built (make build)" >&2; exit 1; }
done
work=$(mktemp -d "${TMPDIR:-/tmp}/mpcal_speed.XXXXXX")
trap 'rm -rf "$work"' EXIT
log=$work/session.csv

# 88 s of rest + 26 × (60 s + 2 s turn) = 1700 s; exact (shortest round
# trip) readings, as a logger of doubles writes them.
echo "generating the session (mpcal simulate static --rate 1000 --dwell 60 --rest 88) ..."
"$mpcal" simulate static --seed 1 --rate 1000 --dwell 60 --rest 88 --positions 26 \
  --digits 0 -o "$log" --truth "$work/truth.json" >/dev/null
rows=$(($(grep -c '' "$log") - 1))
bytes=$(stat -c %s "$log")

# run NAME CMD...: one timed run; appends "µs peak_kB cpu_ms" to $work/NAME.
run() {
  local name=$1; shift
  local t0 t1 peak cpu=0
  t0=$(date +%s%N)
  if [ -x /usr/bin/time ]; then
    /usr/bin/time -f '%M %U %S' -o "$work/rss" "$@" >/dev/null 2>"$work/stderr" ||
      { cat "$work/stderr" >&2; exit 1; }
    read -r peak cpu < <(tail -n1 "$work/rss" | awk '{printf "%d %d\n", $1, ($2 + $3) * 1000}')
  else
    # Without GNU time: the peak (VmHWM) of the child, read by python.
    peak=$(python3 - "$@" <<'EOF'
import resource, subprocess, sys
subprocess.run(sys.argv[1:], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)
EOF
)
  fi
  t1=$(date +%s%N)
  echo "$(( (t1 - t0) / 1000 )) $peak $cpu" >>"$work/$name"
}

# median NAME COLUMN: the median of one column (1 = µs, 2 = peak kB, 3 = CPU ms).
median() {
  sort -n -k"$2","$2" "$work/$1" | awk -v c="$2" '{v[NR]=$c} END {print v[int((NR+1)/2)]}'
}

calib=$work/calib.json
run warmup "$floor" "$log"
rm -f "$work/warmup"
"$mpcal" calibrate "$log" -o "$calib" >/dev/null
for _ in $(seq "$reps"); do
  run floor "$floor" "$log"
  run calibrate "$mpcal" calibrate "$log" -o "$work/c.json"
  run floor_write "$floor" "$log" --write "$work/floor_out.csv"
  run apply "$mpcal" apply "$calib" "$log" -o "$work/applied.csv"
  if [ -f "$xsens" ]; then
    run xsens "$mpcal" calibrate "$xsens" --units counts --gravity 9.81744
  fi
done

fmt_s() { awk -v u="$1" 'BEGIN {printf "%.3f", u / 1e6}'; }
fmt_mb() { awk -v k="$1" 'BEGIN {printf "%.0f", k / 1024}'; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN {printf "%.2f", a / b}'; }

printf 'session: %d rows, %.1f MB (%s); median of %d runs\n' "$rows" \
  "$(awk -v b="$bytes" 'BEGIN {print b / 1e6}')" "$(basename "$log")" "$reps"
cpu_ratio() { [ "$2" -gt 0 ] && ratio "$1" "$2" || echo "-"; }
printf '%-34s %9s %8s %10s %14s\n' "" "time (s)" "ratio" "CPU ratio" "peak RSS (MB)"
f=$(median floor 1); fw=$(median floor_write 1)
c=$(median calibrate 1); a=$(median apply 1)
fc=$(median floor 3); fwc=$(median floor_write 3)
printf '%-34s %9s %8s %10s %14s\n' "floor: read + fast_float" "$(fmt_s "$f")" "1.00" "1.00" \
  "$(fmt_mb "$(median floor 2)")"
printf '%-34s %9s %8s %10s %14s   target <= 1.2\n' "mpcal calibrate" "$(fmt_s "$c")" \
  "$(ratio "$c" "$f")" "$(cpu_ratio "$(median calibrate 3)" "$fc")" \
  "$(fmt_mb "$(median calibrate 2)")"
printf '%-34s %9s %8s %10s %14s\n' "floor + write back (to_chars)" "$(fmt_s "$fw")" "1.00" \
  "1.00" "$(fmt_mb "$(median floor_write 2)")"
printf '%-34s %9s %8s %10s %14s   target <= 2\n' "mpcal apply" "$(fmt_s "$a")" \
  "$(ratio "$a" "$fw")" "$(cpu_ratio "$(median apply 3)" "$fwc")" "$(fmt_mb "$(median apply 2)")"
if [ -f "$work/xsens" ]; then
  printf '%-34s %9s %8s %10s %14s   target < 0.1 s\n' "mpcal calibrate xsens_acc.mat (51k)" \
    "$(fmt_s "$(median xsens 1)")" "" "" "$(fmt_mb "$(median xsens 2)")"
  # Peak RSS against imu_tk's (12.7 MB, measured on this machine with
  # imu_tk built from its source); MB here are MiB, as the table's.
  xsens_rows=$("$mpcal" calibrate "$xsens" --units counts --gravity 9.81744 |
    sed -n 's/^.*: \([0-9]*\) rows,.*$/\1/p')
  awk -v k="$(median xsens 2)" -v rows="$xsens_rows" -v n="$reps" 'BEGIN {
    imu_tk = 12.7; peak = k / 1024; samples = rows * 4 * 8 / 1048576
    printf "xsens_acc.mat calibrate, accelerometer only: peak RSS %.1f MB (median of %d); " \
      "its samples %d rows x 4 doubles = %.2f MB; imu_tk %.1f MB: %s\n",
      peak, n, rows, samples, imu_tk, peak <= imu_tk ? "PASS" : "FAIL"
  }'
fi
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
