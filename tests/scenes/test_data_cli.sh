#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/scenes/test_data_cli.sh HYSTVIZ: measured data through the command (issue 32 item 1,
# docs/SCENES.md "Measured data"): each bad data file is one message FILE:LINE:COL, exit 2,
# nothing written; a file outside the scene's directory is refused; a measured series is in
# the SVG's legend; `hystviz data` writes the measured points and, for a modelled series, the
# measured y and the residual beside the model's.
set -u
hv=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
. "$(dirname "$0")/../lib.sh"
s=$tmp/scenes
mkdir -p "$s/out" "$tmp/elsewhere"
scene() { # scene NAME CSV: a loop figure of the measured file CSV
    printf '[data d]\nfile = "%s"\nu = H\ny = B\n[figure]\nkind = loop\n[series m]\ndata = measured\nof = d\nlabel = "measured B(H)"\n[output]\nformats = svg, png\n' "$2" > "$s/$1.scene"
}
# refused CSV_TEXT MESSAGE: the message exactly, exit 2, no figure and no CSV
refused() {
    printf "$1" > "$s/bad.csv"
    scene bad bad.csv
    rm -rf "$s/out"/*
    "$hv" render "$s/bad.scene" -o "$s/out" > "$tmp/o" 2> "$tmp/e"
    st=$?
    "$hv" data "$s/bad.scene" -o "$s/out/bad.csv" > /dev/null 2>&1
    st2=$?
    [ $st -eq 2 ] && [ $st2 -eq 2 ] && [ "$(cat "$tmp/e")" = "hystviz: $2" ] && [ -z "$(ls -A "$s/out")" ] && [ ! -s "$tmp/o" ] &&
        ok || bad "'$1': exit $st/$st2, '$(cat "$tmp/e")', want '$2'; written: $(ls "$s/out")"
}
refused 'H,B\n1,2\n3,x\n' "$s/bad.csv:3:3: column 2 is not a number"
refused 'H,B\n1,2\n3,nan\n' "$s/bad.csv:3:3: column 2 is not a finite number (nan, inf and overflow are refused)"
refused 'H,B\n1,2\ninf,2\n' "$s/bad.csv:3:1: column 1 is not a finite number (nan, inf and overflow are refused)"
refused 'H,B\n1,2\n3\n' "$s/bad.csv:3:2: the row has 1 column, the rows before it 2"
refused 'X,B\n1,2\n' "$s/bad.csv:1:1: no column named 'H' (u) in the header of 2 columns"
refused '' "$s/bad.csv:1:1: no data rows (the file is empty or holds only comments and a header)"
refused '# only\n\n' "$s/bad.csv:2:1: no data rows (the file is empty or holds only comments and a header)"
# more rows than the cap (4,194,304): 4,194,305 rows of "1 2"
awk 'BEGIN { print "H B"; for (i = 0; i <= 4194304; i++) print "1 2" }' > "$s/big.csv"
scene big big.csv
"$hv" render "$s/big.scene" -o "$s/out" 2> "$tmp/e"
[ $? -eq 2 ] && grep -qxF "hystviz: $s/big.csv:4194306:1: more than 4194304 data rows (the cap on a measured data file)" "$tmp/e" &&
    [ -z "$(ls -A "$s/out")" ] && ok || bad "rows cap: $(cat "$tmp/e")"
# more bytes than the cap (64 MiB): refused at the key before reading
head -c 67108865 /dev/zero > "$s/huge.csv"
scene huge huge.csv
"$hv" render "$s/huge.scene" -o "$s/out" 2> "$tmp/e"
[ $? -eq 2 ] && grep -qF "hystviz: $s/huge.scene:2:1: " "$tmp/e" && grep -qF "larger than the 67108864 bytes allowed" "$tmp/e" &&
    [ -z "$(ls -A "$s/out")" ] && ok || bad "bytes cap: $(cat "$tmp/e")"
rm -f "$s/big.csv" "$s/huge.csv"
# a file outside the scene's directory: refused, nothing of it shown
printf 'H,B\nsecret,1\n' > "$tmp/elsewhere/x.csv"
scene out ../elsewhere/x.csv
"$hv" render "$s/out.scene" -o "$s/out" 2> "$tmp/e"
[ $? -eq 2 ] && grep -qF "lies outside the scene's directory" "$tmp/e" && ! grep -q secret "$tmp/e" &&
    [ -z "$(ls -A "$s/out")" ] && ok || bad "outside: $(cat "$tmp/e")"

# a good file: the legend entry is in the SVG, the axes hold the points
printf '# loop,H,B\n1,-2,-1\n1,0,-1\n1,2,1\n1,0,1\n2,-1,0\n2,1,0.5\n' > "$s/good.csv"
printf '[data d]\nfile = "good.csv"\nu = H\ny = B\nsplit = loop\n[model]\nkind = jiles-atherton\n[data one]\nfile = "good.csv"\nu = 2\ny = 3\nsplit = loop\nrecord = 1\n[input]\nkind = data\ndata = one\n[figure]\nkind = loop\n[series m]\ndata = measured\nof = d\nstyle = none\nmarker = circle\nlabel = "measured B(H)"\n[series f]\ndata = modelled\nof = one\nlabel = "model"\n[output]\nformats = svg\n' > "$s/good.scene"
"$hv" render "$s/good.scene" -o "$s/out" 2> "$tmp/e" && [ -s "$s/out/good.svg" ] && ok || bad "good scene: $(cat "$tmp/e")"
# the legend entry: cairo's SVG draws text as glyphs (<use> of a glyph symbol), so the same
# figure without the measured series' label has fewer glyphs drawn
n1=$(grep -c '<use' "$s/out/good.svg")
sed 's/label = "measured B(H)"//' "$s/good.scene" > "$s/nolabel.scene"
"$hv" render "$s/nolabel.scene" -o "$s/out" 2> "$tmp/e"
n0=$(grep -c '<use' "$s/out/nolabel.svg")
[ "$n1" -gt "$n0" ] && ok || bad "legend entry of the measured series: $n1 glyph uses with the label, $n0 without"
# hystviz data: 6 measured rows (two records), the model's 4 rows and their measured and residual rows
"$hv" data "$s/good.scene" > "$tmp/csv" 2> "$tmp/e" || bad "data: $(cat "$tmp/e")"
[ "$(head -1 "$tmp/csv")" = "series,x,y" ] && ok || bad "header: $(head -1 "$tmp/csv")"
[ "$(grep -c '^m,' "$tmp/csv")" -eq 6 ] && grep -qx 'm,2,1' "$tmp/csv" && grep -qx 'm,1,0.5' "$tmp/csv" && ok ||
    bad "measured rows: $(grep '^m,' "$tmp/csv" | tr '\n' ' ')"
[ "$(grep -c '^f,' "$tmp/csv")" -eq 4 ] && [ "$(grep -c '^f@measured,' "$tmp/csv")" -eq 4 ] &&
    [ "$(grep -c '^f@residual,' "$tmp/csv")" -eq 4 ] && grep -qx 'f@measured,2,1' "$tmp/csv" && ok ||
    bad "modelled rows: $(grep '^f' "$tmp/csv" | tr '\n' ' ')"
# residual = model - measured at every row
awk -F, '$1 == "f" { m[$2 "," NR % 4] = $3; mm[++i] = $3 } $1 == "f@measured" { me[++j] = $3 } $1 == "f@residual" { r[++k] = $3 }
    END { bad = (i != 4 || j != 4 || k != 4); for (n = 1; n <= 4; n++) if (r[n] != mm[n] - me[n] && (r[n] - (mm[n] - me[n]))^2 > 1e-30) bad = 1; exit bad }' "$tmp/csv" &&
    ok || bad "residual is not model - measured"

finish "data_cli"
