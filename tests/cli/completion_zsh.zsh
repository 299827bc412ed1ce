#!/usr/bin/env zsh
# Checks the zsh completion the build wrote without a terminal: the file
# becomes the function _mpcal (as zsh's autoload makes it), and compadd,
# _files and compset are stood in for by functions that collect the
# candidates, filtered by the prefix typed as zsh's own would.
#   zsh completion_zsh.zsh MPCAL COMPLETION_FILE
mpcal=$1
functions[_mpcal]=$(<$2)
fail=0
typeset -a reply

compadd() {
  [[ $1 == -- ]] && shift
  local w
  for w in "$@"; do [[ $w == ${PREFIX}* ]] && reply+=("$w"); done
}
_files() { reply+=(${PREFIX}*(N)) }
compset() { [[ $1 == -P ]] && PREFIX=${PREFIX#*=} }

# The candidates for the words given, the last being the one completed.
candidates() {
  local -a words=("$@")
  local CURRENT=$#words PREFIX=${words[-1]}
  reply=()
  _mpcal
  print -r -- ${(j: :)${(o)reply}}
}
expect() {
  local want=$1; shift
  local got=$(candidates "$@")
  if [[ $got != $want ]]; then
    print -r -- "FAIL: '$*<TAB>' gave '$got', expected '$want'"; fail=1
  fi
}

expect "calibrate" mpcal cal
expect "--units" mpcal calibrate --un
expect "counts g mps2" mpcal calibrate --units ""
expect "counts g mps2" mpcal calibrate --units=
expect "bias-scale-6 shin-el-sheimy-9" mpcal calibrate session.csv --units=g --model ""
expect "--model" mpcal calibrate --units g --mod
expect "" mpcal calibrate --gravity ""
expect "static" mpcal simulate st
expect "--truth" mpcal simulate static --tru
want=$("$mpcal" --help | awk '/^Subcommands:/ {s = 1; next} s && /^  [a-z]/ {print $1}' | sort | tr '\n' ' ' | sed 's/ $//')
expect "$want" mpcal ""

scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
touch "$scratch/session.csv" "$scratch/settings.json"
cd "$scratch" || exit 2
expect "session.csv settings.json" mpcal calibrate -o ""
expect "session.csv" mpcal calibrate ses
(( fail == 0 )) && print "zsh completion checked"
exit $fail
