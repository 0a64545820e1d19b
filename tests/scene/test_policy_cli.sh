#!/bin/sh
# SPDX-License-Identifier: MIT
# The scene file policy and the work budget through the hystviz command
# (docs/SCENES.md, "Files a scene may read and write", "Work budget").
# Everything is written under a temp dir.
set -u
hv=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
. "$(dirname "$0")/../lib.sh"
mkdir -p "$tmp/proj/scenes" "$tmp/elsewhere" "$tmp/styles"
s=$tmp/proj/scenes

# [output] dir is relative to the scene's directory, not to the working directory
printf '[output]\nname = fig\ndir = "figs"\nformats = svg\n[series a]\ndata = input\n' > "$s/a.scene"
(cd "$tmp/elsewhere" && "$hv" render "$s/a.scene") && [ -s "$s/figs/fig.svg" ] && [ ! -e "$tmp/elsewhere/figs" ] &&
    ok || bad "[output] dir relative to the scene"
# ... and must stay below it; nothing is created
printf '[output]\nname = fig\ndir = "../../out"\n[series a]\ndata = input\n' > "$s/up.scene"
(cd "$tmp/elsewhere" && "$hv" render "$s/up.scene") > "$tmp/o1" 2> "$tmp/err"
st=$?
[ $st -eq 2 ] && grep -qxF "hystviz: $s/up.scene:3:1: 'dir' in [output] must stay below the scene's directory, got '../../out' ('..' climbs above it; use -o on the command line)" "$tmp/err" &&
    [ ! -e "$tmp/out" ] && [ ! -s "$tmp/o1" ] && ok || bad "dir escaping: $st $(cat "$tmp/err")"
printf '[output]\ndir = "%s/abs"\n[series a]\ndata = input\n' "$tmp" > "$s/abs.scene"
"$hv" render "$s/abs.scene" 2> "$tmp/err" && bad "absolute dir accepted" || { [ ! -e "$tmp/abs" ] && ok || bad "absolute dir created"; }
# -o is the user's choice
"$hv" render "$s/up.scene" -o "$tmp/chosen" && [ -s "$tmp/chosen/fig.svg" ] && ok || bad "-o"

# includes: an --include-dir is searched; without it the style is not found
printf '[figure]\ndpi = 100\n' > "$tmp/styles/house.scene"
printf 'include "house.scene"\n[series a]\ndata = input\n' > "$s/inc.scene"
"$hv" data "$s/inc.scene" > /dev/null 2> "$tmp/err" && bad "include without --include-dir" ||
    { grep -qF "$s/inc.scene:1:9: cannot read included file 'house.scene'" "$tmp/err" && ok || bad "msg: $(cat "$tmp/err")"; }
"$hv" data "$s/inc.scene" --include-dir "$tmp/styles" | grep -q '^a,' && ok || bad "--include-dir"

# a scene-named input file outside the scene's directory: refused, nothing of it shown
printf 'root:SECRETSECRET:1\n' > "$tmp/elsewhere/token.txt"
printf '[input]\nkind = file\nfile = "../../elsewhere/token.txt"\n[series a]\ndata = input\n' > "$s/tok.scene"
"$hv" data "$s/tok.scene" > "$tmp/out" 2> "$tmp/err"
st=$?
[ $st -ne 0 ] && grep -qF "$s/tok.scene:3:1:" "$tmp/err" && grep -q "outside the scene's directory" "$tmp/err" &&
    ! grep -q SECRET "$tmp/err" && [ ! -s "$tmp/out" ] && ok || bad "input file outside: $(cat "$tmp/err")"
# ... inside it but not samples: the line number, no text
cp "$tmp/elsewhere/token.txt" "$s/token.txt"
printf '[input]\nkind = file\nfile = "token.txt"\n[series a]\ndata = input\n' > "$s/tok2.scene"
"$hv" data "$s/tok2.scene" 2> "$tmp/err" > /dev/null
grep -qF "token.txt:1: expected two numbers 't u'" "$tmp/err" && ! grep -qE "SECRET|root" "$tmp/err" && ok ||
    bad "scene-named input quoted: $(cat "$tmp/err")"
# a FIFO as input file: refused at once (timeout guards the old endless read)
mkfifo "$s/fifo.txt"
printf '[input]\nkind = file\nfile = "fifo.txt"\n[series a]\ndata = input\n' > "$s/fifo.scene"
timeout 10 "$hv" data "$s/fifo.scene" > /dev/null 2> "$tmp/err"
st=$?
[ $st -ne 0 ] && [ $st -ne 124 ] && grep -q "cannot open input file: is a FIFO, not a regular file" "$tmp/err" && ok || bad "FIFO: $st $(cat "$tmp/err")"
# a file the user names: at most 20 bytes of the line
"$hv" loop --input "file:$tmp/elsewhere/token.txt" > /dev/null 2> "$tmp/err"
grep -qF "'root:SECRETSECRET:1'" "$tmp/err" && ok || bad "excerpt: $(cat "$tmp/err")"
printf 'root:$6$abcdefghijklmnopqrstuvwxyz0123456789\n' > "$tmp/elsewhere/long.txt"
"$hv" loop --input "file:$tmp/elsewhere/long.txt" > /dev/null 2> "$tmp/err"
grep -qF "'root:\$6\$abcdefghijkl...'" "$tmp/err" && ! grep -q "mnop" "$tmp/err" && ok || bad "long excerpt: $(cat "$tmp/err")"
"$hv" loop --input "file:/dev/zero" > /dev/null 2> "$tmp/err"
grep -q "character device, not a regular file" "$tmp/err" && ok || bad "/dev/zero: $(cat "$tmp/err")"

# the work budget: refused at once with the estimate and the budget; --max-work raises it
printf '[compute]\npoints = 10000000\ncycles = 2\n' > "$s/work.scene"
for g in 1 2 3 4 5 6 7 8 9 10; do printf '[series g%s]\ndata = ygamma\ngamma = %s\n' $g $g >> "$s/work.scene"; done
timeout 20 "$hv" data "$s/work.scene" > "$tmp/out" 2> "$tmp/err"
st=$?
[ $st -ne 0 ] && [ $st -ne 124 ] && grep -qF "$s/work.scene:2:1: the scene asks for about 9.28e+08 units of work" "$tmp/err" &&
    grep -qF "more than the budget of 1e+08" "$tmp/err" && [ ! -s "$tmp/out" ] && ok || bad "budget: $st $(cat "$tmp/err")"
# a GSL solve over its work limit is refused before any solve starts (issue 36
# item 1: Fig. 4 at 7000 cycles solved gamma = 20 and 200 for 15 s, 12 s of CPU,
# before gamma = 2000 was refused); the CPU limit stops the old behaviour
printf '[model]\nkind = dahl-filter\nrho = 1\nfc = 1\ntau = 1\n[input]\nkind = sine\namp = 1\nperiod = 1\n' > "$s/stiff.scene"
printf '[compute]\ncycles = 7000\npoints = 1500\nsolver = rk8pd\nrtol = 1e-9\natol = 1e-11\n' >> "$s/stiff.scene"
for g in 20 200 2000; do printf '[series g%s]\ndata = ygamma\ngamma = %s\n' $g $g >> "$s/stiff.scene"; done
(ulimit -t 5; timeout 60 "$hv" data "$s/stiff.scene" --max-work 1e9 > "$tmp/out" 2> "$tmp/err")
st=$?
[ $st -eq 2 ] && grep -qF "$s/stiff.scene:13:1: gamma = 2000: refused: rk8pd at rtol 1e-09 needs at least" "$tmp/err" &&
    [ ! -s "$tmp/out" ] && ok || bad "stiff solve refused first: $st $(cat "$tmp/err")"
printf '[compute]\npoints = 1000\n[series a]\ndata = input\n' > "$s/small.scene"
"$hv" data "$s/small.scene" --max-work 100 > /dev/null 2> "$tmp/err" && bad "--max-work 100 not applied" ||
    { grep -q "about 2.32e+03 units of work" "$tmp/err" && ok || bad "small budget: $(cat "$tmp/err")"; }
"$hv" data "$s/small.scene" --max-work 3000 > /dev/null && ok || bad "--max-work 3000"
"$hv" data "$s/small.scene" --max-work abc > /dev/null 2> "$tmp/err"
[ $? -eq 2 ] && ok || bad "--max-work abc: $(cat "$tmp/err")"

# an animation's budget counts every frame (frames x a frame's work); refused before any frame
printf '[compute]\npoints = 100\n[series a]\ndata = input\n[animation]\nduration = 1\nfps = 10\n[keyframe k]\nkey = "model.sigma0"\ntimes = 0, 1\nvalues = 1, 2\n' > "$s/anim.scene"
"$hv" animate "$s/anim.scene" -o "$tmp/frames" --quiet --max-work 1000 > /dev/null 2> "$tmp/err"
st=$?
if [ $st -ne 3 ]; then # 3: built without OSMesa
    [ $st -ne 0 ] && grep -q "units of work (10 frames" "$tmp/err" && [ ! -e "$tmp/frames/anim" ] && ok ||
        bad "animate budget: $st $(cat "$tmp/err")"
fi

finish "scene policy cli"
