#!/bin/sh
# SPDX-License-Identifier: MIT
# The README's sweep speed table is the benchmark's output (issue 23 item 5):
# its rows are exactly those tests/bench/bench_sweep.sh prints, in its order
# (`bench_sweep.sh --rows` gives the labels without running anything), and
# every row has the benchmark's format: wall in s, points/s and points per CPU
# second as whole numbers with thousands commas, max RSS in MB (or, for the
# NumPy pairing, the yardstick's figures in parentheses).  Values are not
# compared: they are measured by `sh tools/setup.sh bench` and copied.
# usage: test_readme_bench.sh SOURCE_ROOT
set -u
root=$1
pass=0
fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

sh "$root/tests/bench/bench_sweep.sh" --rows > "$tmp/want" || bad "bench_sweep.sh --rows failed"
[ "$(wc -l < "$tmp/want")" -ge 10 ] && ok || bad "bench_sweep.sh --rows printed $(wc -l < "$tmp/want") rows"
# the README's table: from its header row to the first line that is not a row
awk '/^\| sweep \| wall \| points\/s \| points per CPU second \| max RSS \|$/ { on = 1; next }
     on && /^\|---/ { next }
     on && /^\|/ { print; next }
     on { exit }' "$root/README.md" > "$tmp/rows"
[ -s "$tmp/rows" ] && ok || bad "README.md has no '| sweep | wall | points/s | points per CPU second | max RSS |' table"
sed 's/^| \(.*\) | [^|]* | [^|]* | [^|]* | [^|]* |$/\1/' "$tmp/rows" > "$tmp/have"
if cmp -s "$tmp/want" "$tmp/have"; then ok; else
    bad "README's sweep table rows differ from bench_sweep.sh's (< benchmark, > README):"
    diff "$tmp/want" "$tmp/have" | grep '^[<>]'
fi
n=0
while IFS= read -r row; do
    n=$((n + 1))
    echo "$row" | grep -Eq '^\| .+ \| [0-9]+\.[0-9]+ s \| [0-9]{1,3}(,[0-9]{3})* \| [0-9]{1,3}(,[0-9]{3})* \| ([0-9]+\.[0-9] MB|\(NumPy loop [0-9.]+ s wall, [0-9.]+ s CPU; ratio hystviz/NumPy [0-9.]+ wall, [0-9.]+ CPU\)) \|$' &&
        ok || bad "README row $n is not in the benchmark's format: $row"
done < "$tmp/rows"
# the text that quotes the table names the command that made it
grep -q 'sh tools/setup.sh bench' "$root/README.md" && ok || bad "README does not name sh tools/setup.sh bench"
echo "test_readme_bench: $pass passed, $fail failed"
[ $fail -eq 0 ]
