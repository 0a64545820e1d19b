#!/bin/sh
# Benchmark of `hystviz sweep` (issue 13), whole processes:
#   1. a 1,000-point sweep of Fig. 15 (analytic: closed forms) with its figures
#      (the scene's formats: SVG, PDF, PNG) at -j 1 and -j 2: points per second
#   2. the same for Fig. 11 with compute.solver = rkf45 (GSL odeiv2, three y_γ
#      solves per point, each also measured against the exact solution)
#   3. the table-only fast path (--formats none) of Fig. 15: points per second
#      of wall time and per CPU second (user + system: per core), goal >= 10,000
#   4. peak memory (max RSS) of table-only sweeps of 1,000 / 10,000 / 100,000
#      points and of figure sweeps of 100 / 1,000 points: it must not grow with
#      the number of points (the table is streamed)
# Everything is written under a temporary directory.  Asserts nothing but that
# the runs work.  Needs /usr/bin/time (Debian package `time`).
# usage: bench_sweep.sh HYSTVIZ SCENES_DIR
set -u
hv=$1
scenes=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "bench_sweep: $*" >&2; exit 1; }
[ -x /usr/bin/time ] || fail "/usr/bin/time is missing (apt-get install time)"
fig15=$scenes/fig15_minor_loop_ex4.scene
fig11=$scenes/fig11_ygamma_ex3.scene
echo "sweep benchmark: $(getconf _NPROCESSORS_ONLN) online CPUs, load $(cut -d' ' -f1-3 /proc/loadavg)"

# run LABEL POINTS ARGS...: one timed sweep into $tmp/out; prints points/s
# (wall and per CPU second) and max RSS
run() {
    label=$1
    pts=$2
    shift 2
    rm -rf "$tmp/out"
    /usr/bin/time -f '%e %U %S %M' -o "$tmp/time" "$hv" sweep "$@" -o "$tmp/out" -q || fail "$label: sweep failed"
    rows=$(($(wc -l < "$tmp/out/sweep.csv") - 1))
    [ "$rows" -eq "$pts" ] || fail "$label: $rows rows, expected $pts"
    grep -q ',failed,\|,invalid,' "$tmp/out/sweep.csv" && fail "$label: a point failed"
    awk -v l="$label" -v n="$pts" '{ cpu = $2 + $3; printf "%-52s %8.2f s wall %9.0f points/s  %9.0f points/CPU-s  max RSS %6.1f MB\n",
        l, $1, n / ($1 > 0 ? $1 : 1e-9), n / (cpu > 0 ? cpu : 1e-9), $4 / 1024 }' "$tmp/time"
}

g15="$fig15 --grid model.sigma0=1:10:log40 --grid input.umin2=0.1:0.5:25"   # 40 x 25 = 1,000 points
g11="$fig11 --set compute.solver=rkf45 --grid model.sigma0=1:10:log40 --grid input.umin2=0.05:0.5:25"
run "Fig. 15, 1,000 points, svg+pdf+png, -j 1" 1000 $g15 -j 1
run "Fig. 15, 1,000 points, svg+pdf+png, -j 2" 1000 $g15 -j 2
run "Fig. 11 (rkf45), 1,000 points, svg+pdf+png, -j 1" 1000 $g11 -j 1
run "Fig. 11 (rkf45), 1,000 points, svg+pdf+png, -j 2" 1000 $g11 -j 2
run "Fig. 11 (rkf45), 1,000 points, table only, -j 1" 1000 $g11 -j 1 --formats none
for n in 1000 10000 100000; do
    run "Fig. 15, $n points, table only (--formats none), -j 1" $n "$fig15" --grid "model.sigma0=1:10:log$((n / 10))" \
        --grid input.umin2=0.1:0.5:10 --formats none -j 1
done
run "Fig. 15, 100,000 points, table only, -j 2" 100000 "$fig15" --grid model.sigma0=1:10:log10000 \
    --grid input.umin2=0.1:0.5:10 --formats none -j 2
run "Fig. 15, 100 points, svg+pdf+png, -j 1 (memory)" 100 "$fig15" --grid model.sigma0=1:10:log10 \
    --grid input.umin2=0.1:0.5:10 -j 1
