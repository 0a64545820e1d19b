#!/bin/sh
# SPDX-License-Identifier: MIT
# test_decoded_only.sh ROOT: the pipeline files converted to the decoded scene (hy_scene_decl.h)
# read its structs, never the scene: no key-at-a-time getter, count, label or location call.
# Add a file here when it converts; the last line prints what the rest of the pipeline still calls.
root=$1
converted="src/pipeline/scene_draw.c src/pipeline/scene_run.c src/pipeline/scene_rateind.c src/pipeline/scene_model.c
src/pipeline/model_friction.c src/pipeline/model_jiles.c src/pipeline/model_preisach.c src/pipeline/model_bwop.c
src/pipeline/scene_boucwen.c src/pipeline/scene_anim.c"
pat='hy_scene_get_[a-z_]*(\|hy_scene_count(\|hy_scene_name_at(\|hy_scene_error_at('
fail=0
for f in $converted; do
    [ -f "$root/$f" ] || { echo "missing $f"; fail=1; continue; }
    if grep -n "$pat" "$root/$f"; then
        echo "$f reads the scene key by key: read the decoded structs (r->doc) instead"
        fail=1
    fi
done
left=$(cat "$root"/src/pipeline/*.c "$root"/src/app/*.c | grep -o "$pat" | wc -l)
echo "decoded-only: $(echo $converted | wc -w) file(s) checked; src/pipeline and src/app still make $left such calls"
exit $fail
