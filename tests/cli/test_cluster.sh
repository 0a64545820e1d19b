#!/bin/sh
# SPDX-License-Identifier: MIT
# Tests of tools/cluster (issue 13): the GNU parallel recipe run for real on
# this machine with N = 1, 3, 7 shards plus the merge equals the single run
# byte for byte (sweep: the Fig. 15 study of the done-when at N = 3; gallery);
# GNU parallel's --sshlogin form with ':' (this machine through the same code
# path); the Slurm array script with SLURM_ARRAY_TASK_ID set by hand and the
# shard count N its argument covers every point exactly once (N = 1, 3, 7),
# refuses an index >= N or no N, and with the merge script gives the single
# run; a task re-run alone (--array=1 of N = 3: SLURM_ARRAY_TASK_COUNT 1) runs
# shard 1/3 only; the merge prints the commands that re-run a missing shard
# (by hand and as `sbatch --array=K ... shard.sbatch N ...`) and they work;
# slurm-submit.sh asks sbatch (a stand-in that records its arguments) for the
# array with N and an afterany merge job.  tests/cli/test_slurm.sh runs it all
# on a real Slurm.
# usage: test_cluster.sh HYSTVIZ SOURCE_ROOT
set -u
hv=$1
root=$2
case $hv in /*) ;; *) hv=$(pwd)/$hv ;; esac     # the test works in a temporary directory
root=$(cd "$root" && pwd)
. "$(dirname "$0")/../lib.sh"
export HYSTVIZ="$hv"
export HOME="$tmp/home"   # GNU parallel keeps its state (and citation notice) under $HOME
mkdir -p "$HOME/.parallel" && touch "$HOME/.parallel/will-cite"
cl=$root/tools/cluster
fig15=$root/scenes/fig15_minor_loop_ex4.scene
if ! command -v parallel > /dev/null; then
    echo "GNU parallel is not installed (tools/setup.sh installs it)"
    exit 1
fi
cd "$tmp" || exit 1

# ---- GNU parallel: the done-when study, 3 shards + merge == one run ----------
big="--grid model.sigma0=1:10:log10 --grid input.umin2=0.1:0.5:5"
"$hv" sweep "$fig15" $big -o one50 -q -j 2 --plot minor1_area
sh "$cl/parallel.sh" -P 3 3 sweep "$fig15" $big -o par50 -q -j 1 --plot minor1_area 2> err
[ $? -eq 0 ] && ok || bad "parallel.sh 3 sweep: status, $(cat err)"
diff -r one50 par50 > diff && ok || bad "parallel 3 shards + merge differs from the single run: $(head -3 diff)"
[ "$(ls par50 | wc -l)" -eq 153 ] && [ -s par50/sweep_minor1_area.svg ] && ok || bad "parallel study: $(ls par50 | wc -l) files"

small="--grid model.sigma0=1:10:log4 --grid input.umin2=0.2,0.4 --formats svg"
"$hv" sweep "$fig15" $small -o one8 -q
for n in 1 7; do
    sh "$cl/parallel.sh" $n sweep "$fig15" $small -o "par$n" -q -j 1 2> err
    [ $? -eq 0 ] && diff -r one8 "par$n" > /dev/null && ok || bad "parallel.sh $n sweep: $(cat err)"
done
# --sshlogin: ':' is this machine, through parallel's remote-login code path
sh "$cl/parallel.sh" -S : 3 sweep "$fig15" $small -o ssh3 -q -j 1 2> err
[ $? -eq 0 ] && diff -r one8 ssh3 > /dev/null && ok || bad "parallel.sh -S : 3: $(cat err)"
# a value with a space and a quote survives parallel's shell (parallel -q)
"$hv" sweep "$fig15" --grid 'figure.title="a b",x'"'"'y' --formats svg -o q1 -q
sh "$cl/parallel.sh" 2 sweep "$fig15" --grid 'figure.title="a b",x'"'"'y' --formats svg -o q2 -q 2> err
[ $? -eq 0 ] && diff -r q1 q2 > /dev/null && ok || bad "quoted grid values through parallel: $(cat err)"

# gallery: a few real scenes (with the include style.scene)
mkdir sc
for f in style fig02_bimodal_input_smooth fig05_g_stribeck fig15_minor_loop_ex4 fig16_minor_loop_ex4_sigma1; do
    cp "$root/scenes/$f.scene" sc/ || bad "scene $f missing"
done
"$hv" gallery --scenes sc -o g1 -q -j 2
for n in 1 3; do
    sh "$cl/parallel.sh" $n gallery --scenes sc -o "g$n-par" -q -j 1 2> err
    [ $? -eq 0 ] && diff -r -x .manifest g1 "g$n-par" > /dev/null && ok || bad "parallel.sh $n gallery: $(cat err)"
done
sh "$cl/parallel.sh" 0 sweep "$fig15" 2> /dev/null
[ $? -eq 2 ] && ok || bad "parallel.sh N=0 accepted"
sh "$cl/parallel.sh" 2 render "$fig15" 2> /dev/null
[ $? -eq 2 ] && ok || bad "parallel.sh with render accepted"

# ---- Slurm: the array script with the variables set by hand ------------------
# run_array N DIR: every task of --array=0-(N-1) of shard.sbatch N
run_array() {
    id=0
    while [ "$id" -lt "$1" ]; do
        SLURM_ARRAY_TASK_ID=$id SLURM_ARRAY_TASK_COUNT=$1 SLURM_ARRAY_TASK_MIN=0 SLURM_ARRAY_TASK_MAX=$(($1 - 1)) \
            sh "$cl/shard.sbatch" "$1" sweep "$fig15" $small -o "$2" -q || return 1
        id=$((id + 1))
    done
}
# the union of the shards' rows: every point exactly once
covered() { cat "$1"/sweep.shard-*.csv | grep -E '^[0-9]+,' | cut -d, -f1 | sort -n | tr '\n' ' '; }
for n in 1 3 7; do
    run_array $n "sl$n" && ok || bad "array 0-$((n - 1)) task failed"
    [ "$(covered "sl$n")" = "0 1 2 3 4 5 6 7 " ] && ok || bad "array of $n: points covered: $(covered "sl$n")"
    sh "$cl/merge.sbatch" sweep --merge "sl$n" -q && diff -r one8 "sl$n" > /dev/null && ok || bad "array of $n + merge differs"
done
# an index that is no shard of N, no N, no array: refused, nothing written
SLURM_ARRAY_TASK_ID=3 SLURM_ARRAY_TASK_COUNT=4 sh "$cl/shard.sbatch" 3 sweep "$fig15" $small -o over -q 2> err
[ $? -eq 2 ] && grep -q 'not a shard of 3' err && [ ! -e over ] && ok || bad "index 3 of N = 3 accepted: $(cat err)"
SLURM_ARRAY_TASK_ID=0 sh "$cl/shard.sbatch" sweep "$fig15" $small -o non -q 2> err
[ $? -eq 2 ] && grep -q 'shard count' err && [ ! -e non ] && ok || bad "shard.sbatch without N accepted: $(cat err)"
sh "$cl/shard.sbatch" 3 sweep "$fig15" $small -o noarr -q 2> err
[ $? -eq 2 ] && [ ! -e noarr ] && ok || bad "shard.sbatch outside an array accepted"
# a task re-run alone (sbatch --array=1 ... shard.sbatch 3: an array of one
# task) runs shard 1/3, not the whole study as 0/1
SLURM_ARRAY_TASK_ID=1 SLURM_ARRAY_TASK_COUNT=1 SLURM_ARRAY_TASK_MIN=1 SLURM_ARRAY_TASK_MAX=1 \
    sh "$cl/shard.sbatch" 3 sweep "$fig15" $small -o alone -q
[ "$(cd alone && ls sweep.shard-*)" = "sweep.shard-1-of-3.csv" ] && [ "$(covered alone)" = "1 4 7 " ] && ok ||
    bad "task 1 of 3 re-run alone: $(ls alone) $(covered alone)"
# one task missing: the merge names it and prints the commands that re-run it
rm sl3/sweep.csv
for k in 0 2; do SLURM_ARRAY_TASK_ID=$k sh "$cl/shard.sbatch" 3 sweep "$fig15" $small -o sl3 -q; done
HYSTVIZ_CLUSTER=$cl sh "$cl/merge.sbatch" sweep --merge sl3 2> err
[ $? -eq 2 ] && grep -q 'missing: 1/3' err && ok || bad "merge job with a task missing: $(cat err)"
grep -q -- "^    HYSTVIZ=.* sbatch --array=1 $cl/shard.sbatch 3 sweep $fig15 --grid model.sigma0=1:10:log4 --grid input.umin2=0.2,0.4 --formats svg -o sl3 -q\$" err &&
    ok || bad "merge: no sbatch re-run line: $(cat err)"
grep -q -- " sweep $fig15 --grid model.sigma0=1:10:log4 --grid input.umin2=0.2,0.4 --formats svg -o sl3 -q --shard 1/3\$" err &&
    ok || bad "merge: no re-run line by hand: $(cat err)"
# the printed lines, run as printed (sbatch a stand-in running the task here), complete the study
mkdir fake
cat > fake/sbatch <<'EOF2'
#!/bin/sh
# a stand-in for sbatch --array=K: runs the script once with SLURM_ARRAY_TASK_ID=K
a=${1#--array=}
shift
SLURM_ARRAY_TASK_ID=$a sh "$@"
EOF2
chmod +x fake/sbatch
line=$(grep '^    HYSTVIZ=.* sbatch ' err)
(PATH="$tmp/fake:$PATH"; eval "$line") && sh "$cl/merge.sbatch" sweep --merge sl3 -q && diff -r one8 sl3 > /dev/null && ok ||
    bad "the printed sbatch line did not complete the study: $line"
rm sl3/sweep.csv
for k in 0 2; do SLURM_ARRAY_TASK_ID=$k sh "$cl/shard.sbatch" 3 sweep "$fig15" $small -o sl3 -q; done
# merged from another directory: the line changes to the shards' one first
(cd / && "$hv" sweep --merge "$tmp/sl3") 2> err
line=$(grep -- '--shard 1/3$' err)
(cd / && eval "$line") && "$hv" sweep --merge sl3 -q && diff -r one8 sl3 > /dev/null && ok ||
    bad "the printed line by hand did not complete the study: $line"

# ---- slurm-submit.sh with a stand-in sbatch ----------------------------------
mkdir bin
cat > bin/sbatch <<'EOF'
#!/bin/sh
echo "$*" >> "$SBATCH_LOG"
n=$(wc -l < "$SBATCH_LOG")
echo "$((1000 + n));cluster"
EOF
chmod +x bin/sbatch
PATH="$tmp/bin:$PATH" SBATCH_LOG="$tmp/sbatch.log" sh "$cl/slurm-submit.sh" 5 sweep "$fig15" $small -o study > out 2> err
[ $? -eq 0 ] && grep -q 'array job 1001 (5 shards), merge job 1002' out && ok || bad "slurm-submit: $(cat out err)"
sed -n 1p sbatch.log | grep -q -- "--array=0-4 --cpus-per-task=1 $cl/shard.sbatch 5 sweep $fig15 --grid" && ok ||
    bad "array submission: $(sed -n 1p sbatch.log)"
sed -n 2p sbatch.log | grep -q -- "--dependency=afterany:1001 $cl/merge.sbatch sweep --merge study\$" && ok ||
    bad "merge submission: $(sed -n 2p sbatch.log)"

finish "test_cluster"
