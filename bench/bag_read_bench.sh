#!/usr/bin/env bash
# The reading alone: the IMU rows of a recording read by ReadLog, the entry
# point the commands read through (bench/read_log.cc: the topic chosen,
# every sensor_msgs/Imu message decoded, the rows put in time order; no
# detection), against the parse floor of the same rows as CSV
# (bench/parse_floor.cc: read the file, parse every number with fast_float,
# nothing kept) and ReadLog on that CSV. The session is long enough (1.2 M
# rows) that process start does not count.
#
# The recordings hold only the IMU topic, one message a row, written by the
# formats' own writers (not mpcal): Debian's python3-rosbag (ROS 1, chunks
# stored and lz4; bench/bag_bench_ros1.py), Foxglove's @mcap/core (MCAP, CDR,
# chunks stored, lz4 and zstd; bench/bag_bench_mcap.mjs) and Python's sqlite3
# in rosbag2's tables (ROS 2; bench/bag_bench_ros2.py).
#
# The target, for each file: reading its rows takes at most the CPU time of
# the parse floor of the same rows as CSV. A message stored is about three
# times a CSV row's bytes (a ROS 1 record of a sensor_msgs/Imu 378 bytes, an
# MCAP one 371, a ROS 2 row 393; a CSV row of seven shortest-round-trip
# doubles 130), so for a file whose chunks are stored this is reading the
# binary at three times the floor's bytes per second; a compressed file's
# messages are unpacked to those bytes first. Every check the format
# provides is made (the LZ4 frame's content checksum, an MCAP chunk's CRC-32,
# each record's lengths). Memory: the peak within 32 MiB of ReadLog on the
# CSV (the rows held are the same), whatever the file's size.
#
#   bench/bag_read_bench.sh BUILD_DIR [REPETITIONS]
#
# The files (~1.5 GB) are made once into $MPCAL_BAG_READ_BENCH_DIR (default
# /tmp/mpcal_bag_read_bench) and kept for the next run; delete that directory
# to free the space. Each time is the CPU time (user + system) of the
# process, from getrusage of the child; each file's runs alternate with the
# floor's, and each figure is the median of REPETITIONS (default 5) after a
# warm-up that puts the file in the page cache.
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
reps=${2:-5}
here=$(cd "$(dirname "$0")" && pwd)
mpcal=$build/mpcal
floor=$build/bench/mpcal_parse_floor
reader=$build/bench/mpcal_read_log
cache=${MPCAL_BAG_READ_BENCH_DIR:-/tmp/mpcal_bag_read_bench}
python=/usr/bin/python3  # Debian's python, where python3-rosbag is

for exe in "$mpcal" "$floor" "$reader"; do
  [ -x "$exe" ] || { echo "bag_read_bench: $exe not built (make build)" >&2; exit 1; }
done
mkdir -p "$cache"
work=$(mktemp -d "${TMPDIR:-/tmp}/mpcal_bag_read_bench.XXXXXX")
trap 'rm -rf "$work"' EXIT

# 100 s of rest + 26 x (110 s still + 2 s turn) = 3012 s at 400 Hz:
# 1,204,800 rows with the gyroscope.
csv=$cache/session.csv
if [ ! -s "$csv" ]; then
  echo "generating the session (mpcal simulate static --rate 400 --gyro) ..."
  "$mpcal" simulate static --seed 1 --gyro --rate 400 --positions 26 --dwell 110 --turn 2 \
    --rest 100 --digits 0 -o "$csv.tmp" >/dev/null
  mv "$csv.tmp" "$csv"
fi
rows=$(($(grep -c '' "$csv") - 1))

if [ ! -s "$cache/imu_none.bag" ]; then
  have_kb=$(df -Pk "$cache" | awk 'NR == 2 {print $4}')
  if [ "$have_kb" -lt $((2 * 1024 * 1024)) ]; then
    echo "bag_read_bench: SKIP ($cache has $((have_kb / 1024)) MB free, the files need ~2 GB)"
    exit 0
  fi
fi
# make_file FILE CMD...: runs CMD (which writes FILE.tmp) unless FILE exists.
make_file() {
  local file=$1; shift
  [ -e "$file" ] && return 0
  echo "writing $(basename "$file") ..."
  rm -rf "$file.tmp"
  "$@"
  mv "$file.tmp" "$file"
}
files=()
if "$python" -c 'import rosbag, roslz4' 2>/dev/null; then
  for c in none lz4; do
    make_file "$cache/imu_$c.bag" "$python" "$here/bag_bench_ros1.py" "$csv" \
      "$cache/imu_$c.bag.tmp" --compression "$c"
    files+=("imu_$c.bag")
  done
else
  echo "bag_read_bench: the ROS 1 bags are left out (python3-rosbag, python3-roslz4 not installed)"
fi
node_dir=$here/../tests/tools
if [ -d "$node_dir/node_modules/@mcap/core" ] && command -v node >/dev/null; then
  for c in none lz4 zstd; do
    make_file "$cache/imu_$c.mcap" bash -c 'cd "$1" && node "$2" "$3" "$4" --compression "$5" --no-camera' \
      _ "$node_dir" "$here/bag_bench_mcap.mjs" "$csv" "$cache/imu_$c.mcap.tmp" "$c"
    files+=("imu_$c.mcap")
  done
else
  echo "bag_read_bench: the MCAP files are left out (node or npm's @mcap/core not available)"
fi
make_file "$cache/imu_ros2" python3 "$here/bag_bench_ros2.py" "$csv" "$cache/imu_ros2.tmp" \
  --no-camera
files+=(imu_ros2)

# run NAME CMD...: one run; appends "µs peak_kB" to $work/NAME: the CPU time
# (user + system) and peak RSS of CMD alone, from getrusage of the child.
run() {
  local name=$1; shift
  "$python" - "$@" >>"$work/$name" 2>"$work/stderr" <<'PY' || { cat "$work/stderr" >&2; exit 1; }
import resource, subprocess, sys
subprocess.run(sys.argv[1:], stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, check=True)
r = resource.getrusage(resource.RUSAGE_CHILDREN)
print(round((r.ru_utime + r.ru_stime) * 1e6), r.ru_maxrss)
PY
}
median() {
  sort -n -k"$2","$2" "$work/$1" | awk -v c="$2" '{v[NR]=$c} END {print v[int((NR+1)/2)]}'
}
# The bytes of a recording: the file, or a ROS 2 bag directory's database.
data_of() { if [ -d "$1" ]; then echo "$1/$(basename "$1")_0.db3"; else echo "$1"; fi; }

# The same rows on both sides: ReadLog on each file gives the CSV's count.
csv_says=$("$reader" "$csv")
for f in "${files[@]}"; do
  says=$("$reader" "$cache/$f")
  [ "${says%%,*}" = "${csv_says%%,*}" ] ||
    { echo "bag_read_bench: $f: $says, the CSV: $csv_says" >&2; exit 1; }
  cat "$(data_of "$cache/$f")" >/dev/null
done
run warmup "$floor" "$csv"
for _ in $(seq "$reps"); do
  run floor_csv "$floor" "$csv"
  run read_csv "$reader" "$csv"
  for f in "${files[@]}"; do
    run "floor_$f" "$floor" "$csv"
    run "read_$f" "$reader" "$cache/$f"
  done
done

csv_bytes=$(stat -c %s "$csv")
printf 'session: %d IMU rows at 400 Hz with the gyroscope (%s, %.1f MB, %.0f bytes a row);\n' \
  "$rows" "$(basename "$csv")" "$(awk -v b="$csv_bytes" 'BEGIN {print b / 1e6}')" \
  "$(awk -v b="$csv_bytes" -v r="$rows" 'BEGIN {print b / r}')"
echo "CPU time (user + system), median of $reps runs, each file's alternating with the floor's"
printf '%-34s %9s %7s %9s %7s %9s %7s %10s\n' "" "size (MB)" "B/row" "CPU (s)" "ns/row" \
  "floor (s)" "/floor" "peak (MiB)"
line() {  # name bytes cpu_us floor_us peak_kB
  awk -v n="$1" -v b="$2" -v c="$3" -v f="$4" -v k="$5" -v r="$rows" 'BEGIN {
    printf "%-34s %9.1f %7.0f %9.3f %7.0f %9.3f %7.2f %10.0f\n", n, b / 1e6, b / r, c / 1e6,
      1e3 * c / r, f / 1e6, c / f, k / 1024 }'
}
f_csv=$(median floor_csv 1)
line "floor: CSV read + fast_float" "$csv_bytes" "$f_csv" "$f_csv" "$(median floor_csv 2)"
line "ReadLog session.csv" "$csv_bytes" "$(median read_csv 1)" "$f_csv" "$(median read_csv 2)"
for f in "${files[@]}"; do
  line "ReadLog $f" "$(stat -c %s "$(data_of "$cache/$f")")" "$(median "read_$f" 1)" \
    "$(median "floor_$f" 1)" "$(median "read_$f" 2)"
done

# The targets: time at most the floor's; peak within 32 MiB of the CSV's.
csv_kb=$(median read_csv 2)
for f in "${files[@]}"; do
  awk -v n="$f" -v c="$(median "read_$f" 1)" -v fl="$(median "floor_$f" 1)" \
    -v b="$(stat -c %s "$(data_of "$cache/$f")")" -v cb="$csv_bytes" 'BEGIN {
    printf "%s: read %.3f s CPU, the CSV parse floor %.3f s (ratio %.2f, target <= 1; " \
      "the file'"'"'s bytes at %.1f times the floor'"'"'s bytes per second): %s\n", n, c / 1e6, fl / 1e6, c / fl,
      (b / c) / (cb / fl), c <= fl ? "PASS" : "FAIL" }'
  awk -v n="$f" -v k="$(median "read_$f" 2)" -v csv="$csv_kb" \
    -v b="$(stat -c %s "$(data_of "$cache/$f")")" 'BEGIN {
    printf "%s: peak RSS %.0f MiB for a file of %.0f MB, ReadLog on the CSV %.0f MiB " \
      "(target: within 32 MiB of it): %s\n", n, k / 1024, b / 1e6, csv / 1024,
      k <= csv + 32 * 1024 ? "PASS" : "FAIL" }'
done
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
echo "(the files stay in $cache for the next run: rm -r $cache frees $(du -sh "$cache" | cut -f1))"
