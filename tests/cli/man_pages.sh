#!/usr/bin/env bash
# Checks the man pages the build wrote: one per command --help lists (and no
# other), each rendered by man(1) without a warning, each naming every flag
# and word its command's --help shows in its option column.
#   man_pages.sh MPCAL MANDIR
set -u
mpcal=$1; mandir=$2
fail=0
err=$(mktemp)
trap 'rm -f "$err"' EXIT

# The subcommands `mpcal WORDS... --help` lists under "Subcommands:".
subcommands() {
  "$mpcal" "$@" --help | awk '/^Subcommands:/ {s = 1; next} s && /^  [a-z]/ {print $1} s && !/^  / {s = 0}'
}
commands=("")
for ((k = 0; k < ${#commands[@]}; k++)); do
  for sub in $(subcommands ${commands[k]}); do commands+=("${commands[k]:+${commands[k]} }$sub"); done
done

pages=0
for command in "${commands[@]}"; do
  page="$mandir/mpcal${command:+-${command// /-}}.1"
  pages=$((pages + 1))
  if [ ! -f "$page" ]; then echo "FAIL: no page $page for 'mpcal $command'"; fail=1; continue; fi
  text=$(MANWIDTH=80 MANPAGER=cat PAGER=cat man --warnings -l "$page" 2>"$err")
  if [ -s "$err" ]; then
    echo "FAIL: man --warnings -l $page:"; cat "$err"; fail=1
  fi
  # The option column of --help: "  -o,--output TEXT:PATH  ..." gives -o, --output.
  for flag in $("$mpcal" $command --help | grep -E '^  +-' | awk '{print $1}' | tr ',' ' '); do
    if ! grep -qE -- "(^|[^A-Za-z0-9-])${flag}([^A-Za-z0-9-]|$)" <<<"$text"; then
      echo "FAIL: $page does not name $flag"; fail=1
    fi
  done
  # The usage line: "Usage: mpcal calibrate [OPTIONS] INPUT".
  usage=$("$mpcal" $command --help | sed -n 's/^Usage: //p')
  if ! grep -qF -- "$usage" <<<"$text"; then
    echo "FAIL: $page does not show the usage '$usage'"; fail=1
  fi
done

found=$(find "$mandir" -name '*.1' | wc -l)
if [ "$found" -ne "$pages" ]; then
  echo "FAIL: $found pages in $mandir for $pages commands"; fail=1
fi
[ $fail -eq 0 ] && echo "$pages pages checked"
exit $fail
