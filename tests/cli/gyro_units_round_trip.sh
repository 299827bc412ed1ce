#!/usr/bin/env bash
# calibrate -> apply -> the corrected gyroscope against the true rates, for
# one unit of the gyroscope's columns and one placement of them.
#   gyro_units_round_trip.sh MPCAL UNITS PLACEMENT
# UNITS: rads, dps (the simulator's rad/s log rewritten in deg/s) or counts.
# PLACEMENT: same (gx, gy, gz in the log) or own (a --gyro-log of its own,
# with a header t,x,y,z).
#
# The true rates are the log corrected by the simulator's true errors
# (--truth): the same samples, so the same noise, and what is left of the
# difference is the calibration's own error, dw = dM w - M db. Each sample
# must lie within 4 of the calibration's 1σ of it, sum_j sd(M_ij) |w_j| +
# sd(b_i) (a bound that holds whatever the correlations) and the 1σ of the
# mean of the bias's random walk over the T s of the session, 2e-5 rad/s/√s
# (the colibri's, presets.cc) times √(T/3): the truth holds the bias at
# time 0, the calibration its mean over the positions. Plus 1e-9 rad/s for
# the digits written. A log in deg/s read as rad/s misses by a factor of
# 57.3, far outside.
set -eu
mpcal=$1
units=$2
placement=$3
case $PWD in */tests/cli/*) rm -rf ./* ;; esac

sim_units=rads
[ "$units" = counts ] && sim_units=counts
"$mpcal" simulate static --preset colibri --gyro --gyro-units "$sim_units" --seed 7 \
  -o sim.csv --truth truth.json >/dev/null
if [ "$units" = dps ]; then
  awk -F, 'BEGIN { OFS = ","; OFMT = CONVFMT = "%.17g"; k = 45 / atan2(1, 1) }
           NR == 1 { print; next } { $5 *= k; $6 *= k; $7 *= k; print }' sim.csv >log.csv
else
  cp sim.csv log.csv
fi

if [ "$placement" = same ]; then
  "$mpcal" calibrate log.csv --gyro-units "$units" --gyro-g-sensitivity off \
    -o c.json >calibrate.txt
else
  cut -d, -f1-4 log.csv >acc.csv
  awk -F, 'NR == 1 { print "t,x,y,z"; next } { print $1 "," $5 "," $6 "," $7 }' \
    log.csv >gyro.csv
  "$mpcal" calibrate acc.csv --gyro-log gyro.csv --gyro-units "$units" \
    --gyro-g-sensitivity off -o c.json >calibrate.txt
fi
grep -q "\"units\": \"$units\"" c.json || {
  echo "c.json does not record the gyroscope's units '$units'"
  exit 1
}

# The calibration's own units (no --gyro-units); the truth's are rad/s or
# counts, so the log's units are given.
"$mpcal" apply c.json log.csv --out-gyro-units rads -o estimated.csv >/dev/null
"$mpcal" apply truth.json log.csv --gyro-units "$units" --out-gyro-units rads \
  -o true.csv >/dev/null

# 1σ of M (row-major) and of the bias from the gyroscope block's "std".
awk '/"gyroscope": \{/ { g = 1 }
     g && /"std": \{/ { s = 1; next }
     s && /"m": \[/ { key = "m"; n = 0; next }
     s && /"bias_radps": \[/ { key = "b"; n = 0; next }
     s && key != "" && /\]/ { key = ""; next }
     s && key != "" { gsub(/[ ,]/, ""); print key, n++, $0 }
     s && /^    \}/ { exit }' c.json >sigma.txt
[ "$(grep -c '' sigma.txt)" -eq 12 ] || {
  echo "c.json: no 1σ of the gyroscope's M and bias"
  cat sigma.txt
  exit 1
}

duration_s=$(tail -n 1 log.csv | cut -d, -f1)
paste -d, estimated.csv true.csv | awk -F, -v sig=sigma.txt -v T="$duration_s" '
  BEGIN {
    while ((getline line < sig) > 0) {
      split(line, f, " ")
      if (f[1] == "m") sm[f[2]] = f[3]; else sb[f[2]] = f[3]
    }
  }
  NR == 1 { next }
  {
    for (i = 0; i < 3; ++i) {
      e = $(5 + i); t = $(12 + i)
      bound = sb[i]
      for (j = 0; j < 3; ++j) { w = $(12 + j); bound += sm[3 * i + j] * (w < 0 ? -w : w) }
      bound = 4 * (bound + 2e-5 * sqrt(T / 3)) + 1e-9
      d = e - t; if (d < 0) d = -d
      if (d / bound > worst) { worst = d / bound; at = NR; axis = i; de = e; dt = t }
      ++checked
    }
  }
  END {
    printf "%d rates checked; worst |estimated - true| is %.3g of its 4-sigma bound\n", checked, worst
    if (checked < 3000 || worst > 1) {
      printf "FAIL at line %d axis %d: estimated %.9g rad/s, true %.9g rad/s\n", at, axis, de, dt
      exit 1
    }
  }'
