#!/usr/bin/env bash
# `mpcal noise` gives one answer to "how long must I record": the table's
# finding, the Kalibr warning, the Kalibr file's comment, the JSON's
# record_needed_s (formatted as every output formats a record length) and
# the files and warnings of `mpcal export` name the same figure for the
# gyroscope's random walk.
#   noise_one_record_length.sh MPCAL RECORD WORKDIR
set -eu
mpcal=$1; record=$2; workdir=$3
mkdir -p "$workdir" && cd "$workdir"
"$mpcal" noise -v "$record" --kalibr k.yaml --json n.json >out.txt 2>err.txt
"$mpcal" export vins n.json -o v.yaml >vout.txt 2>verr.txt
"$mpcal" export openvins n.json "$(dirname "$0")/../data/xsens_imu_half1.json" -o o.yaml >oout.txt 2>oerr.txt
table=$(sed -n 's/^gyroscope rate random walk K on .*record at least \([0-9.]* [a-z]*\) (if .*/\1/p' out.txt)
warning=$(sed -n 's/.*gyroscope_random_walk was not measured.*record at least \([0-9.]* [a-z]*\) to measure it$/\1/p' err.txt)
comment=$(sed -n 's/^# gyroscope_random_walk .*record at least \([0-9.]* [a-z]*\) to measure it.*/\1/p' k.yaml)
# FormatRecordLength: h with one decimal from an hour, whole minutes from a minute, else s.
json=$(python3 -c '
import json, sys
s = json.load(open("n.json"))["gyroscope"]["record_needed_s"]["random_walk"]
print("%.1f h" % (s / 3600) if s >= 3600 else "%.0f min" % (s / 60) if s >= 60 else "%.0f s" % s)')
vins_warning=$(sed -n 's/.*gyr_w was not measured.*record at least \([0-9.]* [a-z]*\) to measure it$/\1/p' verr.txt)
vins_comment=$(sed -n 's/^# gyr_w NOT MEASURED.*record at least \([0-9.]* [a-z]*\) to measure it.*/\1/p' v.yaml)
openvins_comment=$(sed -n 's/^ *# gyroscope_random_walk NOT MEASURED.*record at least \([0-9.]* [a-z]*\) to measure it.*/\1/p' o.yaml)
echo "table '$table', warning '$warning', file comment '$comment', JSON '$json'," \
     "export vins warning '$vins_warning' and comment '$vins_comment', openvins comment '$openvins_comment'"
[ -n "$table" ]
for v in "$warning" "$comment" "$json" "$vins_warning" "$vins_comment" "$openvins_comment"; do
  [ "$v" = "$table" ]
done
