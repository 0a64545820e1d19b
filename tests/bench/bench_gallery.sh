#!/bin/sh
# SPDX-License-Identifier: MIT
# Benchmark of the gallery, whole processes timed by the wall clock:
#   1. the whole gallery of scenes/ from scratch with -j 2   (target < 5 s on 2 cores)
#   2. the same gallery again with nothing changed           (target < 0.3 s)
#   3. Fig. 15 to SVG and a 1600x1200 PNG by `hystviz render` (1600px at dpi 200 = 8in)
# Prints best and median of several runs; asserts nothing but that the runs work.
# usage: bench_gallery.sh GALLERY HYSTVIZ SCENES_DIR
#   GALLERY: a program that runs `GALLERY gallery ARGS` (hystviz, or tests/gallery/gallery_main)
set -u
gal=$1
hv=$2
scenes=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

t() { date +%s.%N; }
# stats LABEL FILE: best and median of the seconds in FILE, one per line
stats() {
    sort -n "$2" | awk -v l="$1" '{ v[NR] = $1 } END { printf "%-58s best %7.3f s  median %7.3f s  (%d runs)\n", l, v[1], v[int((NR + 1) / 2)], NR }'
}
fail() { echo "bench_gallery: $*" >&2; exit 1; }

n=$(ls "$scenes"/*.scene | wc -l)
echo "gallery benchmark: $n scene files in $scenes, $(getconf _NPROCESSORS_ONLN) online CPUs"

: > "$tmp/scratch"
for i in 1 2 3 4 5; do
    rm -rf "$tmp/g"
    a=$(t)
    "$gal" gallery --scenes "$scenes" -o "$tmp/g" -j 2 -q || fail "gallery from scratch failed"
    b=$(t)
    awk -v a="$a" -v b="$b" "BEGIN { print b - a }" >> "$tmp/scratch"
done
nfig=$(grep -c '^[^#]' "$tmp/g/.manifest")
stats "gallery from scratch, -j 2 ($nfig figures)" "$tmp/scratch"

: > "$tmp/scratch1"
for i in 1 2 3; do
    rm -rf "$tmp/g1"
    a=$(t)
    "$gal" gallery --scenes "$scenes" -o "$tmp/g1" -j 1 -q || fail "gallery -j 1 failed"
    b=$(t)
    awk -v a="$a" -v b="$b" "BEGIN { print b - a }" >> "$tmp/scratch1"
done
stats "gallery from scratch, -j 1" "$tmp/scratch1"

: > "$tmp/same"
for i in 1 2 3 4 5 6 7 8 9 10; do
    a=$(t)
    "$gal" gallery --scenes "$scenes" -o "$tmp/g" -j 2 -q || fail "unchanged gallery failed"
    b=$(t)
    awk -v a="$a" -v b="$b" "BEGIN { print b - a }" >> "$tmp/same"
done
stats "gallery, nothing changed" "$tmp/same"

: > "$tmp/fig15"
for i in 1 2 3 4 5 6 7 8 9 10; do
    a=$(t)
    "$hv" render "$scenes/fig15_minor_loop_ex4.scene" --format svg,png --set figure.size=1600px,1200px \
        --set figure.dpi=200 -o "$tmp/f15" || fail "fig15 render failed"
    b=$(t)
    awk -v a="$a" -v b="$b" "BEGIN { print b - a }" >> "$tmp/fig15"
done
size=$(od -An -tu1 -j16 -N8 "$tmp/f15/fig15_minor_loop_ex4.png" |
    awk '{ printf "%dx%d", (($1*256+$2)*256+$3)*256+$4, (($5*256+$6)*256+$7)*256+$8 }')
stats "render fig15 to SVG + PNG $size (one process)" "$tmp/fig15"
