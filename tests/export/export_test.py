#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""tests/export/export_test.py HYSTVIZ SCENES_DIR [--screenshot PNG] [--bench N]

`hystviz export`: the page's payload decoded here with the standard library
(base64, gzip, json, and the coded path lines of src/app/export_page.h)
gives, for every position, the bytes of `hystviz render --set ... --format
svg`; a refused point carries render's message; shards merged equal the
unsharded page byte for byte; the Fig. 15 grid (sigma0: 20 log-spaced values
x u_min,2: 10 values) fits in 2 MB; bad input exits 2 and writes nothing.
Then the page in headless chromium (the DevTools client of
tests/serve/browser_test.py), opened from file:// with no server: at
1024x768 the figure and every slider are on screen, moving a slider shows
render --set's bytes, a refused position says so.  The chromium part SKIPs
(exit 77 if it is all that is left) where chromium is absent.

An animation (scenes/anim_minor_loop_ex4.scene, and a built-in) exports as a
player: the page has no external URL, and frame i taken out of it is byte for
byte `hystviz animate ... --frames i:i+1`; in chromium, from file://, it
plays (the frame counter advances within a deadline) and, paused and
scrubbed to frame i, shows those bytes.

--bench N: instead, the export's size and build time for the Fig. 15 grid
(-j 1 and -j 2) and N slider moves in the page: input event -> new figure
in the DOM and laid out, and -> the next frame (median, p95).
"""
import base64
import gzip
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "serve"))
import browser_test as bt  # noqa: E402  (DevTools client, chromium start-up, check, pct)

check, pct = bt.check, bt.pct
NUMS = {"M": 2, "L": 2, "C": 6, "Z": 0}
FIG15_GRID = ["--grid", "model.sigma0=0.1:1000:log20",
              "--grid", "input.umin2=0.05,0.15,0.25,0.35,0.45,0.55,0.65,0.75,0.85,0.95"]


# ---- the payload, decoded as the page decodes it ---------------------------------

def fmt256(k):
    neg = k < 0
    q, r = divmod(abs(k) * 15625, 4)
    if r == 3 or (r == 2 and q % 2):
        q += 1
    ip, fp = divmod(q, 1000000)
    s = str(ip) + ("." + ("%06d" % fp).rstrip("0") if fp else "")
    return "-" + s if neg else s


def decode_path(c):
    out, k, d, j = [c["h"]], [0, 0], [0, 0], 0
    for cmd in c["c"]:
        out += [cmd, " "]
        for _ in range(NUMS[cmd]):
            p = j & 1
            d[p] += c["x"][j]
            k[p] += d[p]
            out += [fmt256(k[p]), " "]
            j += 1
    if not c["s"]:
        out.pop()
    out.append(c["e"])
    return "".join(out)


def decode_page(path):
    """The page's meta and, per point, ('ok', svg bytes) or ('refused', message)."""
    html = open(path, encoding="utf-8").read()
    meta = json.loads(re.search(r'<script id="meta" type="application/json">(.*?)</script>', html, re.S).group(1))
    b64 = re.search(r'<script id="payload" type="application/octet-stream">(.*?)</script>', html, re.S).group(1)
    data = json.loads(gzip.decompress(base64.b64decode("".join(b64.split()))))
    assert data["format"] == "hystviz-export 1", data["format"]
    chunks = [c if isinstance(c, str) else decode_path(c) for c in data["chunks"]]
    pts = [("refused", p) if isinstance(p, str) else ("ok", "".join(chunks[i] for i in p).encode()) for p in data["points"]]
    coded = sum(1 for c in data["chunks"] if not isinstance(c, str))
    return meta, pts, coded


def sets_of(meta, i):
    """The --set values of point i (row-major, first axis outermost)."""
    sets, rest = [], i
    for ax in reversed(meta["axes"]):
        n = len(ax["values"])
        sets.append(f"{ax['key']}={ax['values'][rest % n]}")
        rest //= n
    return list(meta["sets"]) + sets[::-1]


def render(hv, scene, sets, tmp):
    """render --set ... --format svg: (0, bytes) or (status, message)."""
    out = tempfile.mkdtemp(dir=tmp)
    args = [hv, "render", scene, "--format", "svg", "-o", out]
    for s in sets:
        args += ["--set", s]
    r = subprocess.run(args, capture_output=True, text=True, timeout=300)
    try:
        if r.returncode:
            return r.returncode, r.stderr.strip()
        files = os.listdir(out)
        return 0, open(os.path.join(out, files[0]), "rb").read()
    finally:
        shutil.rmtree(out)


def export(hv, args, timeout=400):
    return subprocess.run([hv, "export"] + args, capture_output=True, text=True, timeout=timeout)


# ---- the tests ------------------------------------------------------------------------

def test_payload(hv, scenes, tmp):
    fig15 = os.path.join(scenes, "fig15_minor_loop_ex4.scene")
    small = os.path.join(tmp, "small.html")
    # u_min,2 = 1.2 > u_max,1 = 1: refused at both sigma0
    grid = ["--grid", "model.sigma0=1,6", "--grid", "input.umin2=0.2,0.5,1.2", "--set", "model.fs=2.5"]
    r = export(hv, [fig15] + grid + ["-o", small, "-j", "2"])
    check(r.returncode == 0 and os.path.exists(small), f"export of a 2 x 3 grid with 2 refused points: exit {r.returncode} "
          f"{r.stderr.strip()}")
    check("2 refused" in r.stderr, "it says how many points the scene refused: " + r.stderr.strip())
    meta, pts, coded = decode_page(small)
    check(len(pts) == 6 and [a["key"] for a in meta["axes"]] == ["model.sigma0", "input.umin2"],
          f"6 positions, the grid keys in order ({len(pts)})")
    check(coded > 0, f"the curves are coded paths ({coded} chunks)")
    for i, (kind, body) in enumerate(pts):
        st, want = render(hv, fig15, sets_of(meta, i), tmp)
        if kind == "ok":
            check(st == 0 and body == want, f"position {i} ({' '.join(sets_of(meta, i))}) == render --set, "
                  f"{len(body)} bytes")
        else:
            check(st == 2 and want == "hystviz: " + body, f"position {i} refused with render's message: '{body}'")

    # shards: three, merged, equal the unsharded page byte for byte
    sh = os.path.join(tmp, "sh", "page.html")
    os.mkdir(os.path.dirname(sh))
    for k in range(3):
        r = export(hv, [fig15] + grid + ["-o", sh, "-j", "1", "--shard", f"{k}/3", "-q"])
        check(r.returncode == 0 and os.path.exists(f"{sh}.shard-{k}-of-3"), f"shard {k}/3: exit {r.returncode} {r.stderr}")
    moved = f"{sh}.shard-1-of-3"
    os.rename(moved, moved + ".away")
    r = export(hv, ["--merge", sh])
    check(r.returncode == 2 and "1 of 3 shards missing: 1/3" in r.stderr and not os.path.exists(sh),
          f"a missing shard: exit 2, named, nothing written ({r.returncode}: {r.stderr.strip()})")
    os.rename(moved + ".away", moved)
    r = export(hv, ["--merge", sh, "-q"])
    same = os.path.exists(sh) and open(sh, "rb").read() == open(small, "rb").read()
    check(r.returncode == 0 and same, f"--merge of 3 shards == the unsharded page, byte for byte ({r.stderr.strip()})")
    check(not any(".shard-" in f for f in os.listdir(os.path.dirname(sh))), "the merge removed the shards")

    # the Fig. 15 grid of the issue: 200 positions in <= 2 MB; a sample equals render
    big = os.path.join(tmp, "fig15.html")
    t0 = time.time()
    r = export(hv, [fig15] + FIG15_GRID + ["-o", big, "-q"])
    dt = time.time() - t0
    size = os.path.getsize(big) if os.path.exists(big) else -1
    check(r.returncode == 0 and 0 < size <= 2 * 1024 * 1024,
          f"Fig. 15, 20 x 10 grid: {size} bytes <= 2 MB (built in {dt:.1f} s) {r.stderr.strip()}")
    meta, pts, _ = decode_page(big)
    check(len(pts) == 200 and all(k == "ok" for k, _ in pts), "200 positions, none refused")
    for i in (0, 37, 111, 199):  # a sample: all 200 would take a render each
        st, want = render(hv, fig15, sets_of(meta, i), tmp)
        check(st == 0 and pts[i][1] == want, f"Fig. 15 position {i} == render --set {' '.join(sets_of(meta, i))}")
    return big, small


# ---- animations -----------------------------------------------------------------------

ANIM_SIZE = "320x180"  # small frames: the test renders every frame of the clip


def decode_anim(path):
    """The animation page's meta and its frames (PNG bytes, frame i = pngs[order[i]]), and the page
    without its frames (where no URL may be)."""
    html = open(path, encoding="utf-8").read()
    meta = json.loads(re.search(r'<script id="meta" type="application/json">(.*?)</script>', html, re.S).group(1))
    frame_re = r'<script class="frame" type="application/octet-stream">(.*?)</script>'
    pngs = [base64.b64decode("".join(b.split())) for b in re.findall(frame_re, html, re.S)]
    return meta, pngs, re.sub(frame_re, "", html, flags=re.S)


def animate_frame(hv, name, i, tmp, extra=()):
    """The PNG of `hystviz animate NAME --frames i:i+1 --size ANIM_SIZE`."""
    out = tempfile.mkdtemp(dir=tmp)
    try:
        r = subprocess.run([hv, "animate", name, "--frames", f"{i}:{i + 1}", "--size", ANIM_SIZE, "-o", out, "-q",
                            "-j", "1"] + list(extra), capture_output=True, text=True, timeout=120)
        if r.returncode:
            return None
        sub = [d for d in os.listdir(out) if os.path.isdir(os.path.join(out, d))][0]
        return open(os.path.join(out, sub, f"frame_{i:05d}.png"), "rb").read()
    finally:
        shutil.rmtree(out)


def test_anim(hv, scenes, tmp):
    scene = os.path.join(scenes, "anim_minor_loop_ex4.scene")
    info = subprocess.run([hv, "animate", scene, "--info", "--size", ANIM_SIZE], capture_output=True, text=True,
                          timeout=60)
    m = re.match(r"frames (\d+) fps (\S+) size (\d+)x(\d+)", info.stdout)
    if not m:
        print("SKIP (animations): hystviz animate cannot render here: " + info.stderr.strip())
        return None
    nframes, fps = int(m.group(1)), float(m.group(2))
    page = os.path.join(tmp, "anim.html")
    t0 = time.time()
    r = export(hv, [scene, "--size", ANIM_SIZE, "-j", "2", "-o", page])
    check(r.returncode == 0 and os.path.exists(page), f"export of an animation scene: exit {r.returncode} "
          f"in {time.time() - t0:.1f} s, {os.path.getsize(page) if os.path.exists(page) else -1} bytes "
          f"{r.stderr.strip()}")
    meta, pngs, rest = decode_anim(page)
    check(meta["frames"] == nframes and meta["fps"] == fps and len(meta["order"]) == nframes and
          max(meta["order"]) == len(pngs) - 1, f"{nframes} frames at {fps} fps, {len(pngs)} distinct PNGs stored")
    urls = re.findall(r"(?:https?:|ftp:|data:|blob:[a-z])\S*|(?:src|href)\s*=\s*\"[^\"#]", rest, re.I)
    check(not urls and "import(" not in rest and "@import" not in rest,
          f"the page names no external resource: {urls[:3]}")
    for i in (0, nframes // 2, nframes - 1):
        want = animate_frame(hv, scene, i, tmp)
        check(want is not None and pngs[meta["order"][i]] == want,
              f"frame {i} of the page == animate --frames {i}:{i + 1}, byte for byte ({len(want or b'')} bytes)")
    # a built-in animation, and -j 1 gives the same page as -j 2
    b1, b2 = os.path.join(tmp, "b1.html"), os.path.join(tmp, "b2.html")
    r1 = export(hv, ["minor-loop-ex4", "--size", ANIM_SIZE, "-j", "1", "-o", b1, "-q"])
    r2 = export(hv, ["minor-loop-ex4", "--size", ANIM_SIZE, "-j", "2", "-o", b2, "-q"])
    same = r1.returncode == 0 and r2.returncode == 0 and open(b1, "rb").read() == open(b2, "rb").read()
    check(same, f"a built-in animation exports; -j 1 and -j 2 give the same page ({r1.stderr}{r2.stderr})")
    bmeta, bpngs, _ = decode_anim(b1)
    k = len(bmeta["order"]) // 3
    check(bpngs[bmeta["order"][k]] == animate_frame(hv, "minor-loop-ex4", k, tmp),
          f"built-in frame {k} == animate --frames {k}:{k + 1}")
    # refused: --grid-less still scene, --shard, an unknown animation; nothing written
    out = os.path.join(tmp, "bad.html")
    for args, want, text in [
            ([os.path.join(scenes, "fig15_minor_loop_ex4.scene"), "-o", out], 2, "no animation"),
            ([scene, "--shard", "0/2", "-o", out], 2, "--shard is for --grid"),
            (["no-such-animation", "-o", out], 2, "no-such-animation"),
            ([scene, "--size", "3x3", "-o", out], 2, "--size")]:
        r = export(hv, args)
        check(r.returncode == want and text in r.stderr and not os.path.exists(out),
              f"export {' '.join(os.path.basename(a) for a in args)}: exit {r.returncode}, nothing written: "
              f"{r.stderr.strip()[:140]}")
    check(not [f for f in os.listdir(tmp) if f.startswith("hystviz-export-")], "no temporary frames left")
    return page


def test_anim_browser(dt, hv, scenes, tmp, page):
    scene = os.path.join(scenes, "anim_minor_loop_ex4.scene")
    meta, pngs, _ = decode_anim(page)
    dt.call("Page.navigate", url="file://" + page)
    check(dt.wait("location.pathname.endsWith('/anim.html') && window.hv && hv.ready", 60,
                  "the animation page to decode"), "the animation page decodes from file://")
    shown = """(async () => { const b = new Uint8Array(await (await fetch(hv.png)).arrayBuffer());
        let s = ''; for (const c of b) s += String.fromCharCode(c); return btoa(s); })()"""
    check(dt.js("hv.frame") == 0 and base64.b64decode(dt.js(shown)) == pngs[meta["order"][0]], "frame 0 is shown first")
    dt.js("hv.play()")
    t0 = time.time()
    ok = dt.wait("hv.frame >= 15", 20, "playback to reach frame 15")
    dt_s = time.time() - t0
    f, text = dt.js("[hv.frame, document.getElementById('counter').textContent]")  # one moment: it plays on
    check(ok and text.startswith(f"frame {f + 1} / {meta['frames']}"),
          f"it plays: frame {f} after {dt_s:.2f} s at {meta['fps']} fps, counter '{text}'")
    dt.js("hv.pause()")
    k = meta["frames"] // 2
    dt.js(f"(() => {{ const s = document.getElementById('scrub'); s.value = {k}; s.dispatchEvent(new Event('input')); }})()")
    check(dt.js("hv.frame") == k and not dt.js("hv.playing") and
          base64.b64decode(dt.js(shown)) == animate_frame(hv, scene, k, tmp),
          f"scrubbed to frame {k} (paused), the page shows animate --frames {k}:{k + 1}, byte for byte")
    # step, speed, loop
    bt.key_focus_body(dt)
    for kind in ("keyDown", "keyUp"):
        dt.call("Input.dispatchKeyEvent", type=kind, key=".", code="Period", text="." if kind == "keyDown" else "")
    check(dt.js("hv.frame") == k + 1, f". steps one frame on: {dt.js('hv.frame')}")
    dt.js("document.getElementById('back').click()")
    check(dt.js("hv.frame") == k, f"the step-back button steps one frame back: {dt.js('hv.frame')}")
    dt.js("(() => { const s = document.getElementById('speed'); s.value = '0.5'; s.dispatchEvent(new Event('change')); })()")
    check(dt.js("hv.speed") == 0.5, "the speed control sets ½×")
    dt.js("(() => { const l = document.getElementById('loop'); l.checked = false; l.dispatchEvent(new Event('change')); })()")
    dt.js(f"hv.seek({meta['frames'] - 3}); hv.setSpeed(2); hv.play()")
    check(dt.wait(f"!hv.playing && hv.frame === {meta['frames'] - 1}", 20, "the end"), "loop off: play stops on the last frame")


def test_presets(dt, hv, scenes, tmp):
    """The scene's presets in the page: keys 1-9 as in serve; a preset whose
    values lie on the grid shows that figure (Fig. 15's: the file's values), one
    that needs values the export did not compute is a disabled button that says so."""
    fig15 = os.path.join(scenes, "fig15_minor_loop_ex4.scene")
    page = os.path.join(tmp, "presets.html")
    r = export(hv, [fig15, "--grid", "model.sigma0=1,6,20", "--grid", "input.umin2=0.2,0.5", "-o", page, "-q"])
    check(r.returncode == 0, "export of a grid with the file's values " + r.stderr.strip()[:200])
    check(open_page(dt, page), "the page with presets decodes")
    b = dt.js("[...document.querySelectorAll('#presets button')].map(b => [b.innerHTML, b.disabled, b.title])")
    check(len(b) == 3 and not b[0][1] and b[1][1] and b[2][1] and "did not compute" in b[1][2] and "<sub>min,2</sub>" in b[2][0],
          f"three preset buttons, typeset; Figs. 16 and 17 need values the export did not compute: {b}")
    bt.key_focus_body(dt)
    for kind in ("keyDown", "keyUp"):
        dt.call("Input.dispatchKeyEvent", type=kind, key="1", code="Digit1", text="1" if kind == "keyDown" else "")
    st, want = render(hv, fig15, [], tmp)
    check(dt.js("hv.preset") == "fig15" and dt.js("hv.index") == 1 * 2 + 1 and st == 0 and dt.js("hv.svg") == want.decode(),
          f"key 1: preset fig15 shows the grid's figure at the file's values == hystviz render {os.path.basename(fig15)} (bytes)")
    for kind in ("keyDown", "keyUp"):
        dt.call("Input.dispatchKeyEvent", type=kind, key="2", code="Digit2", text="2" if kind == "keyDown" else "")
    check(dt.js("hv.preset") == "fig15" and dt.js("hv.index") == 3, "key 2 (not computed) leaves the figure as it is")


def test_errors(hv, scenes, tmp):
    fig15 = os.path.join(scenes, "fig15_minor_loop_ex4.scene")
    out = os.path.join(tmp, "e.html")
    cases = [
        ([fig15, "-o", out], 2, "at least one --grid"),
        ([fig15, "--grid", "model.sigma0=1:2:x", "-o", out], 2, "--grid"),
        ([fig15, "--grid", "input.umin2=1.2,1.3", "-o", out], 2, "refuses every point"),
        ([fig15, "--grid", "model.nosuch=1,2", "-o", out], 2, "refuses every point"),
        ([os.path.join(tmp, "missing.scene"), "--grid", "model.sigma0=1", "-o", out], 2, "missing.scene"),
        ([fig15, "--grid", "model.sigma0=1", "--bogus", "-o", out], 2, "unknown option"),
        (["--merge", os.path.join(tmp, "none.html")], 2, "no shard manifests"),
        ([fig15, "--grid", "model.sigma0=1,2", "-o", tmp], 1, "directory"),
    ]
    for args, want, text in cases:
        r = export(hv, args)
        check(r.returncode == want and text in r.stderr and not os.path.exists(out),
              f"export {' '.join(os.path.basename(a) for a in args)}: exit {r.returncode} (want {want}), "
              f"nothing written: {r.stderr.strip()[:120]}")
    r = export(hv, ["--help"])
    check(r.returncode == 0 and "--grid" in r.stdout and "--shard" in r.stdout, "export --help")
    check(not [f for f in os.listdir(tmp) if "hystviz-tmp" in f], "no temporaries left")


def open_page(dt, path):
    dt.call("Page.navigate", url="file://" + path)
    return dt.wait("window.hv && hv.ready && hv.cached >= 1", 60, "the page to decode")


def set_slider(dt, a, v):
    """Sets slider a to position v and fires its input event; returns the time to the new figure (ms)."""
    return dt.js(f"""(() => {{ const s = document.getElementById('s{a}'); const t0 = performance.now();
        s.value = {v}; s.dispatchEvent(new Event('input'));
        document.getElementById('figbox').getBoundingClientRect(); return performance.now() - t0; }})()""")


def shown_svg(dt):
    """The bytes of the image the page shows (its blob: URL read back), as text."""
    return dt.js("""(async () => { const im = document.querySelector('#figure img');
        if (!im || document.getElementById('figure').style.visibility === 'hidden') return null;
        await im.decode(); if (!im.naturalWidth) return null;
        return await (await fetch(im.src)).text(); })()""")


def test_browser(dt, hv, scenes, tmp, big, small, screenshot):
    fig15 = os.path.join(scenes, "fig15_minor_loop_ex4.scene")
    dt.call("Emulation.setDeviceMetricsOverride", width=1024, height=768, deviceScaleFactor=1, mobile=False)
    check(open_page(dt, big), "the exported page decodes from file:// with no server")
    meta, pts, _ = decode_page(big)
    check(dt.js("location.protocol") == "file:", "it is opened from file://")
    check(dt.js("hv.index") == 0 and shown_svg(dt) == pts[0][1].decode(), "position 0 shows render's SVG")
    # at 1024x768: the figure and every slider with its value inside the viewport
    boxes = dt.js("""[...document.querySelectorAll('#figure img, .ctl input, .ctl .v')].map(e => {
        const b = e.getBoundingClientRect(); return [e.tagName, b.left, b.top, b.right, b.bottom]; })""")
    inside = all(b[1] >= 0 and b[2] >= 0 and b[3] <= 1024 and b[4] <= 768 for b in boxes)
    fig = dt.js("(() => { const b = document.querySelector('#figure img').getBoundingClientRect(); return b.width * b.height; })()")
    # ... and it is what one sees: the element at its centre is part of the SVG (no cover over it)
    check(dt.js("""(() => { const b = document.querySelector('#figure img').getBoundingClientRect();
        const e = document.elementFromPoint(b.left + b.width / 2, b.top + b.height / 2);
        return !!e && e.matches('#figure img'); })()"""), "the figure is visible, not covered")
    check(inside and len(boxes) == 5 and fig >= 0.4 * 1024 * 768,
          f"at 1024x768 the figure ({fig / (1024 * 768):.0%} of the screen) and both sliders with their values are on screen")
    # move sigma0 with the keyboard (three steps) and u_min,2 with the mouse's value
    dt.js("document.getElementById('s0').focus()")
    for _ in range(3):
        dt.key("ArrowRight", "ArrowRight")
    set_slider(dt, 1, 6)
    i = dt.js("hv.index")
    st, want = render(hv, fig15, sets_of(meta, i), tmp)
    check(i == 3 * 10 + 6 and st == 0 and shown_svg(dt) == want.decode() and dt.js("hv.svg") == want.decode(),
          f"after moving the sliders (position {i}) the page shows render --set {' '.join(sets_of(meta, i))}, byte for byte")
    shown = dt.js("[...document.querySelectorAll('.ctl .v')].map(e => e.textContent)")
    v3 = meta["axes"][0]["values"][3]
    short = shown[0].split(" (")[0] if shown else ""
    check(len(shown) == 2 and abs(float(short) - float(v3)) <= 5e-4 * abs(float(v3)) and len(short) <= 7
          and shown[0].endswith(" (4/20)") and shown[1] == "0.65 (7/10)",
          f"each key's value is shown as the live page shows it (4 significant digits of {v3}): {shown}")
    labels = dt.js("[...document.querySelectorAll('.ctl .k')].map(e => e.innerHTML)")
    check(len(labels) == 2 and "σ<sub>0</sub>" in labels[0] and "<sub>min,2</sub>" in labels[1],
          f"the sliders' labels are the schema's symbols, typeset: {labels}")
    # g pins the figure shown: it stays, fainter, under the next one, with a chip naming its values
    bt.key_focus_body(dt)
    dt.key("KeyG", "g")
    set_slider(dt, 1, 2)
    pins = dt.js("[document.querySelectorAll('#figure img.pin').length, [...document.querySelectorAll('#pins .pinchip')].map(c => c.textContent)]")
    check(pins[0] == 1 and len(pins[1]) == 1 and pins[1][0].startswith("pin: σ0 = ") and "u_min,2 = 0.65" in pins[1][0],
          f"g pins the figure under the next one, labelled: {pins}")
    dt.js("document.querySelector('#pins .pinchip button').click()")
    check(dt.js("document.querySelectorAll('#figure img.pin').length") == 0, "its × removes the pin")
    set_slider(dt, 1, 6)
    # p: the presentation view, text at least 1/40 of the height
    dt.key("KeyP", "p")
    pv = dt.js("[getComputedStyle(document.querySelector('header')).display, parseFloat(getComputedStyle(document.getElementById('controls')).fontSize)]")
    check(pv[0] == "none" and pv[1] >= 768 / 40, f"p: the presentation view (header {pv[0]}, controls' text {pv[1]} px)")
    dt.key("KeyP", "p")
    check(dt.js("document.getElementById('cmd').textContent") == "hystviz render " + " ".join(
        [fig15] + [f"--set {s}" for s in sets_of(meta, i)]) + " --format svg", "the page shows the render command")
    if screenshot:
        dt.wait("hv.allCached", 30, "every figure parsed")
        shot = dt.call("Page.captureScreenshot", format="png")
        with open(screenshot, "wb") as f:
            f.write(base64.b64decode(shot["data"]))
        print(f"   screenshot: {screenshot}")
    # a refused position says so, and the next valid one is back
    check(open_page(dt, small), "the small page decodes")
    set_slider(dt, 1, 2)
    msg = dt.js("document.getElementById('refused').hidden ? '' : document.getElementById('refused').textContent")
    _, want = render(hv, fig15, ["model.fs=2.5", "model.sigma0=1", "input.umin2=1.2"], tmp)
    covered = dt.js("""(() => { const b = document.getElementById('figbox').getBoundingClientRect();
        const e = document.elementFromPoint(b.left + b.width / 2, b.top + b.height / 2);
        return !!e && !!e.closest('#refused'); })()""")
    check(covered, "the refusal is what one sees where the figure was")
    check(dt.js("hv.svg") is None and shown_svg(dt) is None and msg.endswith(want[len("hystviz: "):]) and "refuses" in msg,
          f"a refused position shows the scene's message: '{msg[:100]}'")
    set_slider(dt, 1, 1)
    _, want = render(hv, fig15, ["model.fs=2.5", "model.sigma0=1", "input.umin2=0.5"], tmp)
    check(shown_svg(dt) == want.decode() and dt.js("document.getElementById('refused').hidden"),
          "moving back to a valid position shows its figure")


def bench(dt, hv, scenes, tmp, n):
    fig15 = os.path.join(scenes, "fig15_minor_loop_ex4.scene")
    page = os.path.join(tmp, "bench.html")
    for j in (1, 2):
        t0 = time.time()
        r = export(hv, [fig15] + FIG15_GRID + ["-o", page, "-q", "-j", str(j)])
        if r.returncode:
            print("bench-export: export failed: " + r.stderr)
            return
        print(f"bench-export Fig. 15, 20 x 10 grid, -j {j}: {os.path.getsize(page) / 1e6:.3f} MB "
              f"(target <= 2 MB) built in {time.time() - t0:.2f} s", flush=True)
    dt.call("Emulation.setDeviceMetricsOverride", width=1024, height=768, deviceScaleFactor=1, mobile=False)
    open_page(dt, page)
    dt.wait("hv.allCached", 60, "every figure parsed")
    print(f"bench-export page: first figure {dt.js('hv.decodeMs'):.0f} ms after the page's script started, every figure "
          f"decoded up front after {dt.js('hv.allMs'):.0f} ms", flush=True)
    swap, frame = [], []
    for k in range(n):
        a, v = k % 2, (k * 7) % (20 if k % 2 == 0 else 10)
        r = dt.js(f"""new Promise(res => {{ const s = document.getElementById('s{a}'); const t0 = performance.now();
            s.value = {v}; s.dispatchEvent(new Event('input'));
            document.getElementById('figbox').getBoundingClientRect(); const t1 = performance.now();
            requestAnimationFrame(() => setTimeout(() => res([t1 - t0, performance.now() - t0]), 0)); }})""")
        swap.append(r[0])
        frame.append(r[1])
    print(f"bench-export slider -> figure in the page, {n} moves at 1024x768: new SVG in the DOM and laid out "
          f"median {pct(swap, 50):.2f} ms p95 {pct(swap, 95):.2f} ms; to the next frame (rAF + task) median "
          f"{pct(frame, 50):.1f} ms p95 {pct(frame, 95):.1f} ms (target <= 16 ms)", flush=True)


def main():
    hv, scenes = os.path.realpath(sys.argv[1]), os.path.realpath(sys.argv[2])
    screenshot = sys.argv[sys.argv.index("--screenshot") + 1] if "--screenshot" in sys.argv else None
    nbench = int(sys.argv[sys.argv.index("--bench") + 1]) if "--bench" in sys.argv else 0
    have_chromium = shutil.which("chromium") or shutil.which("chromium-browser")
    tmp = tempfile.mkdtemp(prefix="hystviz-export-")
    chrome = None
    try:
        if nbench:
            if not have_chromium:
                print("SKIP: chromium is not installed (Debian: apt-get install chromium)")
                return 77
            chrome, ws = bt.start_chromium(tmp)
            bench(bt.DevTools(ws), hv, scenes, tmp, nbench)
            return 0
        big, small = test_payload(hv, scenes, tmp)
        test_errors(hv, scenes, tmp)
        anim = test_anim(hv, scenes, tmp)
        if not have_chromium:
            if bt.need_chromium():
                raise RuntimeError("chromium is not installed (CI=true: sh tools/setup.sh test installs it)")
            print("SKIP (browser part): chromium is not installed (Debian: apt-get install chromium)")
        else:
            chrome, ws = bt.start_chromium(tmp)
            if not chrome:
                print("SKIP (browser part): chromium did not start headless")
            else:
                dt = bt.DevTools(ws)
                dt.call("Page.enable")
                dt.call("Runtime.enable")
                test_browser(dt, hv, scenes, tmp, big, small, screenshot)
                test_presets(dt, hv, scenes, tmp)
                if anim:
                    test_anim_browser(dt, hv, scenes, tmp, anim)
    finally:
        if chrome:
            bt.stop_group(chrome)  # its renderers too: they write into tmp until gone
        bt.remove_tree(tmp)
    if bt.FAILS:
        print(f"{len(bt.FAILS)} failure(s)")
        return 1
    print("all export tests passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
