#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/gl/frames_decode.sh HYSTVIZ PNG_STRICT SRCDIR [all]
#
# Animation frames (written by hy_zfast, hystviz's deflate encoder) through
# independent decoders (issue 38: three frames zlib took and chromium's
# createImageBitmap refused):
#   png_strict   chunks and CRCs; the IDAT inflated by zlib and by the strict
#                decoder (tests/render/zstrict.c: every Huffman code complete)
#                to the same bytes; the pixels equal to libpng's
#   pngcheck     Debian's pngcheck
#   png_decode   Python's zlib and PIL (tests/gl/png_decode.py)
#   png_browser  chromium headless: createImageBitmap and <img>
#                (tests/serve/png_browser.py, 30 s a frame, 300 s in all)
# Frames: of the seven built-in clips and the two scene clips
# (scenes/anim_*.scene), the last two of each (one hystviz run a clip: the
# runs are most of the time), the first two of gamma-sweep-ex1, and
# gamma-sweep-ex2 59..61 and preisach-plane 48..51 (the frames that froze in
# the browser); with "all", every frame of the nine clips (the benchmark,
# tests/bench: about 1,600 frames).  A decoder that is not installed is
# reported and left out, except under CI=true (tools/setup.sh test installs
# them all), where that fails.  Everything is written under the test's own
# $tmp (tests/lib.sh).
set -u
. "$(dirname "$0")/../lib.sh"
hv=$1 strict=$2 src=$3 mode=${4:-sample}
here=$(dirname "$0")
clips="gamma-sweep-ex1 gamma-sweep-ex2 gamma-sweep-ex3 k-cycle-ex2 k-cycle-ex3 minor-loop-ex4 preisach-plane
$src/scenes/anim_gamma_sweep_ex3.scene $src/scenes/anim_minor_loop_ex4.scene"
render() { # clip, A:B
    "$hv" animate "$1" --frames "$2" -o "$tmp/frames" -q --include-dir "$src/scenes" 2>"$tmp/err" ||
        bad "hystviz animate $1 --frames $2: $(cat "$tmp/err")"
}
nclips=0
for c in $clips; do
    n=$("$hv" animate "$c" --info --include-dir "$src/scenes" | sed -n 's/^frames \([0-9]*\) .*/\1/p')
    [ -n "$n" ] || { bad "hystviz animate $c --info"; continue; }
    nclips=$((nclips + 1))
    if [ "$mode" = all ]; then
        render "$c" 0:
    else
        render "$c" $((n - 2)):
    fi
done
if [ "$mode" != all ]; then
    render gamma-sweep-ex1 0:2
    render gamma-sweep-ex2 59:62
    render preisach-plane 48:52
fi
# the posters (NAME.png) are the last frames again: the frames only
find "$tmp/frames" -name 'frame_*.png' | sort >"$tmp/list"
total=$(wc -l <"$tmp/list")
echo "frames: $total PNGs of $nclips clips ($mode)"
[ "$total" -gt 0 ] || fatal "no frames rendered"
for f in gamma-sweep-ex2/frame_00060 preisach-plane/frame_00049 preisach-plane/frame_00051; do
    grep -q "/$f.png\$" "$tmp/list" || bad "$f.png was not rendered"
done
missing() { # decoder, why
    if [ "${CI:-}" = true ]; then
        bad "$1: $2 (CI=true: sh tools/setup.sh test installs it)"
    else
        echo "$1: not run: $2"
    fi
}
# xargs: one process per 200 files (png_decode and png_browser start once per batch)
xargs -n 200 "$strict" <"$tmp/list" >"$tmp/strict.out" 2>&1 && ok || bad "png_strict refused a frame"
grep FAIL "$tmp/strict.out"
echo "png_strict (zlib, strict inflater, libpng): $(grep -c '^FAIL' "$tmp/strict.out") of $total failed"
if command -v pngcheck >/dev/null; then
    xargs -n 200 pngcheck -q <"$tmp/list" >"$tmp/pngcheck.out" 2>&1 && ok || bad "pngcheck refused a frame"
    cat "$tmp/pngcheck.out"
    echo "pngcheck: $(grep -c . "$tmp/pngcheck.out") of $total failed (it prints only the failures)"
else
    missing pngcheck "pngcheck is not installed"
fi
py=
for p in python3 /usr/bin/python3; do
    command -v "$p" >/dev/null && "$p" -c 'import PIL' 2>/dev/null && { py=$p; break; }
done
if [ -n "$py" ]; then
    xargs -n 200 "$py" "$here/png_decode.py" <"$tmp/list" >"$tmp/pil.out" 2>&1 && ok || bad "png_decode refused a frame"
    grep FAIL "$tmp/pil.out"
    echo "png_decode (Python zlib, PIL): $(grep -c '^FAIL' "$tmp/pil.out") of $total failed"
else
    missing "png_decode (Python zlib, PIL)" "no python3 with PIL (python3-pil)"
fi
py=$(command -v python3 || command -v /usr/bin/python3)
if [ -n "$py" ]; then
    # one chromium for all the frames: a deadline of 300 s (all: 900 s)
    dl=300
    [ "$mode" = all ] && dl=900
    tr '\n' '\0' <"$tmp/list" | TMPDIR=$tmp xargs -0 "$py" "$here/../serve/png_browser.py" --deadline $dl >"$tmp/br.out" 2>&1
    rc=$?
    grep -E '^(FAIL|SKIP)' "$tmp/br.out"
    if grep -q '^SKIP' "$tmp/br.out" && [ "${CI:-}" != true ]; then
        echo "png_browser (chromium): not run"
    else
        [ $rc -eq 0 ] && ok || bad "png_browser refused a frame (exit $rc)"
        echo "png_browser (chromium createImageBitmap, <img>): $(grep -c '^FAIL' "$tmp/br.out") of $total failed"
    fi
else
    missing "png_browser (chromium)" "no python3"
fi
finish "frames_decode ($total frames)"
