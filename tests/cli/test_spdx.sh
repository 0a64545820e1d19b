#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/cli/test_spdx.sh SOURCE_ROOT [MIN]: every source file (C, headers,
# shell, Python, meson, GLSL, the page's HTML/JS/CSS) names its licence in an
# SPDX line within its first three lines (issue 24; LICENSE: MIT).  The files
# are those git tracks when SOURCE_ROOT is the top of a git checkout, else
# (an unpacked `meson dist` tarball, which may lie inside another checkout:
# issue 35 item 5) every file under SOURCE_ROOT but build directories (those
# holding meson-private/).  Fewer than MIN (default 100) files checked is a
# failure: the wrong tree.  tests/cli/test_spdx_modes.sh runs it both ways.
set -u
. "$(dirname "$0")/../lib.sh"
cd "$1" || fatal "cannot cd to $1"
min=${2:-100}
root=$(pwd -P)
top=$(git rev-parse --show-toplevel 2>/dev/null) && top=$(cd "$top" && pwd -P)
# (gallery/ is hystviz's output, written by `hystviz gallery`, not a source)
if [ "${top:-}" = "$root" ]; then
    how="tracked by git"
    list() { git ls-files; }
else
    how="in the tree (no git checkout of its own)"
    list() {
        builds=$(find . -name meson-private -type d -prune | sed 's|/meson-private$||')
        find . -name .git -prune -o -type f -print | sed 's|^\./||' |
            awk -v b="$builds" 'BEGIN { n = split(b, d, "\n"); for (i = 1; i <= n; i++) sub("^\\./", "", d[i]) }
                { for (i = 1; i <= n; i++) if (d[i] != "" && (d[i] == "." || index($0, d[i] "/") == 1)) next; print }'
    }
fi
files=$(list | grep -E '\.(c|h|sh|py|glsl|js|css|html)$|(^|/)meson\.build$' | grep -v '^gallery/')
n=$(printf '%s\n' "$files" | grep -c .)
[ "$n" -ge "$min" ] || fatal "only $n source files $how under $root (at least $min expected)"
# (one head and one awk for all files: a process per file took 30 s under load)
missing=$(printf '%s\n' "$files" | xargs -d '\n' head -v -n 3 -- | awk '
        /^==> .* <==$/ { if (f != "" && !ok) print f; f = substr($0, 5, length($0) - 8); ok = 0; next }
        /SPDX-License-Identifier: MIT/ { ok = 1 }
        END { if (f != "" && !ok) print f }')
if [ -n "$missing" ]; then
    bad "no SPDX line in:"
    echo "$missing"
else
    ok "all $n source files $how have their SPDX line"
fi
finish spdx
