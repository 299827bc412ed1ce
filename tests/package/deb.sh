#!/usr/bin/env bash
# Builds the Debian package of this build tree with CPack
# (cmake/MpcalPackage.cmake) and checks it as a user would meet it: every
# package it Depends on is installed here at a version it accepts; unpacked
# into a fresh folder, its mpcal prints the build's version and runs the
# demo, its man pages render without a warning, and it holds the bash and zsh
# completion, the headers and the CMake package files.
#   deb.sh BUILD_DIR SCRATCH_DIR
set -u
build=$1; scratch=$2
fail=0
rm -rf "$scratch"
mkdir -p "$scratch/out" "$scratch/root" "$scratch/run"
if ! cpack -G DEB --config "$build/CPackConfig.cmake" -B "$scratch/out" >"$scratch/cpack.log" 2>&1; then
  echo "FAIL: cpack"; cat "$scratch/cpack.log"; exit 1
fi
debs=("$scratch"/out/mpcal_*.deb)
if [ ${#debs[@]} -ne 1 ] || [ ! -f "${debs[0]}" ]; then
  echo "FAIL: expected one mpcal_*.deb in $scratch/out:"; ls "$scratch/out"; exit 1
fi
deb=${debs[0]}
echo "package: $deb"

# Depends: "libc6 (>= 2.34), libceres3 (>= 2.1.0), ..."
depends=$(dpkg-deb -f "$deb" Depends)
if [ -z "$depends" ]; then echo "FAIL: no Depends declared"; fail=1; fi
IFS=',' read -ra items <<<"$depends"
for item in "${items[@]}"; do
  # An alternative "a | b" is met by either.
  met=0
  IFS='|' read -ra alternatives <<<"$item"
  for alt in "${alternatives[@]}"; do
    read -r name relation version <<<"$(sed -E 's/[()]/ /g' <<<"$alt")"
    installed=$(dpkg-query -W -f='${Status} ${Version}' "$name" 2>/dev/null)
    [[ $installed == "install ok installed "* ]] || continue
    if [ -z "${relation:-}" ] || dpkg --compare-versions "${installed##* }" "$relation" "$version"; then
      met=1
    fi
  done
  if [ $met -eq 0 ]; then echo "FAIL: Depends '$item' is not installed here"; fail=1; fi
done
echo "Depends: $depends"

dpkg-deb -x "$deb" "$scratch/root"
root=$scratch/root
mpcal=$root/usr/bin/mpcal
if [ "$("$mpcal" --version)" != "$("$build/mpcal" --version)" ]; then
  echo "FAIL: the package's mpcal --version: '$("$mpcal" --version)', the build's: '$("$build/mpcal" --version)'"
  fail=1
fi
if ! (cd "$scratch/run" && "$mpcal" demo >demo.log 2>&1); then
  echo "FAIL: mpcal demo from the package:"; cat "$scratch/run/demo.log"; fail=1
fi
page=$root/usr/share/man/man1/mpcal-calibrate.1
if [ ! -f "$page" ]; then
  echo "FAIL: no $page"; fail=1
elif ! MANPAGER=cat man --warnings -l "$page" 2>"$scratch/man.err" | grep -q -- '--units'; then
  echo "FAIL: man -l $page"; cat "$scratch/man.err"; fail=1
elif [ -s "$scratch/man.err" ]; then
  echo "FAIL: man warns on $page:"; cat "$scratch/man.err"; fail=1
fi
for f in usr/share/man/man1/mpcal.1 usr/share/bash-completion/completions/mpcal \
         usr/share/zsh/vendor-completions/_mpcal \
         usr/include/mpcal/calibrate.h; do
  [ -f "$root/$f" ] || { echo "FAIL: the package has no /$f"; fail=1; }
done
if [ -z "$(find "$root/usr/lib" -name mpcalConfig.cmake)" ]; then
  echo "FAIL: the package has no mpcalConfig.cmake"; fail=1
fi
# The Python module, when the build made one: it imports from the package.
if [ -d "$build/python/mpcal" ]; then
  init=$(find "$root/usr/lib" -path '*-packages/mpcal/__init__.py' | head -n1)
  if [ -z "$init" ]; then
    echo "FAIL: the package has no Python module mpcal"; fail=1
  elif ! version=$(cd "$scratch/run" && PYTHONPATH=$(dirname "$(dirname "$init")") \
                     /usr/bin/python3 -c 'import mpcal; print(mpcal.__version__)' 2>&1) ||
       [ "$version" != "$("$build/mpcal" --version | awk '{print $2}')" ]; then
    echo "FAIL: import mpcal from the package: $version"; fail=1
  fi
fi
[ $fail -eq 0 ] && echo "package checked"
exit $fail
