#!/bin/sh
# SPDX-License-Identifier: MIT
# backends_equal.sh HY_ANIMATE SCENES_DIR OUT: every built-in animation and
# every scene animation (scenes/anim_*.scene) rendered on OSMesa and on EGL
# (llvmpipe under both) gives byte-identical frames: 3 frames each, the first,
# middle and last instants (--fps 2 --duration 1.5), and the poster.  The PNG
# encoder is deterministic, so equal files mean equal pixels; nothing less is
# accepted (docs/ARCHITECTURE.md, "GL backends").  SKIP unless both are built.
# The frames go under the test's own $tmp.
set -u
anim=$1 scenes=$2
case " $("$anim" animate --gl-info 2>/dev/null | sed -n 's/^backends built: //p') " in
*" osmesa egl "*) ;;
*) echo "SKIP: needs both GL backends built"; exit 77 ;;
esac
. "$(dirname "$0")/../lib.sh"
out=$tmp
names=$("$anim" animate --list | sed '/^$/q' | awk 'NF { print $1 }')
[ -n "$names" ] || { bad "no animations listed"; finish backends_equal; exit 1; }
n=0
for what in $names "$scenes"/anim_*.scene; do
    base=$(basename "$what" .scene)
    for b in osmesa egl; do
        "$anim" animate "$what" --gl "$b" -o "$out/$b/$base" --size 320x180 --fps 2 --duration 1.5 \
            --quiet -j 2 || bad "$base: $b run failed"
    done
    k=0
    for f in $(cd "$out/osmesa/$base" && find . -name '*.png' | sort); do
        k=$((k + 1))
        cmp -s "$out/osmesa/$base/$f" "$out/egl/$base/$f" || bad "$base: $f differs between osmesa and egl"
    done
    # 3 frames and a poster, the same count on egl
    m=$(cd "$out/egl/$base" && find . -name '*.png' | wc -l)
    if [ "$k" -ne 4 ] || [ "$m" -ne 4 ]; then
        bad "$base: $k frames on osmesa, $m on egl (4 expected: 3 frames and the poster)"
    else
        ok "$base: $k files identical"
    fi
    n=$((n + 1))
done
nscenes=$(ls "$scenes"/anim_*.scene | wc -l)
echo "$n animations compared ($(echo $names | wc -w) built-in, $nscenes scenes)"
[ "$n" -eq $(($(echo $names | wc -w) + nscenes)) ] && [ "$nscenes" -ge 2 ] ||
    bad "$n animations compared, $(($(echo $names | wc -w) + nscenes)) expected (at least 2 scenes, $nscenes found)"
finish backends_equal
