#!/bin/bash
# SPDX-License-Identifier: MIT
# tests/cli/test_install.sh BUILD_ROOT SOURCE_ROOT: an install works away from
# the source tree (issue 24).  `meson install --destdir` into a temporary
# directory, then from / with HOME there and nothing of the source or build
# tree on the way:
#   - hystviz --version, and after a command (hystviz render --version);
#   - hystviz gallery -o DIR renders every paper scene from the installed
#     share/hystviz/scenes (no scenes/ in the working directory);
#   - a paper scene copied alone (without style.scene) renders: its include
#     is found among the installed scenes; the SVG equals the build tree's;
#   - hystviz animate finds hystviz-animate in libexec (where GL is built);
#   - the Bouc-Wen validation data are found in share/hystviz/boucwen;
#   - pkg-config (relocated to the destdir) builds docs/examples' program
#     against the installed headers and library; it prints Fig. 15's area;
#   - the installed Python package imports and computes (where NumPy is).
set -u
build=$(realpath "$1") src=$(realpath "$2")
. "$(dirname "$0")/../lib.sh"
T=$tmp

timeout 300 meson install -C "$build" --no-rebuild --quiet --destdir "$T/dest" >"$T/install.log" 2>&1 ||
    { cat "$T/install.log"; echo "FAIL: meson install"; exit 1; }
prefix=$(cd "$build" && meson introspect --buildoptions | python3 -c 'import json,sys; print([o["value"] for o in json.load(sys.stdin) if o["name"]=="prefix"][0])')
P="$T/dest$prefix"
hv="$P/bin/hystviz"
[ -x "$hv" ] || { echo "FAIL: no $hv"; exit 1; }
for helper in hystviz-animate hystviz-serve; do # helpers, not commands: in libexec
    [ ! -e "$P/bin/$helper" ] && ok "$helper is not in bin/" || bad "$helper installed in bin/"
done
[ ! -e "$P/bin/hystviz-serve" ] && ok "hystviz-serve is not in bin/" || bad "hystviz-serve installed in bin/"
mkdir -p "$T/home"
run() { (cd / && HOME="$T/home" timeout 300 "$@"); }

v=$(run "$hv" --version) && v_num=${v#hystviz } && [ "$v" = "$(run "$hv" render --version)" ] && ok "--version, also after a command: $v" ||
    bad "hystviz render --version"

nscenes=$(ls "$src/gallery"/*.svg | wc -l) # the committed gallery's figures
run "$hv" gallery -q -o "$T/home/g" >"$T/gallery.log" 2>&1; st=$?
nsvg=$(ls "$T/home/g"/*.svg 2>/dev/null | wc -l)
[ $st -eq 0 ] && [ "$nsvg" -gt 0 ] && [ "$nsvg" -eq "$nscenes" ] &&
    ok "gallery from /: $nsvg figures from the installed scenes" ||
    { cat "$T/gallery.log"; bad "gallery from /: exit $st, $nsvg SVGs for $nscenes figure scenes"; }

mkdir -p "$T/home/mine"
cp "$src/scenes/fig15_minor_loop_ex4.scene" "$T/home/mine/"
run "$hv" render "$T/home/mine/fig15_minor_loop_ex4.scene" -o "$T/home/out" --format svg >"$T/render.log" 2>&1 &&
    "$build/src/app/hystviz" render "$src/scenes/fig15_minor_loop_ex4.scene" -o "$T/tree" --format svg >/dev/null 2>&1 &&
    cmp -s "$T/home/out/fig15_minor_loop_ex4.svg" "$T/tree/fig15_minor_loop_ex4.svg" &&
    ok "a copied paper scene finds style.scene among the installed scenes; SVG == the build tree's" ||
    { cat "$T/render.log"; bad "copied paper scene"; }

if [ -x "$build/src/app/hystviz-animate" ] && "$build/src/app/hystviz" animate --list >/dev/null 2>&1; then
    run "$hv" animate --list >/dev/null 2>&1 && ok "animate finds libexec's hystviz-animate" || bad "installed animate --list"
fi

run "$hv" serve --help >"$T/serve.log" 2>&1; rc=$?
{ [ $rc -eq 0 ] && grep -q 'usage: hystviz serve' "$T/serve.log"; } ||
    { [ $rc -eq 3 ] && grep -q 'libmicrohttpd' "$T/serve.log"; } && ok "serve finds libexec's hystviz-serve" ||
    { cat "$T/serve.log"; bad "installed serve --help (exit $rc)"; }

# serve runs libexec's hystviz-serve on the installed scenes: a URL, then /api/scenes
if [ -x "$build/src/app/hystviz-serve" ] && command -v curl >/dev/null; then
    mkdir -p "$T/home/sv"
    cp "$P/share/hystviz/scenes/fig15_minor_loop_ex4.scene" "$P/share/hystviz/scenes/style.scene" "$T/home/sv/"
    (cd / && HOME="$T/home" exec "$hv" serve "$T/home/sv" --port 0 >"$T/serve.out" 2>"$T/serve.err") &
    sp=$!
    bg_track $sp
    url=
    for _ in $(seq 100); do
        url=$(grep -o 'http://[^ ]*' "$T/serve.out" | head -1)
        [ -n "$url" ] && break
        kill -0 $sp 2>/dev/null || break
        sleep 0.1
    done
    [ -n "$url" ] && curl -s --max-time 30 "${url%/}/api/scenes" | grep -q fig15_minor_loop_ex4 &&
        ok "serve from the install answers with its scenes" || { cat "$T/serve.err"; bad "installed serve: ${url:-no URL}"; }
    kill -INT $sp 2>/dev/null
    for _ in $(seq 50); do kill -0 $sp 2>/dev/null || break; sleep 0.1; done
    kill -9 $sp 2>/dev/null
    wait $sp 2>/dev/null
fi

run "$hv" boucwen data --signal validation -o "$T/home/yval.csv" >/dev/null 2>&1 &&
    [ "$(wc -l <"$T/home/yval.csv")" -gt 1000 ] && ok "Bouc-Wen validation data from share/hystviz/boucwen" ||
    bad "boucwen data --signal validation"

if command -v man >/dev/null; then
    (cd / && MANPATH="$P/share/man" timeout 60 man -P cat hystviz-sweep 2>/dev/null) | grep -q "hystviz-sweep" &&
        ok "man hystviz-sweep opens the installed page" || bad "man hystviz-sweep"
    # libhystviz's reference: a page per function (tools/gen_ref.py)
    for f in hy_steady_init hy_loops_find hy_result_from_file hy_steady_loop; do
        (cd / && MANPATH="$P/share/man" timeout 60 man -P cat "$f" 2>/dev/null) | grep -q "^SYNOPSIS" &&
            ok "man $f opens the installed page" || bad "man $f"
    done
fi
[ -f "$P/share/bash-completion/completions/hystviz" ] && ok "bash completion installed" || bad "no bash completion"
pcfile=$(find "$T/dest" -name hystviz.pc | head -1)
if command -v pkg-config >/dev/null && command -v cc >/dev/null && [ -n "$pcfile" ]; then
    # the .pc names the configured prefix: point it at the destdir's copy
    mkdir -p "$T/pc"
    sed "s|^prefix=.*|prefix=$P|" "$pcfile" >"$T/pc/hystviz.pc"
    flags=$(PKG_CONFIG_PATH="$T/pc" pkg-config --cflags --libs hystviz) &&
        timeout 120 cc -std=c11 "$src/docs/examples/minor_loop_area.c" $flags -o "$T/area" &&
        got=$(LD_LIBRARY_PATH="$(dirname "$(find "$T/dest" -name 'libhystviz.so.0' | head -1)")" "$T/area") &&
        [ "$got" = 0.19910737569481529 ] && ok "pkg-config example against the install prints $got" ||
        bad "pkg-config example against the install: ${got:-no output} ($flags)"
fi

site=$(dirname "$(find "$T/dest" -path '*hystviz/__init__.py' | head -1)")
for py in /usr/bin/python3 python3; do
    "$py" -c "import numpy" 2>/dev/null || continue
    lib=$(dirname "$(find "$T/dest" -name 'libhystviz.so.0' | head -1)")
    out=$(cd / && PYTHONPATH="$(dirname "$site")" LD_LIBRARY_PATH="$lib" timeout 120 "$py" -c \
        "import hystviz; print(repr(hystviz.minor_loops(hystviz.Model('lugre', sigma0=6), hystviz.Input('bimodal', umin1=0, umin2=0.5, umax1=1, umax2=1.5))[0].area))" 2>&1)
    [ "$out" = 0.1991073756948153 ] && ok "the installed Python package prints $out" || bad "installed Python: $out"
    # the installed package finds the installed scenes (hystviz/scenes links to share/hystviz/scenes)
    out=$(cd / && PYTHONPATH="$(dirname "$site")" LD_LIBRARY_PATH="$lib" timeout 120 "$py" -c \
        "import hystviz, os; print(os.path.realpath(hystviz.scene_path('fig15_minor_loop_ex4')))" 2>&1)
    [ "$out" = "$(realpath "$P/share/hystviz/scenes/fig15_minor_loop_ex4.scene")" ] &&
        ok "the installed package's scene_path finds share/hystviz/scenes" || bad "installed scene_path: $out"
    # pip install . (the wheel, libhystviz inside) is tests/python/test_wheel.sh
    break
done
exit $((fail > 0))
