#!/bin/sh
# SPDX-License-Identifier: MIT
# gl_choice.sh HY_ANIMATE OUT "BACKENDS BUILT": how a GL backend is chosen
# (--gl, then HYSTVIZ_GL, then osmesa where built, else egl), what --gl-info
# and --list say, and the refusals: an unknown name (status 2), a backend not
# built or an EGL without any device (3), a bad HYSTVIZ_EGL_DEVICE (2); a
# refused run writes nothing.  Everything it writes is under its own $tmp.
set -u
. "$(dirname "$0")/../lib.sh"
anim=$1 built=$2
out=$tmp
unset HYSTVIZ_GL HYSTVIZ_EGL_DEVICE

# expect STATUS TEXT CMD...: status and a line of stderr; no output directory
expect() {
    want=$1 text=$2; shift 2
    rm -rf "$out/refused"
    "$@" -o "$out/refused" --size 64x64 --frames 0:1 --quiet > "$out/stdout" 2> "$out/stderr"
    rc=$?
    [ "$rc" -eq "$want" ] && ok || bad "$* -> status $rc, $want expected ($(cat "$out/stderr"))"
    grep -q "$text" "$out/stderr" && ok || bad "$* -> stderr lacks '$text': $(cat "$out/stderr")"
    [ ! -e "$out/refused" ] && ok || bad "$* -> wrote $out/refused"
}

first=${built%% *}
"$anim" animate --gl-info > "$out/info" && ok || bad "--gl-info failed"
cat "$out/info"
grep -qx "backends built: $built" "$out/info" && ok || bad "--gl-info does not list '$built'"
grep -qx "backend: $first (default)" "$out/info" && ok || bad "the default is not $first"
case " $built " in *" osmesa "*) [ "$first" = osmesa ] && ok || bad "osmesa is built but not the default" ;; esac
"$anim" animate --list | tail -n 1 | grep -q "^renderer: .*($first)$" && ok || bad "--list does not end with the renderer"

for b in $built; do
    "$anim" animate --gl-info --gl "$b" > "$out/info_$b" && ok || bad "--gl $b --gl-info failed"
    grep -qx "backend: $b (--gl)" "$out/info_$b" && ok || bad "--gl $b is not used"
    grep -q "^renderer: .* ($b)$" "$out/info_$b" && ok || bad "--gl $b: no renderer of $b"
    HYSTVIZ_GL=$b "$anim" animate --gl-info | grep -qx "backend: $b (HYSTVIZ_GL)" && ok || bad "HYSTVIZ_GL=$b is not used"
    other=egl; [ "$b" = egl ] && other=osmesa
    case " $built " in *" $other "*)
        HYSTVIZ_GL=$other "$anim" animate --gl-info --gl "$b" | grep -qx "backend: $b (--gl)" ||
            bad "--gl $b does not beat HYSTVIZ_GL=$other" ;;
    *)  expect 3 "built without the $other backend" "$anim" animate gamma-sweep-ex3 --gl "$other"
        expect 3 "built without the $other backend" env HYSTVIZ_GL=$other "$anim" animate gamma-sweep-ex3 ;;
    esac
done
expect 2 "'vulkan' is not a GL backend" "$anim" animate gamma-sweep-ex3 --gl vulkan
expect 2 "HYSTVIZ_GL 'vulkan' is not a GL backend" env HYSTVIZ_GL=vulkan "$anim" animate gamma-sweep-ex3

case " $built " in *" egl "*)
    grep -q "^egl device 0: " "$out/info_egl" && ok || bad "--gl-info lists no EGL device"
    grep -q "^egl device .* (used)$" "$out/info_egl" && ok || bad "--gl-info marks no EGL device as used"
    expect 2 "HYSTVIZ_EGL_DEVICE='99' is not a device number" \
        env HYSTVIZ_EGL_DEVICE=99 "$anim" animate gamma-sweep-ex3 --gl egl
    HYSTVIZ_EGL_DEVICE=0 "$anim" animate gamma-sweep-ex3 --gl egl -o "$out/dev0" --size 64x64 --frames 0:1 \
        --quiet && [ -f "$out/dev0/gamma-sweep-ex3/frame_00000.png" ] && ok || bad "HYSTVIZ_EGL_DEVICE=0 failed"
    # no EGL driver at all: glvnd's libEGL with no vendor library to load
    if __EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent "$anim" animate --gl-info --gl egl > /dev/null 2>&1; then
        echo "note: libEGL ignores __EGL_VENDOR_LIBRARY_FILENAMES (not glvnd): no-device case not simulated"
    else
        expect 3 "EGL found no device" \
            env __EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent "$anim" animate gamma-sweep-ex3 --gl egl
    fi ;;
esac
finish gl_choice
