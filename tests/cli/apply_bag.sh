#!/bin/sh
# `mpcal apply` on a recording, checked by the other tool's own reader:
#
#   apply_bag.sh MPCAL CALIB BAGS_DIR FIXTURE MCAP_PACKAGES
#
# Corrects BAGS_DIR/session.csv (the rows every fixture holds) and
# BAGS_DIR/FIXTURE with CALIB, then reads the corrected recording with
# Debian's rosbag (apply_bag_ros1.py) or Foxglove's @mcap/core
# (apply_bag_mcap.mjs, its packages in MCAP_PACKAGES/node_modules, as
# tests/data/bags/make_mcap.mjs installs them; the environment's
# MPCAL_MCAP_PACKAGES wins), and with mpcal (detect reads it back). Then
# once more with --noise, the covariances set from a noise analysis of a
# simulated still record, checked against N²·f from the JSON. Exit 77
# (skipped) when those packages are not installed.
set -eu
mpcal=$1 calib=$2 bags=$3 fixture=$4 packages=${MPCAL_MCAP_PACKAGES:-$5}
here=$(cd "$(dirname "$0")" && pwd)
work=apply_bag_$(echo "$fixture" | tr . _)
rm -rf "$work" && mkdir "$work" && cd "$work"
"$mpcal" apply "$calib" "$bags/session.csv" -o corrected.csv >/dev/null
"$mpcal" apply "$calib" "$bags/$fixture" -o "out_$fixture" >stdout 2>stderr
cat stdout stderr
grep -q "^mpcal: the covariances are the input's" stderr
"$mpcal" simulate noise --hours 0.1 --rate 20 --seed 3 -o still.csv --truth truth.json >/dev/null
"$mpcal" noise still.csv --json noise.json >/dev/null
"$mpcal" apply "$calib" "$bags/$fixture" -o "noise_$fixture" --noise noise.json 2>stderr >/dev/null
grep -q "^mpcal: the covariances are set from 'noise.json' as N²·f at 20 Hz" stderr
check() {
  case $fixture in
    *.bag) /usr/bin/python3 "$here/apply_bag_ros1.py" "$bags/$fixture" "$@" ;;
    *.mcap) node "$here/apply_bag_mcap.mjs" "$packages" "$bags/$fixture" "$@" ;;
  esac
}
case $fixture in
  *.mcap)
    if [ ! -d "$packages/node_modules/@mcap/core" ]; then
      echo "skipped: no @mcap/core in '$packages/node_modules' (set MPCAL_MCAP_PACKAGES)"
      exit 77
    fi ;;
esac
check "out_$fixture" corrected.csv
check "noise_$fixture" corrected.csv /imu/data noise.json
# mpcal reads its own output: the same 380 messages, the one swapped pair of
# stamps put in time order as in the input.
"$mpcal" detect "out_$fixture" >detect.txt 2>&1 || true
grep -q "^out_$fixture: 380 rows" detect.txt
grep -q "1 message out of order (the furthest 50 ms back) put in time order" detect.txt
