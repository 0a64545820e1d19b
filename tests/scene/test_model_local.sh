#!/bin/sh
# SPDX-License-Identifier: MIT
# test_model_local.sh ROOT SCHEMA_JSON: a model that declares its own [model] rows (a line of three
# columns [id, kind, file] in the model table of src/pipeline/meson.build) is named in its file and
# that line only: none of its [model] keys, nor its kind as a C string, appears in the C sources
# under src/ outside its file and src/core (its numerics; src/app/cmd_check.c names its core checks
# after the model, and src/app/cmd_forc.c its --preisach option, the core's FORC protocol on
# hy_preisach, not the scene model), and no meson file but the table names its file.
set -u
root=$1
. "$(dirname "$0")/../lib.sh"
json=$("$2") || fatal "$2 failed"
table="$root/src/pipeline/meson.build"
models=$(sed -n "s/^  \['\([a-z_0-9]*\)', '\([a-z0-9-]*\)', '\([a-z_0-9]*\.c\)'\],\$/\1 \2 \3/p" "$table")
[ -n "$models" ] || fatal "no model with its own rows in $table"
n=0
others() { # C sources under src/ but the model's file and src/core
    find "$root/src" \( -name '*.c' -o -name '*.h' \) ! -path "$root/src/core/*" ! -path "$root/src/pipeline/$1"
}
while read -r id kind file; do
    n=$((n + 1))
    keys=$(printf '%s' "$json" | python3 -c 'import json, sys
d = json.load(sys.stdin)
print(" ".join(next(m["params"] for m in d["models"] if m["name"] == sys.argv[1])))' "$kind") ||
        { bad "$kind: not in the schema's model table"; continue; }
    [ -n "$keys" ] || bad "$kind reads no key"
    pat=$(printf '%s\n' $keys | paste -sd'|')
    hits=$(others "$file" | xargs grep -HnwE "$pat")
    [ -z "$hits" ] && ok || bad "$kind's keys are named outside $file:
$hits"
    hits=$(others "$file" | grep -v '/src/app/cmd_check\.c$\|/src/app/cmd_forc\.c$' | xargs grep -lF "\"$kind\"")
    [ -z "$hits" ] && ok || bad "$kind is named outside $file: $hits"
    lines=$(find "$root" -name meson.build ! -path "$root/build*" ! -path "$root/subprojects/*" | xargs grep -n "$file")
    [ "$(printf '%s\n' "$lines" | wc -l)" -eq 1 ] && ok || bad "$file is named in meson more than once: $lines"
    echo "$kind: keys $keys, in $file and one line of the model table"
done <<EOT
$models
EOT
echo "model_local: $n model(s) with their own rows checked"
finish model_local
