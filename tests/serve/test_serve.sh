#!/bin/bash
# SPDX-License-Identifier: MIT
# tests/serve/test_serve.sh HYSTVIZ SCENES_DIR: `hystviz serve` over HTTP (curl):
# byte identity with `render --set` / `data`, every refusal, save as new
# scene, reload after a rename-save through Server-Sent Events, 50 concurrent
# clients, malformed requests and dropped connections, shutdown on SIGINT.
set -u
hv=$(realpath "$1")
src=$(realpath "$2")
. "$(dirname "$0")/../lib.sh"
. "$(dirname "$0")/serve_lib.sh"
need curl
# every request has a deadline
curl() { command curl --max-time 60 "$@"; }

T=$tmp
sse= clients=
trap 'for p in $sse $clients; do kill -9 "$p" 2>/dev/null; done; serve_cleanup' EXIT

# ---- options --------------------------------------------------------------
"$hv" serve --help | grep -q "usage: hystviz serve" || bad "serve --help"
"$hv" serve --port 70000 2>/dev/null; [ $? -eq 2 ] || bad "--port 70000 must exit 2"
"$hv" serve --bogus 2>/dev/null; [ $? -eq 2 ] || bad "unknown option must exit 2"
"$hv" serve --host 0.0.0.0 "$src" 2>"$T/err"; rc=$?
[ $rc -eq 2 ] && grep -q -- "--public" "$T/err" || bad "--host 0.0.0.0 without --public must exit 2 naming --public (rc $rc)"
"$hv" serve --host example.org "$src" 2>/dev/null; [ $? -eq 2 ] || bad "--host with a name must exit 2"
"$hv" serve "$T/missing" 2>/dev/null; [ $? -eq 2 ] || bad "a missing directory must exit 2"
# (SIGINT at any moment of start-up: tests/cli/test_signals.sh)
serve_start "$hv" serve --port 0 "$src"
serve_stop

# ---- a scenes directory of our own --------------------------------------------
mkdir -p "$T/scenes" "$T/out"
cp "$src"/*.scene "$T/scenes/"
printf '[model]\nsigma0 = 7\n' > "$T/outside.scene"
mkdir -p "$T/scenes/sub"
printf '[figure]\nfontsize = 10pt\n' > "$T/scenes/sub/inc.scene"
# a scene whose include leaves the directory, and one whose include stays inside it
sed 's|^include "style.scene"$|include "../outside.scene"|' "$src/fig15_minor_loop_ex4.scene" > "$T/scenes/escape.scene"
sed 's|^include "style.scene"$|include "sub/inc.scene"|' "$src/fig15_minor_loop_ex4.scene" > "$T/scenes/inside.scene"
ln -s "$T/outside.scene" "$T/scenes/link_out.scene"
ln -s /etc/passwd "$T/scenes/passwd.scene"
cd "$T" || fatal "cannot cd to $T"

start() { serve_start "$hv" serve scenes --port 0 "$@"; } # extra options...
start --allow-save # (saving is opt-in; test_serve_attack.sh tests it off)
code() { curl -s -o /dev/null -w "%{http_code}" "$@"; }

# ---- byte identity with render --set and data -------------------------------------
F=fig15_minor_loop_ex4
q="scene=$F.scene&set=model.sigma0%3D3.162&set=input.umin2%3D0.3"
for fmt in svg pdf png; do
    curl -s -o "$T/got.$fmt" "$base/api/render?$q&fmt=$fmt"
    rm -rf "$T/r"
    "$hv" render "scenes/$F.scene" --set model.sigma0=3.162 --set input.umin2=0.3 --format $fmt -o "$T/r" ||
        bad "render $fmt"
    cmp -s "$T/got.$fmt" "$T/r/$F.$fmt" && ok "$fmt from serve == render --set" || bad "$fmt from serve differs from render --set"
done
curl -s -o "$T/got.csv" "$base/api/render?$q&fmt=csv"
"$hv" data "scenes/$F.scene" --set model.sigma0=3.162 --set input.umin2=0.3 -o "$T/want.csv"
cmp -s "$T/got.csv" "$T/want.csv" && ok "csv from serve == data --set" || bad "csv differs from data --set"
# the JSON the page uses carries the same SVG text and the command line
curl -s -o "$T/got.json" "$base/api/render?$q&fmt=json"
if command -v python3 >/dev/null; then
    rm -rf "$T/rsvg"; "$hv" render "scenes/$F.scene" --set model.sigma0=3.162 --set input.umin2=0.3 --format svg -o "$T/rsvg"
    python3 - "$T/got.json" "$T/rsvg/$F.svg" <<'EOF' && ok "page JSON: same SVG, command line" || bad "page JSON"
import json, sys
j = json.load(open(sys.argv[1]))
svg = open(sys.argv[2], encoding="utf-8").read()
assert j["svg"] == svg, "svg differs"
assert j["cmd"] == "hystviz render scenes/fig15_minor_loop_ex4.scene --set model.sigma0=3.162 --set input.umin2=0.3 --format svg", j["cmd"]
EOF
fi
# the catalogue: the gallery's order (paper figures, Bouc-Wen, beyond, animations) and captions
if command -v python3 >/dev/null; then
    curl -s "$base/api/scenes" >"$T/cat.json"
    python3 - "$T/cat.json" scenes/$F.scene <<'EOF' && ok "catalogue in the gallery's order with captions" || bad "catalogue order or captions"
import json, re, sys
j = json.load(open(sys.argv[1]))["scenes"]
files = [s["file"] for s in j if not s.get("builtin")]
def part(f):
    return 0 if re.match(r"fig\d", f) else 1 if f.startswith("bw_fig") else 3 if f.startswith("anim_") else 2
assert files == sorted(files, key=lambda f: (part(f), f)), files
assert "style.scene" not in files                       # an include, no figure
cap = re.search(r'^caption = "(.*)"$', open(sys.argv[2]).read(), re.M).group(1)
fig15 = next(s for s in j if s["file"] == "fig15_minor_loop_ex4.scene")
# its placeholder says the scene's value (as the gallery's caption)
assert "{model.sigma0}" in cap and fig15["caption"] == cap.replace("{model.sigma0}", "6"), fig15
assert fig15["label"] == "Fig. 15", fig15
EOF
fi
# a figure with a GSL solve and one with Newmark, no overrides
for G in fig11_ygamma_ex3 bw_fig1a_quasistatic_loop; do
    curl -s -o "$T/got.svg" "$base/api/render?scene=$G.scene&fmt=svg"
    rm -rf "$T/r"; "$hv" render "scenes/$G.scene" --format svg -o "$T/r"
    cmp -s "$T/got.svg" "$T/r/$G.svg" && ok "$G svg == render" || bad "$G svg differs from render"
done

# ---- invalid combination: the CLI's message, HTTP 422 --------------------------------
curl -s -o "$T/e.json" -w "%{http_code}" "$base/api/render?scene=$F.scene&set=input.umin2%3D1.2&fmt=json" >"$T/code"
"$hv" render "scenes/$F.scene" --set input.umin2=1.2 -o "$T/r" 2>"$T/cli.err"
[ "$(cat "$T/code")" = 422 ] || bad "invalid combination: HTTP $(cat "$T/code"), want 422"
want=$(sed 's/^hystviz: //' "$T/cli.err")
if command -v python3 >/dev/null; then
    got=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["error"])' "$T/e.json")
    [ "$got" = "$want" ] && ok "invalid combination: the CLI's message" || bad "message '$got' != CLI '$want'"
fi

# ---- refusals ------------------------------------------------------------------
expect() { # code url [curl options...]
    local want=$1 url=$2; shift 2
    local got; got=$(code "$@" "$base$url")
    [ "$got" = "$want" ] && ok "$want $url $*" || bad "$url $*: HTTP $got, want $want"
}
expect 404 "/scenes/..%2f..%2fetc%2fpasswd"
expect 404 "/scenes/%2e%2e/outside.scene" --path-as-is
expect 404 "/scenes/../outside.scene" --path-as-is
expect 404 "/scenes/%2e%2e%2foutside.scene"
expect 404 "/scenes/link_out.scene"
expect 404 "/scenes/passwd.scene"
expect 404 "/scenes/%2Fetc%2Fpasswd"
expect 404 "/scenes//etc/passwd" --path-as-is
expect 404 "/api/render?scene=..%2Foutside.scene"
expect 404 "/api/render?scene=%2Fetc%2Fpasswd"
expect 404 "/api/render?scene=link_out.scene"
expect 404 "/api/render?scene=$F.scene%00.scene"
expect 404 "/api/scene?scene=passwd.scene"
expect 404 "/nothing"
expect 422 "/api/render?scene=escape.scene"
# (the scene file policy: a scene reads only files below its directory, the served one)
curl -s "$base/api/render?scene=escape.scene&fmt=json" | grep -q "outside the scene's directory" &&
    ok "an include leaving the directory is named and refused" || bad "escape.scene: no refusal message"
expect 422 "/api/frame?scene=escape.scene&frame=0"
expect 422 "/api/save?scene=escape.scene&name=esc2" -X POST -H "X-Hystviz-Token: $(curl -s "$base/" | sed -n 's/.*name="hystviz-token" content="\([0-9a-f]*\)".*/\1/p')"
expect 200 "/api/render?scene=inside.scene"
# a page cannot ask for unbounded work: the scene work budget refuses it before computing
expect 422 "/api/render?scene=$F.scene&set=compute.points%3D10000000&set=compute.cycles%3D100000"
expect 200 "/scenes/$F.scene"
expect 400 "/api/render?scene=$F.scene&set=input.file%3D%2Fetc%2Fpasswd"
expect 400 "/api/render?scene=$F.scene&set=output.dir%3D%2Ftmp"
expect 400 "/api/render?scene=$F.scene&fmt=exe"
many=""; for i in $(seq 70); do many="$many&set=model.sigma0%3D$i"; done
expect 400 "/api/render?scene=$F.scene$many"
expect 403 "/" -H "Host: evil.example"
expect 403 "/" -H "Host: evil.example:$port"
expect 403 "/" -H "Host: 127.0.0.1:1"
expect 403 "/api/scenes" -H "Host: 10.1.2.3:$port"
expect 403 "/" -H "Host:"
expect 200 "/" -H "Host: localhost:$port"
expect 200 "/" -H "Host: localhost"
expect 405 "/" -X PUT
expect 405 "/api/render" -X DELETE
expect 403 "/api/save?scene=$F.scene&name=x" -X POST
expect 403 "/api/save?scene=$F.scene&name=x" -X POST -H "X-Hystviz-Token: 00000000000000000000000000000000"
head -c 100000 /dev/zero >"$T/big"
expect 413 "/api/render?scene=$F.scene" --data-binary "@$T/big"
[ ! -e scenes/x.scene ] || bad "a refused save wrote a file"

# ---- save as new scene (with the page's token) -------------------------------------
token=$(curl -s "$base/" | sed -n 's/.*name="hystviz-token" content="\([0-9a-f]*\)".*/\1/p')
[ ${#token} -eq 32 ] || bad "no token in the page"
saveq="scene=$F.scene&set=model.sigma0%3D2.5&set=compute.points%3D300&set=series.minor.width%3D2pt"
expect 201 "/api/save?$saveq&name=mine" -X POST -H "X-Hystviz-Token: $token"
if [ -f scenes/mine.scene ]; then
    rm -rf "$T/r" "$T/r2"
    "$hv" render scenes/mine.scene --format svg -o "$T/r" &&
        "$hv" render "scenes/$F.scene" --set model.sigma0=2.5 --set compute.points=300 --set series.minor.width=2pt \
            --format svg -o "$T/r2" &&
        cmp -s "$T/r/mine.svg" "$T/r2/$F.svg" && ok "saved scene renders the figure it was saved from" ||
        bad "saved scene renders something else"
    # the caption's placeholder tells the saved value, and a render with other values tells those
    curl -s "$base/api/scene?scene=mine.scene" | grep -q '"caption":"Example 4 (LuGre, σ0 = 2.5): ' &&
        ok "the saved scene's caption tells the saved sigma0 (2.5)" || bad "saved caption: $(curl -s "$base/api/scene?scene=mine.scene" | head -c 300)"
    curl -s "$base/api/render?scene=mine.scene&set=model.sigma0%3D7&fmt=json" | grep -q '"caption":"Example 4 (LuGre, σ0 = 7): ' &&
        ok "a render's caption tells the values drawn (sigma0 = 7)" || bad "render caption"
    cp scenes/mine.scene "$T/mine.before"
    expect 409 "/api/save?$saveq&name=mine" -X POST -H "X-Hystviz-Token: $token"
    cmp -s scenes/mine.scene "$T/mine.before" || bad "a second save overwrote mine.scene"
else
    bad "save wrote no scenes/mine.scene"
fi
expect 400 "/api/save?$saveq&name=..%2Fevil" -X POST -H "X-Hystviz-Token: $token"
expect 400 "/api/save?$saveq&name=.hidden" -X POST -H "X-Hystviz-Token: $token"
[ ! -e "$T/evil.scene" ] || bad "save escaped the directory"
ls -a scenes | grep -q "tmp" && bad "temporary files left in scenes/: $(ls -a scenes | grep tmp)"

# ---- reload on save: Server-Sent Events after a rename-save ---------------------------------
curl -s -N "$base/events" >"$T/sse" &
sse=$!
wait_until 10 "SSE hello event" grep -q "event: hello" "$T/sse" || bad "SSE: no hello event"
# save as Vim does: write a new file, rename it over the old one
sed 's/^sigma0 = 6$/sigma0 = 5/' "scenes/$F.scene" >"scenes/.$F.scene.swp.new"
t0=$(date +%s%N)
mv "scenes/.$F.scene.swp.new" "scenes/$F.scene"
seen=0
# (an earlier event may name the scene saved above: wait for this one)
wait_until 10 "SSE change event naming $F.scene" grep -q "^data: .*\"files\":\".*$F.scene" "$T/sse" && seen=1
t1=$(date +%s%N)
ms=$(((t1 - t0) / 1000000))
# the latency target (< 1 s) is measured by the benchmark; here: the event comes, naming the file
if [ $seen = 1 ]; then
    ok "SSE change event naming $F.scene $ms ms after a rename-save"
else
    bad "SSE: no change event naming $F.scene within 10 s: $(tr '\n' '|' <"$T/sse")"
fi
# a burst of writes is one event (debounced); counted: the events naming
# style.scene (no earlier one does, however late it comes)
styled() { grep -c '^data: .*style\.scene' "$T/sse"; }
n0=$(styled)
for i in 1 2 3 4 5; do echo "# burst $i" >>scenes/style.scene; done
new_event() { [ "$(styled)" -gt "$n0" ]; }
wait_until 10 "SSE event after a burst of writes" new_event
sleep 0.6 # a second event, if the burst were not debounced, would come within this
n1=$(styled)
[ $((n1 - n0)) -eq 1 ] && ok "a burst of 5 writes gives one event" || bad "a burst of 5 writes gave $((n1 - n0)) events"
# the page's next render follows the file: sigma0 = 5 now
curl -s -o "$T/got.svg" "$base/api/render?scene=$F.scene&fmt=svg"
rm -rf "$T/r"; "$hv" render "scenes/$F.scene" --set model.sigma0=5 --format svg -o "$T/r"
cmp -s "$T/got.svg" "$T/r/$F.svg" && ok "render after the save shows the new file" || bad "render after the save is stale"

# ---- 50 concurrent clients dragging sliders, malformed requests, dropped connections ------------
# (the server under load: pages, supersession, threads; the renders ask for
# CSV, which computes without drawing: the JSON a page gets is checked above,
# and 200 drawn figures took 80 s under ASan on a busy machine)
for c in $(seq 50); do
    (
        for k in 1 2 3 4; do
            curl -s -o /dev/null -w "%{http_code}\n" \
                "$base/api/render?scene=$F.scene&set=model.sigma0%3D$c.$k&fmt=csv&page=p$((c % 10))&seq=$k"
        done
    ) >"$T/cl_$c" &
    clients="$clients $!"
done
# meanwhile: garbage, a request cut in the middle, a download dropped mid-way
exec 3<>"/dev/tcp/127.0.0.1/$port" && printf 'GARBAGE \x01\x02 HTTP/9\r\n\r\n' >&3 && exec 3>&-
exec 3<>"/dev/tcp/127.0.0.1/$port" && printf 'GET /api/render?scene=%s.scene HTTP/1.1\r\nHost: 127.0.0.1:%s\r\nContent-Le' "$F" "$port" >&3 && exec 3>&-
exec 3<>"/dev/tcp/127.0.0.1/$port" && printf 'GET /api/render?scene=%s.scene&fmt=png HTTP/1.1\r\nHost: 127.0.0.1:%s\r\n\r\n' "$F" "$port" >&3 && exec 3>&-
curl -s -o /dev/null --limit-rate 2k --max-time 0.5 "$base/api/render?scene=$F.scene&fmt=pdf"
for p in $clients; do wait_pid "$p" 120 "a client of the 50 (4 requests of 60 s at most)" || bad "client $p of the 50 did not end"; done
clients=
nbad=$(cat "$T"/cl_* | grep -v -x -e 200 -e 409 | wc -l)
n200=$(cat "$T"/cl_* | grep -c -x 200)
[ "$nbad" -eq 0 ] && ok "50 clients x 4 renders: $n200 rendered, the rest superseded (409)" ||
    bad "50 clients: $nbad answers neither 200 nor 409: $(cat "$T"/cl_* | sort | uniq -c)"
# the last request of each page is never superseded
expect 200 "/api/render?scene=$F.scene&fmt=json&page=p1&seq=99"
kill -0 $srv 2>/dev/null && ok "server alive after the storm" || bad "server died"

# ---- animation frames: warm hystviz-animate workers ----------------------------------------
if "$hv" animate --list >/dev/null 2>&1; then
    info=$("$hv" animate scenes/anim_minor_loop_ex4.scene --info | sed 's/^frames \([0-9]*\) fps \([0-9.]*\).*/"frames":\1,"fps":\2/')
    curl -s "$base/api/scene?scene=anim_minor_loop_ex4.scene" | grep -q "\"anim\":{$info}" &&
        ok "animation scene: frames and fps as animate --info ($info)" || bad "animation scene info != $info"
    curl -s "$base/api/scenes" | grep -q '"file":"@minor-loop-ex4","builtin":true' && ok "built-in animations listed" ||
        bad "no built-in animations in the catalogue"
    nb=$(curl -s "$base/api/scenes" | grep -o '"builtin":true' | wc -l)
    nl=$("$hv" animate --list | sed '/^$/q' | grep -c '^[a-z0-9-]* ')
    [ "$nb" -eq "$nl" ] && ok "as many built-ins as animate --list names ($nb)" || bad "$nb built-ins, animate --list names $nl"
    for spec in "@minor-loop-ex4 7 minor-loop-ex4" "anim_gamma_sweep_ex3.scene 3 scenes/anim_gamma_sweep_ex3.scene"; do
        set -- $spec
        rm -rf "$T/fr"
        curl -s -o "$T/frame.png" "$base/api/frame?scene=$1&frame=$2"
        "$hv" animate "$3" --frames "$2:$(($2 + 1))" -o "$T/fr" --quiet
        cmp -s "$T/frame.png" "$(ls "$T"/fr/*/frame_0000"$2".png)" && ok "frame $2 of $1 == animate --frames $2:$(($2 + 1))" ||
            bad "frame $2 of $1 differs from hystviz animate"
    done
    expect 404 "/api/frame?scene=@nosuch&frame=1"
    expect 404 "/api/frame?scene=@..%2Fx&frame=1"
    expect 400 "/api/frame?scene=@minor-loop-ex4&frame=-1"
    expect 400 "/api/frame?scene=@minor-loop-ex4&frame=1x"
    expect 422 "/api/frame?scene=@minor-loop-ex4&frame=100000"
    expect 400 "/api/frame?scene=@minor-loop-ex4&frame=1&set=model.sigma0%3D2"
    expect 400 "/api/frame?scene=anim_gamma_sweep_ex3.scene&frame=1&set=output.dir%3D/tmp"
    expect 422 "/api/frame?scene=anim_gamma_sweep_ex3.scene&frame=1&set=model.sigma0%3D-1"
    # the page's overrides reach the frames: == animate --set
    rm -rf "$T/fr"
    curl -s -o "$T/frame.png" "$base/api/frame?scene=anim_gamma_sweep_ex3.scene&frame=5&set=model.sigma0%3D3"
    "$hv" animate scenes/anim_gamma_sweep_ex3.scene --set model.sigma0=3 --frames 5:6 -o "$T/fr" --quiet
    cmp -s "$T/frame.png" "$T/fr/anim_gamma_sweep_ex3/frame_00005.png" &&
        ok "frame 5 with set=model.sigma0=3 == animate --set model.sigma0=3 --frames 5:6" || bad "frame 5 with an override"
    # a stream of frames for playback: records "frame I LEN", then "end N"
    curl -s -o "$T/stream" "$base/api/frames?scene=anim_minor_loop_ex4.scene&from=8&to=11&page=tp&seq=1"
    rm -rf "$T/fr"
    "$hv" animate scenes/anim_minor_loop_ex4.scene --frames 8:11 -o "$T/fr" --quiet
    python3 - "$T/stream" "$T/fr/anim_minor_loop_ex4" <<'EOF' && ok "/api/frames 8..10 == animate --frames 8:11, then end 3" ||
import sys
b, i, want = open(sys.argv[1], "rb").read(), 0, 8
while True:
    nl = b.index(b"\n", i)
    tag, num, n = b[i:nl].decode().split()
    data, i = b[nl + 1:nl + 1 + int(n)], nl + 1 + int(n)
    if tag == "end":
        assert (int(num), want, i) == (3, 11, len(b)), (num, want, i, len(b))
        break
    assert (tag, int(num)) == ("frame", want), (tag, num)
    assert data == open(f"{sys.argv[2]}/frame_{want:05d}.png", "rb").read(), f"frame {want} differs"
    want += 1
EOF
        bad "/api/frames differs from animate --frames 8:11"
    curl -s "$base/api/frames?scene=anim_minor_loop_ex4.scene&from=0&to=2&page=tp&seq=2&set=model.sigma0%3D-1" |
        head -c 40 | grep -q "^error 422 " && ok "/api/frames: a refused override is an error record" ||
        bad "/api/frames with a refused override"
    expect 400 "/api/frames?scene=anim_minor_loop_ex4.scene&from=3&to=3&page=tp"
    expect 400 "/api/frames?scene=anim_minor_loop_ex4.scene&from=0&to=3"
    # the warm workers: bounded, a killed one restarted and reaped, none after SIGINT
    for i in $(seq 12); do curl -s -o /dev/null "$base/api/frame?scene=@gamma-sweep-ex2&frame=$i" & clients="$clients $!"; done
    most=0
    for _ in $(seq 60); do # sampled while any of the 12 requests runs (3 s at most)
        n=$(pgrep -P $srv | wc -l)
        [ "$n" -gt "$most" ] && most=$n
        running=0
        for p in $clients; do kill -0 $p 2>/dev/null && running=1 && break; done
        [ $running -eq 1 ] || break
        sleep 0.05
    done
    for p in $clients; do wait_pid $p 60 "a frame request"; done
    clients=
    [ "$most" -ge 1 ] && [ "$most" -le 4 ] && ok "12 concurrent frames: at most $most workers (4 at most)" ||
        bad "12 concurrent frames: $most children"
    workers=$(pgrep -P $srv)
    w1=$(echo "$workers" | head -n 1)
    [ -n "$w1" ] && kill -9 "$w1"
    expect 200 "/api/frame?scene=@minor-loop-ex4&frame=2"
    expect 200 "/api/frame?scene=@minor-loop-ex4&frame=3"
    zombies=$(ps -o stat= --ppid $srv | grep -c Z)
    [ -n "$w1" ] && [ "$zombies" -eq 0 ] && ok "a killed worker: frames still come, it was reaped" ||
        bad "$zombies zombie workers (killed: '$w1')"
    workers=$(pgrep -P $srv)
else
    echo "SKIP (frames): hystviz-animate was built without OSMesa"
fi

# ---- shutdown on SIGINT -----------------------------------------------------------------
t0=$(date +%s%N)
kill -INT $srv
wait_pid $srv 60 "serve after SIGINT (LeakSanitizer scans the heap at exit)"
rc=$?
t1=$(date +%s%N)
srv=
kill $sse 2>/dev/null
wait_pid $sse 10 "the SSE client"
sse=
[ $rc -eq 0 ] && ok "SIGINT: exit 0 after $(((t1 - t0) / 1000000)) ms" || bad "SIGINT: exit status $rc"
left=
for w in ${workers:-}; do alive "$w" && left="$left $w"; done
[ -z "$left" ] && ok "no frame worker outlives serve" || bad "frame workers left after serve stopped:$left"
ls -a scenes | grep -q "tmp" && bad "temporary files left after shutdown"

# ---- serve killed (-9): its frame workers see the end of their input and exit ------------------
if "$hv" animate --list >/dev/null 2>&1; then
    start
    expect 200 "/api/frame?scene=@minor-loop-ex4&frame=1"
    w=$(pgrep -P $srv | head -n 1) # (hystviz serve execs hystviz-serve: the same process)
    kill -9 $srv
    wait_pid $srv 10 "serve after kill -9"
    srv=
    gone() { ! alive "$w"; }
    [ -n "$w" ] && wait_until 10 "the worker's exit after serve was killed" gone &&
        ok "serve killed with -9: its frame worker exited by itself" || bad "worker '$w' outlived a killed serve"
fi

# ---- --include-dir: a user's scene that includes the gallery's style.scene ---------------------
mkdir -p "$T/mine"
sed 's/^name = .*/name = mine/' "$src/fig15_minor_loop_ex4.scene" > "$T/mine/mine.scene"
sed 's/^umin2 = 0.5$/umin2 = 1.2/' "$T/mine/mine.scene" > "$T/mine/bad.scene" # parses, refused at load
for inc in "" "$src"; do
    : >"$T/serve.out"; : >"$T/serve.err" # emptied first: the job's own >file may come after a wait read the last run's URL
    "$hv" serve "$T/mine" --port 0 ${inc:+--include-dir "$inc"} >"$T/serve.out" 2>"$T/serve.err" &
    srv=$!
    got_mine() { port=$(sed -n 's|.*http://127.0.0.1:\([0-9]*\)/.*|\1|p' "$T/serve.out"); [ -n "$port" ]; }
    wait_until 30 "URL printed by serve $T/mine" got_mine || bad "serve $T/mine: $(cat "$T/serve.err")"
    curl -s "http://127.0.0.1:$port/api/scenes" > "$T/cat.json"
    code=$(curl -s -o "$T/mine.svg" -w "%{http_code}" "http://127.0.0.1:$port/api/render?scene=mine.scene")
    if [ -z "$inc" ]; then
        grep -q '"file":"mine.scene"[^}]*"error":"[^"]*style.scene[^"]*--include-dir' "$T/cat.json" &&
            ok "without --include-dir the catalogue says why mine.scene is refused (and names --include-dir)" ||
            bad "catalogue without --include-dir: $(cat "$T/cat.json")"
    else
        "$hv" render "$T/mine/mine.scene" --include-dir "$src" --format svg -o "$T/mine_out" 2>"$T/err"
        [ "$code" = 200 ] && cmp -s "$T/mine.svg" "$T/mine_out/mine.svg" &&
            ok "serve --include-dir renders the user's scene as render --include-dir does" ||
            bad "serve --include-dir: HTTP $code, $(cat "$T/err")"
        grep -q '"file":"bad.scene"[^}]*"error":"[^"]*Definition 1 needs u_min,2 ' "$T/cat.json" &&
            ok "the catalogue says why a scene that parses is refused (u_min,2 = 1.2 > u_max,1)" ||
            bad "catalogue: no reason for bad.scene: $(cat "$T/cat.json")"
    fi
    kill -INT $srv
    wait_pid $srv 60 "serve $T/mine after SIGINT" || bad "serve $T/mine: exit status $? after SIGINT"
    srv=
done

# ---- --public: a warning; IP literals are accepted as Host, names are not --------------------
: >"$T/serve.out"; : >"$T/serve.err" # emptied first: the job's own >file may come after a wait read the last run's URL
"$hv" serve scenes --host 127.0.0.2 --public --port 0 >"$T/serve.out" 2>"$T/serve.err" &
srv=$!
wait_until 30 "URL printed by serve --public" grep -q http "$T/serve.out"
grep -q "warning: .*anyone who can reach" "$T/serve.err" && ok "--public prints a warning" ||
    bad "--public: no warning: $(cat "$T/serve.out" "$T/serve.err")"
port=$(sed -n 's|.*http://127.0.0.2:\([0-9]*\)/.*|\1|p' "$T/serve.out")
base="http://127.0.0.2:$port"
expect 200 "/" -H "Host: 192.168.1.7:$port"
expect 403 "/" -H "Host: attacker.example:$port"
kill -INT $srv
wait_pid $srv 60 "serve --public after SIGINT" || bad "serve --public: exit status $? after SIGINT"
srv=

finish serve-http
