#!/bin/bash
# SPDX-License-Identifier: MIT
# tests/serve/test_serve_forc.sh HYSTVIZ SCENES_DIR: a FORC scene in `hystviz
# serve` (issue 33 item 3): the page's controls list [forc] sf as a slider
# (a key the scene sets), a changed sf is accepted and re-renders, and the
# CSV serve gives for it is `hystviz data --set forc.sf=...`, byte for byte.
set -u
hv=$(realpath "$1")
src=$(realpath "$2")
. "$(dirname "$0")/../lib.sh"
. "$(dirname "$0")/serve_lib.sh"
need curl python3
curl() { command curl --max-time 60 "$@"; } # every request has a deadline

T=$tmp
mkdir -p "$T/scenes"
cp "$src/forc_preisach.scene" "$src/style.scene" "$T/scenes/"
cd "$T" || fatal "cannot cd to $T"
serve_start "$hv" serve scenes --port 0

curl -s -o "$T/scene.json" "$base/api/scene?scene=forc_preisach.scene"
python3 - "$T/scene.json" <<'PY' && ok "controls list forc.sf (3) and forc.curves (80) as sliders" || bad "controls: $(head -c 600 "$T/scene.json")"
import json, sys
j = json.load(open(sys.argv[1]))
keys = {c["key"]: c for c in j["controls"]}
assert "forc.sf" in keys and float(keys["forc.sf"]["value"]) == 3, sorted(keys)
assert "forc.curves" in keys and float(keys["forc.curves"]["value"]) == 80, sorted(keys)
PY

# a changed sf re-renders: serve's CSV is data --set's, and differs from sf = 3's
code=$(curl -s -o "$T/sf2.csv" -w "%{http_code}" "$base/api/render?scene=forc_preisach.scene&set=forc.sf%3D2&fmt=csv")
[ "$code" = 200 ] && ok "sf = 2 accepted" || bad "sf = 2: HTTP $code $(head -c 300 "$T/sf2.csv")"
curl -s -o "$T/sf3.csv" "$base/api/render?scene=forc_preisach.scene&fmt=csv"
"$hv" data scenes/forc_preisach.scene --set forc.sf=2 -o "$T/want2.csv" || bad "data --set forc.sf=2"
cmp -s "$T/sf2.csv" "$T/want2.csv" && ok "csv for sf = 2 from serve == data --set forc.sf=2" ||
    bad "csv for sf = 2 differs from data --set"
[ -s "$T/sf3.csv" ] && ! cmp -s "$T/sf2.csv" "$T/sf3.csv" && ok "sf = 2 renders another distribution than sf = 3" ||
    bad "sf = 2 gave the same CSV as sf = 3"
# a value out of the key's range is refused as for any key
code=$(curl -s -o /dev/null -w "%{http_code}" "$base/api/render?scene=forc_preisach.scene&set=forc.sf%3D0.5&fmt=csv")
[ "$code" = 422 ] || [ "$code" = 400 ] && ok "sf = 0.5 refused ($code)" || bad "sf = 0.5: HTTP $code"

serve_stop
finish serve-forc
