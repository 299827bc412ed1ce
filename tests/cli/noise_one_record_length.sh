#!/usr/bin/env bash
# `mpcal noise` gives one answer to "how long must I record": the table's
# finding, the Kalibr warning and the Kalibr file's comment name the same
# figure for the gyroscope's random walk.
#   noise_one_record_length.sh MPCAL RECORD WORKDIR
set -eu
mpcal=$1; record=$2; workdir=$3
mkdir -p "$workdir" && cd "$workdir"
"$mpcal" noise -v "$record" --kalibr k.yaml --json n.json >out.txt 2>err.txt
table=$(sed -n 's/^gyroscope rate random walk K on .*record at least \([0-9.]* [a-z]*\) (if .*/\1/p' out.txt)
warning=$(sed -n 's/.*gyroscope_random_walk was not measured.*record at least \([0-9.]* [a-z]*\) to measure it$/\1/p' err.txt)
comment=$(sed -n 's/^# gyroscope_random_walk .*record at least \([0-9.]* [a-z]*\) to measure it.*/\1/p' k.yaml)
echo "table '$table', warning '$warning', file comment '$comment'"
[ -n "$table" ] && [ "$table" = "$warning" ] && [ "$table" = "$comment" ]
