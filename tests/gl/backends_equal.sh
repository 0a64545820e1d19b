#!/bin/sh
# SPDX-License-Identifier: MIT
# backends_equal.sh HY_ANIMATE SCENES_DIR OUT: every built-in animation and
# every scene animation (scenes/anim_*.scene) rendered on OSMesa and on EGL
# (llvmpipe under both) gives byte-identical frames: 3 frames each, the first,
# middle and last instants (--fps 2 --duration 1.5), and the poster.  The PNG
# encoder is deterministic, so equal files mean equal pixels; nothing less is
# accepted (docs/ARCHITECTURE.md, "GL backends").  SKIP unless both are built.
set -u
anim=$1 scenes=$2 out=$3
case " $("$anim" animate --gl-info 2>/dev/null | sed -n 's/^backends built: //p') " in
*" osmesa egl "*) ;;
*) echo "SKIP: needs both GL backends built"; exit 77 ;;
esac
rm -rf "$out"
names=$("$anim" animate --list | sed '/^$/q' | awk 'NF { print $1 }')
[ -n "$names" ] || { echo "no animations listed"; exit 1; }
fails=0 n=0
for what in $names "$scenes"/anim_*.scene; do
    base=$(basename "$what" .scene)
    for b in osmesa egl; do
        "$anim" animate "$what" --gl "$b" -o "$out/$b/$base" --size 320x180 --fps 2 --duration 1.5 \
            --quiet -j 2 || { echo "$base: $b run failed"; fails=$((fails + 1)); }
    done
    k=0
    for f in $(cd "$out/osmesa/$base" && find . -name '*.png' | sort); do
        k=$((k + 1))
        if ! cmp -s "$out/osmesa/$base/$f" "$out/egl/$base/$f"; then
            echo "$base: $f differs between osmesa and egl"
            fails=$((fails + 1))
        fi
    done
    # 3 frames and a poster, the same count on egl
    m=$(cd "$out/egl/$base" && find . -name '*.png' | wc -l)
    if [ "$k" -ne 4 ] || [ "$m" -ne 4 ]; then
        echo "$base: $k frames on osmesa, $m on egl (4 expected: 3 frames and the poster)"
        fails=$((fails + 1))
    fi
    n=$((n + 1))
    echo "$base: $k files identical"
done
nscenes=$(ls "$scenes"/anim_*.scene | wc -l)
echo "$n animations compared ($(echo $names | wc -w) built-in, $nscenes scenes), $fails differences"
[ "$fails" -eq 0 ] && [ "$n" -eq $(($(echo $names | wc -w) + nscenes)) ] && [ "$nscenes" -ge 2 ]
