#!/bin/sh
# SPDX-License-Identifier: MIT
# Tests of `hystviz sweep --table npy` (issue 37 item 2): NumPy reads
# sweep.npy back and it holds the CSV table's values bit for bit (npy_check.py,
# with invalid rows, text grid values and a long message among them); the file
# is the same bytes for -j 1 and -j 2, and for N = 1, 2, 3, 5 shards merged
# (and 8 shards of a 6-point study: N above the point count); a missing shard or a damaged one makes the
# merge refuse (exit 2, nothing written); a second merge finds sweep.npy.
# usage: test_sweep_npy.sh HYSTVIZ SCENES_DIR
set -u
hv=$1
scenes=$2
here=$(dirname "$0")
. "$(dirname "$0")/../lib.sh"
/usr/bin/python3 -c 'import numpy' 2> /dev/null || { echo "SKIP: python3-numpy is missing"; exit 77; }
fig15=$scenes/fig15_minor_loop_ex4.scene
# umin2 past umax1 = 1: invalid rows with a message; a list axis with a text value
g="--grid model.sigma0=1:100:log7 --grid input.umin2=0.1:1.3:5 --grid model.sigma1=1,2e0,0.5 --grid series.minor.style=solid,dashed"
"$hv" sweep "$fig15" $g --formats none -o "$tmp/csv" -q 2> /dev/null
[ $? -eq 2 ] && ok || bad "the study with invalid points: exit status not 2"
"$hv" sweep "$fig15" $g --formats none -o "$tmp/npy" -q --table npy -j 1 2> /dev/null
[ $? -eq 2 ] && ok || bad "--table npy: exit status not 2"
[ -f "$tmp/npy/sweep.npy" ] && [ ! -e "$tmp/npy/sweep.csv" ] && ok || bad "--table npy: no sweep.npy, or a sweep.csv"
grep -q ',invalid,' "$tmp/csv/sweep.csv" && ok || bad "no invalid row in the study"
/usr/bin/python3 "$here/npy_check.py" "$tmp/npy/sweep.npy" "$tmp/csv/sweep.csv" > "$tmp/check" && ok ||
    bad "npy differs from csv: $(cat "$tmp/check")"
# -j 2: the same bytes
"$hv" sweep "$fig15" $g --formats none -o "$tmp/npy2" -q --table npy -j 2 2> /dev/null
cmp -s "$tmp/npy/sweep.npy" "$tmp/npy2/sweep.npy" && ok || bad "-j 2 gives another sweep.npy"
# shards merged: the same bytes
for n in 1 2 3 5; do
    rm -rf "$tmp/sh"
    k=0
    while [ $k -lt $n ]; do
        "$hv" sweep "$fig15" $g --formats none -o "$tmp/sh" -q --table npy --shard $k/$n 2> /dev/null
        k=$((k + 1))
    done
    "$hv" sweep --merge "$tmp/sh" -q 2> /dev/null
    [ $? -eq 2 ] && cmp -s "$tmp/npy/sweep.npy" "$tmp/sh/sweep.npy" && [ -z "$(ls "$tmp/sh" | grep shard)" ] && ok ||
        bad "$n shards merged: not the unsharded sweep.npy"
done
"$hv" sweep --merge "$tmp/sh" -q 2> /dev/null
[ $? -eq 2 ] && cmp -s "$tmp/npy/sweep.npy" "$tmp/sh/sweep.npy" && ok || bad "a second merge: other status or file"
# more shards than points: 8 shards of a 6-point study (one with a text axis),
# two of them empty (it was 250 shards of the 210 points: 250 processes, 12 s
# of CPU under the sanitizers, for the same property)
g6="--grid model.sigma0=1,2,3 --grid series.minor.style=solid,dashed"
"$hv" sweep "$fig15" $g6 --formats none -o "$tmp/six" -q --table npy 2> /dev/null || bad "the 6-point study failed"
rm -rf "$tmp/sh"
k=0
while [ $k -lt 8 ]; do
    "$hv" sweep "$fig15" $g6 --formats none -o "$tmp/sh" -q --table npy --shard $k/8 2> /dev/null
    k=$((k + 1))
done
"$hv" sweep --merge "$tmp/sh" -q 2> /dev/null && cmp -s "$tmp/six/sweep.npy" "$tmp/sh/sweep.npy" && ok ||
    bad "8 shards of 6 points merged: not the unsharded sweep.npy"
# a missing shard, a damaged shard: refused, nothing written
rm -rf "$tmp/sh"
for k in 0 2; do "$hv" sweep "$fig15" $g --formats none -o "$tmp/sh" -q --table npy --shard $k/3 2> /dev/null; done
"$hv" sweep --merge "$tmp/sh" 2> "$tmp/err"
[ $? -eq 2 ] && grep -q '1/3' "$tmp/err" && [ ! -e "$tmp/sh/sweep.npy" ] && ok || bad "missing shard: $(cat "$tmp/err")"
"$hv" sweep "$fig15" $g --formats none -o "$tmp/sh" -q --table npy --shard 1/3 2> /dev/null
f=$tmp/sh/sweep.shard-1-of-3.npy
head -c $(($(wc -c < "$f") - 5)) "$f" > "$tmp/cut" && cat "$tmp/cut" > "$f"
"$hv" sweep --merge "$tmp/sh" 2> "$tmp/err"
[ $? -eq 2 ] && [ ! -e "$tmp/sh/sweep.npy" ] && ok || bad "damaged shard merged: $(cat "$tmp/err")"
# usage errors
"$hv" sweep "$fig15" $g --formats none -o "$tmp/u" --table xls 2> /dev/null
[ $? -eq 2 ] && [ ! -e "$tmp/u" ] && ok || bad "--table xls accepted"
"$hv" sweep "$fig15" $g --formats none -o "$tmp/u" --table npy --plot energy 2> /dev/null
[ $? -eq 2 ] && [ ! -e "$tmp/u" ] && ok || bad "--table npy --plot accepted"
finish "test_sweep_npy"
