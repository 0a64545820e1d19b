#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/python/test_mypy.sh SOURCE_ROOT: the package's type hints checked by
# `mypy --strict` (Debian's mypy), its cache in the test's own temporary
# directory.  SKIP (77) without mypy; FAIL when CI=true (apt-get install mypy).
set -u
. "$(dirname "$0")/../lib.sh"
src=$1
if ! command -v mypy >/dev/null; then
    [ "${CI:-}" = true ] && fatal "no mypy (apt-get install mypy)"
    skip "no mypy (apt-get install mypy)"
fi
T=$tmp
cd "$src/src/python" || fatal "cannot cd to $src/src/python"
MYPYPATH= timeout 600 mypy --strict --no-error-summary --cache-dir "$T/cache" -p hystviz >"$T/out" 2>&1
rc=$?
cat "$T/out"
[ $rc -eq 0 ] && ok "mypy --strict -p hystviz: no errors" || bad "mypy --strict -p hystviz (exit $rc)"
finish mypy
