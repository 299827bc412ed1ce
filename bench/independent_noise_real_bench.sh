#!/usr/bin/env bash
# `mpcal noise` on still records with the effects of real sensors (a
# low-pass filter, a Gauss-Markov bump, a sinusoid, quantisation, a bias
# instability with and without its flat region) from
# bench/independent/gen_still.py: N, tau_c, K and the model check against
# their bars (noise_real_study.py). The records (23 M rows) are generated
# once into $MPCAL_NOISE_REAL_WORK (default /tmp/mpcal_noise_real) and
# reused by the next run.
#   bench/independent_noise_real_bench.sh BUILD_DIR
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
python3 "$here/independent/noise_real_study.py" "$build/mpcal" \
  --work "${MPCAL_NOISE_REAL_WORK:-/tmp/mpcal_noise_real}" --keep-logs
