#!/bin/bash
# SPDX-License-Identifier: MIT
# tests/bench/bench_serve_attack.sh HYSTVIZ SCENES_DIR ATTACK_CLIENT: the
# latency of a legitimate Fig. 15 render (a page dragging sigma0: page id,
# JSON as the page asks) while `hystviz serve` is under each attack of issue
# 20 (loopback only).  Target: within 1 s during every attack.  Prints one
# row per attack (median and worst of 10 renders); asserts nothing.  Writes
# only under a temporary directory it removes.
set -u
hv=$(realpath "$1")
src=$(realpath "$2")
client=$(realpath "$3")
command -v curl >/dev/null && command -v python3 >/dev/null || { echo "bench-serve-attack: SKIP (curl or python3 missing)"; exit 0; }
T=$(mktemp -d)
srv=
bg=()
cleanup() {
    for p in "${bg[@]}"; do kill -9 "$p" 2>/dev/null; done
    [ -n "$srv" ] && kill -9 "$srv" 2>/dev/null
    rm -rf "$T"
}
trap cleanup EXIT
mkdir -p "$T/scenes"
cp "$src"/*.scene "$T/scenes/"
cp "$T/scenes/fig15_minor_loop_ex4.scene" "$T/scenes/inside.scene"
echo "outside" >"$T/outside.txt"
cd "$T" || exit 1
"$hv" serve scenes --port 0 >"$T/serve.out" 2>"$T/serve.err" &
srv=$!
port=
for _ in $(seq 100); do
    port=$(sed -n 's|.*http://127.0.0.1:\([0-9]*\)/.*|\1|p' "$T/serve.out")
    [ -n "$port" ] && break
    sleep 0.1
done
[ -n "$port" ] || { echo "bench-serve-attack: serve did not start: $(cat "$T/serve.err")"; exit 0; }
base="http://127.0.0.1:$port"
F=fig15_minor_loop_ex4.scene
seq=0
measure() { # label: 10 renders of Fig. 15 with a new sigma0 each
    local ms=()
    for i in $(seq 10); do
        seq=$((seq + 1))
        t=$(curl -s -o /dev/null --max-time 30 -w "%{http_code} %{time_total}" \
            "$base/api/render?scene=$F&set=model.sigma0%3D$((3 + i % 5)).$seq&fmt=json&page=bench&seq=$seq")
        [ "${t%% *}" = 200 ] && ms+=("$(echo "${t#* }" | awk '{printf "%d", $1 * 1000}')") || ms+=(99999)
        sleep 0.1
    done
    printf '%s\n' "${ms[@]}" | sort -n >"$T/ms"
    printf 'bench-serve-attack %-44s median %5d ms  worst %5d ms  (target < 1000 ms)\n' "$1" \
        "$(sed -n 5p "$T/ms")" "$(tail -1 "$T/ms")"
}
during() { # label command...: measure while the command runs in the background
    local label=$1; shift
    "$@" >/dev/null 2>&1 &
    bg+=($!)
    sleep 1.5
    measure "$label"
    kill "${bg[-1]}" 2>/dev/null
    sleep 0.2
    kill -9 "${bg[-1]}" 2>/dev/null # one that ignores TERM must not hang the benchmark
    wait "${bg[-1]}" 2>/dev/null
    sleep 0.5
}
heavy="/api/render?scene=$F&set=compute.points%3D190000&fmt=png"
loop_closed() { while :; do python3 "$client" closed "$port" 24 "$heavy"; sleep 0.2; done; }
loop_race() { python3 "$client" race "$T/scenes" "$port" 100000 "$T/outside.txt"; }
many=""; for i in $(seq 1100); do many="$many&a=$i"; done
measure "no attack"
during "300 idle connections (issue 20.5)" python3 "$client" idle "$port" 300 60
during "40 event streams held (20.5)" python3 "$client" streams "$port" 40 60
during "8 clients of heavy renders, no page (20.6)" python3 "$client" flood "$port" 8 60 "$heavy"
during "24 heavy requests dropped, repeated (20.6)" loop_closed
during "cross-site <img> flood, 16 clients (20.6)" python3 "$client" flood "$port" 16 60 "$heavy" "Sec-Fetch-Site: cross-site"
during "overrides with a blank before '=' (20.2)" python3 "$client" flood "$port" 8 60 \
    "/api/render?scene=$F&set=input.kind%3Dfile&set=input.file%20%3D/etc/passwd"
during "link flipped under /scenes/ (20.3)" loop_race
during "animate --info, 16 clients (20.7)" python3 "$client" flood "$port" 16 60 "/api/scene?scene=anim_minor_loop_ex4.scene"
during "1,100 query arguments, 8 clients (20.11)" python3 "$client" flood "$port" 8 60 "/api/render?scene=$F$many"
grep VmRSS /proc/$srv/status | sed 's/^/bench-serve-attack serve memory after the attacks: /'
kill -INT $srv
t0=$(date +%s%N)
for _ in $(seq 300); do kill -0 $srv 2>/dev/null || break; sleep 0.05; done
echo "bench-serve-attack Ctrl-C: stopped in $((($(date +%s%N) - t0) / 1000000)) ms"
srv=
