# SPDX-License-Identifier: MIT
# tests/lib/wait.sh: bounded waits for the shell tests (sh and bash), sourced:
#     . "$(dirname "$0")/../lib/wait.sh"
# Every wait of a test has a deadline and says what it waited for.

# alive PID: whether process PID runs (a zombie, or one reaped while we look,
# does not; kill -0 would count a zombie)
alive() {
    _st=$(sed -n 's/^[0-9]* (.*) \([A-Za-z]\) .*/\1/p' "/proc/$1/stat" 2>/dev/null)
    [ -n "$_st" ] && [ "$_st" != Z ] && [ "$_st" != X ]
}

# wait_pid PID SECONDS WHAT: waits for the background job PID at most SECONDS
# (a whole number); returns its exit status.  Past the deadline it prints
# "FAIL: WHAT did not end within SECONDS s", kills PID (-9) and returns 124.
wait_pid() {
    _n=$(($2 * 20))
    while [ $_n -gt 0 ] && alive "$1"; do
        sleep 0.05
        _n=$((_n - 1))
    done
    if alive "$1"; then
        echo "FAIL: $3 did not end within $2 s"
        kill -9 "$1" 2>/dev/null
        wait "$1" 2>/dev/null
        return 124
    fi
    wait "$1"
}

# wait_until SECONDS WHAT COMMAND...: runs COMMAND every 50 ms until it
# succeeds (0) or SECONDS passed (1, with "FAIL: no WHAT within SECONDS s").
wait_until() {
    _s=$1 _what=$2
    _n=$((_s * 20))
    shift 2
    while ! "$@"; do
        if [ $_n -le 0 ]; then
            echo "FAIL: no $_what within $_s s"
            return 1
        fi
        sleep 0.05
        _n=$((_n - 1))
    done
}
