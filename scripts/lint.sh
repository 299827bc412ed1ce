#!/usr/bin/env bash
# The habits CI keeps (.ci/run), each a one-line verdict:
#   1. every C++ file is clang-format clean (.clang-format);
#   2. no file in src/ is over 600 lines;
#   3. clang-tidy (.clang-tidy: bugprone-*, performance-*, functions of
#      cognitive complexity <= 40 and <= 80 lines) is clean on src/, apps/
#      and python/.
# usage: scripts/lint.sh [BUILD_DIR]   (clang-tidy's compile commands go to
#        BUILD_DIR/tidy-commands)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
status=0

mapfile -t cxx < <(git ls-files '*.cc' '*.h')
if ! clang-format --dry-run -Werror "${cxx[@]}" 2>/tmp/mpcal-format.$$; then
  grep -o '^[^:]*' /tmp/mpcal-format.$$ | sort -u | sed 's/^/  not formatted: /'
  echo "lint: the files above are not clang-format clean; run: clang-format -i FILE" >&2
  status=1
fi
rm -f /tmp/mpcal-format.$$

while read -r lines file; do
  if [[ $file != total && $lines -gt 600 ]]; then
    echo "lint: $file has $lines lines (at most 600: split it by concern)" >&2
    status=1
  fi
done < <(git ls-files 'src/*.cc' 'src/*.h' | xargs wc -l)

# clang-tidy reads its compile commands from a configure-only tree,
# BUILD_DIR/tidy-commands, of the unity build the library is compiled as:
# each batch of a room's sources is one translation unit, so Eigen's and
# Ceres's headers are parsed and matched once a batch rather than once a
# file, and the diagnostics in the sources a batch includes are reported as
# in a header (.clang-tidy's HeaderFilterRegex). bugprone-suspicious-include
# is left out there: a batch includes .cc files by design.
commands=$build/tidy-commands
if ! cmake -S . -B "$commands" -DMPCAL_UNITY_BUILD=ON -DMPCAL_BUILD_TESTS=OFF \
    -DMPCAL_BUILD_BENCH=OFF -DMPCAL_BUILD_EXAMPLES=OFF >/tmp/mpcal-configure.$$ 2>&1; then
  cat /tmp/mpcal-configure.$$ >&2
  echo "lint: configuring $commands for clang-tidy's compile commands failed (above)" >&2
  exit 1
fi
rm -f /tmp/mpcal-configure.$$
# The one generated header a source includes (`mpcal --version`'s revision).
cmake --build "$commands" --target mpcal_git_revision >/dev/null
# Every translation unit of src/, apps/ and (when pybind11-dev is there and
# it is configured) python/.
units=$(grep -c '"file":' "$commands/compile_commands.json")
if ! run-clang-tidy -quiet -p "$commands" -j "$(nproc)" \
    -checks=-bugprone-suspicious-include >/tmp/mpcal-tidy.$$ 2>&1; then
  grep -E 'warning:|error:' /tmp/mpcal-tidy.$$ | sort -u >&2 || cat /tmp/mpcal-tidy.$$ >&2
  echo "lint: clang-tidy found the problems above" >&2
  status=1
fi
rm -f /tmp/mpcal-tidy.$$
[[ $status == 0 ]] && echo "lint: clang-format, file sizes and clang-tidy clean (${#cxx[@]} files formatted; $units translation units tidied)"
exit $status
