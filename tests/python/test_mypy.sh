#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/python/test_mypy.sh SOURCE_ROOT: the package's type hints checked by
# `mypy --strict` (Debian's mypy), its cache in the test's own temporary
# directory.  SKIP (77) without mypy; FAIL when CI=true (apt-get install mypy).
set -u
src=$1
if ! command -v mypy >/dev/null; then
    [ "${CI:-}" = true ] && { echo "FAIL: no mypy (apt-get install mypy)"; exit 1; }
    echo "SKIP: no mypy (apt-get install mypy)"
    exit 77
fi
T=$(mktemp -d "${TMPDIR:-/tmp}/hystviz-mypy.XXXXXX") || exit 1
trap 'rm -rf "$T"' EXIT
cd "$src/src/python" || exit 1
MYPYPATH= timeout 600 mypy --strict --no-error-summary --cache-dir "$T/cache" -p hystviz >"$T/out" 2>&1
rc=$?
cat "$T/out"
[ $rc -eq 0 ] && echo "ok: mypy --strict -p hystviz: no errors" || echo "FAIL: mypy --strict -p hystviz (exit $rc)"
exit $rc
