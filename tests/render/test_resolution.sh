#!/bin/sh
# SPDX-License-Identifier: MIT
# Lines at the output's resolution (issue 23 item 2), through the command:
#   1. the gallery rendered now shows the pixels of the committed gallery PNGs,
#      per pixel within 1 grey level (png_close decodes both): simplification
#      leaves figures of the gallery's density alone on screen and on paper;
#   2. Fig. 15 with 1e6 points per unit of input (2e6 on the major loop) writes
#      SVG and PDF no larger than with 1e4, and its PNG within 2 % of that size;
#   3. figure.full_resolution = true keeps every point: its SVG holds more
#      path vertices than the default one, and at least the loop's samples.
# usage: test_resolution.sh HYSTVIZ PNG_CLOSE SOURCE_ROOT
set -u
hv=$1
close=$2
src=$3
. "$(dirname "$0")/../lib.sh"

"$hv" gallery --scenes "$src/scenes" -o "$tmp/g" -j 2 -q || bad "gallery failed"
n=0
for ref in "$src"/gallery/*.png; do
    b=$(basename "$ref")
    [ -f "$tmp/g/$b" ] || { bad "$b not rendered"; continue; }
    printf '%-44s ' "$b"
    "$close" 1 "$ref" "$tmp/g/$b" || bad "$b differs from the committed gallery by more than 1 grey level"
    n=$((n + 1))
done
[ "$n" -ge 20 ] || bad "only $n gallery PNGs compared"

f15=$src/scenes/fig15_minor_loop_ex4.scene
for p in 10000 1000000; do
    "$hv" render "$f15" --set compute.points=$p --format svg,pdf,png -o "$tmp/p$p" || bad "render points=$p failed"
done
size() { wc -c < "$1" | tr -d ' '; }
for ext in svg pdf; do
    a=$(size "$tmp/p10000/fig15_minor_loop_ex4.$ext")
    b=$(size "$tmp/p1000000/fig15_minor_loop_ex4.$ext")
    echo "fig15 $ext: $a bytes at 1e4 points, $b at 1e6"
    [ "$b" -le "$a" ] || bad "fig15 $ext at 1e6 points ($b bytes) larger than at 1e4 ($a)"
done
a=$(size "$tmp/p10000/fig15_minor_loop_ex4.png")
b=$(size "$tmp/p1000000/fig15_minor_loop_ex4.png")
echo "fig15 png: $a bytes at 1e4 points, $b at 1e6"
[ "$b" -le $((a + a / 50)) ] || bad "fig15 png at 1e6 points ($b bytes) more than 2 % larger than at 1e4 ($a)"

"$hv" render "$f15" --format svg -o "$tmp/d" || bad "default render failed"
"$hv" render "$f15" --set figure.full_resolution=true --format svg -o "$tmp/f" || bad "full_resolution render failed"
vd=$(grep -o ' L ' "$tmp/d/fig15_minor_loop_ex4.svg" | wc -l)
vf=$(grep -o ' L ' "$tmp/f/fig15_minor_loop_ex4.svg" | wc -l)
echo "fig15 svg line-to commands: $vd default, $vf full_resolution"
[ "$vf" -gt "$vd" ] || bad "full_resolution drew no more vertices ($vf) than the default ($vd)"
[ "$vf" -ge 2000 ] || bad "full_resolution drew $vf vertices, fewer than the 2000 samples of the loop"
[ "$fail" -eq 0 ] && echo "all passed"
exit "$fail"
