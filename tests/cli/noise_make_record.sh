#!/usr/bin/env bash
# Makes a record that `mpcal noise` must refuse (or count a gap in) from a
# still one (CSV t,ax,ay,az,gx,gy,gz at 100 Hz, 60,000 rows):
#   stuck        az always 9.81
#   toggling     gx 0.001, 0.002, 0.001, ...
#   rate_change  100 Hz for 300 s, then 200 Hz
#   one_gap      one row dropped
#   long_gap     200 rows dropped (2 s)
#   noise_make_record.sh CASE IN OUT
set -eu
case $1 in
  stuck) awk -F, -v OFS=, 'NR>1{$4="9.81"}1' "$2" >"$3" ;;
  toggling) awk -F, -v OFS=, 'NR>1{$5=(NR%2?"0.001":"0.002")}1' "$2" >"$3" ;;
  rate_change)
    awk -F, -v OFS=, 'NR>1{i=NR-2; $1=sprintf("%.3f", i<30000 ? i*0.01 : 300+(i-30000)*0.005)}1' "$2" >"$3" ;;
  one_gap) awk 'NR!=5000' "$2" >"$3" ;;
  long_gap) awk 'NR<20000 || NR>20200' "$2" >"$3" ;;
  *) echo "unknown case $1" >&2; exit 2 ;;
esac
