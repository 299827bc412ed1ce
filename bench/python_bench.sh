#!/usr/bin/env bash
# The Python module's speed against the C++ it wraps (bench/python_bench.py):
#   calibrate: mpcal.calibrate on numpy arrays of the 1.7 M-row session of
#              bench/speed_bench.sh against CalibrateRecording on the same
#              rows in C++ (bench/calibrate_floor.cc); target within 1.1x;
#   correct:   Calibration.correct on 10 M rows against the numpy
#              expression of the same affine map; target within 1.5x.
#
#   bench/python_bench.sh BUILD_DIR [REPETITIONS]
#
# Skipped (with a line saying so) when the build has no Python module.
set -euo pipefail
build=$(cd "${1:-build}" && pwd)
reps=${2:-5}
here=$(cd "$(dirname "$0")" && pwd)
python=${MPCAL_PYTHON:-/usr/bin/python3}
if [ ! -d "$build/python/mpcal" ]; then
  echo "python_bench: skipped, $build/python/mpcal not built (needs pybind11-dev and python3-dev)"
  exit 0
fi
[ -x "$build/bench/mpcal_calibrate_floor" ] ||
  { echo "python_bench: $build/bench/mpcal_calibrate_floor not built (make build)" >&2; exit 1; }
PYTHONPATH=$build/python "$python" "$here/python_bench.py" "$build" "$reps"
