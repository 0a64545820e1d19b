#!/bin/sh
# SPDX-License-Identifier: MIT
# Reproducible outputs and build (issue 19): every output written twice by
# identical runs is byte-identical: render's SVG, PDF and PNG, a sweep (its
# figures, sweep.csv, the summary plot), a gallery (figures and index.html;
# its .manifest keeps render times, by design), boucwen's CSV, export's HTML, and with GL
# an animation's PNG frames, poster and MP4, WebM (16 bytes of a random
# segment UID differed before -fflags +bitexact) and GIF, piped and
# assembled.  SOURCE_DATE_EPOCH sets the PDF creation date (without it a
# fixed 2000-01-01).  The programs hold no absolute path of the source or
# build tree (strings).
# usage: test_repro.sh HYSTVIZ SOURCE_ROOT BUILD_ROOT
set -u
hv=$1
src=$(cd "$2" && pwd)
bld=$(cd "$3" && pwd)
case $hv in /*) ;; *) hv=$(pwd)/$hv ;; esac
. "$(dirname "$0")/../lib.sh"
cd "$tmp" || exit 1
unset SOURCE_DATE_EPOCH
fig15=$src/scenes/fig15_minor_loop_ex4.scene
# same DIR1 DIR2 WHAT [diff options]: the two runs wrote the same files, byte for byte
same() {
    a=$1 b=$2 what=$3
    shift 3
    if [ ! -d "$a" ] || [ -z "$(ls "$a")" ]; then
        bad "$what: the first run wrote nothing"
    elif diff -r "$@" "$a" "$b" > diff.out 2>&1; then
        ok
    else
        bad "$what differs between identical runs: $(head -n 3 diff.out)"
    fi
}

for i in 1 2; do
    "$hv" render "$fig15" --set output.formats=svg,pdf,png -o "r$i" > /dev/null 2>&1 || bad "render run $i"
    "$hv" sweep "$fig15" --grid model.sigma0=1:10:log3 --grid input.umin2=0.2,0.4 --formats svg,pdf,png \
        --plot minor1_area -o "s$i" -q -j 2 || bad "sweep run $i"
    mkdir -p "sc"
    cp "$src/scenes/style.scene" "$src/scenes/fig05_g_stribeck.scene" "$fig15" sc/
    "$hv" gallery --scenes sc -o "g$i" -q -j 2 || bad "gallery run $i"
    "$hv" boucwen data --signal multisine --periods 1 -o "b$i.csv" || bad "boucwen run $i"
    "$hv" export "$fig15" --grid model.sigma0=1,2 -o "x$i.html" -q -j 2 || bad "export run $i"
done
same r1 r2 "render svg,pdf,png"
[ "$(ls r1 | wc -l)" -eq 3 ] && ok || bad "render wrote $(ls r1)"
same s1 s2 "sweep (figures, sweep.csv, plot)"
[ -s s1/sweep.csv ] && [ -s s1/sweep_minor1_area.svg ] && ok || bad "sweep wrote $(ls s1 | head -3)"
same g1 g2 "gallery" -x .manifest -x .lock
cmp -s b1.csv b2.csv && [ -s b1.csv ] && ok || bad "boucwen CSV differs between identical runs"
cmp -s x1.html x2.html && [ -s x1.html ] && ok || bad "export's HTML differs between identical runs"

# the PDF creation date: SOURCE_DATE_EPOCH, else fixed
pdf=r1/fig15_minor_loop_ex4.pdf
grep -a -q '/CreationDate (20000101000000Z)' "$pdf" && ok || bad "PDF date without SOURCE_DATE_EPOCH: $(grep -a CreationDate "$pdf")"
SOURCE_DATE_EPOCH=1700000000 "$hv" render "$fig15" --set output.formats=pdf -o e1 > /dev/null 2>&1
grep -a -q '/CreationDate (20231114221320Z)' e1/fig15_minor_loop_ex4.pdf && ok ||
    bad "SOURCE_DATE_EPOCH=1700000000 (2023-11-14 22:13:20 UTC) not the PDF date: $(grep -a CreationDate e1/*.pdf)"
SOURCE_DATE_EPOCH=1700000000 "$hv" sweep "$fig15" --grid model.sigma0=1,2 --formats pdf -o e2 -q
grep -a -q '/CreationDate (20231114221320Z)' e2/p0_*.pdf && ok || bad "sweep PDF ignores SOURCE_DATE_EPOCH"
cmp -s e1/fig15_minor_loop_ex4.pdf "$pdf" && bad "the PDF does not depend on SOURCE_DATE_EPOCH" || ok
SOURCE_DATE_EPOCH=soon "$hv" render "$fig15" --set output.formats=pdf -o e3 > /dev/null 2>&1
cmp -s e3/fig15_minor_loop_ex4.pdf "$pdf" && ok || bad "an invalid SOURCE_DATE_EPOCH is not the fixed date"

# animations (GL): frames, poster and every video format, piped and assembled
"$hv" animate --list > /dev/null 2>&1
if [ $? -eq 3 ]; then
    echo "animate: built without GL, its outputs not compared"
elif ! command -v ffmpeg > /dev/null; then
    bad "ffmpeg is not installed (tools/setup.sh installs it)"
else
    anim="gamma-sweep-ex2 --size 160x96 --fps 10 --duration 1 --quiet -j 2"
    for i in 1 2; do
        for v in mp4 webm gif; do
            # shellcheck disable=SC2086
            "$hv" animate $anim -o "a$i-$v" --video $v || bad "animate --video $v run $i"
            cp -r "a$i-$v/gamma-sweep-ex2" "a$i-$v/asm"
            "$hv" animate gamma-sweep-ex2 --size 160x96 --fps 10 --duration 1 -o "a$i-$v/asmdir" --quiet \
                --frames 0:10 -j 1 > /dev/null && "$hv" animate gamma-sweep-ex2 --size 160x96 --fps 10 \
                --duration 1 -o "a$i-$v/asmdir" --assemble $v > /dev/null || bad "animate --assemble $v run $i"
        done
    done
    for v in mp4 webm gif; do
        same "a1-$v" "a2-$v" "animate --video $v and --assemble $v (frames, poster, video)"
        [ -s "a1-$v/gamma-sweep-ex2.$v" ] && [ -s "a1-$v/asmdir/gamma-sweep-ex2.$v" ] && ok || bad "no $v written"
    done
fi

# no absolute path of the source or build tree in the programs
for p in "$hv" "$(dirname "$hv")/hystviz-animate"; do
    [ -f "$p" ] || continue
    hits=$(strings -a "$p" | grep -F -e "$src" -e "$bld" | head -n 3)
    [ -z "$hits" ] && ok || bad "$(basename "$p") holds build paths: $hits"
done

finish "test_repro"
