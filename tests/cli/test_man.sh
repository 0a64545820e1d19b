#!/bin/bash
# SPDX-License-Identifier: MIT
# tests/cli/test_man.sh HYSTVIZ BUILD_DOCS_DIR GEN_DOCS SOURCE_ROOT: the man pages
# and the bash completion built from the option tables and the schema (issue 24):
#   - every page formats with groff without a warning and has NAME and SYNOPSIS;
#   - for every command (and the program itself) the options of its table
#     (--options-json) == those its --help lists == its man page's == those
#     the completion offers, and the parser accepts each of them (given with a
#     value where it takes one, it is followed by an unknown option, which
#     must be the one refused) and refuses one not in the table;
#   - --version after every command;
#   - a page for every command --help lists, and no other;
#   - completion: commands, a command's options, --set/--grid keys from the schema.
set -u
export LC_ALL=C # sort as python sorts (by code point)
hv=$1 docs=$2 gen=$3 src=$4
. "$(dirname "$0")/../lib.sh"
command -v groff >/dev/null || { echo "SKIP: groff is not installed"; exit 77; }
cmds=$(python3 "$gen" commands "$src/src/app/main.c")
[ "$(echo "$cmds" | wc -w)" -ge 10 ] || bad "only $(echo "$cmds" | wc -w) commands read from main.c"
for page in "$docs"/*.[135]; do
    w=$(groff -man -Tutf8 -ww -z "$page" 2>&1)
    [ -z "$w" ] || bad "$(basename "$page"): groff warns: $w"
    grep -q '^\.SH NAME' "$page" && grep -q '^\.SH \(SYNOPSIS\|DESCRIPTION\)' "$page" || bad "$(basename "$page"): no NAME/SYNOPSIS"
done
complete() { # words... -> the completions of the last word
    bash -c 'source "$1"; shift; COMP_WORDS=("$@"); COMP_CWORD=$(($# - 1)); _hystviz; printf "%s\n" "${COMPREPLY[@]}"' \
        _ "$docs/hystviz" "$@" 2>/dev/null
}
# the option names of --help's "options:" section (from "  -o, --output DIR   text")
help_opts() {
    sed -n '/^options:$/,/^$/p' | grep '^  -' | sed 's/^  //; s/   .*//' |
        tr ', ' '\n\n' | grep -E '^--?[A-Za-z]' | sort | tr '\n' ' '
}
probe=--no-such-option-$$
nprobe=0
# each command's table (one python: its start is slow on a loaded machine):
# "CMD<TAB>its option names, sorted<TAB>each option, with a value where it takes one"
tables=$(python3 -c 'import json, subprocess, sys
hv = sys.argv[1]
for c in sys.argv[2:]:
    t = json.loads(subprocess.run([hv, "--options-json"] if c == "-" else [hv, c, "--options-json"],
                                  capture_output=True, check=True, timeout=60).stdout)
    names = sorted(n for o in t["options"] for n in (o["short"], o["long"]) if n)
    line = [w for o in t["options"] if o["long"] not in ("--help", "--version")
            for n in (o["short"], o["long"]) if n for w in [n] + (["1"] if o["arg"] else [])]
    print(c, " ".join(names) + " ", " ".join(line), sep="\t")' "$hv" - $cmds) || bad "cannot read the option tables"
version=$("$hv" --version)
for c in - $cmds; do
    p="$docs/hystviz-$c.1" args=("$c")
    [ "$c" = - ] && p="$docs/hystviz.1" args=()
    [ -f "$p" ] || { bad "no page for '$c'"; continue; }
    want=$(echo "$tables" | awk -F '\t' -v c="$c" '$1 == c { print $2 }')
    [ -n "$want" ] || { bad "hystviz $c: no option table"; continue; }
    got=$(grep -A1 '^\.TP$' "$p" | grep -v '^\.TP$\|^--$' | grep -o '\\fB[^\\]*\(\\e[^\\]*\)*\\fR' |
        sed 's/\\fB//; s/\\fR//; s/\\e/\\/g' | sort | tr '\n' ' ')
    [ "$got" = "$want" ] || bad "hystviz $c: page names '$got', table '$want'"
    got=$("$hv" "${args[@]}" --help | help_opts)
    [ "$got" = "$want" ] || bad "hystviz $c: --help lists '$got', table '$want'"
    if [ "$c" != - ]; then
        got=$(complete hystviz "$c" - | sort | tr '\n' ' ')
        [ "$got" = "$want" ] || bad "hystviz $c: completion offers '$got', table '$want'"
        v=$("$hv" "$c" --version) && [ "$v" = "$version" ] || bad "hystviz $c --version: '$v'"
    fi
    # the parser: every option of the table accepted (all on one line, each
    # with a value where it takes one; the line is checked whole before any
    # option acts, so the one refused must be the unknown one at its end)
    line=$(echo "$tables" | awk -F '\t' -v c="$c" '$1 == c { print $3 }')
    err=$("$hv" "${args[@]}" $line "$probe" 2>&1 >/dev/null </dev/null)
    st=$?
    [ $st -eq 2 ] && [ "$err" = "hystviz${args:+ $c}: unknown option '$probe' (see hystviz${args:+ $c} --help)" ] ||
        bad "hystviz $c $line $probe: status $st, '$err' (an option of the table not accepted?)"
    nprobe=$((nprobe + $(echo "$line" | tr ' ' '\n' | grep -c '^-')))
done
n=$(ls "$docs"/hystviz-*.1 | wc -l)
[ "$n" -eq "$(echo "$cmds" | wc -w)" ] || bad "$n command pages for $(echo "$cmds" | wc -w) commands"
[ "$(complete hystviz swe)" = sweep ] || bad "complete 'hystviz swe': '$(complete hystviz swe)'"
[ "$(complete hystviz loop --model dahl | tr '\n' ' ')" = "dahl dahl-filter " ] || bad "complete --model dahl (its choices)"
complete hystviz sweep --gr | grep -qx -- --grid || bad "complete 'hystviz sweep --gr'"
complete hystviz render x.scene --set model.sig | grep -qx 'model.sigma0=' || bad "complete --set model.sig"
complete hystviz sweep x.scene --grid input.umi | grep -qx 'input.umin2=' || bad "complete --grid input.umi"
[ $fail -eq 0 ] && echo "ok: $(ls "$docs"/*.[135] | wc -l) man pages format cleanly; tables == --help == pages == completion; $nprobe options accepted by the parser"
exit $((fail > 0))
