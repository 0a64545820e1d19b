#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/cli/test_spdx.sh SOURCE_ROOT: every source file the repository tracks
# (C, headers, shell, Python, meson, GLSL, the page's HTML/JS/CSS) names its
# licence in an SPDX line within its first three lines (issue 24; LICENSE: MIT).
set -u
cd "$1" || exit 1
git rev-parse --git-dir >/dev/null 2>&1 || { echo "SKIP: not a git checkout"; exit 77; }
# (gallery/ is hystviz's output, written by `hystviz gallery`, not a source)
# (one head and one awk for all files: a process per file took 30 s under load)
missing=$(git ls-files | grep -E '\.(c|h|sh|py|glsl|js|css|html)$|(^|/)meson\.build$' | grep -v '^gallery/' |
    xargs -d '\n' head -v -n 3 -- | awk '
        /^==> .* <==$/ { if (f != "" && !ok) print f; f = substr($0, 5, length($0) - 8); ok = 0; next }
        /SPDX-License-Identifier: MIT/ { ok = 1 }
        END { if (f != "" && !ok) print f }')
[ -z "$missing" ] || { echo "FAIL: no SPDX line in:"; echo "$missing"; exit 1; }
echo "ok: every tracked source file has its SPDX line"
