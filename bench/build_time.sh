#!/usr/bin/env bash
# A newcomer's first build, timed: clones this repository's committed HEAD into
# a scratch directory, configures it as `make demo` does (Release) and builds
# without the compiler cache, first what `make demo` compiles (the `mpcal_cli`
# target), then the rest of what `make test` compiles (tests, benches,
# examples). Prints, per step, the wall time and the CPU time (user + sys of
# every compiler and linker the build ran) and the wall time that CPU implies
# on JOBS free cores: the figure to quote when the machine is shared.
#
# Takes minutes, so it is not part of `make bench` (bench/run.sh) or CI.
# Needs the packages of scripts/install-deps.sh.
#
#   bash bench/build_time.sh [--demo-only] [JOBS]     JOBS defaults to nproc
set -euo pipefail

demo_only=0
if [ "${1:-}" = "--demo-only" ]; then
  demo_only=1
  shift
fi
jobs=${1:-$(nproc)}

repo=$(git -C "$(dirname "$0")/.." rev-parse --show-toplevel)
scratch=$(mktemp -d "${TMPDIR:-/tmp}/mpcal-build-time.XXXXXX")
trap 'rm -rf "$scratch"' EXIT

git clone --quiet --no-hardlinks "$repo" "$scratch/mpcal"
cd "$scratch/mpcal"
echo "commit $(git rev-parse --short HEAD), $jobs jobs, no compiler cache," \
  "load average $(cut -d' ' -f1-3 /proc/loadavg)"

# An empty launcher keeps ccache out even where it is installed; CCACHE_DISABLE
# covers a launcher set some other way.
export CCACHE_DISABLE=1
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER_LAUNCHER= \
  > "$scratch/configure.log"

# step NAME CMAKE_BUILD_ARGS...: build, then print wall and CPU seconds.
step() {
  local name=$1
  shift
  if ! /usr/bin/time -f '%e %U %S' -o "$scratch/time" \
    cmake --build build -j "$jobs" "$@" > "$scratch/build.log" 2>&1; then
    tail -n 40 "$scratch/build.log" >&2
    echo "build_time.sh: error: the $name build failed (its log's end above)" >&2
    exit 1
  fi
  local wall user sys
  read -r wall user sys < "$scratch/time"
  awk -v n="$name" -v w="$wall" -v u="$user" -v s="$sys" -v j="$jobs" 'BEGIN {
    cpu = u + s
    printf "%-10s wall %6.1f s (%4.1f min)   CPU %6.1f s (%4.1f min)   CPU / %d cores %4.1f min\n",
           n, w, w / 60, cpu, cpu / 60, j, cpu / 60 / j
  }'
}

step "make demo" --target mpcal_cli
if [ "$demo_only" -eq 0 ]; then
  step "make test" # the tests, benches and examples on top of the demo's build
fi
