#!/usr/bin/env bash
# Installs the Debian packages mpcal needs. Idempotent and non-interactive:
# it installs only what is missing, and runs `apt-get update` first only when
# there is something to install. When not root it prints the apt-get command
# instead of running it.
#
#   scripts/install-deps.sh demo      building the library and the command, and running them
#   scripts/install-deps.sh package   that, and what `make package` adds (dpkg-shlibdeps)
#   scripts/install-deps.sh [all]     that, and what tests, benches, fuzzing and CI add
set -euo pipefail

# The library and the command: what `make demo` builds.
demo=(
  build-essential cmake pkg-config
  libeigen3-dev        # matrices, the error model
  libceres-dev         # nonlinear least squares, autodiff, covariance
  libgeographiclib-dev # WGS84 normal gravity, geodetic <-> local ENU
  libcli11-dev         # command line
  nlohmann-json3-dev   # calibration and result files
  libfmt-dev           # tables and messages
  libfast-float-dev    # parsing numbers from logs
  libyaml-cpp-dev      # Kalibr's imu.yaml (written by the noise analysis)
  libsqlite3-dev       # ROS 2 bags (*.db3)
  libzstd-dev          # MCAP zstd chunks
  liblz4-dev           # ROS 1 and MCAP lz4 chunks (the LZ4 frame format)
  libxxhash-dev        # the LZ4 frame's content checksum (XXH32), header only
  libbz2-dev           # ROS 1 bz2 chunks
  libisal-dev          # MCAP chunks' CRC-32 (Intel ISA-L)
  zlib1g-dev           # zlib's crc32, the reference the CRC-32 is tested against
  libserialport-dev    # serial ports for live sessions (src/record)
)
# The Debian package (cmake/MpcalPackage.cmake).
package=(
  dpkg-dev             # dpkg-shlibdeps: the package's Depends from the binary
  file                 # CPack's DEB generator finds the binaries to give dpkg-shlibdeps
  pybind11-dev python3-dev # the Python module the package carries (python/)
)
# Tests, benches, fuzzing and CI.
develop=(
  libgtest-dev libgmock-dev googletest
  libbenchmark-dev
  chromium             # headless rendering of the HTML report in tests
  python3              # checks the rendered report's DOM and screenshot
  time                 # GNU time: peak memory and CPU in the benches (bench/speed_bench.sh)
  python3-numpy        # bench/independent generators (gen_imu_session.py, gen_still.py)
  python3-jsonschema   # tests/io/schema_test.py: the written files against docs/schemas/
  python3-rosbag python3-sensor-msgs python3-roslz4  # ROS 1 bags by rosbag: written out of order (make_ros1_shuffled.py), read back after apply (apply_bag_ros1.py)
  nodejs               # MCAP files written and read by @mcap/core from npm (tests/tools/)
  clang                # libFuzzer targets (make fuzz)
  clang-format         # the code's layout, checked by scripts/lint.sh (.ci/run)
  clang-tidy           # bug-prone patterns and function size, scripts/lint.sh
  man-db groff-base    # the man pages rendered without a warning (tests/cli/man_pages.sh)
  zsh                  # the zsh completion checked (tests/cli/completion_zsh.zsh)
  socat                # a pseudo-terminal pair standing in for a serial port (tests/cli/record_serial.sh)
  tmux                 # the live screen of record driven and read (tests/cli/record_screen.sh)
  python3-pytest       # its tests (tests/python/)
  python3-matplotlib   # its example (examples/python/), drawn without a display
  python3-setuptools python3-build python3-venv  # `pip install .` and its wheel, offline (docs/guide/python.md)
)

case ${1:-all} in
  demo) packages=("${demo[@]}") ;;
  package) packages=("${demo[@]}" "${package[@]}") ;;
  all) packages=("${demo[@]}" "${package[@]}" "${develop[@]}") ;;
  *)
    echo "mpcal: install-deps.sh: unknown set '$1'; give demo, package or all" >&2
    exit 2
    ;;
esac

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

# The test tools Debian lacks, from the npm registry at the versions
# tests/tools/package-lock.json pins (an MCAP writer and reader that are not
# mpcal's): with `all` only.
install_test_tools() {
  [ "${1:-all}" = all ] || return 0
  local tools
  tools="$(cd "$(dirname "$0")/.." && pwd)/tests/tools"
  [ -d "$tools/node_modules/@mcap/core" ] && return 0
  if ! command -v npm >/dev/null; then
    echo "mpcal: npm not found: the MCAP tests need tests/tools (run npm ci there)" >&2
    return 1
  fi
  echo "mpcal: installing the test tools in tests/tools (npm ci)" >&2
  npm ci --prefix "$tools" --no-audit --no-fund --silent
}

if [ ${#missing[@]} -eq 0 ]; then
  install_test_tools "${1:-all}"
  exit 0
fi

cmd=(apt-get install -y --no-install-recommends "${missing[@]}")
if [ "$(id -u)" -ne 0 ]; then
  echo "mpcal: missing packages: ${missing[*]}" >&2
  echo "run: sudo apt-get update && sudo ${cmd[*]}" >&2
  exit 1
fi
echo "mpcal: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
"${cmd[@]}"
install_test_tools "${1:-all}"
