#!/bin/sh
# SPDX-License-Identifier: MIT
# Tests of `hystviz sweep` (issue 13): the Fig. 15 study gives 50 figures and a
# 50-row table whose loop areas equal `hystviz loops` at the same values (the
# same closed form through another front end: the same doubles); a point's
# files are byte for byte `hystviz render --set ...`; the table does not depend
# on -j or on --formats none; grid values, order and names; bad input exits 2
# with nothing written; a point the scene refuses gets a row and exit 2.
# usage: test_sweep.sh HYSTVIZ SCENES_DIR
set -u
hv=$1
scenes=$2
. "$(dirname "$0")/../lib.sh"
fig15=$scenes/fig15_minor_loop_ex4.scene

# ---- the done-when study ----------------------------------------------------
"$hv" sweep "$fig15" --grid model.sigma0=1:10:log10 --grid input.umin2=0.1:0.5:5 -o "$tmp/study" -j 2 -q
[ $? -eq 0 ] && ok || bad "fig15 study exit status"
for e in svg pdf png; do
    n=$(ls "$tmp/study" | grep -c "\.$e\$")
    [ "$n" -eq 50 ] && ok || bad "$n .$e figures, expected 50"
done
[ "$(wc -l < "$tmp/study/sweep.csv")" -eq 51 ] && ok || bad "sweep.csv: $(wc -l < "$tmp/study/sweep.csv") lines, expected 51"
[ "$(ls "$tmp/study" | wc -l)" -eq 151 ] && ok || bad "study dir holds $(ls "$tmp/study" | wc -l) files, expected 151"
head -1 "$tmp/study/sweep.csv" | grep -q '^index,status,name,model.sigma0,input.umin2,ysteady_min,ysteady_max,nminor,major_area,minor1_area,minor_areas,energy,' &&
    ok || bad "header: $(head -1 "$tmp/study/sweep.csv")"
# row-major order: sigma0 (first --grid) outer, umin2 inner; log and linear values
cut -d, -f4 "$tmp/study/sweep.csv" | sed -n '2p;7p;51p' | tr '\n' ' ' | grep -q '^1 1.2915496650148839 10 $' && ok ||
    bad "sigma0 column: $(cut -d, -f4 "$tmp/study/sweep.csv" | sed -n '2p;7p;51p' | tr '\n' ' ')"
[ "$(cut -d, -f5 "$tmp/study/sweep.csv" | sed -n '2,6p' | tr '\n' ' ')" = "0.1 0.2 0.3 0.4 0.5 " ] && ok || bad "umin2 column"
[ "$(grep -c ',ok,' "$tmp/study/sweep.csv")" -eq 50 ] && ok || bad "not every row ok"
# every row's areas are those of `hystviz loops` for the same values: the same
# doubles (the table prints the shortest decimal that reads back, loops %.17g)
same() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a != "" && b != "" && a + 0 == b + 0) }'; }
mism=0
checked=0
tail -n +2 "$tmp/study/sweep.csv" | while IFS=, read -r idx st name s0 u2 ymin ymax nmin major minor1 minors energy rest; do
    "$hv" loops --model lugre --sigma0 "$s0" --sigma1 1 --fc 1 --fs 2 --vs 1 --beta 1 --input "bimodal:0,$u2,1,1.5" > "$tmp/l.csv"
    lmaj=$(grep '^major,' "$tmp/l.csv" | cut -d, -f10)
    lmin=$(grep '^minor,' "$tmp/l.csv" | cut -d, -f10)
    len=$(sed -n 's/^# energy per cycle.*: //p' "$tmp/l.csv")
    if ! same "$lmaj" "$major" || ! same "$lmin" "$minor1" || ! same "$lmin" "$minors" || ! same "$len" "$energy" || [ "$nmin" != 1 ]; then
        echo "row $idx: sweep $major $minor1 $energy, loops $lmaj $lmin $len"
    fi
done > "$tmp/mism"
[ ! -s "$tmp/mism" ] && ok || bad "areas differ from hystviz loops: $(head -3 "$tmp/mism")"
# and they vary: not one value repeated (sigma0 and umin2 both change the loops)
[ "$(tail -n +2 "$tmp/study/sweep.csv" | cut -d, -f10 | sort -u | wc -l)" -eq 50 ] && ok || bad "minor areas not all distinct"

# ---- a point is `render --set` byte for byte --------------------------------
for idx in 0 17 49; do
    row=$(grep "^$idx," "$tmp/study/sweep.csv")
    name=$(echo "$row" | cut -d, -f3)
    s0=$(echo "$row" | cut -d, -f4)
    u2=$(echo "$row" | cut -d, -f5)
    rm -rf "$tmp/r"
    "$hv" render "$fig15" --set model.sigma0="$s0" --set input.umin2="$u2" --set output.name="$name" -o "$tmp/r" 2> /dev/null
    for e in svg pdf png; do
        cmp -s "$tmp/r/$name.$e" "$tmp/study/$name.$e" && ok || bad "point $idx .$e differs from render --set"
    done
    # the name says index and values
    [ "$name" = "$(printf 'p%02d_sigma0-%s_umin2-%s' "$idx" "$s0" "$u2")" ] && ok || bad "point name $name"
done

# ---- the table depends on neither -j nor --formats none ---------------------
"$hv" sweep "$fig15" --grid model.sigma0=1:10:log10 --grid input.umin2=0.1:0.5:5 -o "$tmp/j1" -j 1 -q --formats none
[ $? -eq 0 ] && cmp -s "$tmp/j1/sweep.csv" "$tmp/study/sweep.csv" && ok || bad "-j 1 --formats none table differs"
[ "$(ls "$tmp/j1")" = "sweep.csv" ] && ok || bad "--formats none wrote figures: $(ls "$tmp/j1" | head -3)"
"$hv" sweep "$fig15" --grid input.umin2=0.1,0.3 -o "$tmp/svg" -q --formats svg
[ "$(ls "$tmp/svg" | tr '\n' ' ')" = "p0_umin2-0.1.svg p1_umin2-0.3.svg sweep.csv " ] && ok || bad "--formats svg: $(ls "$tmp/svg" | tr '\n' ' ')"
# --times adds compute_s after the grid keys
"$hv" sweep "$fig15" --grid input.umin2=0.2 -o "$tmp/t" -q --formats none --times
head -1 "$tmp/t/sweep.csv" | grep -q '^index,status,name,input.umin2,compute_s,ysteady_min' && ok || bad "--times header"
sed -n 2p "$tmp/t/sweep.csv" | cut -d, -f5 | grep -Eq '^[0-9.e-]+$' && ok || bad "--times value"

# ---- the measured error of a GSL solve (Fig. 11 with rkf45 against the exact
# solution, the input being piecewise linear): numbers, below rtol 1e-8 x 100
"$hv" sweep "$scenes/fig11_ygamma_ex3.scene" --set compute.solver=rkf45 --grid model.sigma0=1,6 -o "$tmp/g" -q --formats none --verify
head -1 "$tmp/g/sweep.csv" | grep -q ',err_measured_1_in_1,ystar.err,g1.err,g10.err,g100.err,g1.dist,g10.dist,g100.dist,message$' && ok || bad "fig11 header: $(head -1 "$tmp/g/sweep.csv")"
errs=$(tail -n +2 "$tmp/g/sweep.csv" | cut -d, -f14-16 | tr ',\n' '  ')
[ "$(echo $errs | wc -w)" -eq 6 ] && echo $errs | awk '{ for (i = 1; i <= NF; i++) if (!($i >= 0 && $i < 1e-6)) exit 1 }' && ok ||
    bad "fig11 rkf45 errors: '$errs'"

# ---- errors measured on a sample (1 in 1000 points), every point with --verify;
# the other numbers do not depend on it, and a point outside the sample shows
# no error (none was measured there).  --verify runs on the points 0, 500, ...,
# 2000 only (--shard 0/500: the sampled rows and two between them; measuring
# all 2,002 took 3 s of CPU, several times that under the sanitizers)
g1000="--grid model.sigma0=1:10:log1001 --grid input.umin2=0.2,0.3"
"$hv" sweep "$fig15" $g1000 -o "$tmp/s" -q --formats none
"$hv" sweep "$fig15" $g1000 -o "$tmp/sv" -q --formats none --verify --shard 0/500
sv=$tmp/sv/sweep.shard-0-of-500.csv
every500() { awk -F, '$1 ~ /^[0-9]+$/ && $1 % 500 == 0' "$1"; }
head -1 "$tmp/s/sweep.csv" | grep -q ',energy,err_measured_1_in_1000,major.err,minor.err,t1.err,t5.err,message$' && ok ||
    bad "sampled header: $(head -1 "$tmp/s/sweep.csv")"
[ "$(every500 "$tmp/s/sweep.csv" | cut -d, -f1-12,18)" = "$(every500 "$sv" | cut -d, -f1-12,18)" ] &&
    [ "$(every500 "$sv" | wc -l)" -eq 5 ] && ok || bad "the sample changed the table's other numbers"
# measured: rows 0, 1000, 2000 (and only they), with the errors --verify gives there
[ "$(awk -F, 'NR > 1 && $13 == 1 { printf "%s ", $1 }' "$tmp/s/sweep.csv")" = "0 1000 2000 " ] && ok ||
    bad "measured rows: $(awk -F, 'NR > 1 && $13 == 1 { printf "%s ", $1 }' "$tmp/s/sweep.csv")"
[ "$(grep -E '^(0|1000|2000),' "$tmp/s/sweep.csv" | cut -d, -f1-12,14-)" = "$(grep -E '^(0|1000|2000),' "$sv" | cut -d, -f1-12,14-)" ] &&
    ok || bad "a sampled row differs from --verify's"
[ "$(awk -F, 'NR > 1 && $13 == 0 && ($14 != "" || $15 != "" || $16 != "" || $17 != "")' "$tmp/s/sweep.csv" | wc -l)" -eq 0 ] &&
    ok || bad "an error printed where none was measured"
[ "$(every500 "$sv" | awk -F, '$13 == 1 && $14 + 0 > 0 && $14 + 0 < 1e-12' | wc -l)" -eq 5 ] && ok ||
    bad "--verify: not every row has a measured error"
"$hv" sweep --help | grep -q 'multiple of K = 1000' && ok || bad "--help does not give K"

# ---- grid values ------------------------------------------------------------
"$hv" sweep "$fig15" --grid model.sigma0=1:1e3:log4 --grid input.umin2=0.25:0.25:1 -o "$tmp/v" -q --formats none
[ "$(tail -n +2 "$tmp/v/sweep.csv" | cut -d, -f4 | tr '\n' ' ')" = "1 10 100 1000 " ] && ok || bad "log range 1:1e3:log4"
"$hv" sweep "$fig15" --grid 'model.sigma0= 6, 2 ,1' -o "$tmp/l" -q --formats none
[ "$(tail -n +2 "$tmp/l/sweep.csv" | cut -d, -f4 | tr '\n' ' ')" = "6 2 1 " ] && ok || bad "list order kept"

# ---- bad input: exit 2, a message naming the option, nothing written --------
for g in 'model.sigma0=1:10' 'model.sigma0=1:10:0' 'model.sigma0=0:10:log3' 'model.sigma0=1:2:x' 'model.sigma0=1,,2' \
         'sigma0=1,2' 'model.sigma0=' 'model.sigma0=1:nan:3' 'model.sigma0=1:2:1'; do
    "$hv" sweep "$fig15" --grid "$g" -o "$tmp/bad" -q 2> "$tmp/err"
    st=$?
    [ $st -eq 2 ] && grep -q -- '--grid' "$tmp/err" && [ ! -e "$tmp/bad" ] && ok || bad "--grid '$g': status $st, $(cat "$tmp/err")"
done
"$hv" sweep "$fig15" --grid model.sigma0=1,-1 -o "$tmp/bad" 2> "$tmp/err"
[ $? -eq 2 ] && grep -q "value '-1'" "$tmp/err" && [ ! -e "$tmp/bad" ] && ok || bad "refused value: $(cat "$tmp/err")"
"$hv" sweep "$fig15" --grid model.nosuch=1,2 -o "$tmp/bad" 2> "$tmp/err"
[ $? -eq 2 ] && [ ! -e "$tmp/bad" ] && ok || bad "unknown key: $(cat "$tmp/err")"
"$hv" sweep "$fig15" --grid output.name=a,b -o "$tmp/bad" 2> "$tmp/err"
[ $? -eq 2 ] && [ ! -e "$tmp/bad" ] && ok || bad "output.name as grid key accepted"
"$hv" sweep "$fig15" --grid model.sigma0=1,2 --grid model.sigma0=3 -o "$tmp/bad" 2> "$tmp/err"
[ $? -eq 2 ] && [ ! -e "$tmp/bad" ] && ok || bad "key given twice"
"$hv" sweep "$fig15" --grid model.sigma0=1:10:1000000 --grid input.umin2=0.1:0.5:1000 -o "$tmp/bad" 2> "$tmp/err"
[ $? -eq 2 ] && grep -q 'more than' "$tmp/err" && [ ! -e "$tmp/bad" ] && ok || bad "grid too large: $(cat "$tmp/err")"
for f in 'svg,gif' '' 'none,svg'; do
    "$hv" sweep "$fig15" --grid model.sigma0=1 --formats "$f" -o "$tmp/bad" 2> /dev/null
    [ $? -eq 2 ] && [ ! -e "$tmp/bad" ] && ok || bad "--formats '$f' accepted"
done
for s in '3/3' '-1/3' '1/0' '1' 'a/b' '1/3x'; do
    "$hv" sweep "$fig15" --grid model.sigma0=1 --shard "$s" -o "$tmp/bad" 2> "$tmp/err"
    [ $? -eq 2 ] && grep -q -- '--shard' "$tmp/err" && [ ! -e "$tmp/bad" ] && ok || bad "--shard '$s' accepted"
done
"$hv" sweep "$tmp/none.scene" --grid model.sigma0=1 -o "$tmp/bad" 2> /dev/null
[ $? -eq 2 ] && [ ! -e "$tmp/bad" ] && ok || bad "missing scene"

# a PNG over the raster limits: refused before anything is written, or as the
# row of the one point whose dpi makes it too large
"$hv" sweep "$fig15" --set 'figure.size=100cm, 100cm' --grid figure.dpi=2400 -o "$tmp/bad" --formats png 2> "$tmp/err"
[ $? -eq 2 ] && grep -q -i 'pixels' "$tmp/err" && [ ! -e "$tmp/bad" ] && ok || bad "huge PNG at point 0: $(cat "$tmp/err")"
"$hv" sweep "$fig15" --set 'figure.size=100cm, 100cm' --grid figure.dpi=36,2400 -o "$tmp/dpi" --formats png -q 2> /dev/null
[ $? -eq 2 ] && [ "$(cut -d, -f2 "$tmp/dpi/sweep.csv" | tr '\n' ' ')" = "status ok invalid " ] && [ "$(ls "$tmp/dpi" | wc -l)" -eq 2 ] &&
    ok || bad "huge PNG at point 1: $(cat "$tmp/dpi/sweep.csv" 2> /dev/null)"

# the scene file policy and work budget, as render's: an include from another
# directory needs --include-dir; a budget below the scene's work refuses it up front
mkdir "$tmp/own"
cp "$fig15" "$tmp/own/f15.scene"
"$hv" sweep "$tmp/own/f15.scene" --grid model.sigma0=1,2 -o "$tmp/bad" --formats none 2> "$tmp/err"
[ $? -eq 2 ] && grep -q 'style.scene' "$tmp/err" && [ ! -e "$tmp/bad" ] && ok || bad "include outside the scene dir: $(cat "$tmp/err")"
"$hv" sweep "$fig15" --grid model.sigma0=1,2 -o "$tmp/inc0" --formats none -q
"$hv" sweep "$tmp/own/f15.scene" --include-dir "$scenes" --grid model.sigma0=1,2 -o "$tmp/inc" --formats none -q &&
    cmp -s "$tmp/inc/sweep.csv" "$tmp/inc0/sweep.csv" && ok || bad "--include-dir: table differs"
"$hv" sweep "$fig15" --grid model.sigma0=1,2 --max-work 100 -o "$tmp/bad" --formats none 2> "$tmp/err"
[ $? -eq 2 ] && grep -q 'work' "$tmp/err" && [ ! -e "$tmp/bad" ] && ok || bad "--max-work 100: $(cat "$tmp/err")"
"$hv" sweep "$fig15" --grid compute.points=100,100000 --max-work 5e5 -o "$tmp/w" --formats none -q 2> /dev/null
[ $? -eq 2 ] && [ "$(cut -d, -f2 "$tmp/w/sweep.csv" | tr '\n' ' ')" = "status ok invalid " ] && grep -q 'budget' "$tmp/w/sweep.csv" &&
    ok || bad "a point over the budget: $(cat "$tmp/w/sweep.csv" 2> /dev/null)"

# ---- a point the scene refuses: its row says why, the others are done --------
# umin2 = 1.2 > umax1 = 1 passes the key's own range but not the input's check
"$hv" sweep "$fig15" --grid input.umin2=0.2,1.2,0.4 -o "$tmp/p" -q --formats svg 2> "$tmp/err"
[ $? -eq 2 ] && ok || bad "refused point: exit status not 2"
[ "$(cut -d, -f2 "$tmp/p/sweep.csv" | tr '\n' ' ')" = "status ok invalid ok " ] && ok || bad "statuses: $(cut -d, -f2 "$tmp/p/sweep.csv" | tr '\n' ' ')"
grep '^1,invalid' "$tmp/p/sweep.csv" | grep -q 'umin2' && ok || bad "refused row has no message naming the key"
[ -e "$tmp/p/p0_umin2-0.2.svg" ] && [ -e "$tmp/p/p2_umin2-0.4.svg" ] && [ ! -e "$tmp/p/p1_umin2-1.2.svg" ] && ok || bad "figures of a refused point"

# ---- a Jiles-Atherton study (issue 22): the pinning k of Fig. 1 ------------
fig01=$scenes/fig01_magnetic_minor_loop.scene
# (the schema's ja_c >= 0; c < 1 is jiles1986's own refusal, at the point: jtd1992 takes any c >= 0)
msg=$("$hv" sweep "$fig01" --grid model.ja_c=0.2,-0.1 --formats none -o "$tmp/jac" -q 2>&1)
[ $? -eq 2 ] && [ ! -e "$tmp/jac" ] && echo "$msg" | grep -q "'ja_c' in \[model\] must be >= 0, got -0.1" && ok ||
    bad "ja study: ja_c = -0.1 not refused up front naming ja_c: $msg"
"$hv" sweep "$fig01" --grid model.ja_k=200:600:3 --formats none -o "$tmp/ja" -q
[ $? -eq 0 ] && ok || bad "ja study exit status"
[ "$(grep -c ',ok,' "$tmp/ja/sweep.csv")" -eq 3 ] && ok || bad "ja study: 3 ok rows"
# k = 400 is Fig. 1: its minor loop area as render's {minor1.area} and test_models (816.9296513 J/m^3)
grep '^1,ok,p1_ja_k-400,' "$tmp/ja/sweep.csv" | cut -d, -f9 | grep -q '^816\.92965130' && ok ||
    bad "ja study: k = 400 minor loop area is not Fig. 1's"
a200=$(grep '^0,ok,' "$tmp/ja/sweep.csv" | cut -d, -f9)
a400=$(grep '^1,ok,' "$tmp/ja/sweep.csv" | cut -d, -f9)
awk -v a="$a200" -v b="$a400" 'BEGIN { exit !(a > 0 && a < b) }' && ok || bad "ja study: minor area at k = 200 ($a200) not below k = 400 ($a400)"

finish "test_sweep"
