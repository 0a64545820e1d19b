# SPDX-License-Identifier: MIT
# tests/lib.sh: the shell tests' vocabulary (sh and bash), sourced after set -u:
#     . "$(dirname "$0")/../lib.sh"
#   ok [WHAT]       counts a passed check (prints "ok: WHAT" when given)
#   bad WHAT        counts a failed check and prints "FAIL: WHAT"
#   finish NAME     prints "NAME: P passed, F failed"; its status is the test's
#                   (0 when no check failed): the test's last line
#   fatal WHAT      a failed check the rest cannot go on without: counts it,
#                   prints "FAIL: WHAT" and the summary (NAME: the script's
#                   name without .sh) and ends the test with status 1
#   skip WHY        ends the test as skipped: "SKIP: WHY", status 77 (meson's)
#   need CMD...     skip unless every CMD is installed (names the first missing)
#   $tmp            the test's own directory, $TMPDIR/TESTNAME.XXXXXX, removed
#                   with everything in it when the test exits, also when meson's
#                   timeout stops it (SIGTERM); nothing else is the test's
#   wait_pid PID SECONDS WHAT, wait_until SECONDS WHAT COMMAND..., alive PID:
#                   bounded waits (tests/lib/wait.sh): every wait has a deadline
#   bg_track PID... background processes the test started: lib_cleanup kills
#                   each (and its children) when the test exits, also when
#                   meson's timeout stops it mid-way; one already reaped, or
#                   whose pid now belongs to another process (not this shell's
#                   child), is left alone
# (A test may instead replace the EXIT trap with one that kills its
# background processes and then runs lib_cleanup.)
pass=0
fail=0
ok() {
    pass=$((pass + 1))
    [ $# -eq 0 ] || echo "ok: $*"
}
bad() {
    fail=$((fail + 1))
    echo "FAIL: $*"
}
finish() {
    echo "$1: $pass passed, $fail failed"
    [ "$fail" -eq 0 ]
}
fatal() {
    bad "$*"
    finish "$(basename "$0" .sh)"
    exit 1
}
skip() {
    echo "SKIP: $*"
    exit 77
}
need() {
    for _cmd in "$@"; do
        command -v "$_cmd" >/dev/null || skip "$_cmd is not installed"
    done
}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/$(basename "$0" .sh).XXXXXX") || {
    echo "FAIL: cannot make a temporary directory under ${TMPDIR:-/tmp}"
    exit 1
}
lib_bg=""
bg_track() { lib_bg="$lib_bg $*"; }
lib_cleanup() {
    for _p in $lib_bg; do
        # still this shell's child (field 4 of /proc/PID/stat, after the name)?
        [ "$(sed -n 's/^[0-9]* (.*) [A-Za-z] \([0-9]*\) .*/\1/p' "/proc/$_p/stat" 2>/dev/null)" = "$$" ] || continue
        pkill -KILL -P "$_p" 2>/dev/null
        kill -KILL "$_p" 2>/dev/null
    done
    rm -rf "$tmp"
}
trap lib_cleanup EXIT
trap 'exit 1' INT TERM # (the EXIT trap runs also when meson's timeout stops the test)
. "$(dirname "$0")/../lib/wait.sh"
