#!/bin/sh
# SPDX-License-Identifier: MIT
# The README's Slurm example on a real single-node Slurm (issue 19):
# tools/cluster/slurm-local.sh brings up munged, slurmctld and slurmd on
# loopback in a temporary directory; tools/cluster/slurm-submit.sh submits
# the README's study (Fig. 15, 50 points) as an array of 4 shards, held, and
# the merge job (afterany); task 2 is cancelled before it runs and the array
# released; the merge job refuses, printing the line that re-runs shard 2;
# that line, run as printed, and a second merge job (afterany on it) give
# the unsharded study byte for byte.  slurm-wlm and munge are required
# (tools/setup.sh test installs them): without them, or when the daemons do
# not start, the test fails (with their logs), it does not skip.
# usage: test_slurm.sh HYSTVIZ SOURCE_ROOT
set -u
. "$(dirname "$0")/../lib.sh" # (the outer run's $tmp holds the cluster; the body's own stays empty)
if [ "${1:-}" != --body ]; then
    hv=$1
    root=$(cd "$2" && pwd)
    case $hv in /*) ;; *) hv=$(pwd)/$hv ;; esac
    PATH=$PATH:/usr/sbin:/sbin
    for p in slurmctld slurmd munged sbatch; do
        command -v $p > /dev/null ||
            fatal "$p is not installed (Debian: apt-get install slurm-wlm munge; tools/setup.sh test does)"
    done
    cd "$tmp" || fatal "cannot cd to $tmp"
    # the whole run bounded (the daemons' start and every wait have their own deadlines)
    timeout -k 5 150 sh "$root/tools/cluster/slurm-local.sh" sh "$root/tests/cli/test_slurm.sh" --body "$hv" "$root"
    st=$?
    [ $st -eq 124 ] && echo "FAIL: the Slurm run passed its 150 s bound"
    exit $st
fi

# ---- the body: on the local Slurm (SLURM_CONF set) ---------------------------
hv=$2
root=$3
export HYSTVIZ="$hv"
cl=$root/tools/cluster
fig15=$root/scenes/fig15_minor_loop_ex4.scene
grid="--grid model.sigma0=1:10:log10 --grid input.umin2=0.1:0.5:5"
# wait_done JOBID SECONDS: until the job (every task of an array) has left the queue
wait_done() {
    end=$(($(date +%s) + $2))
    while [ -n "$(timeout 10 squeue -h -j "$1" -o %i 2> /dev/null)" ]; do
        if [ "$(date +%s)" -ge $end ]; then
            echo "FAIL: job $1 still queued after $2 s:"
            timeout 10 squeue -j "$1"
            return 1
        fi
        sleep 0.2
    done
}

"$hv" sweep "$fig15" $grid -o one -q -j 1 || bad "the unsharded study"

t0=$(date +%s)
SBATCH_OPTS=--hold sh "$cl/slurm-submit.sh" 4 sweep "$fig15" $grid -o study -q > submit.out 2>&1
[ $? -eq 0 ] && ok || bad "slurm-submit.sh: $(cat submit.out)"
jid=$(sed -n 's/^array job \([0-9]*\) (4 shards), merge job \([0-9]*\)$/\1/p' submit.out)
mid=$(sed -n 's/^array job \([0-9]*\) (4 shards), merge job \([0-9]*\)$/\2/p' submit.out)
if [ -z "$jid" ] || [ -z "$mid" ]; then
    fatal "no job ids in: $(cat submit.out)"
fi
# task 2 cancelled while held (never run), then the rest released
timeout 10 scancel "${jid}_2" && ok || bad "scancel ${jid}_2"
timeout 10 scontrol release "$jid" && timeout 10 scontrol release "$mid" && ok || bad "scontrol release"
wait_done "$jid" 60 && wait_done "$mid" 60 || fatal "the array or the merge job did not end"
t1=$(date +%s)
echo "array of 4 tasks (one cancelled) and the merge job: $((t1 - t0)) s"
out=hystviz-merge-$mid.out
[ ! -e study/sweep.csv ] && ok || bad "the merge wrote sweep.csv with a shard missing"
grep -q '1 of 4 shards missing: 2/4' "$out" && ok || bad "the merge job did not name shard 2/4: $(cat "$out")"
line=$(grep '^    HYSTVIZ=.* sbatch --array=2 ' "$out" | sed 's/^ *//')
expect="sbatch --array=2 $cl/shard.sbatch 4 sweep $fig15 $grid -o study -q"
[ "${line#* }" = "$expect" ] && ok || bad "the re-run line of the merge: '$line', expected '... $expect'"
[ $(ls study | grep -c '^sweep.shard-') -eq 3 ] && ok || bad "study holds: $(ls study | grep shard)"

# the printed line, run as printed, then the merge again (afterany on it)
rid=$(eval "$line" | sed -n 's/^Submitted batch job \([0-9]*\)$/\1/p')
[ -n "$rid" ] && ok || bad "the printed line submitted nothing: $line"
mid2=$(sbatch --parsable --dependency=afterany:"$rid" "$cl/merge.sbatch" sweep --merge study)
wait_done "$rid" 60 && wait_done "${mid2%%;*}" 60 || fatal "the re-run task or the second merge did not end"
echo "re-run task and the second merge job: $(($(date +%s) - t1)) s"
grep -q 'sweep --merge: 4 shards, 50 points: 50 ok' "hystviz-merge-${mid2%%;*}.out" && ok ||
    bad "second merge: $(cat "hystviz-merge-${mid2%%;*}.out")"
diff -r one study > diff.out && ok || bad "the merged study differs from the unsharded one: $(head -n 3 diff.out)"
[ "$(ls study | wc -l)" -eq "$(ls one | wc -l)" ] && ok || bad "study has $(ls study | wc -l) files, one $(ls one | wc -l)"

finish test_slurm
