#!/usr/bin/env bash
# Holds one mpcal command line's peak resident memory under a bound.
#   peak_rss.sh LIMIT_KIB RUNS WORKDIR -- COMMAND ARGS...
# Runs COMMAND RUNS times in WORKDIR and passes when it succeeds every time
# and the median of its peaks (the kernel's maximum resident set of the
# process, in KiB, as GNU time reports it) is under LIMIT_KIB. The median,
# not each run: on a shared machine a run now and then keeps more pages.
# GNU time rather than a script's own child: the peak of a process started
# by fork counts its parent's pages until the exec, and time's are few.
set -u
limit=$1; runs=$2; workdir=$3; shift 3
[ "$1" = "--" ] && shift
[ -x /usr/bin/time ] || { echo "FAIL: needs GNU time (/usr/bin/time)"; exit 1; }
mkdir -p "$workdir" && cd "$workdir" || exit 2
peaks=()
for _ in $(seq "$runs"); do
  if ! /usr/bin/time -f '%M' -o peak.txt "$@" </dev/null >/dev/null 2>stderr.txt; then
    echo "FAIL: $* failed:"; cat stderr.txt; exit 1
  fi
  peaks+=("$(tail -n1 peak.txt)")
done
median=$(printf '%s\n' "${peaks[@]}" | sort -n | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}')
echo "peaks (KiB): ${peaks[*]}; median $median; limit $limit"
if [ "$median" -ge "$limit" ]; then
  echo "FAIL: median peak $median KiB, limit $limit KiB: $*"
  exit 1
fi
