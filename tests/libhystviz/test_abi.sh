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
. "$(dirname "$0")/../lib.sh"
lib=$1 prog=$2 list=$3
command -v nm >/dev/null || skip "nm is not installed"
timeout 30 "$prog" >"$tmp/layout" || fatal "$prog exited non-zero"
{
    echo "# libhystviz ABI: exported symbols and the public structs' layout (tests/libhystviz/test_abi.sh)"
    echo "# machine $(uname -m)"
    cat "$tmp/layout"
    nm -D --defined-only "$lib" | awk '$2 == "T" || $2 == "D" || $2 == "B" {print "symbol", $3}' | sort
} >"$tmp/now" || fatal "cannot write $tmp/now"
grep -q '^symbol hy_version@@HYSTVIZ_0$' "$tmp/now" ||
    fatal "no hy_version@@HYSTVIZ_0 among the exported symbols: is the version script applied?"
if [ "${HY_ABI_UPDATE:-}" = 1 ]; then
    cp "$tmp/now" "$list" || fatal "cannot write $list"
    ok "wrote $list ($(grep -c '^symbol' "$list") symbols, $(grep -c '^struct' "$list") structs)"
    finish lib-abi
    exit
fi
want_machine=$(sed -n 's/^# machine //p' "$list")
[ "$want_machine" = "$(uname -m)" ] || skip "$list holds the layout on $want_machine, this is $(uname -m)"
if ! diff -u "$list" "$tmp/now" >"$tmp/diff"; then
    cat "$tmp/diff"
    echo "A struct that grows or a removed symbol breaks programs built against libhystviz.so.0"
    echo "(docs/LIBRARY.md, \"ABI\"). If the change is deliberate and the policy allows it, update the"
    echo "list with:  HY_ABI_UPDATE=1 meson test -C <build> lib-abi   and say why in the commit."
    fatal "libhystviz's ABI differs from $list (- committed, + now)."
fi
ok "$(grep -c '^symbol' "$list") symbols and $(grep -c '^struct' "$list") struct layouts as in $list"
finish lib-abi
