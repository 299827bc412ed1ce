#!/usr/bin/env bash
# Reading the IMU out of a ~2 GB recording: a 400 Hz sensor_msgs/Imu topic
# among 30 Hz camera images (640x480 mono8), written by the formats' own
# writers (Debian's python3-rosbag for ROS 1, Foxglove's @mcap/core for MCAP,
# Python's sqlite3 for a ROS 2 bag; bench/bag_bench_ros1.py,
# bench/bag_bench_mcap.mjs, bench/bag_bench_ros2.py) from one simulated
# session. For each file, `mpcal detect FILE` (reads every IMU message, then
# finds the positions) is timed and its peak memory (RSS) measured, against:
#   - the parse floor of the same rows as CSV (bench/parse_floor.cc: read the
#     file, parse every number with fast_float; as in speed_bench.sh),
#   - `mpcal detect` on that CSV,
#   - reading the file's bytes (cat to /dev/null: the I/O floor),
# and the bytes mpcal reads (strace) against the file's size. The chunks
# that hold no IMU message, which the readers skip unread, are counted from
# rosbag's own index. An IMU-only bag of the same rows gives the cost per row
# of the binary read itself.
#
#   bench/bag_bench.sh BUILD_DIR [REPETITIONS]
#
# The recordings (~8 GB) are made once into $MPCAL_BAG_BENCH_DIR (default
# /tmp/mpcal_bag_bench) and kept for the next run; delete that directory to
# free the space. Each time is the CPU time (user + system) of the command,
# the median of REPETITIONS runs (default 3) after a warm-up that puts the
# file in the page cache.
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
reps=${2:-3}
here=$(cd "$(dirname "$0")" && pwd)
mpcal=$build/mpcal
floor=$build/bench/mpcal_parse_floor
cache=${MPCAL_BAG_BENCH_DIR:-/tmp/mpcal_bag_bench}
rosbag_python=/usr/bin/python3  # Debian's python, where python3-rosbag is

for exe in "$mpcal" "$floor"; do
  [ -x "$exe" ] || { echo "bag_bench: $exe not built (make build)" >&2; exit 1; }
done
if ! "$rosbag_python" -c 'import rosbag, roslz4' 2>/dev/null; then
  echo "bag_bench: SKIP (python3-rosbag and python3-roslz4 not installed: scripts/install-deps.sh all)"
  exit 0
fi
mkdir -p "$cache"
work=$(mktemp -d "${TMPDIR:-/tmp}/mpcal_bag_bench.XXXXXX")
trap 'rm -rf "$work"' EXIT

# 10 s of rest + 26 x (6 s still + 2 s turn) = 218 s at 400 Hz: 87,200 rows,
# 6,540 images (2.0 GB).
csv=$cache/session.csv
if [ ! -s "$csv" ]; then
  echo "generating the session (mpcal simulate static --rate 400 --gyro) ..."
  "$mpcal" simulate static --seed 1 --gyro --rate 400 --positions 26 --dwell 6 --turn 2 \
    --rest 10 --digits 0 -o "$csv.tmp" >/dev/null
  mv "$csv.tmp" "$csv"
fi
rows=$(($(grep -c '' "$csv") - 1))

# make FILE CMD...: runs CMD (which writes FILE.tmp) unless FILE exists.
make_file() {
  local file=$1; shift
  [ -s "$file" ] && return 0
  echo "writing $(basename "$file") ..."
  "$@"
  mv "$file.tmp" "$file"
}
need_kb=$((9 * 1024 * 1024))
have_kb=$(df -Pk "$cache" | awk 'NR == 2 {print $4}')
if [ ! -s "$cache/camera_none.bag" ] && [ "$have_kb" -lt "$need_kb" ]; then
  echo "bag_bench: SKIP ($cache has $((have_kb / 1024)) MB free, the recordings need ~9 GB)"
  exit 0
fi
ros1=$here/bag_bench_ros1.py
make_file "$cache/imu_lz4.bag" "$rosbag_python" "$ros1" "$csv" "$cache/imu_lz4.bag.tmp" \
  --compression lz4
make_file "$cache/camera_lz4.bag" "$rosbag_python" "$ros1" "$csv" \
  "$cache/camera_lz4.bag.tmp" --compression lz4 --camera
make_file "$cache/camera_none.bag" "$rosbag_python" "$ros1" "$csv" \
  "$cache/camera_none.bag.tmp" --compression none --camera
# MCAP: Foxglove's packages where scripts/install-deps.sh installs them.
node_dir=$here/../tests/tools
files=(imu_lz4.bag camera_lz4.bag camera_none.bag)
if [ ! -d "$cache/camera_ros2" ]; then
  echo "writing camera_ros2/ ..."
  rm -rf "$cache/camera_ros2.tmp"
  python3 "$here/bag_bench_ros2.py" "$csv" "$cache/camera_ros2.tmp"
  mv "$cache/camera_ros2.tmp" "$cache/camera_ros2"
fi
files+=(camera_ros2)
if [ -d "$node_dir/node_modules/@mcap/core" ] && command -v node >/dev/null; then
  make_file "$cache/camera_lz4.mcap" \
    bash -c 'cd "$1" && node "$2" "$3" "$4"' _ "$node_dir" "$here/bag_bench_mcap.mjs" "$csv" \
    "$cache/camera_lz4.mcap.tmp"
  files+=(camera_lz4.mcap)
else
  echo "bag_bench: the MCAP file is left out (node or npm's @mcap/core not available)"
fi

# run NAME CMD...: one run; appends "µs peak_kB" to $work/NAME: the CPU time
# (user + system) and peak RSS of CMD alone, from getrusage of the child (µs
# resolution). CPU time rather than the wall clock: on a loaded machine the
# wall clock counts the wait for a core, and favours a command that parses on
# two threads (detect on a CSV) over one that reads on one (a bag), as
# `perf stat -e task-clock` does not. detect exits 1 when the positions are
# too few to calibrate; only other codes fail.
run() {
  local name=$1; shift
  local rc=0
  "$rosbag_python" - "$@" >"$work/usage" 2>"$work/stderr" <<'PY' || rc=$?
import resource, subprocess, sys
p = subprocess.run(sys.argv[1:], stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL)
r = resource.getrusage(resource.RUSAGE_CHILDREN)
print(round((r.ru_utime + r.ru_stime) * 1e6), r.ru_maxrss)
sys.exit(p.returncode)
PY
  if [ "$rc" -gt 1 ]; then cat "$work/stderr" >&2; exit 1; fi
  cat "$work/usage" >>"$work/$name"
}
# The bytes of a recording: the file, or a ROS 2 bag directory's database.
data_of() { if [ -d "$1" ]; then echo "$1/$(basename "$1")_0.db3"; else echo "$1"; fi; }
median() {
  sort -n -k"$2","$2" "$work/$1" | awk -v c="$2" '{v[NR]=$c} END {print v[int((NR+1)/2)]}'
}
# The bytes the process read (read and pread system calls), by strace.
bytes_read() {
  strace -f -qq -e trace=read,pread64 -o "$work/strace" "$@" >/dev/null 2>&1 || true
  awk '/= [0-9]+$/ {s += $NF} END {printf "%.0f", s}' "$work/strace"
}
# Chunks, and chunks holding no /imu/data message, from rosbag's index.
ros1_chunks() {
  "$rosbag_python" - "$1" <<'PY'
import sys, rosbag
with rosbag.Bag(sys.argv[1]) as b:
    imu = {c.id for c in b._connections.values() if c.topic == "/imu/data"}
    print(len(b._chunks), sum(1 for c in b._chunks if not imu & set(c.connection_counts)))
PY
}

run warmup "$floor" "$csv"
"$mpcal" detect "$csv" >/dev/null 2>&1 || true
for _ in $(seq "$reps"); do
  run floor "$floor" "$csv"
  run detect_csv "$mpcal" detect "$csv"
done
for f in "${files[@]}"; do
  cat "$(data_of "$cache/$f")" >/dev/null
  for _ in $(seq "$reps"); do
    run "cat_$f" cat "$(data_of "$cache/$f")"
    run "detect_$f" "$mpcal" detect "$cache/$f"
  done
done

fmt_s() { awk -v u="$1" 'BEGIN {printf "%.3f", u / 1e6}'; }
fmt_mb() { awk -v k="$1" 'BEGIN {printf "%.0f", k / 1024}'; }
ratio() { awk -v a="$1" -v b="$2" 'BEGIN {printf "%.2f", a / b}'; }
f=$(median floor 1)
dc=$(median detect_csv 1)
dc_kb=$(median detect_csv 2)
printf 'session: %d IMU rows at 400 Hz (%s, %.1f MB as CSV); median of %d runs\n' "$rows" \
  "$(basename "$csv")" "$(awk -v b="$(stat -c %s "$csv")" 'BEGIN {print b / 1e6}')" "$reps"
printf '%-30s %9s %9s %9s %9s %10s %10s\n' "" "size (MB)" "CPU (s)" "/floor" "/cat" \
  "read (MB)" "peak (MiB)"
printf '%-30s %9s %9s %9s %9s %10s %10s\n' "floor: CSV read + fast_float" \
  "$(awk -v b="$(stat -c %s "$csv")" 'BEGIN {printf "%.0f", b / 1e6}')" "$(fmt_s "$f")" \
  "1.00" "" "" "$(fmt_mb "$(median floor 2)")"
printf '%-30s %9s %9s %9s %9s %10s %10s\n' "mpcal detect session.csv" "" "$(fmt_s "$dc")" \
  "$(ratio "$dc" "$f")" "" "" "$(fmt_mb "$dc_kb")"
for f_name in "${files[@]}"; do
  path=$cache/$f_name
  size=$(stat -c %s "$(data_of "$path")")
  d=$(median "detect_$f_name" 1)
  kb=$(median "detect_$f_name" 2)
  c=$(median "cat_$f_name" 1)
  read_b=$(bytes_read "$mpcal" detect "$path")
  printf '%-30s %9.0f %9s %9s %9s %10.0f %10s\n' "mpcal detect $f_name" \
    "$(awk -v b="$size" 'BEGIN {print b / 1e6}')" "$(fmt_s "$d")" "$(ratio "$d" "$f")" \
    "$(ratio "$d" "$c")" "$(awk -v b="$read_b" 'BEGIN {print b / 1e6}')" "$(fmt_mb "$kb")"
  echo "$f_name $size $d $kb $c $read_b" >>"$work/results"
done
for f_name in "${files[@]}"; do
  [[ $f_name == *.bag ]] || continue
  read -r chunks empty < <(ros1_chunks "$cache/$f_name")
  echo "$f_name: $chunks chunks, $empty of them without an /imu/data message (skipped unread)"
done

# The targets.
# 1. The binary read of the IMU-only bag is faster than reading the same rows
#    as text: detect on it (the same detection after the read, the same
#    process start) takes at most 0.8 times detect on the CSV.
d=$(median detect_imu_lz4.bag 1)
awk -v d="$d" -v c="$dc" 'BEGIN {
  printf "IMU-only bag: detect %.3f s CPU, on the CSV %.3f s (ratio %.2f, target <= 0.8): %s\n",
    d / 1e6, c / 1e6, d / c, d <= 0.8 * c ? "PASS" : "FAIL" }' | tee -a "$work/verdicts"
# 2. Memory does not grow with the recording: each camera file's peak RSS is
#    within 32 MiB of detect on the CSV (a few chunks: rosbag closes a chunk
#    past 768 KiB, @mcap/core past 1 MiB; the rows themselves are the same).
while read -r f_name size _ kb _ _; do
  [[ $f_name == camera_* ]] || continue
  awk -v n="$f_name" -v kb="$kb" -v csv="$dc_kb" -v size="$size" 'BEGIN {
    printf "%s: peak RSS %.0f MiB for a file of %.0f MB (%.1f%%), on the CSV %.0f MiB " \
      "(target: within 32 MiB of it): %s\n", n, kb / 1024, size / 1e6,
      100 * kb * 1024 / size, csv / 1024, kb <= csv + 32 * 1024 ? "PASS" : "FAIL" }'
done <"$work/results" | tee -a "$work/verdicts"
# 3. Time: a compressed chunk that holds IMU messages has to be read and
#    unpacked whole (of a stored ROS 1 chunk only the IMU's records are
#    read, by its index): a camera file's read is judged against the I/O
#    floor, cat of the same file from the page cache (target: at most 3
#    times it).
while read -r f_name _ d _ c _; do
  [[ $f_name == camera_* ]] || continue
  awk -v n="$f_name" -v d="$d" -v c="$c" 'BEGIN {
    printf "%s: detect %.3f s CPU, cat %.3f s (ratio %.2f, target <= 3): %s\n", n, d / 1e6,
      c / 1e6, d / c, d <= 3 * c ? "PASS" : "FAIL" }'
done <"$work/results" | tee -a "$work/verdicts"
# 4. A recording is calibrated as its CSV is, in the same bounded memory:
#    mpcal calibrate once on the CSV and on each camera file; the peak RSS
#    within 32 MiB of the CSV's, and the accelerometer's nine parameters
#    within a thousandth of their 1-sigma of the CSV's (the same rows; the
#    bags' stamps are in ns from an epoch, the CSV's in s from 0).
run calibrate_csv "$mpcal" calibrate "$csv" -o "$work/calibration_csv.json"
for f_name in "${files[@]}"; do
  [[ $f_name == camera_* ]] || continue
  run "calibrate_$f_name" "$mpcal" calibrate "$cache/$f_name" -o "$work/calibration_$f_name.json"
  "$rosbag_python" - "$work/calibration_csv.json" "$work/calibration_$f_name.json" \
    "$f_name" "$(median "calibrate_$f_name" 2)" "$(median calibrate_csv 2)" <<'PY'
import json, sys
csv, bag = (json.load(open(p)) for p in sys.argv[1:3])
name, kb, csv_kb = sys.argv[3], int(sys.argv[4]), int(sys.argv[5])
keys = ("bias_mps2", "scale_factor_error", "non_orthogonality_rad")
def values(d, k):
    v = d[k]
    return list(v.values()) if isinstance(v, dict) else v
worst = max(abs(a - b) / s for k in keys
            for a, b, s in zip(values(csv, k), values(bag, k), values(csv["std"], k)))
ok = kb <= csv_kb + 32 * 1024 and worst <= 1e-3
print("%s: calibrate peak RSS %.0f MiB, on the CSV %.0f MiB; parameters within %.1e sigma of "
      "the CSV's (target: within 32 MiB, 1e-3 sigma): %s"
      % (name, kb / 1024, csv_kb / 1024, worst, "PASS" if ok else "FAIL"))
PY
done | tee -a "$work/verdicts"
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
echo "(the recordings stay in $cache for the next run: rm -r $cache frees $(du -sh "$cache" | cut -f1))"
