#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/cli/test_spdx.sh SOURCE_ROOT: every source file the repository tracks
# (C, headers, shell, Python, meson, GLSL, the page's HTML/JS/CSS) names its
# licence in an SPDX line within its first three lines (issue 24; LICENSE: MIT).
set -u
cd "$1" || exit 1
git rev-parse --git-dir >/dev/null 2>&1 || { echo "SKIP: not a git checkout"; exit 77; }
# (gallery/ is hystviz's output, written by `hystviz gallery`, not a source)
missing=$(git ls-files | grep -E '\.(c|h|sh|py|glsl|js|css|html)$|(^|/)meson\.build$' | grep -v '^gallery/' | while read -r f; do
    head -3 "$f" | grep -q 'SPDX-License-Identifier: MIT' || echo "$f"
done)
[ -z "$missing" ] || { echo "FAIL: no SPDX line in:"; echo "$missing"; exit 1; }
echo "ok: every tracked source file has its SPDX line"
