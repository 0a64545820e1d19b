#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""tests/serve/lecture_test.py HYSTVIZ SCENES_DIR [--screenshots DIR]

Issue 38's page in chromium (headless, DevTools, browser_test.py's helpers;
every wait has a deadline):

- every clip (the built-ins of animate --list and both animation scenes) plays
  past frame 75 with no frame skipped as undecodable (two froze at frames 59
  and 48 on frames chromium refused);

- a player that cannot stall: frame 5 of a built-in clip is spoiled on its way
  into the page (the test wraps the page's fetch and overwrites the frame's
  PNG bytes after the signature in the /api/frames stream and in /api/frame):
  playing shows a note that names the cause (the frame came, the browser
  cannot decode it), the frames shown keep increasing, and scrubbed to, the
  frame never reads "the server did not answer"; a frame createImageBitmap
  refuses (the test makes it refuse frame 8's bytes) is shown through <img>;
- animations in the presentation view at 1024x768, 1920x1080 and 390x844
  (touch): the clip's box and its controls (play, step, speed, loop,
  scrubber, frame counter with the clip time) lie inside the viewport, the
  clip fills >= 80 % of the width or of the height left by the controls, no
  heading, note or still is shown; a touch drag on the scrubber moves the
  frame; the keys , and . step one frame;
- comparisons: two pins labelled with their values ("σ0 = 6"), each
  removable; l holds the axes (figure.xlim/ylim in the command line, the SVG
  == hystviz render --set with them, byte for byte); a slider's ▶ holds the
  axes over its whole range (the limits drawn do not change while it plays),
  and so does a mouse drag of sigma0 over its whole range (dragged back, the
  limits stay);
  speed ½× and step; key 7 on a scene with 3 presets says so (the help
  lists 1–3, not 7); preset buttons show typeset symbols; the controls' text
  in the presentation view is >= 1/40 of the window height.

Exit 77 (SKIP) where chromium is absent; the clip checks SKIP where
hystviz-animate has no OSMesa.
"""
import base64
import json
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import browser_test as bt  # noqa: E402
from browser_test import check  # noqa: E402

F15 = "fig15_minor_loop_ex4"
CLIP = "@minor-loop-ex4"
SCENE_CLIP = "anim_minor_loop_ex4.scene"

# the page's fetch, wrapped: frame SPOIL's PNG bytes overwritten after the
# 8-byte signature (no decoder takes it) in /api/frames' records "TAG NUM
# LEN\n<bytes>" and in /api/frame; frame REFUSE's size noted (createImageBitmap
# is then made to refuse blobs of that size)
WRAP = r"""(() => {
  const SPOIL = 5, REFUSE = 8, f = window.fetch, real = window.createImageBitmap;
  window.hvt = { spoiled: 0, refuseSize: -1, refused: 0 };
  const spoil = d => { for (let k = 8; k < d.length; k++) d[k] = 0x5a; hvt.spoiled++; };
  window.createImageBitmap = (x, ...a) => {
    if (x instanceof Blob && x.size === hvt.refuseSize) {
      hvt.refused++;
      return Promise.reject(new DOMException('The source image could not be decoded.', 'InvalidStateError'));
    }
    return real(x, ...a);
  };
  window.fetch = async (u, o) => {
    const r = await f(u, o);
    if (typeof u !== 'string' || r.status !== 200) return r;
    if (u.startsWith('/api/frame?') && new RegExp('[?&]frame=' + SPOIL + '(&|$)').test(u)) {
      const d = new Uint8Array(await r.arrayBuffer());
      spoil(d);
      return new Response(d, { status: 200, headers: r.headers });
    }
    if (!u.startsWith('/api/frames?')) return r;
    let buf = new Uint8Array(0);
    const ts = new TransformStream({
      transform(chunk, ctl) {
        const b = new Uint8Array(buf.length + chunk.length);
        b.set(buf); b.set(chunk, buf.length); buf = b;
        for (;;) {
          const nl = buf.indexOf(10);
          if (nl < 0) return;
          const [tag, num, len] = new TextDecoder().decode(buf.subarray(0, nl)).trim().split(' ');
          const end = nl + 1 + (+len);
          if (buf.length < end) return;
          const rec = buf.slice(0, end);
          if (tag === 'frame' && +num === SPOIL) spoil(rec.subarray(nl + 1));
          if (tag === 'frame' && +num === REFUSE) hvt.refuseSize = +len;
          ctl.enqueue(rec);
          buf = buf.slice(end);
        }
      },
      flush(ctl) { if (buf.length) ctl.enqueue(buf); },
    });
    return new Response(r.body.pipeThrough(ts), { status: 200, headers: r.headers });
  };
  return true; })()"""


def viewport(dt, w, h, mobile=False):
    dt.call("Emulation.setDeviceMetricsOverride", width=w, height=h, deviceScaleFactor=1, mobile=mobile)
    dt.call("Emulation.setTouchEmulationEnabled", enabled=mobile, maxTouchPoints=1)


def open_clip(dt, base, frag, what):
    dt.call("Page.navigate", url="about:blank")
    dt.call("Page.navigate", url=base + "#" + frag)
    f = frag.split("?")[0]
    return dt.wait(f"window.hv && hv.info && hv.info.file === '{f}' && hv.info.anim && hv.frame >= 0 && !hv.frameInflight",
                   90, what)


def has_gl(hv, tmp):
    r = subprocess.run([hv, "animate", CLIP[1:], "--frames", "0:1", "-o", os.path.join(tmp, "gl"), "--quiet"],
                       capture_output=True, text=True, timeout=120)
    if r.returncode != 0:
        print("SKIP (clips): hystviz-animate cannot render here: " + r.stderr.strip()[:300])
    return r.returncode == 0


def test_undecodable(dt, base):
    viewport(dt, 1024, 768)
    ok = open_clip(dt, base, CLIP, "the clip")
    check(ok, f"{CLIP} opens on frame 0")
    if not ok:
        return
    dt.js(WRAP)
    dt.js("document.getElementById('play').click()")
    check(dt.wait("hvt.spoiled > 0 && hv.anim.skipped > 0 && !document.getElementById('framewarn').hidden", 60,
                  "the note for frame 5"), "frame 5, spoiled on its way in, is skipped with a note")
    note = dt.js("document.getElementById('framewarn').textContent")
    check("frame 5" in note and "came from the server" in note and "cannot decode" in note,
          f"the note names the frame and the cause: '{note}'")
    n0 = dt.js("hv.anim.shown")
    check(dt.wait(f"hv.anim.shown >= {n0} + 15", 30, "15 more frames"), "the frames shown keep increasing after it")
    check(dt.js("hv.playing"), "... and the clip still plays")
    check(dt.wait("hvt.refused > 0 && hv.anim.viaImg > 0", 60, "frame 8 through <img>"),
          f"a frame createImageBitmap refuses is decoded through <img> ({dt.js('hv.anim.viaImg')} so far)")
    check(dt.js("!hv.anim.bad.has(8)"), "... and is not skipped")
    dt.js("document.getElementById('play').click()")
    dt.wait("!hv.playing", 10, "pause")
    # scrubbed to the spoiled frame (it comes alone through /api/frame)
    dt.js("(() => { const s = document.getElementById('scrub'); s.value = 5; s.dispatchEvent(new Event('input')); })()")
    check(dt.wait("hv.frame === 5 && !hv.frameInflight", 30, "frame 5 scrubbed"), "scrubbed to frame 5")
    info = dt.js("document.getElementById('frameinfo').textContent + ' | ' + document.getElementById('framewarn').textContent")
    check("did not answer" not in info and "cannot decode" in info, f"scrubbed to it, the page says why: '{info}'")


def rect(dt, sel):
    return dt.js(f"""(() => {{ const e = document.querySelector({sel!r}); if (!e || !e.offsetParent && e.tagName !== 'CANVAS') return null;
        const b = e.getBoundingClientRect(); return [b.left, b.top, b.right, b.bottom]; }})()""")


def inside(b, w, h):
    return b is not None and b[0] >= -0.5 and b[1] >= -0.5 and b[2] <= w + 0.5 and b[3] <= h + 0.5 and b[2] > b[0] and b[3] > b[1]


def test_present_anim(dt, base, shots):
    for w, h, mobile in ((1024, 768, False), (1920, 1080, False), (390, 844, True)):
        viewport(dt, w, h, mobile)
        for frag in (CLIP, SCENE_CLIP):
            tag = f"{w}x{h} {frag}"
            ok = open_clip(dt, base, frag + "?view=present", tag)
            check(ok, f"{tag}: opens in the presentation view")
            if not ok:
                continue
            dt.wait("document.getElementById('frame').style.width !== ''", 10, "the frame fitted")
            c = rect(dt, "#frame")
            check(inside(c, w, h), f"{tag}: the clip lies inside the viewport: {c}")
            for sel in ("#play", "#stepback", "#stepon", "#animspeed", "#loop", "#scrub", "#frameinfo"):
                r = rect(dt, sel)
                check(inside(r, w, h), f"{tag}: {sel} lies inside the viewport: {r}")
            ctl = dt.js("""(() => { let s = 0; for (const q of ['#anim .animctl', '#stage', '#framewarn']) {
                const e = document.querySelector(q); if (e && e.offsetParent) s += e.getBoundingClientRect().height; }
                return s; })()""")
            fw, fh = (c[2] - c[0]) / w, (c[3] - c[1]) / (h - ctl) if c else (0, 0)
            check(max(fw, fh) >= 0.8, f"{tag}: the clip fills {100 * fw:.0f} % of the width, {100 * fh:.0f} % of the "
                                      f"height the controls leave ({h - ctl:.0f} px): >= 80 % of one")
            hidden = dt.js("""['#title', '#caption', '#anim h3', '#framenote', '#figbox', 'nav', 'header']
                .filter(q => { const e = document.querySelector(q); return e && e.offsetParent !== null; })""")
            check(hidden == [], f"{tag}: no heading, note or still shown ({hidden})")
            check(dt.js("document.documentElement.scrollHeight <= innerHeight && document.documentElement.scrollWidth <= innerWidth"),
                  f"{tag}: nothing to scroll")
            info = dt.js("document.getElementById('frameinfo').textContent")
            check(" s / " in info, f"{tag}: the frame counter shows the clip time: '{info}'")
            fs = dt.js("parseFloat(getComputedStyle(document.getElementById('play')).fontSize)")
            check(fs >= h / 40 - 0.01, f"{tag}: the clip's buttons' text is {fs} px (>= 1/40 of {h})")
            if shots and not mobile or shots and frag == CLIP:
                shot = dt.call("Page.captureScreenshot", format="png")
                path = os.path.join(shots, f"present-anim-{w}x{h}-{frag.strip('@').split('.')[0]}.png")
                with open(path, "wb") as f:
                    f.write(base64.b64decode(shot["data"]))
                print(f"   screenshot: {path}")
            if mobile and frag == CLIP:  # a touch drag along the scrubber
                s = rect(dt, "#scrub")
                y = (s[1] + s[3]) / 2
                f0 = dt.js("hv.frame")
                pts = [s[0] + 3 + (s[2] - s[0] - 6) * k / 8 for k in range(9)]
                dt.call("Input.dispatchTouchEvent", type="touchStart", touchPoints=[{"x": pts[0], "y": y}])
                for x in pts[1:]:
                    dt.call("Input.dispatchTouchEvent", type="touchMove", touchPoints=[{"x": x, "y": y}])
                dt.call("Input.dispatchTouchEvent", type="touchEnd", touchPoints=[])
                check(dt.wait(f"+document.getElementById('scrub').value > {f0} + 20 && hv.frame > {f0} + 20 && !hv.frameInflight",
                              30, "the touch drag"), f"{tag}: a touch drag along the scrubber moves the frame to {dt.js('hv.frame')}")
            if not mobile and frag == CLIP:  # , and . step one frame
                f0 = dt.js("hv.frame")
                bt.key_focus_body(dt)
                for kind in ("keyDown", "keyUp"):
                    dt.call("Input.dispatchKeyEvent", type=kind, key=".", code="Period", text="." if kind == "keyDown" else "")
                check(dt.wait(f"hv.frame === {f0 + 1} && !hv.frameInflight", 30, ". steps"), f"{tag}: . steps to frame {f0 + 1}")
                for kind in ("keyDown", "keyUp"):
                    dt.call("Input.dispatchKeyEvent", type=kind, key=",", code="Comma", text="," if kind == "keyDown" else "")
                check(dt.wait(f"hv.frame === {f0} && !hv.frameInflight", 30, ", steps"), f"{tag}: , steps back to frame {f0}")
    viewport(dt, 1400, 1000)


def press(dt, key, code):
    for kind in ("keyDown", "keyUp"):
        dt.call("Input.dispatchKeyEvent", type=kind, key=key, code=code, text=key if kind == "keyDown" else "")


def open_fig(dt, base, frag, what):
    dt.call("Page.navigate", url="about:blank")
    dt.call("Page.navigate", url=base + "#" + frag)
    scene = frag.split("?")[0]
    return dt.wait(f"window.hv && hv.info && hv.info.file === '{scene}' && hv.renders >= 1 && hv.svg "
                   "&& !hv.inflight && !hv.pending", 60, what)


def settled(dt, what, timeout=60):
    return dt.wait("!hv.inflight && !hv.pending && !hv.holding", timeout, what)


def set_value(dt, key, v):
    dt.js(f"""(() => {{ const b = document.querySelector('input[type=text][data-key="{key}"]');
        b.value = '{v}'; b.dispatchEvent(new Event('change')); }})()""")
    return dt.wait(f"hv.sets['{key}'] === '{v}' && !hv.inflight && !hv.pending && hv.error === null", 60, f"{key} = {v}")


def test_compare(dt, hv, base, scenes, tmp):
    viewport(dt, 1920, 1080)
    check(open_fig(dt, base, F15 + ".scene?view=present", "Fig. 15"), "Fig. 15 opens in the presentation view")
    fs = dt.js("parseFloat(getComputedStyle(document.querySelector('#controls .ctl.main label')).fontSize)")
    bs = dt.js("parseFloat(getComputedStyle(document.querySelector('#controls button.preset')).fontSize)")
    check(fs >= 27 and bs >= 27, f"1920x1080: the controls' text is {fs} px, the buttons' {bs} px (>= 1080/40 = 27)")
    sub = dt.js("Array.from(document.querySelectorAll('button.preset')).map(b => b.innerHTML)")
    check(len(sub) == 3 and "<sub>" in sub[2] and "u_min" not in "".join(sub),
          f"the preset buttons set the symbols as the sliders do: {sub[2]}")
    # two pins, labelled, each removable
    viewport(dt, 1024, 768)
    bt.key_focus_body(dt)
    press(dt, "g", "KeyG")
    check(set_value(dt, "model.sigma0", "20"), "sigma0 = 20")
    press(dt, "g", "KeyG")
    check(set_value(dt, "model.sigma0", "60"), "sigma0 = 60")
    labels = dt.js("Array.from(document.querySelectorAll('#figure svg text.pinlabel')).map(t => t.textContent)")
    check(len(labels) == 2 and labels[0].startswith("σ0 = 6,") and labels[1].startswith("σ0 = 20,"),
          f"two pins under the figure, labelled with their values: {labels}")
    chips = dt.js("Array.from(document.querySelectorAll('#pins .pinchip')).map(c => c.textContent)")
    check(len(chips) == 2, f"each pin has a chip: {chips}")
    tone = dt.js("""(() => { const svg = document.querySelector('#figure svg');
        const g = svg.querySelector('g.ghost path'), first = Array.from(svg.querySelectorAll('path')).find(p => !p.closest('g.ghost')
            && /fill:none/.test(p.getAttribute('style')) && /stroke-linejoin:round/.test(p.getAttribute('style')));
        const rgb = s => (/stroke:rgb\\(([^)]*)\\)/.exec(s) || [0, ''])[1];
        return [rgb(first.getAttribute('style')), rgb(g.getAttribute('style'))]; })()""")
    check(tone[0] != tone[1] and tone[1] != "", f"a pinned curve is drawn in a lighter tone: {tone}")
    dt.js("document.querySelector('#pins .pinchip button').click()")
    left = dt.js("Array.from(document.querySelectorAll('#figure svg text.pinlabel')).map(t => t.textContent)")
    check(len(left) == 1 and left[0].startswith("σ0 = 20,"), f"its × removes one pin: {left} left")
    # l holds the axes: the figure is render --set with the limits, byte for byte
    bt.key_focus_body(dt)
    press(dt, "l", "KeyL")
    check(settled(dt, "the held figure") and dt.js("!!hv.axesHeld"), "l holds the axes")
    sets = dt.js("Object.entries(hv.sets).map(([k, v]) => k + '=' + v)")
    cmd = dt.js("hv.cmd")
    check(any(s.startswith("figure.xlim=") for s in sets) and "figure.xlim=" in cmd, f"the command line says so: {cmd}")
    want = bt.render_svg(hv, os.path.join(scenes, F15 + ".scene"), sets, os.path.join(tmp, "held"))
    check(dt.js("hv.svg") == want, f"held: the figure == hystviz render --set {' --set '.join(sets)} (bytes)")
    press(dt, "l", "KeyL")
    check(settled(dt, "the freed figure") and not dt.js("hv.axesHeld") and "figure.xlim" not in dt.js("hv.cmd"),
          "l again releases them")
    # a slider's play holds the axes over its range: the limits drawn stay
    dt.js("""(() => { hv.t = { maps: [] };
        document.addEventListener('hv-rendered', () => { if (hv.axesHeld) hv.t.maps.push(JSON.stringify(
            [hv.map.xlo, hv.map.xhi, hv.map.ylo, hv.map.yhi])); });
        document.querySelector('button.playkey[data-key="model.sigma0"]').click(); })()""")
    check(dt.wait("hv.t.maps.length >= 6", 90, "six held figures while playing"),
          f"sigma0 plays with the axes held ({dt.js('hv.t.maps.length')} figures)")
    maps = [json.loads(m) for m in dt.js("hv.t.maps")]
    same = all(abs(a - b) <= 1e-9 * max(1.0, abs(b)) for m in maps for a, b in zip(m, maps[0]))
    check(same, f"the axes' limits do not change while the slider plays (to 1e-9): {maps[0]}, {len(maps)} figures")
    # a mouse drag over sigma0's whole range holds the axes (once its two limits renders are in)
    dt.key("Space", " ")
    settled(dt, "stopped")
    press(dt, "l", "KeyL")  # free again
    settled(dt, "free")
    check(not dt.js("hv.axesHeld"), "the axes are free before the drag")
    dt.js("hv.t.maps = []")
    bt.drag(dt, "model.sigma0", 0.02, 0.98, steps=40)
    dt.wait("!hv.holding", 30, "the limits")
    settled(dt, "the drag")
    held = dt.js("hv.axesHeld && hv.sets['figure.xlim']")
    check(bool(held), f"a drag over sigma0's range holds the axes: figure.xlim={held}")
    dt.js("hv.t.maps = []")
    bt.drag(dt, "model.sigma0", 0.98, 0.02, steps=40)
    settled(dt, "the second drag")
    maps = [json.loads(m) for m in dt.js("hv.t.maps")]
    same = len(maps) >= 2 and all(abs(a - b) <= 1e-9 * max(1.0, abs(b)) for m in maps for a, b in zip(m, maps[0]))
    check(same, f"dragged back over the whole range, the axes' limits do not change: {maps[:1]}, {len(maps)} figures")
    dt.js("document.querySelector('button.playkey[data-key=\"model.sigma0\"]').click()")
    # speed and step of a slider's play
    press(dt, "[", "BracketLeft")
    check(dt.js("hv.speed") == 0.5, "[ halves the speed")
    press(dt, "]", "BracketRight")
    check(dt.js("hv.speed") == 1, "] restores it")
    dt.key("Space", " ")
    check(dt.js("hv.sliderPlay === null"), "space stops the slider")
    settled(dt, "stopped")
    v0 = float(dt.js("hv.sets['model.sigma0']"))
    press(dt, ".", "Period")
    ok = dt.wait(f"+hv.sets['model.sigma0'] !== {v0} && !hv.inflight", 20, ". steps")
    v1 = dt.js("hv.sets['model.sigma0']")
    check(ok, f". steps the slider played last: sigma0 {v0} -> {v1}")
    settled(dt, "stepped")
    # key 7: this scene has 3 presets
    press(dt, "7", "Digit7")
    flash = dt.js("document.getElementById('flash').hidden ? '' : document.getElementById('flash').textContent")
    check("no preset 7" in flash and "3" in flash, f"key 7 says there is no 7th preset: '{flash}'")
    helps = dt.js("Array.from(document.querySelectorAll('#keylist kbd')).map(k => k.textContent)")
    check("1–3" in helps and "7" not in "".join(helps), f"the help lists the keys the page binds: {helps}")


def clips(hv):
    """The built-in clips (hystviz animate --list) and the two animation scenes."""
    r = subprocess.run([hv, "animate", "--list"], capture_output=True, text=True, timeout=60)
    names = [m.group(1) for m in (re.match(r"([a-z0-9][a-z0-9-]*) {2,}\S", ln) for ln in r.stdout.splitlines()) if m]
    return ["@" + n for n in names] + [SCENE_CLIP, "anim_gamma_sweep_ex3.scene"]


def test_play_through(dt, hv, base):
    """Every clip plays past frame 75 (gamma-sweep-ex2 froze at 59, preisach-plane at
    48, on frames chromium could not decode) with no frame skipped as undecodable:
    a deadline of 120 s a clip, not a rate (the rate is the benchmark's).  At
    1024x768; the two clips that froze also at 1920x1080."""
    runs = [(c, 1024, 768) for c in clips(hv)] + [("@gamma-sweep-ex2", 1920, 1080), ("@preisach-plane", 1920, 1080)]
    check(len(runs) >= 9, f"{len(runs)} clip runs (the built-ins and both scene clips)")
    for frag, w, h in runs:
        viewport(dt, w, h)
        if not open_clip(dt, base, frag, f"{frag} opened"):
            check(False, f"{frag}: opened")
            continue
        n = dt.js("hv.anim.n") or 0
        want = min(75, n - 1)
        dt.js("hv.anim.loop = false; document.getElementById('play').click()")
        ok = dt.wait(f"hv.frame >= {want} || hv.anim.skipped > 0 || !!hv.anim.error", 120, f"{frag} at frame {want}")
        frame, skipped, err = dt.js("[hv.frame, hv.anim.skipped, String(hv.anim.error || '')]")
        check(ok and frame >= want and not skipped and not err,
              f"{frag} at {w}x{h}: played to frame {frame} of {n} (want >= {want}), {skipped} skipped, error '{err}'")
        if dt.js("hv.playing"):
            dt.js("document.getElementById('play').click()")


def main():
    hv, src = os.path.realpath(sys.argv[1]), os.path.realpath(sys.argv[2])
    shots = os.path.realpath(sys.argv[sys.argv.index("--screenshots") + 1]) if "--screenshots" in sys.argv else None

    def body(dt, base, scenes, tmp):
        test_compare(dt, hv, base, scenes, tmp)
        if has_gl(hv, tmp):
            test_play_through(dt, hv, base)
            test_undecodable(dt, base)
            test_present_anim(dt, base, shots)
    rc = bt.run_session(hv, src, "hystviz-lecture-", body)
    if rc == 0:
        print("all lecture tests passed")
    return rc


if __name__ == "__main__":
    sys.exit(main())
