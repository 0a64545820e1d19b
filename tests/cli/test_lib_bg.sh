#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/cli/test_lib_bg.sh: tests/lib.sh's bg_track.  A test sourcing lib.sh
# starts two background processes (one with a child of its own) and tracks
# them, and also tracks a pid that is not its child (this test's own sleep).
# Ended mid-way, by a fatal check or by SIGTERM while it waits, its exit trap
# kills its processes and their children, leaves the stranger alone, and
# removes its $tmp.  (meson's timeout signals the test's whole process group;
# what bg_track adds is the test that stops early, and processes that left
# the group.)
set -u
. "$(dirname "$0")/../lib.sh"
here=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$tmp/t/x" "$tmp/t/lib"
cp "$here/lib.sh" "$tmp/t/lib.sh"
cp "$here/lib/wait.sh" "$tmp/t/lib/wait.sh"
# inner.sh STRANGER PIDFILE HOW: HOW is fatal (a failed check ends it) or
# term (it waits, and is sent SIGTERM)
cat >"$tmp/t/x/inner.sh" <<'INNER'
set -u
. "$(dirname "$0")/../lib.sh"
sleep 300 &
a=$!
sh -c 'sleep 300 & echo $! >"$1"; wait' sh "$tmp/grandchild" &
b=$!
bg_track $a $b "$1"
wait_until 30 "the grandchild's pid" test -s "$tmp/grandchild" || exit 3
echo "$a $b $(cat "$tmp/grandchild") $tmp" >"$2.part" && mv "$2.part" "$2"
[ "$3" = fatal ] && fatal "a check the rest cannot go on without"
wait $a
INNER
sleep 300 &
stranger=$!
bg_track $stranger
for how in fatal term; do
    rm -f "$tmp/pids"
    mkdir "$tmp/$how"
    TMPDIR="$tmp/$how" sh "$tmp/t/x/inner.sh" "$stranger" "$tmp/pids" $how >"$tmp/$how.out" 2>&1 &
    inner=$!
    bg_track $inner
    wait_until 30 "the inner test's ($how) background processes" test -s "$tmp/pids" || { cat "$tmp/$how.out"; fatal "the inner test ($how) did not start"; }
    read -r a b g itmp <"$tmp/pids"
    [ $how = term ] && kill -TERM $inner
    wait_pid $inner 30 "the inner test ($how)" >/dev/null
    gone() { ! alive $a && ! alive $b && ! alive $g; }
    wait_until 10 "end of the tracked processes ($how)" gone &&
        ok "$how: the tracked processes and a child of theirs were killed by the exit trap" ||
        bad "$how: left running:$(alive $a && echo " $a")$(alive $b && echo " $b")$(alive $g && echo " $g (grandchild)")"
    alive $stranger && ok "$how: a tracked pid that is not the test's child was left alone" ||
        bad "$how: the exit trap killed a process that was not its child"
    [ ! -e "$itmp" ] && ok "$how: the inner test's \$tmp was removed" || bad "$how: the inner test's \$tmp is still there"
done
kill $stranger 2>/dev/null
wait $stranger 2>/dev/null
finish lib_bg
