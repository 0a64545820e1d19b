#!/bin/sh
# SPDX-License-Identifier: MIT
# Tests of `--shard K/N` and `--merge` (issue 13) for `hystviz sweep`: for every
# N from 1 to 7 (and N above the point count) the shards run into separate
# directories write disjoint sets of files whose union, merged, is the
# unsharded study byte for byte (diff -r); a missing shard, a shard of another
# study or split, a damaged manifest make the merge refuse (exit 2, nothing
# written, the missing shards named); a killed shard re-run alone completes the
# study.
# usage: test_shard.sh HYSTVIZ SCENES_DIR [split|rest]
#   split: the union for every N (tests/cli/meson.build: shard-split, release
#   build only); rest: everything else (shard, also under the sanitizers);
#   neither: both
set -u
hv=$1
scenes=$2
part=${3:-all}
. "$(dirname "$0")/../lib.sh"
fig15=$scenes/fig15_minor_loop_ex4.scene
grid="--grid model.sigma0=1:10:log5 --grid input.umin2=0.1,0.3,0.5"   # 15 points

"$hv" sweep "$fig15" $grid -o "$tmp/one" -q --formats svg,png || bad "unsharded run"

[ "$part" = rest ] || for n in 1 2 3 4 5 6 7 20; do
    rm -rf "$tmp/s" "$tmp/all"
    mkdir -p "$tmp/all"
    k=$((n - 1))
    while [ $k -ge 0 ]; do   # last shard first: order does not matter
        "$hv" sweep "$fig15" $grid -o "$tmp/s/$k" -q --formats svg,png --shard "$k/$n" || bad "shard $k/$n status"
        ls "$tmp/s/$k" >> "$tmp/s/names"
        cp "$tmp/s/$k"/* "$tmp/all/"
        k=$((k - 1))
    done
    # no two shards write the same file; together they write every figure
    [ -z "$(sort "$tmp/s/names" | uniq -d)" ] && ok || bad "N=$n: files written by two shards: $(sort "$tmp/s/names" | uniq -d | head -3)"
    [ "$(grep -c 'sweep.shard-' "$tmp/s/names")" -eq "$n" ] && ok || bad "N=$n: not one manifest per shard"
    "$hv" sweep --merge "$tmp/all" -q && ok || bad "N=$n: merge status"
    diff -r "$tmp/one" "$tmp/all" > "$tmp/diff" && ok || bad "N=$n: merged study differs from the unsharded run: $(head -3 "$tmp/diff")"
    # issue 20 item 11: a merge run again (a retried job) succeeds with the same table
    "$hv" sweep --merge "$tmp/all" -q && diff -r "$tmp/one" "$tmp/all" > /dev/null && ok || bad "N=$n: a second merge failed or changed the study"
done
[ "$part" != split ] || { finish "test_shard (split)"; exit; }
# the summary figure drawn by the merge is the unsharded run's
"$hv" sweep "$fig15" $grid -o "$tmp/p1" -q --formats none --plot minor1_area
for k in 0 1; do "$hv" sweep "$fig15" $grid -o "$tmp/p2" -q --formats none --plot minor1_area --shard $k/2; done
[ ! -e "$tmp/p2/sweep_minor1_area.svg" ] && ok || bad "a shard drew the summary figure"
"$hv" sweep --merge "$tmp/p2" --plot minor1_area -q && diff -r "$tmp/p1" "$tmp/p2" > /dev/null && ok || bad "merged --plot differs"
[ -s "$tmp/p1/sweep_minor1_area.svg" ] && [ -s "$tmp/p1/sweep_minor1_area.png" ] && ok || bad "no summary figure"
"$hv" sweep "$fig15" $grid -o "$tmp/p3" -q --formats none --plot energy
cmp -s "$tmp/p3/sweep_energy.svg" "$tmp/p1/sweep_minor1_area.svg" && bad "the plot does not depend on the column" || ok
"$hv" sweep "$fig15" $grid -o "$tmp/p4" -q --formats none --plot model.sigma0 2> "$tmp/err"
[ $? -eq 2 ] && grep -q 'not a result column' "$tmp/err" && [ ! -e "$tmp/p4" ] && ok || bad "--plot of a grid key: $(cat "$tmp/err")"

# balanced: shard k of 4 holds 4, 4, 4, 3 of the 15 points
for k in 0 1 2 3; do
    "$hv" sweep "$fig15" $grid -o "$tmp/b$k" -q --formats none --shard "$k/4"
    c=$(tail -n +3 "$tmp/b$k/sweep.shard-$k-of-4.csv" | wc -l)
    [ "$c" -eq $((k < 3 ? 4 : 3)) ] && ok || bad "shard $k/4 has $c points"
done

# the table-only study in 3 shards written into one directory, as GNU parallel does
rm -rf "$tmp/t"
# (each bounded: timeout ends a shard that hangs, wait_pid gives it 130 s)
pids=
for k in 0 1 2; do timeout 120 "$hv" sweep "$fig15" $grid -o "$tmp/t" -q --formats none --shard "$k/3" & pids="$pids $!"; done
for p in $pids; do wait_pid "$p" 130 "a concurrent shard" || bad "a concurrent shard failed"; done
"$hv" sweep "$fig15" $grid -o "$tmp/t1" -q --formats none
"$hv" sweep --merge "$tmp/t" -q && cmp -s "$tmp/t/sweep.csv" "$tmp/t1/sweep.csv" && ok || bad "concurrent shards in one directory"
[ "$(ls "$tmp/t")" = "sweep.csv" ] && ok || bad "merge left: $(ls "$tmp/t" | tr '\n' ' ')"

# ---- refusals ---------------------------------------------------------------
mk() { rm -rf "$tmp/m"; for k in "$@"; do "$hv" sweep "$fig15" $grid -o "$tmp/m" -q --formats none --shard "$k"; done; }
mk 0/3 2/3
"$hv" sweep --merge "$tmp/m" 2> "$tmp/err"
[ $? -eq 2 ] && grep -q '1 of 3 shards missing: 1/3' "$tmp/err" && [ ! -e "$tmp/m/sweep.csv" ] && ok || bad "missing shard: $(cat "$tmp/err")"
[ -e "$tmp/m/sweep.shard-0-of-3.csv" ] && ok || bad "a refused merge removed a shard manifest"
# the failed shard re-run alone completes the study
"$hv" sweep "$fig15" $grid -o "$tmp/m" -q --formats none --shard 1/3
"$hv" sweep --merge "$tmp/m" -q && cmp -s "$tmp/m/sweep.csv" "$tmp/t1/sweep.csv" && ok || bad "re-run shard did not complete the study"
mk 0/2 1/2 1/3
"$hv" sweep --merge "$tmp/m" 2> "$tmp/err"
[ $? -eq 2 ] && grep -q 'two splits' "$tmp/err" && [ ! -e "$tmp/m/sweep.csv" ] && ok || bad "mixed splits: $(cat "$tmp/err")"
mk 0/2
"$hv" sweep "$fig15" --grid model.sigma0=1,2 -o "$tmp/m" -q --formats none --shard 1/2
"$hv" sweep --merge "$tmp/m" 2> "$tmp/err"
[ $? -eq 2 ] && grep -q 'another study' "$tmp/err" && [ ! -e "$tmp/m/sweep.csv" ] && ok || bad "other study: $(cat "$tmp/err")"
mk 0/2 1/2
head -n 5 "$tmp/m/sweep.shard-1-of-2.csv" > "$tmp/cut" && mv "$tmp/cut" "$tmp/m/sweep.shard-1-of-2.csv"
"$hv" sweep --merge "$tmp/m" 2> "$tmp/err"
[ $? -eq 2 ] && grep -q 'incomplete or damaged' "$tmp/err" && [ ! -e "$tmp/m/sweep.csv" ] && ok || bad "truncated shard: $(cat "$tmp/err")"
rm -rf "$tmp/m" && mkdir "$tmp/m"
"$hv" sweep --merge "$tmp/m" 2> "$tmp/err"
[ $? -eq 2 ] && grep -q 'no shard manifests' "$tmp/err" && ok || bad "empty dir merge"
"$hv" sweep --merge "$tmp/nosuch" 2> /dev/null
[ $? -eq 2 ] && ok || bad "merge of a missing dir"
"$hv" sweep "$fig15" --merge "$tmp/m" 2> /dev/null
[ $? -eq 2 ] && ok || bad "--merge with a scene accepted"

# a killed shard (its manifest never written, some figures missing) re-run alone
rm -rf "$tmp/k"
for k in 0 1 2; do "$hv" sweep "$fig15" $grid -o "$tmp/k" -q --formats svg,png --shard "$k/3"; done
rm "$tmp/k/sweep.shard-2-of-3.csv" "$tmp/k"/p02_* "$tmp/k"/p05_*
"$hv" sweep --merge "$tmp/k" 2> /dev/null
[ $? -eq 2 ] && ok || bad "merge without the killed shard"
"$hv" sweep "$fig15" $grid -o "$tmp/k" -q --formats svg,png --shard 2/3 && "$hv" sweep --merge "$tmp/k" -q &&
    diff -r "$tmp/one" "$tmp/k" > /dev/null && ok || bad "killed shard re-run: study differs"

finish "test_shard"
