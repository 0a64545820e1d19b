#!/bin/sh
# SPDX-License-Identifier: MIT
# The default -j of every command with -j (sweep, gallery, export, animate) is the
# CPUs the process may run on: pinned to one CPU (taskset -c 0) each --help
# shows "here 1"; unpinned it shows hy_jobs_default's value, at most nproc.
# usage: test_jobs.sh HYSTVIZ
set -u
hv=$1
. "$(dirname "$0")/../lib.sh"
command -v taskset > /dev/null || { echo "FAIL: taskset (util-linux) is not installed"; exit 1; }
cpu=$(taskset -pc $$ | sed 's/.*: *//; s/[,-].*//')   # the first CPU this shell may use
n=$(nproc)
for c in sweep gallery export animate; do
    out=$(taskset -c "$cpu" "$hv" $c --help)
    echo "$out" | grep -q 'rounded up: here 1)$' && ok || bad "$c --help under taskset -c $cpu: $(echo "$out" | grep -A2 -- '--jobs N')"
    echo "$out" | grep -q 'affinity' && ok || bad "$c --help does not describe the default"
    here=$("$hv" $c --help | sed -n 's/.*rounded up: here \([0-9]*\))$/\1/p')
    [ -n "$here" ] && [ "$here" -ge 1 ] && [ "$here" -le "$n" ] && ok || bad "$c --help default '$here' (nproc $n)"
done
# one description, not a copy per command
[ "$("$hv" sweep --help | grep -A2 -- '-j, --jobs N')" = "$("$hv" gallery --help | grep -A2 -- '-j, --jobs N')" ] && ok ||
    bad "sweep and gallery describe -j differently"
finish "test_jobs"
