#!/bin/sh
# SPDX-License-Identifier: MIT
# tools/cluster/slurm-submit.sh: submits a hystviz sweep or gallery as a Slurm
# job array of N shards (tools/cluster/shard.sbatch) and a merge job that
# starts when the array is done (tools/cluster/merge.sbatch, afterany).
#
# usage: tools/cluster/slurm-submit.sh N sweep SCENE --grid ... [-o DIR] [...]
#        tools/cluster/slurm-submit.sh N gallery [--scenes DIR] [-o DIR] [...]
# SBATCH_OPTS: extra sbatch options for both jobs (e.g. "--partition=short
# --time=1:00:00"); CPUS: --cpus-per-task of each shard (default 1).
# Prints the two job ids.  Re-run a failed shard K alone with
#   sbatch --array=K tools/cluster/shard.sbatch N sweep SCENE ...  (the same
# arguments), then merge again; the merge job's output (hystviz-merge-ID.out)
# holds these lines for every missing shard.
# Size the shards so that each runs for minutes: a task costs a few seconds
# of scheduling (about 3 s measured on a single-node Slurm, README).
set -u
here=$(cd "$(dirname "$0")" && pwd)
# the merge prints re-run lines naming $here/shard.sbatch (sbatch passes the environment on)
export HYSTVIZ_CLUSTER="$here"
[ $# -ge 2 ] || { sed -n '6,7p' "$0" | sed 's/^# //' >&2; exit 2; }
n=$1
cmd=$2
shift 2
case $n in
'' | *[!0-9]* | 0*) echo "slurm-submit.sh: N must be a positive integer (got '$n')" >&2; exit 2 ;;
esac
[ "$cmd" = sweep ] || [ "$cmd" = gallery ] || { echo "slurm-submit.sh: the command is sweep or gallery" >&2; exit 2; }
out=sweep
plot=
prev=
for a in "$@"; do
    case $prev in -o | --output) out=$a ;; --plot) plot=$a ;; esac
    prev=$a
done
# shellcheck disable=SC2086 # SBATCH_OPTS is a list of words
jid=$(sbatch --parsable ${SBATCH_OPTS:-} --array=0-$((n - 1)) --cpus-per-task="${CPUS:-1}" "$here/shard.sbatch" "$n" "$cmd" "$@") ||
    { echo "slurm-submit.sh: sbatch of the array failed" >&2; exit 1; }
jid=${jid%%;*}
if [ "$cmd" = sweep ]; then
    # shellcheck disable=SC2086
    mid=$(sbatch --parsable ${SBATCH_OPTS:-} --dependency=afterany:"$jid" "$here/merge.sbatch" sweep --merge "$out" ${plot:+--plot "$plot"})
else
    # shellcheck disable=SC2086
    mid=$(sbatch --parsable ${SBATCH_OPTS:-} --dependency=afterany:"$jid" "$here/merge.sbatch" gallery "$@" --merge)
fi || { echo "slurm-submit.sh: sbatch of the merge failed (array job $jid is queued)" >&2; exit 1; }
echo "array job $jid ($n shards), merge job ${mid%%;*}"
echo "re-run shard K: sbatch ${SBATCH_OPTS:+$SBATCH_OPTS }--array=K --cpus-per-task=${CPUS:-1} $here/shard.sbatch $n $cmd ..."
