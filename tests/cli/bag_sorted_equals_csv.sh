#!/bin/sh
# A session calibrated from its CSV and from a ROS 1 bag of the same rows
# written out of order, twice and with impostors at their stamps by Debian's
# rosbag (tests/data/bags/make_ros1_shuffled.py): the same calibration, every
# number identical; and the warning counts what the script did.
#   bag_sorted_equals_csv.sh MPCAL BAGS_DIR CLI_DIR WORKDIR
set -eu
mpcal=$1 bags=$2 cli=$3 work=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work"
# 128 Hz: every time is a whole number of ns, as the bag's stamps are.
"$mpcal" simulate static --preset mti-g --gyro --rate 128 --seed 2 --digits 0 -o s.csv >/dev/null
/usr/bin/python3 "$bags/make_ros1_shuffled.py" --csv s.csv --out shuffled.bag >made.txt
"$mpcal" calibrate s.csv -o csv.json >/dev/null 2>csv_err.txt
"$mpcal" calibrate shuffled.bag -o bag.json >/dev/null 2>bag_err.txt
python3 "$cli/same_numbers.py" csv.json bag.json provenance.input input.columns \
  input.time_unit
# made.txt: "out_of_order=N worst_back_ms=X duplicated=N same_time_other_readings=N"
eval "$(tr ' ' '\n' <made.txt)"
plural() { [ "$1" -eq 1 ] && echo "$1 message" || echo "$1 messages"; }
line="shuffled.bag: $(plural "$out_of_order") out of order (the furthest ${worst_back_ms} ms back) put in time order; $(plural "$duplicated") recorded twice (same time and readings) dropped; $(plural "$same_time_other_readings") at the time of an earlier one with other readings dropped (the first kept)"
if ! grep -qF "mpcal: warning: $line" bag_err.txt; then
  echo "FAIL: the warning does not say what the script made: $(cat made.txt)"
  echo "expected: mpcal: warning: $line"
  echo "got:"; cat bag_err.txt
  exit 1
fi
[ "$out_of_order" -gt 0 ] && [ "$duplicated" -gt 0 ] && [ "$same_time_other_readings" -gt 0 ]
echo "bag_sorted_equals_csv: same calibration; $(cat made.txt)"
