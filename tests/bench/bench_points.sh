#!/bin/sh
# SPDX-License-Identifier: MIT
# Large series (issue 23 item 2): Fig. 15 to SVG + PDF + PNG (300 dpi) in one
# process, with compute.points = N (N points on the minor loop, 2N on the
# major) for N = 1e3 .. 1e6, hystviz and matplotlib (tests/bench/mpl_points.py,
# the same loop from its closed form) paired and alternating: wall time
# (median of the runs), CPU time (user + system, median) and peak memory
# (/usr/bin/time, max RSS), the files' sizes, the machine's load.  Prints a
# Markdown table, docs/PERFORMANCE.md's (tests/cli/test_readme_bench.sh checks its
# rows and format); asserts nothing but that the runs work.
# Goals: 1e6 points in <= 0.25 s and <= 48 MB, files no larger than at 1e4.
# usage: bench_points.sh HYSTVIZ SCENES_DIR [RUNS]
#        bench_points.sh --rows   (the table's header and first cells, nothing run)
set -u
header() {
    echo "| N (minor loop points) | hystviz wall | hystviz CPU | hystviz max RSS | hystviz SVG / PDF / PNG | matplotlib wall | matplotlib CPU | matplotlib max RSS | matplotlib SVG / PDF / PNG |"
    echo "|---|---|---|---|---|---|---|---|---|"
}
sizes_n="1000 10000 100000 1000000"
if [ "${1:-}" = --rows ]; then
    header
    for n in $sizes_n; do echo "| $n |"; done
    exit 0
fi
hv=$1
scenes=$2
runs=${3:-5}
here=$(dirname "$0")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "bench_points: $*" >&2; exit 1; }
[ -x /usr/bin/time ] || fail "needs /usr/bin/time (Debian: time)"
mpl=0
/usr/bin/python3 -c "import matplotlib, numpy" 2>/dev/null && mpl=1

# one timed process: appends "seconds kB cpu-seconds" to FILE
timed() {
    f=$1
    shift
    /usr/bin/time -f "%e %M %U %S" -o "$tmp/t" "$@" > /dev/null 2> "$tmp/err" || { cat "$tmp/err"; fail "$* failed"; }
    awk '{ print $1, $2, $3 + $4 }' "$tmp/t" >> "$f"
}
# medians of columns 1 and 3, largest column 2 of FILE: "s | s | MB"
med() {
    awk '{ print $3 }' "$1" | sort -n > "$1.cpu"
    sort -n "$1" | awk -v cf="$1.cpu" '{ v[NR] = $1; if ($2 > m) m = $2 }
        END { n = 0; while ((getline c < cf) > 0) u[++n] = c
              printf "%.3f s | %.3f s | %.1f MB", v[int((NR + 1) / 2)], u[int((n + 1) / 2)], m / 1024 }'
}
sizes() { printf '%s / %s / %s kB' "$(($(wc -c < "$1.svg") / 1000))" "$(($(wc -c < "$1.pdf") / 1000))" "$(($(wc -c < "$1.png") / 1000))"; }

echo "bench-points: load average at start $(cut -d' ' -f1-3 /proc/loadavg), $runs runs each, alternating"
header
for n in $sizes_n; do
    : > "$tmp/h" && : > "$tmp/m"
    for r in $(seq "$runs"); do
        timed "$tmp/h" "$hv" render "$scenes/fig15_minor_loop_ex4.scene" --set compute.points=$n \
            --format svg,pdf,png -o "$tmp/h$n"
        [ $mpl -eq 1 ] && timed "$tmp/m" /usr/bin/python3 "$here/mpl_points.py" $n "$tmp/m$n"
    done
    row="| $n | $(med "$tmp/h") | $(sizes "$tmp/h$n/fig15_minor_loop_ex4")"
    if [ $mpl -eq 1 ]; then
        row="$row | $(med "$tmp/m") | $(sizes "$tmp/m$n/fig15")"
    else
        row="$row | (matplotlib missing) | | | "
    fi
    echo "$row |"
done
echo "bench-points: load average at end $(cut -d' ' -f1-3 /proc/loadavg)"
