#!/bin/sh
# SPDX-License-Identifier: MIT
# test_check.sh RUN_CMD [OPTIONS]: `check` exits 0, prints the header, one row
# per case and a summary whose case count matches the rows.
set -u
. "$(dirname "$0")/../lib.sh"
RUN=$1
shift
out=$("$RUN" check "$@") || { echo "$out"; fatal "check exited non-zero"; }
echo "$out"
echo "$out" | head -1 | grep -q '^case  *parameters  *result  *error  *bound  *time_s$' && ok || bad "header"
rows=$(echo "$out" | grep -c -E ' (ok|refused) +[-0-9.e+]+ +[0-9.e+-]+ +[0-9.]+$')
n=$(echo "$out" | sed -n 's/^check: \([0-9]*\) cases, 0 failed.*/\1/p')
[ -n "$n" ] && [ "$n" = "$rows" ] && [ "$n" -ge 40 ] && ok || bad "$rows rows for '$n' cases"
# issue 22: the rate-independent models' extremes, finite or refused naming the parameter
echo "$out" | grep -q '^jiles-atherton  *a=1e-3 a=0.001 k=400 c=0.2 alpha=0  *ok ' && ok || bad "JA a = 1e-3"
echo "$out" | grep -q '^jiles-atherton  *c->1 .* ok ' && ok || bad "JA c -> 1"
echo "$out" | grep -q 'Jiles-Atherton c (reversibility) must be in \[0, 1)' && ok || bad "JA c = 1 not refused naming c"
echo "$out" | grep -q 'Jiles-Atherton alpha = 0.0016 is too large' && ok || bad "JA alpha not refused naming alpha"
echo "$out" | grep -q '^preisach  *gaussian width=2e-09 (range 2)  *ok ' && ok || bad "Preisach width 1e-9 of the range"
"$RUN" check --bogus >/dev/null 2>&1; [ $? = 2 ] && ok || bad "bad option not refused"
finish "check ($n cases)"
