#!/bin/bash
# SPDX-License-Identifier: MIT
# tests/serve/test_watch.sh HYSTVIZ SCENES_DIR: `hystviz watch`: a line per
# render, a re-render after an in-place save, a rename-save and an edit of an
# included file, scene errors reported while watching goes on, no render for
# an unchanged text, exit 0 on SIGINT with no temporary file left.
set -u
hv=$(realpath "$1")
src=$(realpath "$2")
. "$(dirname "$0")/../lib.sh"
T=$tmp
w=
trap '[ -n "$w" ] && kill -9 $w 2>/dev/null; lib_cleanup' EXIT
mkdir -p "$T/scenes" "$T/out"
cp "$src/fig15_minor_loop_ex4.scene" "$src/style.scene" "$T/scenes/"
cd "$T" || fatal "cannot cd to $T"
F=scenes/fig15_minor_loop_ex4.scene

"$hv" watch 2>/dev/null; [ $? -eq 2 ] || bad "watch without scenes must exit 2"
"$hv" watch --bogus "$F" 2>/dev/null; [ $? -eq 2 ] || bad "watch --bogus must exit 2"
"$hv" watch "$F" -o out --format svg >"$T/log" 2>"$T/err" &
w=$!
lines() { grep -c "" "$T/log"; }
wait_lines() { # n: wait up to 15 s for n lines
    for _ in $(seq 300); do [ "$(lines)" -ge "$1" ] && return 0; sleep 0.05; done
    return 1
}
wait_lines 1 && grep -q "out/fig15_minor_loop_ex4.svg in .* s; max error .* against" "$T/log" &&
    ok "first render: $(head -1 "$T/log")" || bad "no first render line: $(cat "$T/log" "$T/err")"
cp out/fig15_minor_loop_ex4.svg "$T/first.svg"

# in-place save with a new sigma0
sed -i 's/^sigma0 = 6$/sigma0 = 4/' "$F"
wait_lines 2 && ok "in-place save re-rendered" || bad "in-place save: no new line"
"$hv" render "$F" --format svg -o "$T/r" && cmp -s out/fig15_minor_loop_ex4.svg "$T/r/fig15_minor_loop_ex4.svg" &&
    ok "the file written is render's" || bad "watch output differs from render"

# rename-save (as Vim does)
sed 's/^sigma0 = 4$/sigma0 = 3/' "$F" >"$T/scenes/.new"
mv "$T/scenes/.new" "$F"
wait_lines 3 && ok "rename-save re-rendered" || bad "rename-save: no new line"

# an edit of the included style.scene
sed -i 's/^fontsize = 9pt$/fontsize = 10pt/' scenes/style.scene
wait_lines 4 && ok "edit of an included file re-rendered" || bad "include edit: no new line"

# a save that changes nothing in the text: no render (a touch, and a
# rename-save of the same bytes; an in-place cp truncates first, and under
# load watch could read the empty file between truncate and write: a
# fresh-clone CI at load 12 saw "the scene draws nothing" and a render)
touch "$F"
cp "$F" "$T/scenes/.same" && mv "$T/scenes/.same" "$F"
sleep 0.8
[ "$(lines)" -eq 4 ] && ok "unchanged text: no render" || bad "unchanged text rendered again ($(lines) lines)"

# a scene error: one line naming file:line:col, watching goes on
cp out/fig15_minor_loop_ex4.svg "$T/good.svg"
sed -i 's/^sigma0 = 3$/sigma0 = -1/' "$F"
wait_lines 5 && grep -q "error: scenes/fig15_minor_loop_ex4.scene:9:10: " "$T/log" &&
    ok "scene error reported: $(tail -1 "$T/log")" || bad "scene error line: $(tail -1 "$T/log")"
cmp -s out/fig15_minor_loop_ex4.svg "$T/good.svg" || bad "the last good file was touched by a failed render"
kill -0 $w 2>/dev/null && ok "still watching after the error" || bad "watch died on a scene error"
sed -i 's/^sigma0 = -1$/sigma0 = 6/' "$F"
wait_lines 6 && tail -1 "$T/log" | grep -q "max error" && ok "fixed scene rendered" || bad "no render after the fix"

kill -INT $w
wait_pid $w 30 "watch after SIGINT"
rc=$?
w=
[ $rc -eq 0 ] && ok "SIGINT: exit 0" || bad "SIGINT: exit $rc"
ls -a out scenes | grep -q tmp && bad "temporary files left: $(ls -a out scenes)"
[ "$fail" -eq 0 ] || cat "$T/log"
finish watch
