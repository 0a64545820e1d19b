#!/bin/sh
# SPDX-License-Identifier: MIT
# test_check.sh RUN_CMD [OPTIONS]: `check` exits 0, prints the header, one row
# per case and a summary whose case count matches the rows.
set -u
RUN=$1
shift
out=$("$RUN" check "$@") || { echo "$out"; echo "FAIL: check exited non-zero"; exit 1; }
echo "$out"
echo "$out" | head -1 | grep -q '^case  *parameters  *result  *error  *bound  *time_s$' || { echo "FAIL: header"; exit 1; }
rows=$(echo "$out" | grep -c -E ' (ok|refused) +[-0-9.e+]+ +[0-9.e+-]+ +[0-9.]+$')
n=$(echo "$out" | sed -n 's/^check: \([0-9]*\) cases, 0 failed.*/\1/p')
[ -n "$n" ] && [ "$n" = "$rows" ] && [ "$n" -ge 40 ] || { echo "FAIL: $rows rows for '$n' cases"; exit 1; }
# issue 22: the rate-independent models' extremes, finite or refused naming the parameter
echo "$out" | grep -q '^jiles-atherton  *a=1e-3 a=0.001 k=400 c=0.2 alpha=0  *ok ' || { echo "FAIL: JA a = 1e-3"; exit 1; }
echo "$out" | grep -q '^jiles-atherton  *c->1 .* ok ' || { echo "FAIL: JA c -> 1"; exit 1; }
echo "$out" | grep -q 'Jiles-Atherton c (reversibility) must be in \[0, 1)' || { echo "FAIL: JA c = 1 not refused naming c"; exit 1; }
echo "$out" | grep -q 'Jiles-Atherton alpha = 0.0016 is too large' || { echo "FAIL: JA alpha not refused naming alpha"; exit 1; }
echo "$out" | grep -q '^preisach  *gaussian width=2e-09 (range 2)  *ok ' || { echo "FAIL: Preisach width 1e-9 of the range"; exit 1; }
"$RUN" check --bogus >/dev/null 2>&1; [ $? = 2 ] || { echo "FAIL: bad option not refused"; exit 1; }
echo "check tests passed ($n cases)"
