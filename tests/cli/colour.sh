#!/usr/bin/env bash
# Colour on a terminal only: the verdict words of `mpcal calibrate` are
# green under a pseudo-terminal (util-linux `script`), plain in a pipe and
# with NO_COLOR set.
#   colour.sh MPCAL LOG ARGS...
set -u
mpcal=$1; shift
esc=$'\x1b'
fail=0
tty_out=$(script -qec "$(printf '%q ' "$mpcal" calibrate "$@")" /dev/null </dev/null)
if ! grep -q "fit *${esc}\[32mgood${esc}\[0m" <<<"$tty_out"; then
  echo "FAIL: no green 'good' on a terminal"; fail=1
fi
pipe_out=$("$mpcal" calibrate "$@" 2>&1 </dev/null)
if grep -q "$esc" <<<"$pipe_out"; then echo "FAIL: colour in a pipe"; fail=1; fi
if ! grep -q "^  fit *good " <<<"$pipe_out"; then echo "FAIL: no plain 'good' in a pipe"; fail=1; fi
no_color_out=$(NO_COLOR=1 script -qec "$(printf '%q ' "$mpcal" calibrate "$@")" /dev/null </dev/null)
if grep -q "$esc" <<<"$no_color_out"; then echo "FAIL: colour with NO_COLOR=1"; fail=1; fi
[ $fail -eq 0 ] || { echo "--- terminal:"; cat -v <<<"$tty_out"; }
exit $fail
