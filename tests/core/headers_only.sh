#!/bin/sh
# SPDX-License-Identifier: MIT
# The numerical core includes no graphics header (STYLE.md, NanoVG): every
# src/core file must compile with only the C library, GSL and its own headers.
set -eu
src=$1
bad=$(grep -nE '#include *[<"](cairo|GL/|GLES|png|osmesa|EGL)' "$src"/src/core/*.[ch] || true)
if [ -n "$bad" ]; then
    echo "graphics headers in src/core:"
    echo "$bad"
    exit 1
fi
for f in "$src"/src/core/*.h; do
    printf '#include "%s"\nint main(void){return 0;}\n' "$(basename "$f")" |
        ${CC:-cc} -std=c11 -Wall -Wextra -Wpedantic -Werror -I"$src/src/core" -x c - -fsyntax-only
done
echo "headers_only: $(ls "$src"/src/core/*.h | wc -l) passed, 0 failed"
