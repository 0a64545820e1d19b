#!/bin/sh
# SPDX-License-Identifier: MIT
# The Bouc-Wen scenes through the hystviz command: `hystviz data` of Fig. 1(b),
# `hystviz render` of all six, and a malformed scene refused with
# file:line:col, exit status 2 (invalid input) and no output file.
set -u
hv=$1
scenes=$2
. "$(dirname "$0")/../lib.sh"

"$hv" data "$scenes/bw_fig1b_linear_loop.scene" -o "$tmp/f1b.csv" && ok || bad "data fig1b"
[ "$(head -1 "$tmp/f1b.csv")" = "series,x,y" ] && ok || bad "data header"
[ "$(wc -l < "$tmp/f1b.csv")" -eq 7501 ] && ok || bad "fig1b rows: $(wc -l < "$tmp/f1b.csv")"
# linear: y (mm) = u / (k + alpha) * 1e3 up to the 1 Hz phase: |y - u/100| < 0.01 mm
awk -F, 'NR > 1 { d = $3 - $2 / 100; if (d < 0) d = -d; if (d > m) m = d } END { exit !(m < 0.01) }' \
    "$tmp/f1b.csv" && ok || bad "fig1b is not y = u / (k + alpha)"

"$hv" render "$scenes"/bw_*.scene -o "$tmp/out" --format svg && ok || bad "render bw scenes"
for s in bw_fig1a_quasistatic_loop bw_fig1b_linear_loop bw_fig2a_output_periods bw_fig2b_transient_db \
         bw_validation_sweep bw_sinc_upsampling_error; do
    [ -s "$tmp/out/$s.svg" ] && ok || bad "no $s.svg"
done

printf 'include "style.scene"\n[model]\nkind = boucwen\nnu = 0\n' > "$tmp/bad.scene"
"$hv" render "$tmp/bad.scene" --include-dir "$scenes" -o "$tmp/badout" > "$tmp/stdout" 2> "$tmp/err"
st=$?
[ $st -eq 2 ] && ok || bad "bad scene: status $st"
grep -qF "$tmp/bad.scene:4:6: 'nu' in [model] must be > 0, got 0" "$tmp/err" && ok || bad "message: $(cat "$tmp/err")"
[ ! -e "$tmp/badout" ] && ok || bad "a refused scene left output"

printf '[model]\nkind = boucwen\n[input]\nkind = sine\nperiod = 1\n[series y]\ndata = boucwen\nquantity = speed\n' > "$tmp/badq.scene"
"$hv" data "$tmp/badq.scene" -o "$tmp/badq.csv" 2> "$tmp/err"
st=$?
[ $st -ne 0 ] && grep -qF "$tmp/badq.scene:8:12: 'quantity' in [series y] must be one of" "$tmp/err" && ok ||
    bad "unknown quantity: status $st, $(cat "$tmp/err")"
[ ! -e "$tmp/badq.csv" ] && ok || bad "a refused scene left data"

finish "boucwen scenes cli"
