#!/bin/sh
# SPDX-License-Identifier: MIT
# Benchmark of annotation placement (issue 20 item 8: 400 annotations took
# 6 s, 800 18 s, 3000 over 60 s, quadratic): `hystviz render` of a Fig. 15
# scene with N annotations at scattered points of the loop, SVG only, for
# N = 100, 400, 800, 3000; prints the wall time of each.  Writes only under a
# temporary directory; asserts nothing but that the renders work.
# usage: bench_annotations.sh HYSTVIZ SCENES_DIR
set -u
hv=$1
scenes=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cp "$scenes/style.scene" "$tmp/"
echo "annotation placement: load $(cut -d' ' -f1-3 /proc/loadavg)"
for n in 100 400 800 3000; do
    {
        sed 's/^\[output\].*//; s/^formats.*//; s/^name = .*//' "$scenes/fig15_minor_loop_ex4.scene"
        i=0
        while [ $i -lt $n ]; do
            echo "[annotation a$i]"
            echo "text = \"a_{$i}\""
            echo "x = 0.$(( (i * 7919) % 1000 ))"
            echo "y = 0.$(( (i * 104729) % 1000 ))"
            i=$((i + 1))
        done
    } > "$tmp/many.scene"
    t0=$(date +%s.%N)
    "$hv" render "$tmp/many.scene" -o "$tmp/out" --format svg --max-work 1e9 || { echo "bench_annotations: N=$n failed" >&2; exit 1; }
    t1=$(date +%s.%N)
    echo "$n annotations: $(echo "$t1 - $t0" | bc 2>/dev/null || awk "BEGIN{print $t1 - $t0}") s"
done
