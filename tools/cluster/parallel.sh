#!/bin/sh
# SPDX-License-Identifier: MIT
# tools/cluster/parallel.sh: a hystviz sweep or gallery split into N shards run
# by GNU parallel (Debian package `parallel`), on this machine's cores or on
# several machines (-S, GNU parallel's --sshlogin), then merged.
#
# usage: tools/cluster/parallel.sh [-S SSHLOGINS] [-P JOBS] N sweep SCENE --grid ... [-o DIR] [...]
#        tools/cluster/parallel.sh [-S SSHLOGINS] [-P JOBS] N gallery [--scenes DIR] [-o DIR] [...]
#
# It runs, for K = 0 .. N-1,   hystviz ARGS... --shard K/N
# then                         hystviz sweep --merge DIR     (sweep)
#                              hystviz gallery ARGS... --merge   (gallery)
# which is the one-liner
#   parallel -q hystviz sweep S --grid ... -o DIR -j 1 --shard {}/N ::: $(seq 0 N-1) && hystviz sweep --merge DIR
# with the exit statuses collected.  -P JOBS: shards at a time per machine
# (GNU parallel -j; default: one per core).  With -S every machine must see
# the scene files and DIR at the same path (a shared file system, as on a
# cluster); shards write disjoint files, so directories filled on separate
# machines may also be copied together before the merge.
# HYSTVIZ: the hystviz program (default: hystviz from PATH).
#
# Exit status: the merge's (0 all done; 2 refused: a shard missing, its list
# printed; 1 or 2 as hystviz sweep/gallery for failed or invalid points), or 2
# for a usage error.
set -u
hv=${HYSTVIZ:-hystviz}
ssh=
jobs=
while [ $# -gt 0 ]; do
    case $1 in
    -S) [ $# -ge 2 ] || { echo "parallel.sh: -S needs a value" >&2; exit 2; }; ssh=$2; shift 2 ;;
    -P) [ $# -ge 2 ] || { echo "parallel.sh: -P needs a value" >&2; exit 2; }; jobs=$2; shift 2 ;;
    *) break ;;
    esac
done
if [ $# -lt 2 ]; then
    sed -n '4,6p' "$0" | sed 's/^# //' >&2
    exit 2
fi
n=$1
cmd=$2
shift 2
case $n in
'' | *[!0-9]* | 0*) echo "parallel.sh: N must be a positive integer (got '$n')" >&2; exit 2 ;;
esac
[ "$cmd" = sweep ] || [ "$cmd" = gallery ] || { echo "parallel.sh: the command is sweep or gallery (got '$cmd')" >&2; exit 2; }
command -v parallel > /dev/null || { echo "parallel.sh: GNU parallel is not installed (Debian: apt-get install parallel)" >&2; exit 3; }

# the merge: sweep --merge DIR [--plot C] (from -o/--output, default sweep, and --plot); gallery ARGS --merge
out=sweep
plot=
prev=
for a in "$@"; do
    case $prev in -o | --output) out=$a ;; --plot) plot=$a ;; esac
    prev=$a
done

set -- "$cmd" "$@"
popts="--halt never"
[ -n "$ssh" ] && popts="$popts --sshlogin $ssh --workdir $(pwd)"
[ -n "$jobs" ] && popts="$popts -j $jobs"
# shellcheck disable=SC2086 # popts is a list of words
parallel $popts -q "$hv" "$@" --shard "{}/$n" ::: $(seq 0 $((n - 1)))
shard_status=$?
if [ "$cmd" = sweep ]; then
    "$hv" sweep --merge "$out" ${plot:+--plot "$plot"}
else
    "$hv" "$@" --merge
fi
st=$?
[ $st -eq 0 ] && [ $shard_status -ne 0 ] && st=1
exit $st
