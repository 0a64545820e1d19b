#!/bin/sh
# SPDX-License-Identifier: MIT
# test_model_named.sh ROOT: every model of the model table (src/pipeline/meson.build, one line
# [id, kind, file] or [id, kind, file, 'shared'] per model: Dahl, LuGre, the filter system, Bouc-Wen,
# Jiles-Atherton, Preisach, the Bouc-Wen operator, play, ...) is named only in its own file: its kind
# as a C string ("dahl") and its table entry (hy_scene_model_<id>) appear in no C or JavaScript source
# under src/ outside that file, src/core (the models' numerics) and the table's own code
# (scene_model.[ch]), so the generic driver scene_run.c, serve, the schema and the rest reach a model
# through the table only (issue 34 item 2).  A few names are not the scene model's; each is listed
# below as FILE|PATTERN with the reason, and only lines matching PATTERN in FILE are passed over.
set -u
root=$1
. "$(dirname "$0")/../lib.sh"
table="$root/src/pipeline/meson.build"
models=$(sed -n "s/^  \['\([a-z_0-9]*\)', '\([a-z0-9-]*\)', '\([a-z_0-9]*\.c\)'\(, '[a-z]*'\)*\],\$/\1 \2 \3/p" "$table")
[ "$(printf '%s\n' "$models" | wc -l)" -ge 8 ] || { echo "FAIL: fewer than 8 models read from $table"; exit 1; }
# Names that are not the scene model's, with why:
cat > "$tmp/allowed" <<'EOT'
src/app/cmd_check.c|case_start\(|hystviz check names its core checks after the model they check
src/app/cmd_forc.c|"preisach", 0, "SPEC"|forc --preisach: the core's FORC protocol on hy_preisach, not the scene model
src/app/cli_util.c|cm->kind = |the core model options (--sigma0 ...) of the commands that drive src/core directly
src/app/main.c|hy_cmd_boucwen|the `hystviz boucwen` command (the benchmark of seeds/001 over the core)
src/app/cmd_boucwen.[ch]|.|the `hystviz boucwen` command itself
src/app/cmd_fit.c|o->bench|fit --bench boucwen: the benchmark's data set
src/pipeline/hy_workprec.c|X\("boucwen", init_boucwen|the work-precision problem of the Bouc-Wen benchmark (core, Newmark)
src/pipeline/hy_workprec.h|"lugre-stiff", "boucwen"|the work-precision problems' names
src/scene/hy_scene_schema.h|X\(BOUCWEN, "boucwen"\)|series data = boucwen: a data kind's name (the model table's data column says who draws it)
EOT
sources() { # C and JavaScript sources under src/ but src/core, the table's code and the model's file
    (cd "$root" && find src \( -name '*.c' -o -name '*.h' -o -name '*.js' \) ! -path 'src/core/*' \
        ! -name 'scene_model.[ch]' ! -path "src/pipeline/$1" | sort)
}
# The lines of file that an allowed entry passes over are dropped.
unexcused() {
    while IFS= read -r hit; do
        file=${hit%%:*}
        line=${hit#*:}
        line=${line#*:}
        skip=0
        while IFS='|' read -r glob pat why; do
            case $file in $glob) printf '%s\n' "$line" | grep -qE "$pat" && skip=1 ;; esac
        done < "$tmp/allowed"
        [ "$skip" -eq 1 ] || printf '%s\n' "$hit"
    done
}
n=0
while read -r id kind file; do
    n=$((n + 1))
    [ -f "$root/src/pipeline/$file" ] || { bad "$kind: its file src/pipeline/$file does not exist"; continue; }
    hits=$(sources "$file" | (cd "$root" && xargs grep -HnF "\"$kind\"") | unexcused)
    if [ -z "$hits" ]; then ok "$kind: named as a string in $file only"; else bad "$kind is named outside $file:
$hits"; fi
    hits=$(sources "$file" | (cd "$root" && xargs grep -HnwE "hy_scene_model_$id") | unexcused)
    if [ -z "$hits" ]; then ok "$kind: entry hy_scene_model_$id used in $file and the table only"; else
        bad "$kind's entry is used outside $file:
$hits"; fi
done <<EOT
$models
EOT
[ "$n" -ge 8 ] && ok "$n models checked" || bad "only $n models checked"
finish model_named
