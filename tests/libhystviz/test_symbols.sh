#!/bin/bash
# SPDX-License-Identifier: MIT
# tests/libhystviz/test_symbols.sh LIB LIST-TOOL HEADER...: libhystviz exports
# exactly the functions its installed headers declare (issue 24: symbol
# visibility): no internal function leaks, none of the API is missing.
set -u
lib=$1 tool=$2
shift 2
command -v nm >/dev/null || { echo "SKIP: nm is not installed"; exit 77; }
exported=$(nm -D --defined-only "$lib" | awk '$2 == "T" || $2 == "D" || $2 == "B" {print $3}' | sed 's/@.*//' | sort)
declared=$(python3 "$tool" --list "$@")
if [ "$exported" != "$declared" ]; then
    echo "FAIL: exported (<) and declared (>) differ:"
    diff <(echo "$exported") <(echo "$declared")
    exit 1
fi
n=$(echo "$exported" | wc -l)
[ "$n" -ge 100 ] || { echo "FAIL: only $n symbols: the header scan found too few"; exit 1; }
echo "ok: $n exported functions, each declared in an installed header, and every declared one exported"
