#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/) with clang and runs each for SECONDS
# (default 60), one after the other, starting from the seed corpus in
# tests/fuzz/<target>/. New inputs go to build-fuzz/corpus/<target>/ (the seed
# corpus in the source tree is left alone); a crash is saved in
# build-fuzz/artifacts/<target>/ and makes the script exit non-zero.
#   scripts/fuzz.sh [SECONDS]           (make fuzz FUZZ_SECONDS=600)
# Environment: FUZZ_BUILD (build directory), FUZZ_TARGETS (names, default
# all), JOBS (build parallelism).
set -euo pipefail
seconds=${1:-60}
root=$(cd "$(dirname "$0")/.." && pwd)
build=${FUZZ_BUILD:-$root/build-fuzz}
targets=${FUZZ_TARGETS:-"log_reader live_log calibration_file gnss_reader ros1_bag mcap_bag ros2_bag import"}
jobs=${JOBS:-$(nproc)}

# Debian's clang (bookworm: 14); libFuzzer comes with it.
cc=clang-14; cxx=clang++-14
command -v "$cxx" >/dev/null || { cc=clang; cxx=clang++; }
command -v "$cxx" >/dev/null || { echo "fuzz.sh: clang++ not found (apt-get install clang)" >&2; exit 2; }

CC=$cc CXX=$cxx cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DMPCAL_FUZZ=ON -DMPCAL_BUILD_TESTS=OFF -DMPCAL_BUILD_BENCH=OFF -DMPCAL_BUILD_EXAMPLES=OFF >/dev/null
build_targets=()
for t in $targets; do build_targets+=("${t}_fuzzer"); done
cmake --build "$build" -j "$jobs" --target "${build_targets[@]}" >"$build/build.log" 2>&1 ||
  { cat "$build/build.log" >&2; echo "fuzz.sh: build failed" >&2; exit 2; }

status=0
for t in $targets; do
  corpus=$build/corpus/$t
  artifacts=$build/artifacts/$t/
  mkdir -p "$corpus" "$artifacts"
  dict=()
  [ -f "$root/tests/fuzz/$t.dict" ] && dict=(-dict="$root/tests/fuzz/$t.dict")
  # Inputs of up to 16 KiB; a ROS 1 bag's seeds up to 32 KiB, so that one
  # with camera images between its IMU messages keeps its index (at the end).
  max_len=16384
  [ "$t" = ros1_bag ] && max_len=32768
  echo "== $t: ${seconds} s"
  # Corpus dirs: the first receives new inputs, the seeds are read only.
  if ! "$build/fuzz/${t}_fuzzer" "$corpus" "$root/tests/fuzz/$t" "${dict[@]}" \
      -max_total_time="$seconds" -max_len="$max_len" -timeout=10 -rss_limit_mb=2048 \
      -artifact_prefix="$artifacts" -print_final_stats=1 2>"$build/$t.log"; then
    status=1
    grep -E -A25 '^==[0-9]+==|invariant broken|does not read back|deadly signal' "$build/$t.log" |
      head -n 40 >&2 || true
    echo "fuzz.sh: $t found a crash; see $build/$t.log and $artifacts" >&2
  fi
  grep -E '^(#[0-9]+[[:space:]]+DONE|stat::number_of_executed_units|stat::peak_rss_mb)' \
    "$build/$t.log" || true
done
exit $status
