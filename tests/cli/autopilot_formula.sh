#!/bin/sh
# The autopilots' correction, written here from their source, applied to a
# log's raw rows with the parameters `mpcal export` wrote, against `mpcal
# apply` of the calibration `mpcal import` read back from the same file:
#   PX4 (src/lib/sensor_calibration/Accelerometer.hpp, Correct):
#     (data - offset).emult(scale)
#   ArduPilot (AP_InertialSensor_Backend::_rotate_and_correct_accel):
#     accel -= offset; accel.x *= scale.x ...
# Usage: autopilot_formula.sh MPCAL CALIB.json LOG.csv (columns 3-5: ax, ay, az)
set -e
mpcal=$1 calib=$2 log=$3
for ap in px4 ardupilot; do
  "$mpcal" export $ap "$calib" -o $ap.txt > /dev/null 2>&1
  "$mpcal" import $ap $ap.txt -o $ap.json > /dev/null
  "$mpcal" apply $ap.json "$log" -o $ap.csv > /dev/null
  # name value, from either file's lines.
  if [ $ap = px4 ]; then
    grep -v '^#' $ap.txt | awk -F'\t' '{print $3, $4}' > $ap.values
    pat_off=CAL_ACC0_%sOFF pat_scale=CAL_ACC0_%sSCALE
  else
    grep -v '^#' $ap.txt | awk -F',' '{print $1, $2}' > $ap.values
    pat_off=INS_ACCOFFS_%s pat_scale=INS_ACCSCAL_%s
  fi
  awk -v po="$pat_off" -v ps="$pat_scale" '
    FILENAME == ARGV[1] { v[$1] = $2; next }
    FILENAME == ARGV[2] { if ($0 ~ /^[0-9-]/) { n++; split($0, f, ","); for (i = 0; i < 3; i++) raw[n, i] = f[3 + i] }; next }
    $0 ~ /^[0-9-]/ {
      m++; split($0, f, ",")
      for (i = 0; i < 3; i++) {
        ax = substr("XYZ", i + 1, 1)
        want = (raw[m, i] - v[sprintf(po, ax)]) * v[sprintf(ps, ax)]
        d = want - f[3 + i]; if (d < 0) d = -d
        if (d > worst) worst = d
      }
    }
    END {
      if (m == 0 || m != n) { print "rows: " m " corrected, " n " raw"; exit 1 }
      if (worst > 1e-6) { print "largest difference " worst " m/s^2"; exit 1 }
      print m " rows, largest difference " worst " m/s^2"
    }' $ap.values "$log" $ap.csv
done
