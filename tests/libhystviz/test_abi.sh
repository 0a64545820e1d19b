#!/bin/bash
# SPDX-License-Identifier: MIT
# tests/libhystviz/test_abi.sh LIB LAYOUT-PROG LIST: libhystviz's ABI is the
# committed LIST (tests/libhystviz/abi.txt): the exported symbols with their
# version node (nm -D) and the size and alignment of every struct the
# installed headers define (LAYOUT-PROG, generated from them by
# tools/lib_abi.py).  A change fails here; a deliberate one (docs/LIBRARY.md,
# "ABI") rewrites the list with
#     HY_ABI_UPDATE=1 meson test -C build lib-abi
# and the commit says why.  The list holds one machine's layout (its
# "# machine" line); on another the test is skipped.
set -u
lib=$1 prog=$2 list=$3
command -v nm >/dev/null || { echo "SKIP: nm is not installed"; exit 77; }
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
{
    echo "# libhystviz ABI: exported symbols and the public structs' layout (tests/libhystviz/test_abi.sh)"
    echo "# machine $(uname -m)"
    timeout 30 "$prog" || { echo "FAIL: $prog exited non-zero" >&2; exit 1; }
    nm -D --defined-only "$lib" | awk '$2 == "T" || $2 == "D" || $2 == "B" {print "symbol", $3}' | sort
} >"$T/now" || exit 1
grep -q '^symbol hy_version@@HYSTVIZ_0$' "$T/now" ||
    { echo "FAIL: no hy_version@@HYSTVIZ_0 among the exported symbols: is the version script applied?"; exit 1; }
if [ "${HY_ABI_UPDATE:-}" = 1 ]; then
    cp "$T/now" "$list" && echo "ok: wrote $list ($(grep -c '^symbol' "$list") symbols, $(grep -c '^struct' "$list") structs)"
    exit 0
fi
want_machine=$(sed -n 's/^# machine //p' "$list")
if [ "$want_machine" != "$(uname -m)" ]; then
    echo "SKIP: $list holds the layout on $want_machine, this is $(uname -m)"
    exit 77
fi
if ! diff -u "$list" "$T/now" >"$T/diff"; then
    cat "$T/diff"
    echo "FAIL: libhystviz's ABI differs from $list (- committed, + now)."
    echo "A struct that grows or a removed symbol breaks programs built against libhystviz.so.0"
    echo "(docs/LIBRARY.md, \"ABI\"). If the change is deliberate and the policy allows it, update the"
    echo "list with:  HY_ABI_UPDATE=1 meson test -C <build> lib-abi   and say why in the commit."
    exit 1
fi
echo "ok: $(grep -c '^symbol' "$list") symbols and $(grep -c '^struct' "$list") struct layouts as in $list"
