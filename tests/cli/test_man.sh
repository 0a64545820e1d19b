#!/bin/bash
# SPDX-License-Identifier: MIT
# tests/cli/test_man.sh HYSTVIZ BUILD_DOCS_DIR GEN_DOCS SOURCE_ROOT: the man pages
# and the bash completion built from the --help texts and the schema (issue 24):
#   - every page formats with groff without a warning and has NAME and SYNOPSIS;
#   - each command's page names exactly the options its --help names (a page
#     left behind by a changed --help fails here);
#   - a page for every command --help lists, and no other;
#   - completion: commands, a command's options, --set keys from the schema.
set -u
hv=$1 docs=$2 gen=$3 src=$4
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
command -v groff >/dev/null || { echo "SKIP: groff is not installed"; exit 77; }
cmds=$(python3 "$gen" commands "$src/src/app/main.c")
[ "$(echo "$cmds" | wc -w)" -ge 10 ] || fail "only $(echo "$cmds" | wc -w) commands read from main.c"
for page in "$docs"/*.[135]; do
    w=$(groff -man -Tutf8 -ww -z "$page" 2>&1)
    [ -z "$w" ] || fail "$(basename "$page"): groff warns: $w"
    grep -q '^\.SH NAME' "$page" && grep -q '^\.SH \(SYNOPSIS\|DESCRIPTION\)' "$page" || fail "$(basename "$page"): no NAME/SYNOPSIS"
done
for c in - $cmds; do
    p="$docs/hystviz-$c.1"
    [ "$c" = - ] && p="$docs/hystviz.1"
    [ -f "$p" ] || { fail "no page for '$c'"; continue; }
    want=$(python3 "$gen" options "$hv" "$c" | tr '\n' ' ')
    got=$(grep '^Every option this page names:' "$p" | sed 's/\\fB//g; s/\\fR//g; s/\\e/\\/g; s/^Every option this page names: //; s/\.$//; s/, /\n/g' | sort | tr '\n' ' ')
    [ "$got" = "$want" ] || fail "hystviz $c: page names '$got', --help '$want'"
done
n=$(ls "$docs"/hystviz-*.1 | wc -l)
[ "$n" -eq "$(echo "$cmds" | wc -w)" ] || fail "$n command pages for $(echo "$cmds" | wc -w) commands"
complete() { # words... -> the completions of the last word
    bash -c 'source "$1"; shift; COMP_WORDS=("$@"); COMP_CWORD=$(($# - 1)); _hystviz; printf "%s\n" "${COMPREPLY[@]}"' \
        _ "$docs/hystviz" "$@" 2>/dev/null
}
[ "$(complete hystviz swe)" = sweep ] || fail "complete 'hystviz swe': '$(complete hystviz swe)'"
complete hystviz sweep --gr | grep -qx -- --grid || fail "complete 'hystviz sweep --gr'"
complete hystviz render x.scene --set model.sig | grep -qx 'model.sigma0=' || fail "complete --set model.sig"
complete hystviz sweep x.scene --grid input.umi | grep -qx 'input.umin2=' || fail "complete --grid input.umi"
[ $fails -eq 0 ] && echo "ok: $(ls "$docs"/*.[135] | wc -l) man pages format cleanly and match --help; completion works"
exit $((fails > 0))
