#!/usr/bin/env bash
# make bench: every benchmark executable, then every whole-process script.
#   bench/run.sh BUILD_DIR
set -euo pipefail
build=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)
shopt -s nullglob
for exe in "$build"/bench/mpcal_*_bench; do
  echo "=== $(basename "$exe")"
  "$exe"
done
for script in "$here"/*_bench.sh; do
  echo "=== $(basename "$script")"
  bash "$script" "$build"
done
