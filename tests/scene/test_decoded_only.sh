#!/bin/sh
# SPDX-License-Identifier: MIT
# test_decoded_only.sh ROOT: the pipeline (src/pipeline), the commands (src/app) and serve (src/serve) read the decoded
# scene (hy_scene_decl.h: hy_scene_decode, hy_scene_doc_find, hy_decl_error), never the scene key by
# key: no getter, count, label or location call in any of their C files.  What is about the parse
# itself (a scene's text written back, placeholders filled as text, a PATH key's file read) calls
# functions outside this pattern (hy_scene_expand, hy_scene_read_path, hy_scene_preset_sets).
set -u
. "$(dirname "$0")/../lib.sh"
root=$1
pat='hy_scene_get_[a-z_]*(\|hy_scene_count(\|hy_scene_name_at(\|hy_scene_error_at('
files=$(cd "$root" && ls src/pipeline/*.c src/pipeline/*.h src/app/*.c src/app/*.h src/serve/*.c src/serve/*.h)
[ -n "$files" ] || fatal "no sources under $root/src/pipeline, $root/src/app and $root/src/serve"
for f in $files; do
    if grep -n "$pat" "$root/$f"; then
        bad "$f reads the scene key by key (above): read the decoded structs (hy_scene_doc) instead"
    else
        ok
    fi
done
echo "decoded-only: $(echo $files | wc -w) file(s) of src/pipeline, src/app and src/serve checked"
finish decoded-only
