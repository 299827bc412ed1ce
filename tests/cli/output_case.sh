#!/usr/bin/env bash
# One way an output can be named, for a command that writes one (run under
# expect.sh, in the test's scratch directory).
#   output_case.sh CASE MPCAL ARGS...   (@OUT@ in ARGS: the output path)
# CASE: null (a character device made with mknod, like /dev/null), full (like
# /dev/full: the write fails), fifo, symlink (to a regular file), fd_link (a
# symlink to /proc/self/fd/1), stdout (/dev/stdout), empty (''), stdout_full
# (standard output is /dev/full), stdout_closed (>&-). Checks afterwards that
# no device node, FIFO or link was replaced by a regular file; exits 9 if one
# was, else with mpcal's code.
set -u
case=$1; mpcal=$2; shift 2
case $PWD in */tests/cli/*) rm -rf ./* ;; esac
out=out.file
redirect=""
case $case in
  null) mknod out.file c 1 3 ;;
  full) mknod out.file c 1 7 ;;
  fifo) mkfifo out.file; timeout 60 cat out.file >fifo.got & reader=$! ;;
  symlink) echo old >target.file; ln -s target.file out.file ;;
  fd_link) ln -s /proc/self/fd/1 out.file ;;
  stdout) out=/dev/stdout ;;
  empty) out="" ;;
  stdout_full|stdout_closed) out=quiet.out ;;
  *) echo "output_case.sh: unknown case $case" >&2; exit 2 ;;
esac
args=()
for a in "$@"; do
  if [ "$a" = "@OUT@" ]; then args+=("$out"); else args+=("$a"); fi
done
case $case in
  stdout_full) "$mpcal" "${args[@]}" >/dev/full; code=$? ;;
  stdout_closed) "$mpcal" "${args[@]}" >&-; code=$? ;;
  *) "$mpcal" "${args[@]}"; code=$? ;;
esac
case $case in
  null|full) [ -c out.file ] || { echo "out.file is no longer a device"; exit 9; } ;;
  fifo)
    wait "$reader"
    [ -p out.file ] || { echo "out.file is no longer a FIFO"; exit 9; }
    [ -s fifo.got ] || { echo "nothing came through the FIFO"; exit 9; } ;;
  symlink)
    [ -L out.file ] || { echo "out.file is no longer a link"; exit 9; }
    [ "$(head -c 3 target.file)" != old ] || { echo "the link's target was not written"; exit 9; } ;;
  fd_link) [ -L out.file ] || { echo "out.file is no longer a link"; exit 9; } ;;
esac
echo "exit $code"
exit $code
