#!/usr/bin/env bash
# mpcal's estimates and their 1σ on sessions that its own simulator did not
# make: bench/independent/gen_session.py, written in plain Python from the
# error model (docs/method.md §2) and the README's conventions, with hand turns,
# tremor, bumps, placement wobble, coloured noise and 14 logger formats in g,
# m/s² or raw counts. Per parameter the RMS of z = (estimate − truth)/σ over
# 60 sessions; PASS when every session ran and z over all parameters has an
# RMS within 0.8-1.25. About a minute on two cores: generating the sessions
# in plain Python takes most of it (one session per core at a time).
#
#   bench/independent_bench.sh BUILD_DIR
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
mpcal=$build/mpcal

[ -x "$mpcal" ] || { echo "independent_bench: $mpcal not built (make build)" >&2; exit 1; }
python3 "$here/independent/study.py" "$mpcal" --sessions 60
