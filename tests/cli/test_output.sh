#!/bin/sh
# SPDX-License-Identifier: MIT
# Every file hystviz writes goes through one writer (src/io/hy_out.h): these
# tests drive it through the commands, in a temporary directory only.
#  - targets: an existing directory (was a double free), /dev/full (ENOSPC:
#    the failure is printed), a file size limit (EFBIG), /dev/null and a FIFO
#    (written directly, never replaced), a symbolic link (its file replaced,
#    the link kept), a dangling link (refused), '-' (standard output);
#  - no predictable temporary name (a planted PATH.tmp.PID symlink was
#    followed), file modes from the umask (boucwen data wrote 0600);
#  - a multi-format render writes all its files or none; an absurd PNG is
#    refused before computing;
#  - exit statuses 0/1/2/3 and write errors on standard output (> /dev/full).
# usage: test_output.sh HYSTVIZ SCENES_DIR
set -u
hv=$1
scenes=$2
. "$(dirname "$0")/../lib.sh"
umask 022
fig=$scenes/fig15_minor_loop_ex4.scene
loop_in=bimodal:0,0.5,1,1.5
# temporaries of the writer (or of the old PATH.tmp.* writers) left in a directory
tmps() { find "$1" -name '*hystviz-tmp*' -o -name '*.tmp.*' | wc -l; }
# st CMD...: runs hystviz, stdout in $tmp/o, stderr in $tmp/e, status in $st
run() {
    "$hv" "$@" > "$tmp/o" 2> "$tmp/e"
    st=$?
}
has() { grep -qF -- "$1" "$tmp/e"; }

# ---- targets ---------------------------------------------------------------
# Character devices: as root, nodes of our own (mknod) stand for /dev/null and
# /dev/full, so that a regressed hystviz, which replaced them with a file,
# cannot break the machine's; as another user the real ones are safe.
null=/dev/null
full=/dev/full
if [ "$(id -u)" -eq 0 ]; then
    null=; full=
    mknod "$tmp/null" c 1 3 2> /dev/null && : 2> /dev/null > "$tmp/null" && null=$tmp/null # not on a nodev mount
    mknod "$tmp/full" c 1 7 2> /dev/null && : 2> /dev/null > "$tmp/full" && full=$tmp/full
fi
mkdir "$tmp/dir"
run data "$fig" -o "$tmp/dir"
[ $st -eq 1 ] && has "cannot write '$tmp/dir': it is a directory" && ok || bad "data -o DIR: status $st, $(cat "$tmp/e")"
[ -d "$tmp/dir" ] && [ -z "$(ls -A "$tmp/dir")" ] && ok || bad "data -o DIR changed the directory"
for cmd in "loop --input $loop_in" "loops --input $loop_in" "boucwen data --signal sine --periods 1"; do
    # shellcheck disable=SC2086
    run $cmd -o "$tmp/dir"
    [ $st -eq 1 ] && has "it is a directory" && ok || bad "$cmd -o DIR: status $st, $(cat "$tmp/e")"
done

if [ -n "$full" ]; then
    for cmd in "data $fig" "loop --input $loop_in" "loops --input $loop_in" "boucwen data --signal sine --periods 1"; do
        # shellcheck disable=SC2086
        run $cmd -o "$full"
        [ $st -eq 1 ] && has "cannot write '$full': No space left on device" && ok ||
            bad "$cmd -o $full: status $st, stderr: $(cat "$tmp/e")"
    done
    [ -c "$full" ] && ok || bad "$full replaced"
fi

# a file size limit makes every write past it fail (EFBIG), as a full disk does
# for a regular file: the message names the file, nothing is left behind
mkdir "$tmp/lim"
(
    trap '' XFSZ
    ulimit -f 16
    "$hv" data "$fig" -o "$tmp/lim/fig15.csv" > "$tmp/o" 2> "$tmp/e"
    echo $? > "$tmp/st"
)
[ "$(cat "$tmp/st")" -eq 1 ] && has "cannot write '$tmp/lim/fig15.csv': File too large" && ok ||
    bad "data past a file size limit: status $(cat "$tmp/st"), $(cat "$tmp/e")"
[ -z "$(ls -A "$tmp/lim")" ] && ok || bad "a failed data -o left: $(ls -A "$tmp/lim")"

if [ -n "$null" ]; then
    for cmd in "data $fig" "loop --input $loop_in" "loops --input $loop_in" "boucwen data --signal sine --periods 1"; do
        # shellcheck disable=SC2086
        run $cmd -o "$null"
        [ $st -eq 0 ] && [ -c "$null" ] && ok || bad "$cmd -o $null: status $st, $(ls -l "$null")"
    done
fi

"$hv" loop --input "$loop_in" > "$tmp/want.csv"
mkfifo "$tmp/fifo"
timeout 10 cat "$tmp/fifo" > "$tmp/got.csv" &  # no hang when the FIFO is replaced
reader=$!
run loop --input "$loop_in" -o "$tmp/fifo"
wait $reader
[ $st -eq 0 ] && [ -p "$tmp/fifo" ] && cmp -s "$tmp/want.csv" "$tmp/got.csv" && ok ||
    bad "-o FIFO: status $st, fifo kept: $([ -p "$tmp/fifo" ] && echo yes || echo no)"

echo old > "$tmp/target.csv"
ln -s target.csv "$tmp/link.csv"
run loop --input "$loop_in" -o "$tmp/link.csv"
[ $st -eq 0 ] && [ -L "$tmp/link.csv" ] && cmp -s "$tmp/target.csv" "$tmp/want.csv" && ok ||
    bad "-o SYMLINK: status $st, link kept: $([ -L "$tmp/link.csv" ] && echo yes || echo no)"
ln -s missing.csv "$tmp/dangling.csv"
run loop --input "$loop_in" -o "$tmp/dangling.csv"
[ $st -eq 1 ] && has "is a symbolic link to a missing file" && [ ! -e "$tmp/missing.csv" ] && ok ||
    bad "-o dangling link: status $st, $(cat "$tmp/e")"

for cmd in "loop --input $loop_in" "loops --input $loop_in" "data $fig" "boucwen data --signal sine --periods 1"; do
    # shellcheck disable=SC2086
    "$hv" $cmd > "$tmp/a" 2> /dev/null && "$hv" $cmd -o - > "$tmp/b" 2> /dev/null && [ -s "$tmp/a" ] &&
        cmp -s "$tmp/a" "$tmp/b" && [ ! -e ./- ] && ok || bad "$cmd -o -: not standard output"
done

# a symlink planted at the old predictable temporary name PATH.tmp.PID
# (exec keeps the shell's PID) must not be followed
echo victim > "$tmp/victim"
sh -c 'ln -s "$1" "$2.tmp.$$" && exec "$3" loop --input "$4" -o "$2"' sh "$tmp/victim" "$tmp/plant.csv" "$hv" "$loop_in" \
    2> "$tmp/e"
[ "$(cat "$tmp/victim")" = victim ] && cmp -s "$tmp/plant.csv" "$tmp/want.csv" && ok ||
    bad "the planted PATH.tmp.PID symlink was followed: victim now $(head -c 40 "$tmp/victim")"
rm -f "$tmp"/plant.csv.tmp.*

# issue 20 item 1: a file whose name comes from a scene or an output directory
# is written only below that directory; a symbolic link planted at the
# figure's name (a stranger's scene tree) must not lead the file out
mkdir -p "$tmp/pr/scenes" "$tmp/pr/victim" "$tmp/pr/gallery"
echo 'victim data' > "$tmp/pr/victim/bashrc"
printf '[model]\nkind = lugre\n[input]\nkind = bimodal\n[compute]\npoints = 50\n[series ystar]\ndata = ystar\n[output]\nformats = svg\n' \
    > "$tmp/pr/scenes/evil.scene"
ln -s ../victim/bashrc "$tmp/pr/scenes/evil.svg"
ln -s ../victim/bashrc "$tmp/pr/gallery/evil.svg"
run render "$tmp/pr/scenes/evil.scene"
[ $st -eq 2 ] && has "refusing to write '$tmp/pr/scenes/evil.svg'" && [ "$(cat "$tmp/pr/victim/bashrc")" = 'victim data' ] &&
    [ -L "$tmp/pr/scenes/evil.svg" ] && [ "$(tmps "$tmp/pr")" -eq 0 ] && ok ||
    bad "render followed a planted link out of the scene's directory: status $st, victim $(head -c 40 "$tmp/pr/victim/bashrc"), $(cat "$tmp/e")"
run render "$tmp/pr/scenes/evil.scene" -o "$tmp/pr/gallery"
[ $st -eq 2 ] && has "refusing to write" && [ "$(cat "$tmp/pr/victim/bashrc")" = 'victim data' ] && ok ||
    bad "render -o DIR followed a planted link out of DIR: status $st, $(cat "$tmp/e")"
run gallery --scenes "$tmp/pr/scenes" -o "$tmp/pr/gallery" -j 1 -q
[ $st -ne 0 ] && has "refusing to write" && [ "$(cat "$tmp/pr/victim/bashrc")" = 'victim data' ] && ok ||
    bad "gallery followed a planted link out of its directory: status $st, $(cat "$tmp/e")"
# a link that stays below the directory is followed (its file replaced, the link kept)
rm "$tmp/pr/scenes/evil.svg"
echo old > "$tmp/pr/scenes/kept.svg"
ln -s kept.svg "$tmp/pr/scenes/evil.svg"
run render "$tmp/pr/scenes/evil.scene"
[ $st -eq 0 ] && [ -L "$tmp/pr/scenes/evil.svg" ] && grep -q '<svg' "$tmp/pr/scenes/kept.svg" && ok ||
    bad "a link inside the scene's directory: status $st, $(cat "$tmp/e")"
# the user's own -o FILE keeps the shell's '>' semantics: followed anywhere
ln -s ../victim/out.csv "$tmp/pr/scenes/mine.csv"
echo old > "$tmp/pr/victim/out.csv"
run data "$tmp/pr/scenes/evil.scene" -o "$tmp/pr/scenes/mine.csv"
[ $st -eq 0 ] && head -n 1 "$tmp/pr/victim/out.csv" | grep -q '^series,x,y' && ok ||
    bad "data -o LINK (the user's own file) was not followed: status $st, $(cat "$tmp/e")"
# issue 20 item 11: -o /dev/stdout into a pipe (a link to "pipe:[N]")
if [ -e /dev/stdout ]; then
    "$hv" data "$tmp/pr/scenes/evil.scene" -o /dev/stdout 2> "$tmp/e" | head -n 1 > "$tmp/o"
    grep -q '^series,x,y' "$tmp/o" && ok || bad "data -o /dev/stdout into a pipe: $(cat "$tmp/e")"
    "$hv" loop --input "$loop_in" -o /dev/stdout 2> "$tmp/e" | cat > "$tmp/o"
    cmp -s "$tmp/o" "$tmp/want.csv" && ok || bad "loop -o /dev/stdout into a pipe: $(cat "$tmp/e")"
fi

# issue 20 item 11: a killed `data -o FILE` left its temporary; the next run sweeps it
mkdir -p "$tmp/k"
: > "$tmp/k/.x.csv.hystviz-tmp.AbCdEf"
run data "$tmp/pr/scenes/evil.scene" -o "$tmp/k/x.csv"
[ $st -eq 0 ] && [ ! -e "$tmp/k/.x.csv.hystviz-tmp.AbCdEf" ] && [ "$(tmps "$tmp/k")" -eq 0 ] && ok ||
    bad "data -o: a killed run's temporary was not swept: status $st, $(ls -a "$tmp/k")"

# modes come from the umask, for every command
mode() { stat -c %a "$1"; }
rm -rf "$tmp/m" && mkdir "$tmp/m"
(
    umask 027
    "$hv" boucwen data --signal sine --periods 1 -o "$tmp/m/bw.csv"
    "$hv" loop --input "$loop_in" -o "$tmp/m/loop.csv"
    "$hv" data "$fig" -o "$tmp/m/data.csv"
    "$hv" render "$fig" -o "$tmp/m" --format svg,png
) 2> "$tmp/e"
for f in bw.csv loop.csv data.csv fig15_minor_loop_ex4.svg fig15_minor_loop_ex4.png; do
    [ "$(mode "$tmp/m/$f")" = 640 ] && ok || bad "$f: mode $(mode "$tmp/m/$f") under umask 027, want 640"
done
[ "$(tmps "$tmp")" -eq 0 ] && ok || bad "temporaries left: $(find "$tmp" -name '*tmp*')"

# ---- all or nothing ----------------------------------------------------------
# the PDF cannot be written (a directory has its name): neither the SVG nor the PNG appear
mkdir -p "$tmp/aon/fig15_minor_loop_ex4.pdf"
run render "$fig" -o "$tmp/aon" --format svg,pdf,png
[ $st -eq 1 ] && has "fig15_minor_loop_ex4.pdf': it is a directory" && ok || bad "render onto a directory: status $st, $(cat "$tmp/e")"
[ "$(ls -A "$tmp/aon")" = fig15_minor_loop_ex4.pdf ] && ok || bad "a failed render left: $(ls -A "$tmp/aon")"
rmdir "$tmp/aon/fig15_minor_loop_ex4.pdf"
# the same past a file size limit: whatever fails, nothing is replaced
"$hv" render "$fig" -o "$tmp/aon" --format svg,pdf,png 2> "$tmp/e" && ok || bad "render: $(cat "$tmp/e")"
ls -li "$tmp/aon" > "$tmp/before"
(
    trap '' XFSZ
    ulimit -f 24
    "$hv" render "$fig" -o "$tmp/aon" --format svg,pdf,png --set figure.dpi=600 > /dev/null 2> "$tmp/e"
    echo $? > "$tmp/st"
)
[ "$(cat "$tmp/st")" -eq 1 ] && has "File too large" && ok || bad "render past a size limit: status $(cat "$tmp/st"), $(cat "$tmp/e")"
ls -li "$tmp/aon" > "$tmp/after"
cmp -s "$tmp/before" "$tmp/after" && ok || bad "a failed render replaced files: $(diff "$tmp/before" "$tmp/after")"
# an absurd PNG (40 in x 40 in at 2400 dpi = 96000 px a side) is refused at once
run render "$fig" -o "$tmp/big" -v --set figure.size=40in,40in --set figure.dpi=2400
[ $st -eq 2 ] && has "a PNG of 96000 x 96000 pixels (40 x 40 in at 2400 dpi) is too large" && ok ||
    bad "absurd PNG: status $st, $(cat "$tmp/e")"
grep -q 'plan' "$tmp/e" && bad "the absurd PNG was computed before it was refused" || ok
[ ! -e "$tmp/big" ] && ok || bad "the refused render left $(ls -A "$tmp/big")"

# ---- exit statuses -----------------------------------------------------------
run render "$fig" -o "$tmp/jpg" --format svg,jpg -v
[ $st -eq 2 ] && has "unknown format 'jpg'" && ! grep -q plan "$tmp/e" && [ ! -e "$tmp/jpg" ] && ok ||
    bad "--format jpg: status $st (want 2 before computing), $(cat "$tmp/e")"
run boucwen table2 --set-param m=-1
st1=$st
run boucwen data --signal sine --set-param m=-1
[ $st1 -eq 2 ] && [ $st -eq 2 ] && ok || bad "a refused Bouc-Wen parameter: table2 $st1, data $st (want 2, 2)"
run loop --gamma 0 --input "$loop_in"
[ $st -eq 2 ] && ok || bad "loop --gamma 0: status $st"
run data "$tmp/no-such.scene"
[ $st -eq 2 ] && ok || bad "data of a missing scene: status $st"
printf '[model]\nkind = lugre\nsigma0 = -1\n' > "$tmp/bad.scene"
run render "$tmp/bad.scene" -o "$tmp/badout"
[ $st -eq 2 ] && has "bad.scene:3:" && [ ! -e "$tmp/badout" ] && ok || bad "invalid scene: status $st, $(cat "$tmp/e")"
"$hv" --help | grep -q '^  3  feature not built' && ok || bad "--help does not document the exit statuses"

# write errors on standard output are reported by every command
if [ -w /dev/full ]; then
    for cmd in "boucwen table2" "check --quick" "loop --input $loop_in" "data $fig" "--help" "render --help" \
        "animate --list"; do
        # shellcheck disable=SC2086
        "$hv" $cmd > /dev/full 2> "$tmp/e"
        st=$?
        if [ "$cmd" = "animate --list" ] && [ $st -eq 3 ]; then ok; continue; fi # built without OSMesa
        [ $st -eq 1 ] && grep -q "standard output: No space left on device" "$tmp/e" && ok ||
            bad "$cmd > /dev/full: status $st, stderr: $(tail -2 "$tmp/e")"
    done
fi

finish "output"
