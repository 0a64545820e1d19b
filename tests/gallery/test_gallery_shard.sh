#!/bin/sh
# SPDX-License-Identifier: MIT
# Tests of `hystviz gallery --shard K/N` and `--merge` (issue 13) on small
# scenes written here (an include, seven figures, one that fails to compute):
# for N = 1, 2, 3, 7 and 9 (> figures) the shards run into separate
# directories write disjoint files; copied together and merged they give the
# unsharded gallery byte for byte (figures, index.html; .manifest too except
# its render-time column, a measurement); the failing scene makes shards and
# merge exit 1 as the unsharded run does; a missing shard or a scene set
# changed since the shards ran makes the merge refuse (exit 2, nothing
# written); a second sharded run skips the unchanged scenes.
# usage: test_gallery_shard.sh HYSTVIZ [split|rest]
#   split: the union for every N (tests/gallery/meson.build: gallery_shard-split,
#   release build only); rest: everything else (gallery_shard, also under the
#   sanitizers); neither: both
set -u
hv=$1
part=${2:-all}
. "$(dirname "$0")/../lib.sh"
S=$tmp/scenes
mkdir "$S"
cat > "$S/look.scene" <<'EOF'
[figure]
size = 6cm, 4.5cm
dpi = 50
font = "DejaVu Sans"
[output]
formats = svg, png
EOF
i=0
for kind in "dahl triangle" "lugre triangle" "lugre bimodal" "dahl sine" "lugre sine" "dahl bimodal"; do
    set -- $kind
    cat > "$S/f$i.scene" <<EOF
include "look.scene"
[model]
kind = $1
[input]
kind = $2
[compute]
points = 100
[figure]
kind = loop
[series ys]
data = ystar
EOF
    i=$((i + 1))
done
cat > "$S/g_psi.scene" <<'EOF'
include "look.scene"
[input]
kind = bimodal
[figure]
kind = psi
[series p]
data = psi
EOF
# parses, fails when computed: umin2 > umax1
cat > "$S/h_bad.scene" <<'EOF'
include "look.scene"
[input]
kind = bimodal
umin2 = 1.2
umax1 = 1
[figure]
kind = loop
[series ys]
data = ystar
EOF

nomtime() { cut -f1-3,5- "$1"; }   # the manifest without its seconds column

"$hv" gallery --scenes "$S" -o "$tmp/one" -j 1 -q 2> /dev/null
[ $? -eq 1 ] && ok || bad "unsharded run with a failing scene: status not 1"

[ "$part" = rest ] || for n in 1 2 3 7 9; do
    rm -rf "$tmp/s" "$tmp/all"
    mkdir -p "$tmp/all"
    : > "$tmp/names"
    k=0
    while [ $k -lt $n ]; do
        "$hv" gallery --scenes "$S" -o "$tmp/s/$k" -j 1 -q --shard "$k/$n" 2> /dev/null
        st=$?
        # the failing scene is figure 7 (f0..f5, g_psi, h_bad): shard 7 mod n
        [ $st -eq $((k == 7 % n ? 1 : 0)) ] && ok || bad "N=$n shard $k: status $st"
        [ ! -e "$tmp/s/$k/index.html" ] && [ ! -e "$tmp/s/$k/.manifest" ] && ok || bad "N=$n shard $k wrote the index or manifest"
        ls -A "$tmp/s/$k" | grep -v '^\.lock$' >> "$tmp/names"   # .lock: every run's (shared) lock file, empty
        cp -p "$tmp/s/$k"/* "$tmp/s/$k"/.manifest.shard-* "$tmp/all/" 2> /dev/null
        k=$((k + 1))
    done
    [ -z "$(sort "$tmp/names" | uniq -d)" ] && ok || bad "N=$n: files written by two shards: $(sort "$tmp/names" | uniq -d | head -3)"
    "$hv" gallery --scenes "$S" -o "$tmp/all" --merge -q 2> /dev/null
    [ $? -eq 1 ] && ok || bad "N=$n: merge status not 1 (a scene failed)"
    diff -r -x .manifest "$tmp/one" "$tmp/all" > "$tmp/diff" && ok || bad "N=$n: merged gallery differs: $(head -3 "$tmp/diff")"
    [ "$(nomtime "$tmp/one/.manifest")" = "$(nomtime "$tmp/all/.manifest")" ] && ok || bad "N=$n: manifests differ"
done
if [ "$part" = split ]; then
    grep -q 'render failed' "$tmp/all/index.html" && ok || bad "the failure is not on the merged index"
    finish "test_gallery_shard (split)"
    exit
fi

# shards into one directory, twice: the second run renders nothing, merge still equal
G=$tmp/g
for k in 0 1 2; do "$hv" gallery --scenes "$S" -o "$G" -j 1 -q --shard "$k/3" 2> /dev/null; done
"$hv" gallery --scenes "$S" -o "$G" --merge -q 2> /dev/null
for k in 0 1 2; do "$hv" gallery --scenes "$S" -o "$G" -j 1 --shard "$k/3" 2>> "$tmp/second.err"; done
[ "$(grep -c ' 0 rendered' "$tmp/second.err")" -eq 3 ] && ok || bad "second sharded run re-rendered: $(cat "$tmp/second.err")"
"$hv" gallery --scenes "$S" -o "$G" --merge -q 2> /dev/null
diff -r -x .manifest "$tmp/one" "$G" > /dev/null && ok || bad "second sharded run: gallery differs"
grep -q 'render failed' "$G/index.html" && ok || bad "the failure is not on the merged index"

# shards at the same time in one directory (they share its lock)
rm -rf "$G"
# (each bounded: timeout ends a shard that hangs, wait_pid gives it 130 s)
pids=
for k in 0 1 2; do timeout 120 "$hv" gallery --scenes "$S" -o "$G" -j 1 -q --shard "$k/3" 2> /dev/null & pids="$pids $!"; done
# (a shard's status is not asked: the one with the failing scene exits 1)
for p in $pids; do st=0; wait_pid "$p" 130 "a concurrent shard" || st=$?; [ $st -ne 124 ] || bad "a concurrent shard hung"; done
"$hv" gallery --scenes "$S" -o "$G" --merge -q 2> /dev/null
diff -r -x .manifest "$tmp/one" "$G" > /dev/null && ok || bad "concurrent shards in one directory: gallery differs"

# refusals: a missing shard, scenes changed since the shards ran
rm -rf "$G"
for k in 0 2; do "$hv" gallery --scenes "$S" -o "$G" -j 1 -q --shard "$k/3" 2> /dev/null; done
"$hv" gallery --scenes "$S" -o "$G" --merge 2> "$tmp/err"
[ $? -eq 2 ] && grep -q '1 of 3 shards missing: 1/3' "$tmp/err" && [ ! -e "$G/index.html" ] && ok || bad "missing shard: $(cat "$tmp/err")"
"$hv" gallery --scenes "$S" -o "$G" -j 1 -q --shard 1/3 2> /dev/null
cp "$S/g_psi.scene" "$S/g_psi2.scene"
"$hv" gallery --scenes "$S" -o "$G" --merge 2> "$tmp/err"
[ $? -eq 2 ] && grep -q 'another set of scenes' "$tmp/err" && [ ! -e "$G/index.html" ] && ok || bad "changed scenes: $(cat "$tmp/err")"
rm "$S/g_psi2.scene"
"$hv" gallery --scenes "$S" -o "$G" --merge -q 2> /dev/null
[ $? -eq 1 ] && [ -e "$G/index.html" ] && [ -z "$(ls -A "$G" | grep shard)" ] && ok || bad "merge after restoring the scenes"
"$hv" gallery --scenes "$S" -o "$G" --merge --shard 0/2 2> /dev/null
[ $? -eq 2 ] && ok || bad "--merge with --shard accepted"
"$hv" gallery --scenes "$S" -o "$G" --shard 2/2 2> /dev/null
[ $? -eq 2 ] && ok || bad "--shard 2/2 accepted"

finish "test_gallery_shard"
