# SPDX-License-Identifier: MIT
# tests/serve/serve_lib.sh: `hystviz serve` in the serve shell tests (bash),
# sourced after tests/lib.sh:
#     . "$(dirname "$0")/serve_lib.sh"
#   serve_start CMD...  runs CMD (a `hystviz serve ... --port 0` command line,
#                       a prefix such as taskset allowed) in the background,
#                       its output in $tmp/serve.out and $tmp/serve.err, and
#                       waits at most 30 s for the URL serve prints: sets $srv
#                       (its pid), $port and $base.  A serve built without
#                       libmicrohttpd (exit 3 naming it): skip (77); no URL
#                       (serve exited, or printed none in time): fatal
#   serve_stop          SIGINT, then at most 60 s for serve to end (-9 past
#                       that); a sanitizer's report in serve.err is a failure
#   bg                  the pids of the test's background jobs (an array):
#                       killed on exit, as serve is
srv=
bg=()
serve_cleanup() {
    [ -n "$srv" ] && kill -9 "$srv" 2>/dev/null
    for p in "${bg[@]}"; do kill -9 "$p" 2>/dev/null; done
    lib_cleanup
}
trap serve_cleanup EXIT

serve_listening() { # whether serve printed its URL ($port set), or is gone
    port=$(sed -n 's|.*http://127.0.0.1:\([0-9]*\)/.*|\1|p' "$tmp/serve.out")
    [ -n "$port" ] || ! alive "$srv"
}

serve_start() {
    # emptied first: the job's own >file may come after a wait read the last run's URL
    : >"$tmp/serve.out"
    : >"$tmp/serve.err"
    "$@" >"$tmp/serve.out" 2>"$tmp/serve.err" &
    srv=$!
    port=
    wait_until 30 "URL printed by serve" serve_listening
    if [ -z "$port" ]; then
        kill -9 "$srv" 2>/dev/null # still running without a URL
        wait_pid "$srv" 10 "serve (SIGKILL)" 2>/dev/null
        _rc=$?
        srv=
        [ $_rc -eq 3 ] && grep -q "libmicrohttpd" "$tmp/serve.err" && skip "built without libmicrohttpd"
        fatal "serve printed no URL (exit $_rc): $(cat "$tmp/serve.err")"
    fi
    base="http://127.0.0.1:$port"
}

serve_stop() {
    [ -n "$srv" ] || return 0
    kill -INT "$srv" 2>/dev/null
    wait_pid "$srv" 60 "serve after SIGINT (LeakSanitizer scans the heap at exit)"
    srv=
    ! grep -E -A12 "ERROR: (Address|Leak)Sanitizer|runtime error" "$tmp/serve.err" || bad "serve: sanitizer report above"
}
