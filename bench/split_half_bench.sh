#!/usr/bin/env bash
# Split-half study of the real recordings (README, "Honest 1σ on real
# recordings"): each recording cut by time into two logs, each calibrated,
# the two compared in physical units (z = difference / combined 1σ), and
# `mpcal repeat` on the two halves. PASS when the RMS z is at most 1.25 and
# repeat flags nothing at 1 %. A few seconds.
#
#   bench/split_half_bench.sh BUILD_DIR
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
mpcal=$build/mpcal

[ -x "$mpcal" ] || { echo "split_half_bench: $mpcal not built (make build)" >&2; exit 1; }
python3 "$here/split_half/split_half.py" "$mpcal" "$here/../tests/data/real"
