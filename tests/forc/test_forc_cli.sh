#!/bin/sh
# SPDX-License-Identifier: MIT
# `hystviz forc` as a user runs it: the measured file to CSV, -v timings,
# refused files (exit 2, file:line:col, nothing written), the Preisach
# protocol (the density's peak where the model puts it), --curves-out, --help.
# tests/forc/test_forc_cli.sh HYSTVIZ FILE.forc
set -u
hv=$1 data=$2
. "$(dirname "$0")/../lib.sh"

"$hv" forc --help > "$tmp/help" && grep -q '^usage: hystviz forc FILE' "$tmp/help" && ok || bad "--help"

# the measured file: 43 x 120 nodes (one per field step) + the header line
"$hv" forc "$data" -v -o "$tmp/rho.csv" 2> "$tmp/err" && ok || bad "forc FILE: $(cat "$tmp/err")"
[ "$(head -1 "$tmp/rho.csv")" = "hc,hu,rho" ] && [ "$(wc -l < "$tmp/rho.csv")" -eq 5161 ] && ok ||
    bad "rho.csv: $(head -1 "$tmp/rho.csv"), $(wc -l < "$tmp/rho.csv") lines"
grep -q '120 curves, 8394 points, 120 calibration points, fields in T, moments in A m2' "$tmp/err" && ok ||
    bad "-v: $(cat "$tmp/err")"
grep -q 'read [0-9.]* ms (CPU [0-9.]* ms), regression [0-9.]* ms' "$tmp/err" && ok || bad "-v timings: $(cat "$tmp/err")"
# finite values where fitted, nan outside the data; not all nan
n=$(awk -F, 'NR > 1 && $3 != "nan"' "$tmp/rho.csv" | wc -l)
[ "$n" -eq 4257 ] && ok || bad "$n fitted nodes (4257 expected)"
# drift correction and SF options are accepted and change the result
"$hv" forc "$data" --drift --sc0 2 --sc1 5 -o "$tmp/rho2.csv" && ! cmp -s "$tmp/rho.csv" "$tmp/rho2.csv" && ok ||
    bad "--drift --sc0 --sc1"

# refused files: exit 2 at file:line:col, no output
head -n 1999 "$data" > "$tmp/cut.forc"
"$hv" forc "$tmp/cut.forc" -o "$tmp/out.csv" 2> "$tmp/err"
[ $? -eq 2 ] && grep -q "cut.forc:1999:[0-9]*: the file ends after 43 curves; the header says NCrv = 120" "$tmp/err" &&
    [ ! -e "$tmp/out.csv" ] && ok || bad "truncated file: $(cat "$tmp/err")"
sed '19s/120/12O/' "$data" > "$tmp/head.forc"
"$hv" forc "$tmp/head.forc" -o "$tmp/out.csv" 2> "$tmp/err"
[ $? -eq 2 ] && grep -q "head.forc:19:18: broken header: NCrv" "$tmp/err" && [ ! -e "$tmp/out.csv" ] && ok ||
    bad "broken header: $(cat "$tmp/err")"
printf 'ha,hb,m\n0,0,1\n0,0.1,inf\n' > "$tmp/bad.csv"
"$hv" forc "$tmp/bad.csv" -o "$tmp/out.csv" 2> "$tmp/err"
[ $? -eq 2 ] && grep -q "bad.csv:3:7: NaN or infinity" "$tmp/err" && [ ! -e "$tmp/out.csv" ] && ok ||
    bad "inf in CSV: $(cat "$tmp/err")"
printf 'ha,hb,m\n0,0,1\n0,0.1,2\n-0.1,-0.1,0\n-0.1,0,1\n-0.1,0.1,2\n' > "$tmp/ok.csv"
"$hv" forc "$tmp/ok.csv" --drift -o "$tmp/out.csv" 2> "$tmp/err"
[ $? -eq 2 ] && grep -q "no calibration point" "$tmp/err" && [ ! -e "$tmp/out.csv" ] && ok ||
    bad "--drift without calibration points: $(cat "$tmp/err")"
"$hv" forc "$tmp/missing.forc" 2> "$tmp/err"
[ $? -eq 2 ] && ok || bad "missing file"
"$hv" forc "$data" --grid 0:1:10 2> "$tmp/err"
[ $? -eq 2 ] && grep -q 'HC0:HC1:NC,HU0:HU1:NU' "$tmp/err" && ok || bad "bad --grid: $(cat "$tmp/err")"
"$hv" forc "$data" --sf 0.5 -o "$tmp/out.csv" 2> "$tmp/err"
[ $? -eq 2 ] && grep -q 'SF must be in' "$tmp/err" && [ ! -e "$tmp/out.csv" ] && ok || bad "--sf 0.5: $(cat "$tmp/err")"

# the Preisach protocol: the distribution peaks at the density's centre
# (H_c, H_u) = (hc, 0) = (0.3, 0) with the density's peak 1/(2 pi 0.1^2) = 15.9
# (its mass on alpha >= beta is 1 - 1e-5); SF = 3 at the step 1.4/80 = 0.0175 (a
# box of half-width 0.06 = 0.6 sigma) lowers it by about 7 %: 14.5 to 16
"$hv" forc --preisach gaussian:0.3,0.1 --curves 81 --grid 0:0.6:61,-0.3:0.3:61 -o "$tmp/pr.csv" \
    --curves-out "$tmp/curves.csv" 2> "$tmp/err" && ok || bad "--preisach: $(cat "$tmp/err")"
awk -F, 'NR > 1 && $3 != "nan" && $3 > m {m = $3; c = $1; u = $2}
    END {exit !(m > 14.5 && m < 16 && c > 0.29 && c < 0.31 && u > -0.01 && u < 0.01)}' "$tmp/pr.csv" && ok ||
    bad "Preisach peak: $(awk -F, 'NR > 1 && $3 != "nan" && $3 > m {m = $3; c = $1; u = $2} END {print m, c, u}' "$tmp/pr.csv")"
[ "$(head -1 "$tmp/curves.csv")" = "ha,hb,m" ] && [ "$(wc -l < "$tmp/curves.csv")" -eq $((81 * 82 / 2 + 1)) ] && ok ||
    bad "curves.csv: $(wc -l < "$tmp/curves.csv") lines"
# the curves written read back as CSV and give the same distribution
"$hv" forc "$tmp/curves.csv" --grid 0:0.6:61,-0.3:0.3:61 -o "$tmp/pr2.csv" && cmp -s "$tmp/pr.csv" "$tmp/pr2.csv" &&
    ok || bad "curves.csv read back"
"$hv" forc --preisach cauchy:0.3,0.1 2> "$tmp/err"
[ $? -eq 2 ] && grep -q "unknown distribution 'cauchy'" "$tmp/err" && ok || bad "bad --preisach"
"$hv" forc "$data" --preisach gaussian:0.3,0.1 2> /dev/null
[ $? -eq 2 ] && ok || bad "FILE and --preisach together"

# the figure: SVG with the map as one embedded PNG image and vector paths
# (contours, frame, ticks, glyphs), PDF, PNG at 150 dpi (400 x 320 pt -> 833 x 667)
"$hv" forc "$data" --figure "$tmp/f.svg" -o "$tmp/rho3.csv" && ok || bad "--figure svg"
[ "$(grep -c '<image' "$tmp/f.svg")" -eq 1 ] && grep -q 'xlink:href="data:image/png;base64,' "$tmp/f.svg" &&
    [ "$(grep -c '<path' "$tmp/f.svg")" -ge 50 ] && ok ||
    bad "svg: $(grep -c '<image' "$tmp/f.svg") images, $(grep -c '<path' "$tmp/f.svg") paths"
cmp -s "$tmp/rho.csv" "$tmp/rho3.csv" && ok || bad "--figure changed the CSV"
"$hv" forc "$data" --figure "$tmp/f.pdf" --levels 0,0.5 && [ "$(head -c 5 "$tmp/f.pdf")" = "%PDF-" ] && ok || bad "pdf"
"$hv" forc --preisach gaussian:0.3,0.1 --curves 40 --figure "$tmp/f.png" && ok || bad "png"
[ "$(od -An -tx1 -j16 -N8 "$tmp/f.png" | tr -d ' \n')" = "000003410000029b" ] && ok ||
    bad "png size: $(od -An -tx1 -j16 -N8 "$tmp/f.png")"
"$hv" forc "$data" --figure "$tmp/f.gif" 2> "$tmp/err"
[ $? -eq 2 ] && grep -q "does not end in .svg, .pdf or .png" "$tmp/err" && ok || bad "--figure f.gif"
"$hv" forc "$tmp/cut.forc" --figure "$tmp/g.svg" -o "$tmp/g.csv" 2> /dev/null
[ $? -eq 2 ] && [ ! -e "$tmp/g.svg" ] && [ ! -e "$tmp/g.csv" ] && ok || bad "refused file wrote a figure"
"$hv" forc "$data" --levels 0,x 2> "$tmp/err"
[ $? -eq 2 ] && grep -q -- "--levels" "$tmp/err" && ok || bad "--levels 0,x"

finish "forc_cli"
