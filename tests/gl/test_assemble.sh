#!/bin/sh
# SPDX-License-Identifier: MIT
# Tests of animations rendered in pieces (issue 13): frames rendered with
# --frames A:B in three pieces, and with --shard K/N for N = 3 and 20 (more
# pieces than frames), are byte for byte the frames and poster of one run;
# a scene animation in two shards too; `animate --assemble mp4` of the pieces
# decodes to the same frames as the one run's --video mp4 (ffmpeg framemd5);
# a missing frame makes --assemble refuse (exit 2, the range named, no video);
# without ffmpeg it exits 3; --assemble with --frames is a usage error.
# usage: test_assemble.sh HYSTVIZ SCENES_DIR   (SKIP, 77, without ffmpeg)
set -u
hv=$1
scenes=$2
command -v ffmpeg > /dev/null || { echo "SKIP: no ffmpeg"; exit 77; }
. "$(dirname "$0")/../lib.sh"
A=minor-loop-ex4
O="--size 320x180 --fps 10 --duration 1.5 --quiet"   # 15 frames

"$hv" animate $A -o "$tmp/one" $O -j 2 --video mp4 || bad "one run"
[ "$(ls "$tmp/one/$A" | wc -l)" -eq 15 ] && ok || bad "one run: $(ls "$tmp/one/$A" | wc -l) frames"
same() { # DIR: every frame and the poster equal the one run's
    [ "$(ls "$1/$A" | wc -l)" -eq 15 ] || return 1
    for f in "$tmp/one/$A"/*.png "$tmp/one/$A.png"; do
        cmp -s "$f" "$1${f#"$tmp/one"}" || return 1
    done
}
for r in 0:4 4:9 9:; do "$hv" animate $A -o "$tmp/fr" $O --frames $r || bad "--frames $r"; done
same "$tmp/fr" && ok || bad "frames in three --frames pieces differ from one run"
for k in 0 1 2; do "$hv" animate $A -o "$tmp/s3" $O --shard $k/3 || bad "--shard $k/3"; done
same "$tmp/s3" && ok || bad "frames of --shard K/3 differ from one run"
k=0
while [ $k -lt 20 ]; do "$hv" animate $A -o "$tmp/s20" $O --shard $k/20 || bad "--shard $k/20"; k=$((k + 1)); done
same "$tmp/s20" && ok || bad "frames of --shard K/20 differ from one run"

# a scene animation ([keyframe] sections) in two shards
sc=$scenes/anim_minor_loop_ex4.scene
"$hv" animate "$sc" -o "$tmp/sc1" $O -j 2 || bad "scene one run"
for k in 0 1; do "$hv" animate "$sc" -o "$tmp/sc2" $O --shard $k/2 || bad "scene --shard $k/2"; done
diff -r "$tmp/sc1" "$tmp/sc2" > /dev/null && ok || bad "scene animation in two shards differs"

# the pieces assembled: the one run's video, frame for frame
"$hv" animate $A -o "$tmp/fr" $O --assemble mp4 && ok || bad "--assemble status"
ffmpeg -loglevel error -i "$tmp/one/$A.mp4" -f framemd5 - > "$tmp/one.md5"
ffmpeg -loglevel error -i "$tmp/fr/$A.mp4" -f framemd5 - > "$tmp/fr.md5"
[ "$(grep -c '^0,' "$tmp/fr.md5")" -eq 15 ] && cmp -s "$tmp/one.md5" "$tmp/fr.md5" && ok ||
    bad "assembled video decodes differently: $(diff "$tmp/one.md5" "$tmp/fr.md5" | head -3)"

# refusals
rm "$tmp/s3/$A/frame_00007.png" "$tmp/s3/$A/frame_00008.png"
"$hv" animate $A -o "$tmp/s3" $O --assemble mp4 2> "$tmp/err"
[ $? -eq 2 ] && grep -q '2 of the 15 frames' "$tmp/err" && grep -q ' 7:9' "$tmp/err" && [ ! -e "$tmp/s3/$A.mp4" ] && ok ||
    bad "missing frames: $(cat "$tmp/err")"
"$hv" animate $A -o "$tmp/s3" $O --frames 7:9 && "$hv" animate $A -o "$tmp/s3" $O --assemble gif && [ -s "$tmp/s3/$A.gif" ] &&
    ok || bad "re-rendered range then --assemble gif"
PATH=/nonexistent "$hv" animate $A -o "$tmp/fr" $O --assemble webm 2> "$tmp/err"
[ $? -eq 3 ] && grep -q ffmpeg "$tmp/err" && [ ! -e "$tmp/fr/$A.webm" ] && ok || bad "no ffmpeg: $(cat "$tmp/err")"
"$hv" animate $A -o "$tmp/fr" $O --assemble mp4 --frames 0:3 2> /dev/null
[ $? -eq 2 ] && ok || bad "--assemble with --frames accepted"
"$hv" animate $A -o "$tmp/fr" $O --shard 0/2 --frames 0:3 2> /dev/null
[ $? -eq 2 ] && ok || bad "--shard with --frames accepted"
"$hv" animate $A -o "$tmp/fr" $O --assemble avi 2> /dev/null
[ $? -eq 2 ] && ok || bad "--assemble avi accepted"
"$hv" animate $A -o "$tmp/fr" $O --shard 3/3 2> /dev/null
[ $? -eq 2 ] && ok || bad "--shard 3/3 accepted"

finish "test_assemble"
