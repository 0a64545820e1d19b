#!/bin/sh
# SPDX-License-Identifier: MIT
# Benchmark of `hystviz sweep` (issues 13, 23), whole processes:
#   1. a 1,000-point sweep of Fig. 15 (analytic: closed forms) with its figures
#      (the scene's formats: SVG, PDF, PNG) at -j 1 and -j 2: points per second
#   2. the same for Fig. 11 with compute.solver = rkf45 (GSL odeiv2, three y_γ
#      solves per point)
#   3. the table-only fast path (--formats none) of Fig. 15 from 1,000 to
#      1,000,000 points: points per second of wall time and per CPU second
#      (user + system: per core), goal >= 100,000 per CPU second; peak memory
#      (max RSS) must not grow with the number of points (the table is streamed)
#   4. paired with the NumPy yardstick (tests/bench/np_sweep.py, the same
#      closed form and scalars in a Python loop, checked against hystviz's
#      table first): ROUNDS alternating runs of the issue's 10,000-point grid,
#      medians and the ratio hystviz / NumPy (goal < 0.25)
# Rows are printed as docs/PERFORMANCE.md's table rows (its "Parameter
# studies" section), in its units; `bench_sweep.sh --rows` prints the rows'
# labels only, without running anything: tests/cli/test_readme_bench.sh checks
# that docs/PERFORMANCE.md's table has exactly these rows, in this order.
# Everything is written under a temporary directory.  Asserts nothing but that
# the runs work.  Needs /usr/bin/time (Debian `time`) and python3-numpy.
# usage: bench_sweep.sh HYSTVIZ SCENES_DIR [ROUNDS] | bench_sweep.sh --rows
set -u
labels_only=0
if [ "${1:-}" = "--rows" ]; then
    labels_only=1
else
    hv=$1
    scenes=$2
    rounds=${3:-5}
    tmp=$(mktemp -d)
    trap 'rm -rf "$tmp"' EXIT
fi
fail() { echo "bench_sweep: $*" >&2; exit 1; }
here=$(dirname "$0")
load() { cut -d' ' -f1-3 /proc/loadavg; }
# 1234567.8 -> 1,234,568
commas='function c(x,  s, r) { s = sprintf("%.0f", x); r = ""; while (length(s) > 3) { r = "," substr(s, length(s) - 2) r; s = substr(s, 1, length(s) - 3) } return s r }'

if [ $labels_only = 0 ]; then
    [ -x /usr/bin/time ] || fail "/usr/bin/time is missing (apt-get install time)"
    fig15=$scenes/fig15_minor_loop_ex4.scene
    fig11=$scenes/fig11_ygamma_ex3.scene
    echo "sweep benchmark: $(getconf _NPROCESSORS_ONLN) online CPUs, load $(load)"
    echo
    echo "| sweep | wall | points/s | points per CPU second | max RSS |"
    echo "|---|---|---|---|---|"
fi

# run LABEL POINTS ARGS...: one timed sweep into $tmp/out, printed as a docs/PERFORMANCE.md
# table row (with --rows: the label only).  BENCH_SWEEP_FROM=N runs only the
# rows from the Nth on (the 1,000-point figure sweeps, rows 1-4, take minutes
# on a loaded machine).
nrow=0
run() {
    label=$1
    pts=$2
    shift 2
    nrow=$((nrow + 1))
    if [ $labels_only = 1 ]; then
        echo "$label"
        return
    fi
    [ "$nrow" -ge "${BENCH_SWEEP_FROM:-1}" ] || return 0
    rm -rf "$tmp/out"
    /usr/bin/time -f '%e %U %S %M' -o "$tmp/time" "$hv" sweep "$@" -o "$tmp/out" -q || fail "$label: sweep failed"
    rows=$(($(wc -l < "$tmp/out/sweep.csv") - 1))
    [ "$rows" -eq "$pts" ] || fail "$label: $rows rows, expected $pts"
    grep -q ',failed,\|,invalid,' "$tmp/out/sweep.csv" && fail "$label: a point failed"
    awk -v l="$label" -v n="$pts" "$commas"'{ cpu = $2 + $3; printf "| %s | %.2f s | %s | %s | %.1f MB |\n",
        l, $1, c(n / ($1 > 0 ? $1 : 0.005)), c(n / (cpu > 0 ? cpu : 0.005)), $4 / 1024 }' "$tmp/time"
}

g15="--grid model.sigma0=1:10:log40 --grid input.umin2=0.1:0.5:25"   # 40 x 25 = 1,000 points
g11="--set compute.solver=rkf45 --grid model.sigma0=1:10:log40 --grid input.umin2=0.05:0.5:25"
run "Fig. 15 (analytic), 1,000 points, SVG+PDF+PNG, \`-j 1\`" 1000 "${fig15:-}" $g15 -j 1
run "the same, \`-j 2\`" 1000 "${fig15:-}" $g15 -j 2
run "Fig. 11 with \`compute.solver=rkf45\` (GSL, 3 solves a point), 1,000 points, SVG+PDF+PNG, \`-j 1\`" 1000 "${fig11:-}" $g11 -j 1
run "the same, \`-j 2\`" 1000 "${fig11:-}" $g11 -j 2
run "Fig. 11 rkf45, 1,000 points, table only" 1000 "${fig11:-}" $g11 -j 1 --formats none
run "Fig. 15, 100 points, SVG+PDF+PNG, \`-j 1\` (memory)" 100 "${fig15:-}" --grid model.sigma0=1:10:log10 \
    --grid input.umin2=0.1:0.5:10 -j 1
for n in 1000 10000 100000 1000000; do
    run "Fig. 15, table only (\`--formats none\`), $(echo $n | awk "$commas"'{ print c($1) }') points, \`-j 1\`" $n \
        "${fig15:-}" --grid "model.sigma0=1:100:log$((n / 50))" --grid input.umin2=0.1:0.5:50 --formats none -j 1
done
run "… 1,000,000 points, \`-j 2\`" 1000000 "${fig15:-}" --grid model.sigma0=1:100:log20000 \
    --grid input.umin2=0.1:0.5:50 --formats none -j 2

# ---- paired with the NumPy loop --------------------------------------------
# the issue's grid: 200 x 50 = 10,000 points
np_label="Fig. 15, table only, 10,000 points, \`-j 1\`, against a NumPy loop (median of alternating runs)"
# ---- issue 37: table only at 1e4, 1e5, 1e6 points, CSV and .npy, paired ----
# One round is, in turn: hystviz CSV, hystviz .npy, NumPy vectorised CSV
# (np.savetxt) and .npy (np.save), the Python loop CSV (np_sweep.py), all whole
# processes under /usr/bin/time (Python's start and NumPy's import, about
# 0.1 s, included: what a user pays); PAIR_ROUNDS rounds (default 3; 1 at
# 1e6 points, where the loop alone takes 15 s or more), medians.
# BENCH_SWEEP_RAW=FILE appends every run's "KIND POINTS wall user sys maxrss_kB load ..." to FILE.
kinds="hv-csv hv-npy vec-csv vec-npy loop-csv"
kind_label() {
    case $1 in
    hv-csv) echo "CSV: hystviz \`-j 1\`" ;;
    hv-npy) echo ".npy: hystviz \`--table npy\`, \`-j 1\`" ;;
    vec-csv) echo "CSV: NumPy vectorised over the grid (\`np.savetxt\` %.17g)" ;;
    vec-npy) echo ".npy: NumPy vectorised over the grid (\`np.save\`)" ;;
    loop-csv) echo "CSV: Python loop (\`np_sweep.py\`)" ;;
    esac
}
pair_label() { echo "Fig. 15 table only, $(echo $2 | awk "$commas"'{ print c($1) }') points, $(kind_label $1)"; }
if [ $labels_only = 1 ]; then
    echo "$np_label"
    for n in 10000 100000 1000000; do for k in $kinds; do pair_label $k $n; done; done
    exit 0
fi
/usr/bin/python3 -c 'import numpy' 2> /dev/null || fail "python3-numpy is missing (apt-get install python3-numpy)"
grid="--grid model.sigma0=1:100:log200 --grid input.umin2=0.1:0.5:50"
"$hv" sweep "$fig15" $grid --formats none -o "$tmp/hv" -q -j 1 || fail "the NumPy grid: sweep failed"
/usr/bin/python3 "$here/np_sweep.py" 1 100 200 0.1 0.5 50 "$tmp/np.csv" "$tmp/hv/sweep.csv" > "$tmp/check1" ||
    fail "np_sweep: $(cat "$tmp/check1")"
: > "$tmp/pairs"
r=0
while [ $r -lt "$rounds" ]; do # alternating: hystviz, NumPy, hystviz, ...
    /usr/bin/time -f '%e %U %S' -o "$tmp/time" "$hv" sweep "$fig15" $grid --formats none -o "$tmp/hv" -q -j 1 ||
        fail "sweep failed"
    /usr/bin/python3 "$here/np_sweep.py" 1 100 200 0.1 0.5 50 "$tmp/np.csv" > "$tmp/np" || fail "np_sweep failed"
    echo "$(cat "$tmp/time") $(awk '{ print $4, $7 }' "$tmp/np") $(load)" >> "$tmp/pairs"
    r=$((r + 1))
done
# columns: hv wall, user, sys, np wall, np cpu, load1, load5, load15
awk -v l="$np_label" "$commas"'
    function med(a, n,  i, j, t) { for (i = 1; i <= n; i++) for (j = i + 1; j <= n; j++) if (a[j] < a[i]) { t = a[i]; a[i] = a[j]; a[j] = t }
                                    return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2 }
    { n++; hw[n] = $1; hc[n] = $2 + $3; nw[n] = $4; nc[n] = $5; rw[n] = $1 / $4; rc[n] = ($2 + $3) / $5; ld = ld " " $6 }
    END { w = med(hw, n); cpu = med(hc, n); printf "| %s | %.3f s | %s | %s | (NumPy loop %.3f s wall, %.3f s CPU; ratio hystviz/NumPy %.2f wall, %.2f CPU) |\n",
              l, w, c(10000 / w), c(10000 / cpu), med(nw, n), med(nc, n), med(rw, n), med(rc, n)
          printf "\n%d alternating pairs; load (1 min) at each: %s\n", n, ld > "/dev/stderr" }' "$tmp/pairs" 2> "$tmp/pairs.txt"

one() { # one KIND N: a timed run, "KIND N wall user sys rss" into $tmp/pt
    ns=$(($2 / 50))
    g="--grid model.sigma0=1:100:log$ns --grid input.umin2=0.1:0.5:50"
    rm -rf "$tmp/p"
    case $1 in
    hv-csv) set -- "$1" "$2" "$hv" sweep "$fig15" $g --formats none -o "$tmp/p" -q -j 1 ;;
    hv-npy) set -- "$1" "$2" "$hv" sweep "$fig15" $g --formats none -o "$tmp/p" -q -j 1 --table npy ;;
    vec-csv) set -- "$1" "$2" /usr/bin/python3 "$here/np_sweep.py" --vector csv 1 100 $ns 0.1 0.5 50 "$tmp/p.out" ;;
    vec-npy) set -- "$1" "$2" /usr/bin/python3 "$here/np_sweep.py" --vector npy 1 100 $ns 0.1 0.5 50 "$tmp/p.out" ;;
    loop-csv) set -- "$1" "$2" /usr/bin/python3 "$here/np_sweep.py" 1 100 $ns 0.1 0.5 50 "$tmp/p.out" ;;
    esac
    k=$1
    n=$2
    shift 2
    /usr/bin/time -f '%e %U %S %M' -o "$tmp/time" "$@" > /dev/null || fail "$k at $n points failed"
    echo "$k $n $(cat "$tmp/time")" >> "$tmp/pt"
    [ -z "${BENCH_SWEEP_RAW:-}" ] || echo "$k $n $(cat "$tmp/time") load $(load)" >> "$BENCH_SWEEP_RAW"
}
"$hv" sweep "$fig15" --grid model.sigma0=1:100:log200 --grid input.umin2=0.1:0.5:50 --formats none -o "$tmp/hv" -q -j 1 ||
    fail "sweep failed"
/usr/bin/python3 "$here/np_sweep.py" --vector csv 1 100 200 0.1 0.5 50 "$tmp/v.csv" "$tmp/hv/sweep.csv" > "$tmp/check" ||
    fail "np_sweep --vector: $(cat "$tmp/check")"
cat "$tmp/check" >> "$tmp/check1"
: > "$tmp/pt"
l0=$(load)
for n in 10000 100000 1000000; do
    rr=${PAIR_ROUNDS:-3}
    [ $n -lt 1000000 ] || rr=1
    r=0
    while [ $r -lt $rr ]; do
        for k in $kinds; do one $k $n; done
        r=$((r + 1))
    done
done
for n in 10000 100000 1000000; do
    for k in $kinds; do
        awk -v k=$k -v n=$n -v l="$(pair_label $k $n)" "$commas"'
            function med(a, m,  i, j, t) { for (i = 1; i <= m; i++) for (j = i + 1; j <= m; j++) if (a[j] < a[i]) { t = a[i]; a[i] = a[j]; a[j] = t }
                                            return m % 2 ? a[(m + 1) / 2] : (a[m / 2] + a[m / 2 + 1]) / 2 }
            $1 == k && $2 == n { m++; aw[m] = $3; ac[m] = $4 + $5; ar[m] = $6 }
            END { W = med(aw, m); C = med(ac, m); R = med(ar, m)
                  printf "| %s | %.2f s | %s | %s | %.1f MB |\n", l, W, c(n / (W > 0 ? W : 0.005)), c(n / (C > 0 ? C : 0.005)), R / 1024 }' "$tmp/pt"
    done
done
echo
cat "$tmp/pairs.txt"
echo "issue 37 rows: ${PAIR_ROUNDS:-3} alternating rounds (1 at 1,000,000 points), medians, whole processes; load (1, 5, 15 min) before: $l0, after: $(load)"
cat "$tmp/check1"
