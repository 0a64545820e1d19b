#!/bin/sh
# SPDX-License-Identifier: MIT
# Benchmark of annotation placement (issue 20 item 8: 400 annotations took
# 6 s, 800 18 s, 3000 over 60 s, quadratic): `hystviz render` of a Fig. 15
# scene with N annotations at scattered points of the loop, SVG only, for
# N = 100, 400, 800, 3000; then the adversarial case of issue 36 item 1, N
# labels all asking for one place (N = 200 … 3200: a pile that every later
# label's spots walked, 0.77 s, 1.77 s, 4.5 s for 200, 400, 800 before);
# prints the wall and CPU time of each.  Writes only under a
# temporary directory; asserts nothing but that the renders work.
# usage: bench_annotations.sh HYSTVIZ SCENES_DIR
set -u
hv=$1
scenes=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cp "$scenes/style.scene" "$tmp/"
echo "annotation placement: load $(cut -d' ' -f1-3 /proc/loadavg)"
scene() { # N MODE
    n=$1
    {
        sed 's/^\[output\].*//; s/^formats.*//; s/^name = .*//' "$scenes/fig15_minor_loop_ex4.scene"
        i=0
        while [ $i -lt $n ]; do
            echo "[annotation a$i]"
            if [ "$2" = scattered ]; then
                echo "text = \"a_{$i}\""
                echo "x = 0.$(( (i * 7919) % 1000 ))"
                echo "y = 0.$(( (i * 104729) % 1000 ))"
            else
                echo "text = \"a long annotation number $i\""
                echo "x = 0.5"
                echo "y = 0.1"
            fi
            i=$((i + 1))
        done
    } > "$tmp/many.scene"
}
run() { # N MODE
    scene "$1" "$2"
    /usr/bin/time -f '%e %U %S' -o "$tmp/time" "$hv" render "$tmp/many.scene" -o "$tmp/out" --format svg --max-work 1e12 ||
        { echo "bench_annotations: N=$1 ($2) failed" >&2; exit 1; }
    read -r wall user sys < "$tmp/time"
    echo "$1 annotations, $2: $wall s wall, $(awk "BEGIN{print $user + $sys}") s CPU"
}
for n in 100 400 800 3000; do run $n scattered; done
for n in 200 400 800 1600 3200; do run $n "at one place"; done
