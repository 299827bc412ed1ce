#!/usr/bin/env bash
# `mpcal noise` on still recordings from bench/independent/gen_still.py (not
# mpcal's simulator): N within 3 %, K inside its interval on at least 90 % of
# the axes where it is measured, B where present (noise_study.py).
#   bench/independent_noise_bench.sh BUILD_DIR [CASES]
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
args=()
[ -n "${2:-}" ] && args=(--cases "$2")
python3 "$here/independent/noise_study.py" "$build/mpcal" "${args[@]}"
