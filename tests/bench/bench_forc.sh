#!/bin/sh
# SPDX-License-Identifier: MIT
# bench_forc.sh HYSTVIZ FILE.forc: the whole `hystviz forc` command (process
# start, read, regression, CSV) on the measured file at SF = 3 and on a
# 400-curve Preisach protocol: wall time and peak memory (GNU time when
# installed), median of 11 runs of the file.  Prints; asserts nothing.
set -u
hv=$1 data=$2
tmp=$(mktemp -d "${TMPDIR:-/tmp}/bench_forc.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
ms() { date +%s%N; }
runs=""
for i in 1 2 3 4 5 6 7 8 9 10 11; do
    t0=$(ms); "$hv" forc "$data" --sf 3 -o "$tmp/rho.csv"; t1=$(ms)
    runs="$runs $(( (t1 - t0) / 1000 ))"
done
med=$(echo $runs | tr ' ' '\n' | sort -n | sed -n 6p)
echo "hystviz forc FILE --sf 3 -o rho.csv (whole command): median $((med / 1000)).$(printf %03d $((med % 1000))) ms of 11"
"$hv" forc "$data" --sf 3 -v -o "$tmp/rho.csv" 2>&1 | sed 's/^/  /'
if [ -x /usr/bin/time ]; then
    /usr/bin/time -f "  peak RSS %M kB, %e s wall, %U s user" "$hv" forc "$data" --sf 3 -o "$tmp/rho.csv"
    /usr/bin/time -f "  peak RSS %M kB, %e s wall, %U s user" "$hv" forc --preisach gaussian:0.3,0.1 --curves 400 \
        -v -o "$tmp/pr.csv"
else
    t0=$(ms); "$hv" forc --preisach gaussian:0.3,0.1 --curves 400 -v -o "$tmp/pr.csv"; t1=$(ms)
    echo "hystviz forc --preisach gaussian:0.3,0.1 --curves 400 (whole command): $(( (t1 - t0) / 1000000 )) ms"
fi
