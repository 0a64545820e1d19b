#!/bin/bash
# SPDX-License-Identifier: MIT
# tests/libhystviz/test_symbols.sh LIB LIST-TOOL HEADER...: libhystviz exports
# exactly the functions its installed headers declare (issue 24: symbol
# visibility): no internal function leaks, none of the API is missing.
set -u
. "$(dirname "$0")/../lib.sh"
lib=$1 tool=$2
shift 2
command -v nm >/dev/null || skip "nm is not installed"
exported=$(nm -D --defined-only "$lib" | awk '$2 == "T" || $2 == "D" || $2 == "B" {print $3}' | sed 's/@.*//' | sort)
declared=$(python3 "$tool" --list "$@")
if [ "$exported" != "$declared" ]; then
    diff <(echo "$exported") <(echo "$declared")
    fatal "exported (<) and declared (>) differ (above)"
fi
n=$(echo "$exported" | wc -l)
[ "$n" -ge 100 ] || fatal "only $n symbols: the header scan found too few"
ok "$n exported functions, each declared in an installed header, and every declared one exported"
finish lib-symbols
