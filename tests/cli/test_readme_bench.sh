#!/bin/sh
# SPDX-License-Identifier: MIT
# docs/PERFORMANCE.md's sweep speed table is the benchmark's output (issue 23 item 5):
# its rows are exactly those tests/bench/bench_sweep.sh prints, in its order
# (`bench_sweep.sh --rows` gives the labels without running anything), and
# every row has the benchmark's format: wall in s, points/s and points per CPU
# second as whole numbers with thousands commas, max RSS in MB (or, for the
# NumPy pairing, the yardstick's figures in parentheses).  The same for the
# large-series table of tests/bench/bench_points.sh (its header line, its N
# in order, wall and CPU in s with 3 decimals, max RSS in MB, the three
# files' sizes in kB).  Values are not compared: they are measured by
# `sh tools/setup.sh bench` and copied.
# The serve tables likewise: tests/bench/bench_serve.c's (warm process) and
# tests/serve/browser_test.py --bench's (chromium).  tests/bench/bench_pysweep.py's
# (hystviz.sweep against vectorised NumPy) likewise.
# Speed figures quoted in README.md and in every command's --help (issue 37
# item 4): each line that states one (the pattern `speed` below: µs, ms, s of
# CPU / wall / in all, N x the time, points/s, points per CPU second, kB a
# frame, about N s, a range of seconds) names its benchmark as "[bench NAME]";
# NAME is a benchmark of tests/bench/meson.build (run by `sh tools/setup.sh
# bench`) and docs/PERFORMANCE.md's "Figures quoted" table has its row
# ("| `[bench NAME]` | ...": what it prints, the last recorded run); every
# row of that table is quoted somewhere.
# usage: test_readme_bench.sh SOURCE_ROOT BENCH_SERVE HYSTVIZ
set -u
root=$1
bench_serve=$2
hv=$3
. "$(dirname "$0")/../lib.sh"

sh "$root/tests/bench/bench_sweep.sh" --rows > "$tmp/want" || bad "bench_sweep.sh --rows failed"
[ "$(wc -l < "$tmp/want")" -ge 10 ] && ok || bad "bench_sweep.sh --rows printed $(wc -l < "$tmp/want") rows"
# the docs/PERFORMANCE.md's table: from its header row to the first line that is not a row
awk '/^\| sweep \| wall \| points\/s \| points per CPU second \| max RSS \|$/ { on = 1; next }
     on && /^\|---/ { next }
     on && /^\|/ { print; next }
     on { exit }' "$root/docs/PERFORMANCE.md" > "$tmp/rows"
[ -s "$tmp/rows" ] && ok || bad "docs/PERFORMANCE.md has no '| sweep | wall | points/s | points per CPU second | max RSS |' table"
sed 's/^| \(.*\) | [^|]* | [^|]* | [^|]* | [^|]* |$/\1/' "$tmp/rows" > "$tmp/have"
if cmp -s "$tmp/want" "$tmp/have"; then ok; else
    bad "docs/PERFORMANCE.md's sweep table rows differ from bench_sweep.sh's (< benchmark, > docs/PERFORMANCE.md):"
    diff "$tmp/want" "$tmp/have" | grep '^[<>]'
fi
n=0
while IFS= read -r row; do
    n=$((n + 1))
    echo "$row" | grep -Eq '^\| .+ \| [0-9]+\.[0-9]+ s \| [0-9]{1,3}(,[0-9]{3})* \| [0-9]{1,3}(,[0-9]{3})* \| ([0-9]+\.[0-9] MB|\(NumPy loop [0-9.]+ s wall, [0-9.]+ s CPU; ratio hystviz/NumPy [0-9.]+ wall, [0-9.]+ CPU\)) \|$' &&
        ok || bad "docs/PERFORMANCE.md row $n is not in the benchmark's format: $row"
done < "$tmp/rows"
# a table of another benchmark: WANT (its --rows output: header, separator,
# first cells) against the docs/PERFORMANCE.md's table that starts at the same header;
# each row's other cells must match the extended regex REST
table() {
    name=$1 want=$2 rest=$3
    head -n 1 "$want" > "$tmp/head"
    awk -v h="$(cat "$tmp/head")" '$0 == h { on = 1; print; next }
         on && /^\|/ { print; next }
         on { exit }' "$root/docs/PERFORMANCE.md" > "$tmp/rows"
    [ -s "$tmp/rows" ] && ok || { bad "docs/PERFORMANCE.md has no $name table headed: $(cat "$tmp/head")"; return; }
    { sed 2q "$tmp/rows"; sed -n '3,$s/^\(| [^|]* |\).*$/\1/p' "$tmp/rows"; } > "$tmp/have"
    if cmp -s "$want" "$tmp/have"; then ok; else
        bad "docs/PERFORMANCE.md's $name table (header, separator, first cells) differs from the benchmark's (< benchmark, > docs/PERFORMANCE.md):"
        diff "$want" "$tmp/have" | grep '^[<>]'
    fi
    sed 1,2d "$tmp/rows" | while IFS= read -r row; do
        echo "$row" | grep -Eq "^\| [^|]+ \| $rest \|\$" || echo "$row"
    done > "$tmp/bad"
    [ -s "$tmp/bad" ] && bad "docs/PERFORMANCE.md $name rows not in the benchmark's format: $(cat "$tmp/bad")" || ok
}
# large series: wall and CPU in s with 3 decimals, max RSS in MB, the files in kB
cell='[0-9]+\.[0-9]{3} s \| [0-9]+\.[0-9]{3} s \| [0-9]+\.[0-9] MB \| [0-9]+ / [0-9]+ / [0-9]+ kB'
sh "$root/tests/bench/bench_points.sh" --rows > "$tmp/points" || bad "bench_points.sh --rows failed"
table large-series "$tmp/points" "$cell \| ($cell|\(matplotlib missing\) \| \| \| )"
# serve, warm process: ms with 2 decimals, the load with 1
"$bench_serve" --rows > "$tmp/serve" || bad "bench_serve --rows failed"
table serve "$tmp/serve" '[0-9]+\.[0-9]{2} / [0-9]+\.[0-9]{2} ms \(min [0-9]+\.[0-9]{2}\) \| [0-9]+\.[0-9]{2} ms \| [0-9]+\.[0-9]'
# serve in chromium: ms with 1 decimal
python3 "$root/tests/serve/browser_test.py" --rows > "$tmp/browser" || bad "browser_test.py --rows failed"
table serve-browser "$tmp/browser" '[0-9]+\.[0-9] / [0-9]+\.[0-9] ms \| [0-9]+\.[0-9] / [0-9]+\.[0-9] ms \| [0-9]+\.[0-9] / [0-9]+\.[0-9] ms \| [0-9]+\.[0-9]'
# the matplotlib yardstick of serve (tests/bench/mpl_fig15.py): ms with 1 decimal, the SVG in bytes
python3 "$root/tests/bench/mpl_fig15.py" --rows > "$tmp/mpl" || bad "mpl_fig15.py --rows failed"
table serve-yardstick "$tmp/mpl" '[0-9]+\.[0-9] / [0-9]+\.[0-9] ms \| [0-9]+\.[0-9] / [0-9]+\.[0-9] ms \| [0-9]+ bytes \| [0-9]+\.[0-9]'
# hystviz.sweep against NumPy (tests/bench/bench_pysweep.py): s with 3 decimals, rates with commas, a ratio
/usr/bin/python3 "$root/tests/bench/bench_pysweep.py" --rows > "$tmp/pysweep" || bad "bench_pysweep.py --rows failed"
table sweep-python "$tmp/pysweep" '[0-9]+\.[0-9]{3} s \| [0-9]{1,3}(,[0-9]{3})* \| [0-9]{1,3}(,[0-9]{3})* \| [0-9]+\.[0-9]{2}'
# speed figures of README.md and --help: each names its benchmark row
speed='[0-9][0-9.,]* ?(µs|ms)([^A-Za-z]|$)|[0-9][0-9.,]* ?s (of CPU|wall|in all|a frame|per)|[0-9][0-9.,]* ?(x|×) (the|faster|slower)|points/s|points per (CPU )?second|kB a frame|about [0-9][0-9.,]* ?s([^A-Za-z]|$)|[0-9][0-9.,]*–[0-9][0-9.,]* ?s([^A-Za-z]|$)'
for s in "100,000–102,000 points per CPU second" "the clip in 0.59–0.68 s" "75 kB a frame" "3.8–4.0 µs per Python call" \
    "about 30 s of CPU" "3x the time"; do # the pattern catches the figures issue 37 found stale
    echo "$s" | grep -Eq "$speed" && ok || bad "the speed-figure pattern misses '$s'"
done
cp "$root/README.md" "$tmp/quoting"
cmds=$("$hv" --help | awk '/^commands:/ { on = 1; next } on && /^  [a-z]/ { print $1 } on && /^$/ { exit }')
[ -n "$cmds" ] && ok || bad "hystviz --help lists no commands"
for c in $cmds; do
    "$hv" "$c" --help > "$tmp/help" 2>&1 || bad "hystviz $c --help failed"
    sed "s/^/hystviz $c --help: /" "$tmp/help" >> "$tmp/quoting"
done
grep -E "$speed" "$tmp/quoting" > "$tmp/figures"
[ -s "$tmp/figures" ] && ok || bad "no speed figure found in README.md or --help (the pattern is broken?)"
while IFS= read -r line; do
    names=$(echo "$line" | grep -o '\[bench [A-Za-z0-9_-]*\]' | sed 's/^\[bench \(.*\)\]$/\1/')
    [ -n "$names" ] && ok || { bad "a speed figure names no benchmark ([bench NAME]): $line"; continue; }
    for n in $names; do
        grep -q "^ *benchmark('$n'" "$root/tests/bench/meson.build" && ok ||
            bad "[bench $n]: no benchmark '$n' in tests/bench/meson.build: $line"
        grep -q "^| \`\[bench $n\]\` |" "$root/docs/PERFORMANCE.md" && ok ||
            bad "[bench $n]: docs/PERFORMANCE.md's 'Figures quoted' table has no row | \`[bench $n]\` |: $line"
    done
done < "$tmp/figures"
grep -o '^| `\[bench [A-Za-z0-9_-]*\]` |' "$root/docs/PERFORMANCE.md" | sed 's/^| `\(.*\)` |$/\1/' | sort -u > "$tmp/rowsq"
[ -s "$tmp/rowsq" ] && ok || bad "docs/PERFORMANCE.md has no 'Figures quoted' rows"
while IFS= read -r q; do
    grep -qF "$q" "$tmp/figures" && ok || bad "docs/PERFORMANCE.md quotes $q, which README.md and --help no longer state"
done < "$tmp/rowsq"
# the text that quotes the table names the command that made it
grep -q 'sh tools/setup.sh bench' "$root/docs/PERFORMANCE.md" && ok || bad "docs/PERFORMANCE.md does not name sh tools/setup.sh bench"
finish "test_readme_bench"
