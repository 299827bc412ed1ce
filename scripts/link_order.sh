#!/usr/bin/env bash
# Writes apps/mpcal/calibrate.order: the functions of the mpcal executable
# that `mpcal calibrate` runs on the Xsens accelerometer recording, writing
# the calibration file, one mangled name a line, as callgrind sees them.
# Linked with lld, mpcal lays these out first and together
# (apps/mpcal/CMakeLists.txt): the kernel maps an executable's code 64 KiB
# around each page first run, so code run once but spread over the 6 MB of
# text is resident as a whole. Names no longer in the code are ignored by the
# link, and new functions lie where they would anyway: rerun this after
# changes to what calibrate runs. (The gyroscope's functions added after
# these grew the accelerometer's peak by 0.3 MB: they lie where they would.)
#
#   scripts/link_order.sh [BUILD_DIR]     (needs valgrind)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
exe=$(readlink -f "$build/mpcal")
data=tests/data/real/xsens-multiposition
work=$(mktemp -d "${TMPDIR:-/tmp}/mpcal_order.XXXXXX")
trap 'rm -rf "$work"' EXIT

valgrind --tool=callgrind --demangle=no --compress-strings=no --compress-pos=no \
  --callgrind-out-file="$work/callgrind.out" "$exe" calibrate "$data/xsens_acc.mat" \
  --units counts --gravity 9.81744 -o "$work/c.json" >/dev/null 2>"$work/log" ||
  { cat "$work/log" >&2; exit 1; }

python3 - "$exe" "$work/callgrind.out" >apps/mpcal/calibrate.order <<'PY'
import os
import sys

exe, profile = sys.argv[1:]
names = set()
obj = None
for line in open(profile):
    if line.startswith("ob="):
        obj = os.path.realpath(line[3:].strip())
    elif line.startswith("fn=") and obj == exe:
        name = line[3:].strip()
        if not name.startswith(("0x", "(")):
            names.add(name)
print("\n".join(sorted(names)))
PY
echo "link_order: $(wc -l <apps/mpcal/calibrate.order) functions in apps/mpcal/calibrate.order"
