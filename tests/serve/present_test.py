#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""tests/serve/present_test.py HYSTVIZ SCENES_DIR [--screenshots DIR]

The presentation view, links and controls of `hystviz serve` in chromium
(headless, over the DevTools protocol, with browser_test.py's helpers):

- at 1024x768 in the presentation view (URL flag view=present, and the p
  key), the figure's and the main sliders' boxes lie inside the viewport and
  the figure takes at least 60 % of it; at 1920x1080 too;
- the arrow keys step the focused slider and the figure follows;
- a URL with values reproduces the SVG of `hystviz render --set` byte for
  byte; back walks to the previous values;
- keys 1, 2, 3 switch to the presets of Fig. 15's scene, whose figures are
  those of the scene files of Figs. 15, 16 and 17, byte for byte;
- a link with frame=N opens an animation on frame N;
- Fig. 2 (an input-only figure) shows no model control; labels are the
  schema's symbols;
- every slider of Fig. 15 and of bw_fig1a through 26 evenly spaced
  positions (issue 21 counted refusals at 26; 50 took 48 s of CPU) (the page's own value at each position, the others at their
  values) is refused at 0 of them;
- Fig. 4 shows one control per named time scale ([param gamma20], read by
  a loop and its transient), and moving it changes both series (the SVG
  equals `render --set param.gamma20.value=...`);
- pin keeps the curves in a lighter tone under the next figure (its × or
  another scene drops it); a slider's play button moves its value back and
  forth (three new figures within a deadline, one figure request in flight
  at a time, every value inside the slider's domain) until space stops it;
- a decimal comma is read as a point; a value out of its domain gets one
  plain-language line and moves nothing; a refused value's message has no
  "--set" prefix.

--screenshots DIR: PNGs of the presentation view at 1024x768 (both themes).
Exit 77 (SKIP) where chromium is absent (FAIL under CI=true).
"""
import base64
import os
import re
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import browser_test as bt  # noqa: E402
from browser_test import check  # noqa: E402

F15 = "fig15_minor_loop_ex4"


def viewport(dt, w, h):
    dt.call("Emulation.setDeviceMetricsOverride", width=w, height=h, deviceScaleFactor=1, mobile=False)


def open_url(dt, base, frag, what):
    dt.call("Page.navigate", url="about:blank")
    dt.call("Page.navigate", url=base + "#" + frag)
    scene = frag.split("?")[0]
    return dt.wait(f"window.hv && hv.info && hv.info.file === '{scene}' && hv.renders >= 1 && hv.svg "
                   "&& !hv.inflight && !hv.pending", 60, what)


def boxes(dt):
    """The viewport, the figure's box and the visible main sliders' boxes."""
    return dt.js("""(() => {
        const r = e => { const b = e.getBoundingClientRect(); return [b.left, b.top, b.right, b.bottom]; };
        const svg = document.querySelector('#figure svg');
        const main = Array.from(document.querySelectorAll('.ctl.main input[type=range]')).map(e => [e.dataset.key, r(e)]);
        return {w: innerWidth, h: innerHeight, sw: document.documentElement.scrollWidth,
                sh: document.documentElement.scrollHeight, fig: svg ? r(svg) : null, main: main}; })()""")


def inside(b, w, h):
    return b[0] >= 0 and b[1] >= 0 and b[2] <= w + 0.5 and b[3] <= h + 0.5 and b[2] > b[0] and b[3] > b[1]


def test_present(dt, base, shots):
    for w, h in ((1024, 768), (1920, 1080)):
        viewport(dt, w, h)
        check(open_url(dt, base, F15 + ".scene?view=present", "Fig. 15 in the presentation view"),
              f"{w}x{h}: the presentation view opens from the URL flag")
        b = boxes(dt)
        fig = b["fig"]
        keys = [k for k, _ in b["main"]]
        check(keys == ["model.sigma0", "input.umin2"], f"{w}x{h}: the main controls are the scene's: {keys}")
        check(fig is not None and inside(fig, b["w"], b["h"]), f"{w}x{h}: the figure lies inside the viewport: {fig}")
        check(all(inside(r, b["w"], b["h"]) for _, r in b["main"]),
              f"{w}x{h}: every main slider lies inside the viewport: {b['main']}")
        area = (fig[2] - fig[0]) * (fig[3] - fig[1]) / (b["w"] * b["h"]) if fig else 0
        check(area >= 0.6, f"{w}x{h}: the figure takes {100 * area:.0f} % of the viewport (>= 60 %)")
        check(b["sh"] <= b["h"] and b["sw"] <= b["w"], f"{w}x{h}: nothing to scroll ({b['sw']}x{b['sh']})")
        if shots and w == 1024:
            for theme in ("paper", "slides"):
                if theme == "slides":
                    dt.js("setTheme(true)")
                    bt.settle(dt)
                    dt.wait("hv.svg.includes('rgb(10.9') || hv.svg.includes('#1c1f24') || hv.svg.length > 0", 5)
                shot = dt.call("Page.captureScreenshot", format="png")
                path = os.path.join(shots, f"present-{w}x{h}-{theme}.png")
                with open(path, "wb") as f:
                    f.write(base64.b64decode(shot["data"]))
                print(f"   screenshot: {path}")
    # the p key toggles the view, from the ordinary page
    viewport(dt, 1024, 768)
    check(open_url(dt, base, F15 + ".scene", "Fig. 15"), "Fig. 15 opens in the ordinary view")
    check(not dt.js("document.body.classList.contains('present')"), "the ordinary view shows the catalogue")
    dt.js("document.activeElement && document.activeElement.blur && document.activeElement.blur()")
    dt.key("KeyP", "p")
    check(dt.wait("document.body.classList.contains('present') && location.hash.includes('view=present')", 5, "p"),
          "the p key opens the presentation view and the URL says so")
    check(dt.js("getComputedStyle(document.getElementById('catalogue')).display") == "none",
          "the presentation view hides the catalogue")


def key_arrow(dt, right=True):
    code = "ArrowRight" if right else "ArrowLeft"
    for kind in ("rawKeyDown", "keyUp"):
        dt.call("Input.dispatchKeyEvent", type=kind, key=code, code=code,
                windowsVirtualKeyCode=39 if right else 37)


def test_keys_and_links(dt, hv, base, scenes, tmp):
    viewport(dt, 1024, 768)
    check(open_url(dt, base, F15 + ".scene?view=present", "Fig. 15"), "Fig. 15 opens")
    focused = dt.js("document.activeElement && document.activeElement.dataset.key")
    check(focused == "model.sigma0", f"the presentation view focuses the first main slider ({focused})")
    n0 = dt.js("hv.renders")
    key_arrow(dt, True)
    key_arrow(dt, True)
    bt.settle(dt)
    v1 = dt.js("hv.sets['model.sigma0']")
    check(v1 is not None and float(v1) > 6 and dt.js("hv.renders") > n0, f"two → steps move sigma0 from 6 to {v1}")
    key_arrow(dt, False)
    bt.settle(dt)
    v2 = dt.js("hv.sets['model.sigma0']")
    check(v2 is not None and 6 < float(v2) < float(v1), f"← steps back: sigma0 = {v2}")
    # the link holds the values: a fresh page from it shows render --set's bytes
    url = dt.js("location.href")
    check(f"model.sigma0={v2}" in url, f"the URL holds the value: {url}")
    frag = url.split("#", 1)[1]
    check(open_url(dt, base, frag, "the link"), "the link opens")
    want = bt.render_svg(hv, os.path.join(scenes, F15 + ".scene"), [f"model.sigma0={v2}"], os.path.join(tmp, "l1"))
    check(dt.js("hv.svg") == want, f"the link's figure == hystviz render --set model.sigma0={v2} (byte for byte)")
    # a link with several values and the slides theme, typed by hand
    sets = ["model.sigma0=60", "input.umin2=0.3", "figure.theme=slides"]
    frag = F15 + ".scene?" + "&".join(sets)
    check(open_url(dt, base, frag, "a hand-written link"), "a hand-written link opens")
    want = bt.render_svg(hv, os.path.join(scenes, F15 + ".scene"), sets, os.path.join(tmp, "l2"))
    check(dt.js("hv.svg") == want, "a link with three values and the slides theme == hystviz render --set ... (bytes)")
    check(dt.js("document.body.classList.contains('slides')"), "the page is dark with the slides theme")
    # back/forward walk through changes
    dt.js("""(() => { const b = document.querySelector('input[type=text][data-key="model.sigma0"]');
        b.value = '100'; b.dispatchEvent(new Event('change')); })()""")
    bt.settle(dt)
    check("model.sigma0=100" in dt.js("location.hash"), "a typed value is in the URL")
    dt.js("history.back()")
    check(dt.wait("hv.sets['model.sigma0'] === '60' && !hv.inflight && !hv.pending", 20, "back"),
          "back restores the previous value")
    bt.settle(dt)
    check(dt.js("hv.svg") == want, "after back the figure is the previous one again")
    dt.js("history.forward()")
    check(dt.wait("hv.sets['model.sigma0'] === '100'", 20, "forward"), "forward restores the typed value")
    bt.settle(dt)
    # a drag (input events, the button still held) is one history entry,
    # written once the slider rests (not at every input event)
    h0 = dt.js("history.length")
    dt.js("""(() => { const r = document.querySelector('input[type=range][data-key="model.sigma0"]');
        for (const p of [300, 320, 340]) { r.value = p; r.dispatchEvent(new Event('input')); } })()""")
    v3 = dt.js("hv.sets['model.sigma0']")
    check(dt.wait(f"location.hash.includes('model.sigma0={v3}')", 10, "the URL once the slider rests"),
          f"the URL holds the dragged value once the slider rests: {v3}")
    check(dt.js("history.length") == h0 + 1, f"... one new history entry for the whole drag ({h0} -> {dt.js('history.length')})")
    dt.js("""document.querySelector('input[type=range][data-key="model.sigma0"]').dispatchEvent(new Event('change'))""")
    bt.settle(dt)


def drawn(svg):
    """An SVG without its <title> and <desc> (the caption's words, not the drawing)."""
    return re.sub(r"\n<(title|desc)>[^<]*</\1>", "", svg or "")


def test_presets(dt, hv, base, scenes, tmp):
    """Figs. 15, 16 and 17 as the presets of one scene: keys 1, 2, 3 show what
    the gallery's three scene files render, byte for byte."""
    viewport(dt, 1024, 768)
    check(open_url(dt, base, F15 + ".scene?view=present", "Fig. 15"), "Fig. 15 opens")
    names = dt.js("hv.info.presets.map(p => p.name)")
    check(names == ["fig15", "fig16", "fig17"], f"the scene's presets: {names}")
    for digit, name, fig in (("2", "fig16", "fig16_minor_loop_ex4_sigma1"), ("3", "fig17", "fig17_minor_loop_ex4_sigma1_umin02"),
                             ("1", "fig15", F15)):
        dt.js("document.activeElement && document.activeElement.blur && document.activeElement.blur()")
        for kind in ("keyDown", "keyUp"):
            dt.call("Input.dispatchKeyEvent", type=kind, key=digit, code="Digit" + digit, text=digit if kind == "keyDown" else "")
        dt.wait(f"hv.preset === '{name}'", 10, f"preset {name}")
        bt.settle(dt)
        want = bt.render_svg(hv, os.path.join(scenes, fig + ".scene"), [], os.path.join(tmp, "p" + digit))
        # the drawing byte for byte; the <title> and <desc> follow each scene file's own caption
        check(drawn(dt.js("hv.svg")) == drawn(want) and f"preset={name}" in dt.js("location.hash"),
              f"key {digit}: preset {name} == hystviz render {fig}.scene (bytes but its <title> and <desc>), "
              "and the URL says so")


def test_frame_link(dt, base):
    """A link with frame=N opens the animation on frame N, and the frame
    scrubbed to is in the URL (skipped where hystviz-animate has no GL)."""
    A = "anim_minor_loop_ex4.scene"
    dt.call("Page.navigate", url="about:blank")
    dt.call("Page.navigate", url=base + "#" + A + "?frame=12")
    if not dt.wait(f"window.hv && hv.info && hv.info.file === '{A}' && hv.info.anim", 60, "the animation"):
        check(False, "the animation scene opens")
        return
    if dt.js("!!hv.info.anim.error"):
        print("SKIP (frame link): " + dt.js("hv.info.anim.error"))
        return
    check(dt.wait("hv.frame === 12", 60, "frame 12"), f"a link with frame=12 opens on frame 12 ({dt.js('hv.frame')})")
    dt.js("document.getElementById('scrub').value = 20; document.getElementById('scrub').dispatchEvent(new Event('input'))")
    check(dt.wait("hv.frame === 20 && location.hash.includes('frame=20')", 60, "frame 20 in the URL"),
          "the frame scrubbed to is in the URL")


def test_controls(dt, base):
    viewport(dt, 1400, 1000)
    check(open_url(dt, base, "fig02_bimodal_input_smooth.scene", "Fig. 2"), "Fig. 2 opens")
    keys = dt.js("hv.info.controls.map(c => c.key)")
    check(keys and not any(k.startswith("model.") for k in keys), f"Fig. 2 (input only) shows no model control: {keys}")
    check(open_url(dt, base, F15 + ".scene", "Fig. 15"), "Fig. 15 opens")
    lab = dt.js("document.querySelector('.ctl[data-key=\"input.umin2\"] label').textContent")
    sub = dt.js("document.querySelector('.ctl[data-key=\"input.umin2\"] label sub').textContent")
    check(lab.startswith("umin,2") and sub == "min,2", f"u_min,2 is typeset with its subscript: '{lab}'")
    tip = dt.js("document.querySelector('.ctl[data-key=\"model.sigma0\"] label').title")
    check(tip.startswith("model.sigma0: bristle stiffness"), f"hover tells the key and its description: '{tip}'")
    # a decimal comma is a point
    dt.js("""(() => { const b = document.querySelector('input[type=text][data-key="model.sigma0"]');
        b.value = '2,5'; b.dispatchEvent(new Event('change')); })()""")
    bt.settle(dt)
    check(dt.js("hv.sets['model.sigma0']") == "2.5" and dt.js("hv.error") is None, "2,5 is read as 2.5")
    # out of the domain: one plain line, nothing moves
    svg, pos = dt.js("hv.svg"), dt.js("document.querySelector('input[type=range][data-key=\"input.umin2\"]').value")
    n = dt.js("hv.renders + hv.seq")
    dt.js("""(() => { const b = document.querySelector('input[type=text][data-key="input.umin2"]');
        b.value = '1.2'; b.dispatchEvent(new Event('change')); })()""")
    msg = dt.js("document.querySelector('.err[data-key=\"input.umin2\"]').textContent")
    check(msg == "u_min,2 must be greater than u_min,1 = 0 and less than u_max,1 = 1",
          f"an out-of-domain value gets one plain line: '{msg}'")
    check(dt.js("hv.renders + hv.seq") == n and dt.js("hv.svg") == svg and
          dt.js("document.querySelector('input[type=range][data-key=\"input.umin2\"]').value") == pos,
          "... and neither the figure nor the slider moved")
    # a value the server refuses (u_max,2 below u_max,1 is caught by the domain; sigma1 < 0 by the schema)
    dt.js("""(() => { const b = document.querySelector('input[type=text][data-key="model.sigma1"]');
        b.value = '-1'; b.dispatchEvent(new Event('change')); })()""")
    dt.wait("hv.error !== null && !hv.inflight", 20, "the error")
    msg = dt.js("document.querySelector('.err[data-key=\"model.sigma1\"]').textContent")
    check(msg and "--set" not in msg, f"the server's message without the --set prefix: '{msg}'")


def test_pin_play(dt, base):
    """Pin keeps the curves under the next figure (its × drops it);
    a slider's play button moves its value back and forth, one request at a
    time, until space stops it, inside the slider's domain."""
    check(open_url(dt, base, F15 + ".scene", "Fig. 15"), "Fig. 15 opens")
    ncurves = dt.js("curvesOf(hv.svg).length")
    dt.js("document.getElementById('pin').click()")
    label = dt.js("document.querySelector('#pins .pinchip') && document.querySelector('#pins .pinchip').textContent")
    check(dt.js("hv.pins.length === 1 && hv.pins[0].curves.length") == ncurves and ncurves > 0
          and label and label.startswith("pin: σ0 = 6"), f"pin keeps the {ncurves} curves shown (its chip says '{label}')")
    dt.js("""(() => { const b = document.querySelector('input[type=text][data-key="model.sigma0"]');
        b.value = '20'; b.dispatchEvent(new Event('change')); })()""")
    check(dt.wait("hv.sets['model.sigma0'] === '20' && !hv.inflight && !hv.pending && hv.error === null", 60,
                  "sigma0 = 20"), "sigma0 = 20 renders")
    ghost = dt.js("""(() => { const svg = document.querySelector('#figure svg'), g = svg.querySelector('g.ghost');
        const first = Array.from(svg.querySelectorAll('path')).find(p => !p.closest('g.ghost')
            && /fill:none/.test(p.getAttribute('style')) && /stroke-linejoin:round/.test(p.getAttribute('style')));
        return g ? [g.querySelectorAll('path').length, g.querySelector('path').getAttribute('style') !== first.getAttribute('style'),
                    !!(g.compareDocumentPosition(first) & Node.DOCUMENT_POSITION_FOLLOWING)] : null; })()""")
    check(ghost is not None and ghost[0] == ncurves and ghost[1] and ghost[2],
          f"after pin and a move the old curves lie in a lighter tone under the new ones: {ghost}")
    check(dt.js("!hv.svg.includes('ghost')"), "... drawn by the page: the server's SVG is unchanged")
    dt.js("document.querySelector('#pins .pinchip button').click()")
    check(dt.js("hv.pins.length === 0 && !document.querySelector('#figure svg g.ghost')"), "its × removes the pin")
    bt.key_focus_body(dt)
    dt.key("KeyG", "g")
    check(dt.js("hv.pins.length === 1"), "key g pins")
    # play sigma0: count the figures that arrive and the requests in flight
    dt.js("""(() => { hv.t = { svgs: new Set(), vals: [], now: 0, max: 0 };
        const f = window.fetch;
        window.fetch = (u, o) => {
            // the figures (not the two renders that find the limits over the slider's range)
            if (typeof u !== 'string' || !u.startsWith('/api/render?') || !u.includes('&page=' + hv.page + '&')) return f(u, o);
            hv.t.now++; hv.t.max = Math.max(hv.t.max, hv.t.now);
            return f(u, o).finally(() => { hv.t.now--; }); };
        document.addEventListener('hv-rendered', () => { hv.t.svgs.add(hv.svg); hv.t.vals.push(+hv.sets['model.sigma0']); });
        document.querySelector('button.playkey[data-key="model.sigma0"]').click(); })()""")
    check(dt.js("hv.sliderPlay && hv.sliderPlay.key") == "model.sigma0", "the play button of sigma0 plays it")
    check(dt.wait("hv.t.svgs.size >= 3", 60, "three figures while playing"),
          f"playing sigma0 shows new figures ({dt.js('hv.t.svgs.size')} distinct SVGs)")
    dt.key("Space", " ")
    check(dt.js("hv.sliderPlay === null"), "space stops the play")
    bt.settle(dt)
    n = dt.js("hv.renders")
    lo, hi, vals = dt.js("ctlOf('model.sigma0').lo"), dt.js("ctlOf('model.sigma0').hi"), dt.js("hv.t.vals")
    v = float(dt.js("hv.sets['model.sigma0']"))
    check(lo <= v <= hi and all(lo <= x <= hi for x in vals),
          f"every value played lies in the slider's domain [{lo}, {hi}]: {vals[:6]}..., stopped at {v}")
    check(dt.js("hv.t.max") == 1, f"never more than one render request in flight ({dt.js('hv.t.max')})")
    dt.js("new Promise(r => setTimeout(r, 300))")
    check(dt.js("hv.renders") == n and not dt.js("hv.inflight"), "stopped: no more renders")
    dt.js("document.querySelector('button.playkey[data-key=\"input.umin2\"]').click()")
    dt.js("document.querySelector('button.playkey[data-key=\"input.umin2\"]').click()")
    check(dt.js("hv.sliderPlay === null"), "a second click on the button stops it")
    bt.settle(dt)


def test_linked(dt, hv, base, scenes, tmp):
    """Fig. 4's time scales are [param] values, each read by a loop and its
    transient: one control per gamma, and moving it moves both series."""
    f4 = "fig04_example1_gamma_loops"
    check(open_url(dt, base, f4 + ".scene", "Fig. 4"), "Fig. 4 opens")
    check(dt.js("hv.pins.length === 0 && !document.querySelector('#figure svg g.ghost')"),
          "another scene drops the pinned curves")
    keys = [k for k in dt.js("hv.info.controls.map(c => c.key)") if "gamma" in k]
    check(keys == ["param.gamma20.value", "param.gamma200.value", "param.gamma2000.value"],
          f"Fig. 4 shows one control per named gamma, none per series: {keys}")
    lab = dt.js("document.querySelector('.ctl[data-key=\"param.gamma20.value\"] label').textContent")
    check(lab.startswith("γ"), f"the parameter's control has the symbol of the keys it feeds: '{lab}'")
    dt.js("""(() => { const b = document.querySelector('input[type=text][data-key="param.gamma20.value"]');
        b.value = '30'; b.dispatchEvent(new Event('change')); })()""")
    check(dt.wait("hv.sets['param.gamma20.value'] === '30' && !hv.inflight && !hv.pending && hv.error === null", 60,
                  "gamma20 = 30"), "typing 30 into gamma20 re-renders")
    scene = os.path.join(scenes, f4 + ".scene")
    got = dt.js("hv.svg")
    check(got == bt.render_svg(hv, scene, ["param.gamma20.value=30"], os.path.join(tmp, "f4a")),
          "the figure == hystviz render --set param.gamma20.value=30 (bytes)")
    lab = 'series.g20.label="\\gamma = 30"'
    both = bt.render_svg(hv, scene, ["series.transient20.gamma=30", "series.g20.gamma=30", lab], os.path.join(tmp, "f4b"))
    one = bt.render_svg(hv, scene, ["series.g20.gamma=30", lab], os.path.join(tmp, "f4c"))
    check(got == both and got != one, "... which moved the loop, its transient and its legend entry (== both series "
          "and the label set to 30, != the loop alone)")


def sweep(dt, base, scene, npos=26, deadline=600):
    """Every slider through npos evenly spaced positions (the others at their
    file values): the value the page would send at each, rendered by serve.
    Two at a time (two page ids of this page load, each asking for the next position when its
    last is answered): serve has at least two render slots (cores + 1), so
    neither waits with nothing running and neither stops the other's render
    (serve_slots.c's preemption would restart the heavy positions, e.g. the
    highest fs and upsample of bw_fig1a, and answer 503 after two restarts);
    serve remembers each page id's last seq, so the ids are new with each scene.
    The page runs the sweep; the test awaits it 20 s at a time (each DevTools
    answer well within a minute), deadline seconds in all."""
    check(open_url(dt, base, scene + ".scene", scene), f"{scene} opens")
    keys = dt.js("hv.info.controls.map(c => c.key)")
    dt.js(f"""(() => {{
        const todo = [], bad = {{}};
        for (const c of hv.info.controls.map(c => ctlOf(c.key)))
            for (let i = 0; i < {npos}; i++) todo.push([c, valueAt(c, Math.round(1000 * i / ({npos} - 1)))]);
        // a 503 is serve's fair share giving the turn to another page: asked
        // again after Retry-After (1 s), as the page does, at most 5 times;
        // a refused value is anything else
        const get = async (url, n) => {{ const r = await fetch(url);
            if (r.status === 503 && n < 5) {{ await new Promise(s => setTimeout(s, 1000)); return get(url, n + 1); }}
            return r; }};
        let seq = 0;
        const worker = async w => {{
            for (let t = todo.shift(); t; t = todo.shift()) {{
                const [c, v] = t;
                const url = '/api/render?' + query() + '&set=' + encodeURIComponent(c.key + '=' + v)
                    + '&fmt=json&seq=' + (++seq) + '&page=sweep' + w + '-' + hv.page;
                const r = await get(url, 0);
                if (r.status !== 200) (bad[c.key] = bad[c.key] || []).push(v + ': ' + ((await r.json()).error || r.status));
            }} }};
        hv.sweepDone = null;
        hv.sweep = Promise.all([worker(0), worker(1)]).then(() => {{ hv.sweepDone = bad; }});
        return todo.length; }})()""")
    t0 = time.monotonic()
    while dt.js("hv.sweepDone") is None and time.monotonic() - t0 < deadline:
        dt.js("Promise.race([hv.sweep, new Promise(r => setTimeout(r, 20000))])")
    refused = dt.js("hv.sweepDone")
    if refused is None:
        check(False, f"{scene}: the sweep of {len(keys)} sliders x {npos} positions ended within {deadline} s")
        return
    total = sum(len(v) for v in refused.values())
    check(total == 0, f"{scene}: {len(keys)} sliders x {npos} positions, {total} refused"
          + (f": {dict((k, (len(v), v[:2])) for k, v in refused.items())}" if refused else ""))


def main():
    hv, src = os.path.realpath(sys.argv[1]), os.path.realpath(sys.argv[2])
    shots = os.path.realpath(sys.argv[sys.argv.index("--screenshots") + 1]) if "--screenshots" in sys.argv else None

    def body(dt, base, scenes, tmp):
        test_present(dt, base, shots)
        test_keys_and_links(dt, hv, base, scenes, tmp)
        test_presets(dt, hv, base, scenes, tmp)
        test_frame_link(dt, base)
        test_controls(dt, base)
        test_pin_play(dt, base)
        test_linked(dt, hv, base, scenes, tmp)
        sweep(dt, base, F15)
        sweep(dt, base, "bw_fig1a_quasistatic_loop")
    rc = bt.run_session(hv, src, "hystviz-present-", body)
    if rc == 0:
        print("all presentation tests passed")
    return rc


if __name__ == "__main__":
    sys.exit(main())
