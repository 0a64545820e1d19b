#!/bin/sh
# SPDX-License-Identifier: MIT
# `hystviz loop --solver` edges (issue 11, parts 2-3): output times one ulp
# from a breakpoint, --atol and its scaled default, quick refusals of stiff
# runs (exit status 2, advice), and the σ1 default that the help states.
set -u
hv=$1
. "$(dirname "$0")/../lib.sh"
ex3="--sigma0 1 --sigma1 1 --fc 1 --fs 2 --vs 1 --beta 1 --x0 0 --input bimodal:0,0.2,1,1.5"
stiff="--sigma0 1e5 --sigma1 316.22776601683796 --fc 1 --fs 1.5 --vs 1e-3 --beta 2 --x0 0"

# the issue's command: t = 36.800000000000004 is one ulp past a breakpoint
"$hv" loop $ex3 --gamma 1 --cycles 10 --points 81 --solver msbdf > "$tmp/msbdf.csv" 2> "$tmp/err" &&
    [ "$(wc -l < "$tmp/msbdf.csv")" -eq 82 ] && ok || bad "msbdf, 10 cycles: $(cat "$tmp/err")"
# it agrees with the exact solution (max |Δy| < 1e-7 at rtol 1e-10; a wrong
# piece at the breakpoint would be off by O(1))
"$hv" loop $ex3 --gamma 1 --cycles 10 --points 81 > "$tmp/exact.csv"
paste -d, "$tmp/exact.csv" "$tmp/msbdf.csv" | tail -n +2 |
    awk -F, '{d = $3 - $6; if (d < 0) d = -d; if (d > m) m = d} END {exit !(m < 1e-7)}' && ok || bad "msbdf vs exact"
# implicit steppers on the stiff problem: 4 cycles of 81 points put
# t = 0.00138 = 3T within an ulp of a breakpoint
for s in rk2imp rk4imp bsimp msbdf; do
    "$hv" loop $stiff --input bimodal:0,0.2e-4,1e-4,1.5e-4 --gamma 1 --cycles 4 --points 81 --solver $s \
        > /dev/null 2> "$tmp/err" && ok || bad "$s on the stiff problem: $(cat "$tmp/err")"
done

# --atol: accepted, validated (exit 2), and it moves the result
"$hv" loop $stiff --input bimodal:0,0.2e-4,1e-4,1.5e-4,0.1,0.18,0.31,0.46 --gamma 1 --cycles 3 --solver rkf45 \
    --rtol 1e-10 > "$tmp/scaled.csv" && ok || bad "rkf45, scaled atol"
"$hv" loop $stiff --input bimodal:0,0.2e-4,1e-4,1.5e-4,0.1,0.18,0.31,0.46 --gamma 1 --cycles 3 > "$tmp/sexact.csv"
"$hv" loop $stiff --input bimodal:0,0.2e-4,1e-4,1.5e-4,0.1,0.18,0.31,0.46 --gamma 1 --cycles 3 --solver rkf45 \
    --rtol 1e-10 --atol 1e-12 > "$tmp/fixed.csv" && ok || bad "rkf45 --atol 1e-12"
maxerr() { paste -d, "$tmp/sexact.csv" "$1" | tail -n +2 | awk -F, '{d = $3 - $6; if (d < 0) d = -d; if (d > m) m = d} END {printf "%.3g", m}'; }
es=$(maxerr "$tmp/scaled.csv")
ef=$(maxerr "$tmp/fixed.csv")
# the default atol = 1e-2 rtol g(0)/σ0 (1.5e-17 here) reaches 2.8e-11 (g(0) =
# 1.5); the old fixed atol 1e-2 rtol = 1e-12 (1e-7 g(0) in y = σ0 z) stalls
# at 1.9e-8: require < 1e-10 and a 100x difference
awk -v a="$es" -v b="$ef" 'BEGIN {exit !(a < 1e-10 && b > 100 * a)}' && ok ||
    bad "scaled default atol: error $es, with --atol 1e-12: $ef"
echo "rkf45 on the stiff problem: error $es with the scaled default atol, $ef with --atol 1e-12"
"$hv" loop $ex3 --gamma 1 --solver rkf45 --atol -1 > "$tmp/out" 2> "$tmp/err"
[ $? -eq 2 ] && grep -q "tolerances" "$tmp/err" && [ ! -s "$tmp/out" ] && ok || bad "--atol -1: $(cat "$tmp/err")"
"$hv" loop --help | grep -q -- "--atol A" && "$hv" loop --help | grep -q "1e-2 rtol g(0)/sigma0" && ok ||
    bad "loop --help states --atol and its default"

# refusals up front: exit status 2, the advice, no output
"$hv" loop --sigma0 1e8 --fc 1e-6 --fs 1e-6 --input bimodal:0,0.2,1,1.5 --gamma 1 --solver rkf45 --rtol 1e-10 \
    > "$tmp/out" 2> "$tmp/err"
[ $? -eq 2 ] && grep -q "refused" "$tmp/err" && grep -q "bsimp or msbdf" "$tmp/err" && [ ! -s "$tmp/out" ] && ok ||
    bad "extreme rkf45 not refused: $(cat "$tmp/err")"
"$hv" loop $stiff --input bimodal:0,0.2e-4,1e-4,1.5e-4,0.1,0.18,0.31,0.46 --gamma 1 --cycles 3 --solver rk1imp \
    > "$tmp/out" 2> "$tmp/err"
[ $? -eq 2 ] && grep -q "refused" "$tmp/err" && ok || bad "rk1imp at rtol 1e-10 on the stiff problem: $(cat "$tmp/err")"

# σ1: the default is Example 2's σ1 = 1, as the help says
"$hv" loop --help | grep -q "sigma0 = sigma1 = FC = VS" && ok || bad "help states sigma1 = 1"
"$hv" loop --input bimodal:0,0.2,1,1.5 --gamma 2 > "$tmp/d.csv"
"$hv" loop --input bimodal:0,0.2,1,1.5 --gamma 2 --sigma1 1 > "$tmp/s1.csv"
"$hv" loop --input bimodal:0,0.2,1,1.5 --gamma 2 --sigma1 0 > "$tmp/s0.csv"
cmp -s "$tmp/d.csv" "$tmp/s1.csv" && ! cmp -s "$tmp/d.csv" "$tmp/s0.csv" && ok || bad "sigma1 default is not 1"

finish "loop_solver"
