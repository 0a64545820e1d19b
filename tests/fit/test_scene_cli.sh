#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/fit/test_scene_cli.sh HYSTVIZ: `hystviz fit SCENE --free KEY,...` through
# the command (issue 32 item 2; docs/FIT.md "Fitting a scene"): a play operator
# fitted to its own noise-free output recovers r and writes the fitted scene
# (which renders) and the residual figure; bad --free keys and bad data files
# are one line on standard error, exit 2, nothing written.
set -u
hv=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
. "$(dirname "$0")/../lib.sh"
s=$tmp/s
mkdir -p "$s/out"
# play with r = 0.3 driven 0 -> 1 -> -1 -> 1 from y0 = 0: y = u - r on the way up
# after the first turn, u + r on the way down (computed by hand, not by hystviz)
awk 'BEGIN { print "u,y"; y = 0; r = 0.3;
  for (i = 0; i <= 60; i++) { x = i / 60 * 4; u = x < 1 ? x : x < 3 ? 2 - x : x - 4;
    if (u - y > r) y = u - r; if (y - u > r) y = u + r; printf "%.17g,%.17g\n", u, y } }' > "$s/play.csv"
scene() { # scene NAME CSV R
    printf '[model]\nkind = play\nplay_r = %s\n[data d]\nfile = "%s"\nu = u\ny = y\n[input]\nkind = data\ndata = d\n[figure]\nkind = loop\n[series m]\ndata = measured\nof = d\nstyle = none\nmarker = circle\n[series f]\ndata = modelled\nof = d\nlabel = "fit, RMS {f.rms}"\n[output]\nformats = svg\n' "$3" "$2" > "$s/$1.scene"
}
scene play play.csv 0.2
"$hv" fit "$s/play.scene" --free play_r -o "$s/fitted.scene" --residuals "$s/resid.svg" -q > "$tmp/o" 2> "$tmp/e"
st=$?
[ $st -eq 0 ] && [ ! -s "$tmp/e" ] && ok || bad "fit: exit $st: $(cat "$tmp/e")"
# the estimate within 1e-8 of 0.3 (exact data: the model is piecewise linear in r)
r=$(sed -n 's/^play_r = //p' "$s/fitted.scene")
awk -v r="$r" 'BEGIN { exit !(r != "" && (r - 0.3 < 1e-8 && 0.3 - r < 1e-8)) }' && ok || bad "play_r = '$r', want 0.3"
grep -q '^ *play_r ' "$tmp/o" && grep -q 'RMS' "$tmp/o" && ok || bad "no report: $(head -5 "$tmp/o")"
grep -q '<svg' "$s/resid.svg" && ok || bad "no residual figure"
# (the label's {f.rms} is checked as text in tests/fit/test_scene.c: cairo's SVG draws glyphs)
"$hv" render "$s/fitted.scene" -o "$s/out" > /dev/null 2> "$tmp/e" && grep -q '<svg' "$s/out/fitted.svg" && ok ||
    bad "the fitted scene does not render: $(cat "$tmp/e")"
# two data sets at once (--data d,e): one residual vector of 2 x 61 points, the
# modelled series following each set in turn
cp "$s/play.csv" "$s/play2.csv"
{ cat "$s/play.scene"; printf '[data e]\nfile = "play2.csv"\nu = u\ny = y\n'; } > "$s/two.scene"
"$hv" fit "$s/two.scene" --free play_r --data d --data e -q > "$tmp/o" 2> "$tmp/e"
grep -q '122 measured points in \[data d\] (1 record), \[data e\] (1 record)' "$tmp/o" && ok ||
    bad "--data d --data e: $(cat "$tmp/e") $(head -1 "$tmp/o")"
# --set before fitting (as render's): a free key's start (the start column,
# the range around it), a fixed key's value (y_0 = 0.2 where the data have 0:
# the first point alone misses by 0.2, so max |error| = 0.2 and RMS > 0)
"$hv" fit "$s/play.scene" --free play_r --set model.play_r=0.25 -q > "$tmp/o" 2> "$tmp/e"
grep -Eq '^play_r +0\.25 +0\.0025 +25 +log' "$tmp/o" && ok || bad "--set start: $(cat "$tmp/e") $(head -3 "$tmp/o")"
"$hv" fit "$s/play.scene" --free play_r --set model.play_y0=0.2 -q > "$tmp/o" 2> "$tmp/e"
grep -q 'max |error| 0\.2,' "$tmp/o" && ok || bad "--set fixed y0: $(cat "$tmp/e") $(grep RMS "$tmp/o")"
# a key the scene does not write has no start unless --set gives it one
"$hv" fit "$s/play.scene" --free play_r,play_y0 --set model.play_y0=0.01 -o "$s/fitted.scene" -q > "$tmp/o" 2> "$tmp/e"
grep -q '^# fitted with --set model.play_y0=0.01$' "$s/fitted.scene" && ok || bad "--set not noted: $(cat "$tmp/e")"
rm -f "$s/fitted.scene" "$s/resid.svg"
# refused ARGS... : one line on standard error, exit 2, nothing written
refused() {
    want=$1
    shift
    "$hv" fit "$@" -o "$s/fitted.scene" --residuals "$s/resid.svg" -q > "$tmp/o" 2> "$tmp/e"
    st=$?
    [ $st -eq 2 ] && [ "$(wc -l < "$tmp/e")" -eq 1 ] && grep -q -- "$want" "$tmp/e" && [ ! -e "$s/fitted.scene" ] &&
        [ ! -e "$s/resid.svg" ] && ok || bad "fit $*: exit $st, '$(cat "$tmp/e")', want '$want'"
}
refused "\[model\] has no key 'nosuch'" "$s/play.scene" --free nosuch
refused "the play model does not read it" "$s/play.scene" --free ja_a
refused "not a number: only \[model\] number keys" "$s/play.scene" --free kind
refused "not a number: only \[model\] number keys" "$s/play.scene" --free ja_variant
refused "named twice" "$s/play.scene" --free play_r,model.play_r
refused "an empty name" "$s/play.scene" --free play_r,
refused "no \[data nosuch\]" "$s/play.scene" --free play_r --data nosuch
refused "free KEY" "$s/play.scene"
refused "unknown key 'nosuch' in \[model\]" "$s/play.scene" --free play_r --set model.nosuch=1
refused "takes no --set" --benchmark boucwen --set model.m=1
"$hv" fit "$s/play.scene" --free play_r --residuals "$s/r.txt" -o "$s/fitted.scene" -q > /dev/null 2> "$tmp/e"
st=$?
[ $st -eq 2 ] && grep -q "must end in .svg" "$tmp/e" && [ ! -e "$s/fitted.scene" ] && [ ! -e "$s/r.txt" ] && ok ||
    bad "--residuals r.txt: exit $st, '$(cat "$tmp/e")'"
printf 'u,y\n1,2\n3,x\n' > "$s/bad.csv"
scene badx bad.csv 0.2
refused "bad.csv:3:3: column 2 is not a number" "$s/badx.scene" --free play_r
printf 'u,y\n1,2\n3,nan\n' > "$s/bad.csv"
refused "bad.csv:3:3: column 2 is not a finite number" "$s/badx.scene" --free play_r
printf 'u,y\n1,2\n3\n' > "$s/bad.csv"
refused "bad.csv:3:2: the row has 1 column" "$s/badx.scene" --free play_r
printf 'u,y\n1,2\n' > "$s/bad.csv"
refused "a piecewise-linear input needs at least 3 points" "$s/badx.scene" --free play_r
"$hv" fit --help | grep -q -- '--free KEY' && ok || bad "--help does not list --free"
finish "scene_cli"
