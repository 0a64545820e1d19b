#!/bin/sh
# SPDX-License-Identifier: MIT
# Tests of hystviz sweep's closed-form kernel (issue 37, src/lib/hy_sweep.c):
# a table-only study of a Dahl/LuGre scene with a bimodal input is computed
# by the kernel, and its table is the pipeline's byte for byte.  Each study
# below runs with the kernel and with HYSTVIZ_SWEEP_GENERIC=1 (the pipeline
# at every point), CSV and .npy, and the tables must be the same bytes (no
# tolerance: the kernel calls the pipeline's own functions, so any
# difference is a bug); the kernel's table also for -j 2 and for 3 shards
# merged.  The summary line says how many points the kernel computed: every
# ok point outside the error sample (1 in 1000) where it applies, none where
# it does not (a γ solve, a text axis) or with the variable set.
# The studies: Fig. 15 at edge values (σ0 from the smallest normal number
# to 1e300; u_min,2 equal to u_min,1, just below u_max,1, 1e-300, and
# invalid: below u_min,1, equal to and above u_max,1), six model and input
# keys at once over 1,152 points (so that point 1000 is in the error sample
# inside the study), Dahl, half-cosine pieces with t1..t4, an input-only
# scene (no steady state: empty columns), points over --max-work (a ystar
# series over a tspan whose period count depends on u_min,1).
# usage: test_sweep_kernel.sh HYSTVIZ SCENES_DIR
set -u
hv=$1
scenes=$2
. "$(dirname "$0")/../lib.sh"
fig15=$scenes/fig15_minor_loop_ex4.scene

# kernel_count FILE: N of "(N by the closed-form kernel)" in a summary line
kernel_count() { sed -n 's/.*ok (\([0-9]*\) by the closed-form kernel).*/\1/p' "$1"; }
# ok_count FILE: the ok points of the summary line
ok_count() { sed -n 's/.*points: \([0-9]*\) ok .*/\1/p' "$1"; }

# same NAME WANT SCENE ARGS...: the study through the kernel and the pipeline;
# WANT: "all" (every ok point outside the sample by the kernel) or "none"
same() {
    name=$1
    want=$2
    shift 2
    d=$tmp/$name
    for table in csv npy; do
        rm -rf "$d"
        "$hv" sweep "$@" --formats none --table $table -o "$d/k" -j 1 2> "$d.k.err"
        rk=$?
        HYSTVIZ_SWEEP_GENERIC=1 "$hv" sweep "$@" --formats none --table $table -o "$d/g" -j 1 2> "$d.g.err"
        rg=$?
        [ -s "$d/g/sweep.$table" ] || { bad "$name ($table): the pipeline wrote no table: $(tail -1 "$d.g.err")"; continue; }
        [ $rk -eq $rg ] && cmp -s "$d/k/sweep.$table" "$d/g/sweep.$table" && ok ||
            bad "$name ($table): the kernel's table (exit $rk) differs from the pipeline's (exit $rg): $(cmp "$d/k/sweep.$table" "$d/g/sweep.$table" 2>&1)"
        nk=$(kernel_count "$d.k.err")
        nok=$(ok_count "$d.k.err")
        ng=$(kernel_count "$d.g.err")
        if [ "$want" = all ]; then
            # ok points outside the error sample (indices 0, 1000, ...; all ok in these studies)
            npts=$(sed -n 's/^sweep: \([0-9]*\) of.*/\1/p' "$d.k.err")
            sample=$(((npts + 999) / 1000))
            [ -n "$nk" ] && [ "$nk" -gt 0 ] && [ "$nk" -ge $((nok - sample)) ] && [ "$nk" -lt "$nok" ] && ok ||
                bad "$name ($table): the kernel computed ${nk:-?} of ${nok:-?} ok points ($sample in the sample)"
        else
            [ "$nk" = 0 ] && ok || bad "$name ($table): the kernel computed ${nk:-?} points where it does not apply"
        fi
        [ "$ng" = 0 ] && ok || bad "$name ($table): HYSTVIZ_SWEEP_GENERIC=1 left ${ng:-?} points to the kernel"
        # -j 2 and 3 shards merged: the same bytes
        "$hv" sweep "$@" --formats none --table $table -o "$d/j2" -j 2 2> /dev/null
        cmp -s "$d/g/sweep.$table" "$d/j2/sweep.$table" && ok || bad "$name ($table): -j 2 differs from the pipeline's table"
        for k in 0 1 2; do
            "$hv" sweep "$@" --formats none --table $table -o "$d/sh" -j 1 --shard $k/3 2> /dev/null
        done
        "$hv" sweep --merge "$d/sh" -q 2> /dev/null
        cmp -s "$d/g/sweep.$table" "$d/sh/sweep.$table" && ok || bad "$name ($table): 3 shards merged differ from the pipeline's table"
    done
}

# Fig. 15 at edge values, invalid points among them (exit 2 on both sides)
same edges all "$fig15" --grid model.sigma0=6,1e-6,0.5,1e5,1e12,2.2250738585072014e-308,1e300 \
    --grid input.umin2=0.2,-0.5,0,0.999999,1,1.2,1e-300
grep -q ', [1-9][0-9]* invalid,' "$tmp/edges.g.err" && ok || bad "edges: no invalid point in the study"
# six keys, 1,152 points: g(0) = fs, fc, σ1 (0 allowed), u_max,2 = u_max,1, u_min,1 < 0, σ0
same keys all "$fig15" --grid model.fs=2,1e-3,1e3 --grid model.fc=1,0.5,3 --grid model.sigma1=1,0 \
    --grid input.umax2=1.5,1 --grid input.umin1=0,-0.3 --grid model.sigma0=0.1:1e3:log16
# Dahl (its own keys), half-cosine pieces at given times
# (a copy without LuGre's keys: a Dahl model refuses them)
sed '/^\(sigma0\|sigma1\|fs\|vs\|beta\) *=/d' "$fig15" >"$tmp/dahl.scene"
cp "$scenes/style.scene" "$tmp/"
same dahl all "$tmp/dahl.scene" --set model.kind=dahl --grid model.rho=2,1e-3,1e4 --grid model.fc=1,0.25 \
    --grid input.umin2=0.3,0,0.7
same cosine all "$fig15" --set input.shape=cosine --set "input.t=1,2.2,3.2,5" --grid input.umin2=0.5,0.1,0 \
    --grid model.sigma0=6,1,40
# an input-only scene: no steady state, its columns empty
same input all "$scenes/fig02_bimodal_input_smooth.scene" --grid input.umin2=0.5,0.1,0 --grid input.umax1=1,2
# over the work budget at some points (invalid rows with the budget's message)
same budget all "$fig15" --set compute.tspan=0,400 --set series.t1.data=ystar --grid input.umin1=-100,-50,0 \
    --grid model.sigma0=1,3 --max-work 1.8e5  # the scene's own 1.72e5 units (hy_cost.h) pass, 2 points do not
grep -q 'budget' "$tmp/budget.g.err" && ok || bad "budget: no point over the budget"
# where the kernel does not apply: a γ solve, a text axis; the variable
same ygamma none "$scenes/fig11_ygamma_ex3.scene" --grid model.sigma0=1,2 --grid input.umin2=0.1,0.3
same text none "$fig15" --grid model.sigma0=1,2 --grid series.minor.style=solid,dashed
rm -rf "$tmp/v"
HYSTVIZ_SWEEP_GENERIC=1 "$hv" sweep "$fig15" --grid model.sigma0=1,2 --formats none -o "$tmp/v" 2> "$tmp/v.err"
[ "$(kernel_count "$tmp/v.err")" = 0 ] && ok || bad "HYSTVIZ_SWEEP_GENERIC=1: the kernel ran: $(cat "$tmp/v.err")"
finish "test_sweep_kernel"
