#!/bin/sh
# SPDX-License-Identifier: MIT
# The numerical core includes no graphics header (STYLE.md, NanoVG): every
# src/core file must compile with only the C library, GSL and its own headers.
set -u
. "$(dirname "$0")/../lib.sh"
src=$1
graphics=$(grep -nE '#include *[<"](cairo|GL/|GLES|png|osmesa|EGL)' "$src"/src/core/*.[ch])
[ -z "$graphics" ] && ok "no graphics header in src/core" || bad "graphics headers in src/core:
$graphics"
for f in "$src"/src/core/*.h; do
    printf '#include "%s"\nint main(void){return 0;}\n' "$(basename "$f")" |
        ${CC:-cc} -std=c11 -Wall -Wextra -Wpedantic -Werror -I"$src/src/core" -x c - -fsyntax-only &&
        ok || bad "src/core/$(basename "$f") does not compile alone (above)"
done
finish headers_only
