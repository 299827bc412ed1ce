#!/bin/sh
# Two streams at two rates (docs/validation.md, "Two streams at two rates"):
# for each seed and each pair of rates, one simulated session at 2000 Hz is
# split by tests/data/streams/make_streams.py (Python, apart from mpcal's
# reader and resampler) into an accelerometer and a gyroscope stream, each
# at its own rate and jittered stamps, and into the single-stream logs at
# either stream's stamps; each is calibrated, and every parameter of the
# two-stream calibration is compared with each single-stream one in units of
# the single-stream file's 1σ (tests/cli/within_sigma.py).
#
#   sh bench/streams_study.sh BUILD/mpcal [SEEDS]   (SEEDS default "1 2 3")
set -e
M=$1
SEEDS=${2:-"1 2 3"}
HERE=$(cd "$(dirname "$0")/.." && pwd)
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
printf "%-5s %-9s %-28s %-28s %-28s\n" seed rates "two vs single@accel (a/g)" "two vs single@gyro (a/g)" "single@accel vs single@gyro"
for seed in $SEEDS; do
  "$M" simulate static --preset mti-g --gyro --seed "$seed" --positions 12 --dwell 5 \
    --turn 1.5 --rest 3 --rate 2000 --noise-density 0.0005 --digits 9 \
    -o "$W/dense.csv" >/dev/null
  for rates in 63/200 63/400 250/200 250/400; do
    ar=${rates%/*}; gr=${rates#*/}
    rm -rf "$W/s"
    /usr/bin/python3 "$HERE/tests/data/streams/make_streams.py" "$W/dense.csv" "$W/s" \
      --format csv --accel-rate "$ar" --gyro-rate "$gr" --seed "$seed"
    # A session whose twelve positions do not span the sphere (seed 3) is
    # refused by every log of it alike: said, and the next one taken.
    if ! "$M" calibrate "$W/s/accel.csv" --gyro-log "$W/s/gyro.csv" -o "$W/two.json" >/dev/null 2>&1 ||
       ! "$M" calibrate "$W/s/single_at_accel.csv" -o "$W/sa.json" >/dev/null 2>&1 ||
       ! "$M" calibrate "$W/s/single_at_gyro.csv" -o "$W/sg.json" >/dev/null 2>&1; then
      why=$( { "$M" calibrate "$W/s/accel.csv" --gyro-log "$W/s/gyro.csv"
               "$M" calibrate "$W/s/single_at_accel.csv"
               "$M" calibrate "$W/s/single_at_gyro.csv"; } 2>&1 | grep -m1 "^mpcal: error" | cut -c1-70)
      printf "%-5s %-9s not calibrated: %s\n" "$seed" "$rates" "$why"
      continue
    fi
    z() { python3 "$HERE/tests/cli/within_sigma.py" "$1" "$2" 1e9 |
            awk '/^(bias_mps2|scale|non_orth)/ { if ($(NF-1)+0 > a) a = $(NF-1) }
                 /^(m\[|bias_radps)/ { if ($(NF-1)+0 > g) g = $(NF-1) }
                 END { printf "%.2f / %.2f", a, g }'; }
    printf "%-5s %-9s %-28s %-28s %-28s\n" "$seed" "$rates" "$(z "$W/sa.json" "$W/two.json")" \
      "$(z "$W/sg.json" "$W/two.json")" "$(z "$W/sg.json" "$W/sa.json")"
  done
done
