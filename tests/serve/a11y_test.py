#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""tests/serve/a11y_test.py HYSTVIZ SCENES_DIR [--screenshots DIR]

Issue 38 item 6 in chromium (headless, DevTools, browser_test.py's helpers;
every wait has a deadline): the live page of `hystviz serve` and the pages
`hystviz export` writes, as a keyboard and a screen reader meet them.

- names: in chromium's accessibility tree (`Accessibility.getFullAXTree`)
  every interactive node (slider, button, checkbox, link, combobox, textbox,
  ...) that is not ignored has a non-empty name; the figure is one node of
  role image whose name is the SVG's <title> (else the scene's caption) and
  whose description is the SVG's <desc> where it has one; sliders are named
  with the parameter's symbol and unit and say their value (aria-valuetext);
  a pin's x is "remove pin σ0 = ...";
- contrast: every visible text (text nodes, and the text of inputs and
  selects) has a WCAG contrast ratio >= 4.5 against its effective background
  (its own and its ancestors' background colours composited over white, the
  ancestors' opacity applied), >= 3 for large text (>= 24 px, or >= 18.66 px
  bold); in the default and the slides theme, in the presentation view, with
  a pin, an error and the key list shown; disabled controls are exempt (WCAG
  1.4.3); SVG figures' own text is the renderer's;
- the keyboard: Tab from the top reaches the skip link first; following it
  (Enter), a control within 3 presses; Tab goes on through the controls, then
  the figure, then the catalogue, and on to the end of the page and round to
  the skip link again (no trap); each element reached has a focus ring of at
  least 2 px whose colour is >= 3:1 against what it is drawn on;
- status messages: an error and a frame's note reach a live region that is
  always in the page (assertive for errors, polite for notes);
- the exported pages (a grid of Fig. 15; an animation where hystviz-animate
  can render): the same names, contrast (default, dark page, presentation
  view) and skip link.

--screenshots DIR: PNGs at 1024x768 and 1920x1080 with the focus on a
control (default, slides theme, presentation view, export).
Exit 77 (SKIP) where chromium is absent (FAIL under CI=true).
"""
import base64
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import browser_test as bt  # noqa: E402
from browser_test import check  # noqa: E402

F15 = "fig15_minor_loop_ex4"
ANIM_SCENE = "anim_minor_loop_ex4.scene"

# In the page: contrast of every visible text, the focus ring of an element,
# where the focus is.  window.a11y, defined once per document.
A11Y_JS = r"""(() => { if (window.a11y) return true;
const parse = s => {
  const m = /rgba?\(([^)]*)\)/.exec(s || '');
  if (!m) return null;
  const p = m[1].split(/[\s,\/]+/).filter(Boolean).map(Number);
  return [p[0], p[1], p[2], p.length > 3 ? p[3] : 1];
};
const over = (top, bot) => [0, 1, 2].map(k => top[k] * top[3] + bot[k] * (1 - top[3])).concat([1]);
const lin = v => { v /= 255; return v <= 0.03928 ? v / 12.92 : Math.pow((v + 0.055) / 1.055, 2.4); };
const lum = c => 0.2126 * lin(c[0]) + 0.7152 * lin(c[1]) + 0.0722 * lin(c[2]);
const ratio = (a, b) => { const x = lum(a), y = lum(b); return (Math.max(x, y) + 0.05) / (Math.min(x, y) + 0.05); };
// e's background: its own and its ancestors' colours, composited from the first opaque one, over white
function background(e) {
  const layers = [];
  for (let n = e; n && n.nodeType === 1; n = n.parentElement) {
    const c = parse(getComputedStyle(n).backgroundColor);
    if (c && c[3] > 0) { layers.push(c); if (c[3] >= 1) break; }
  }
  let bg = [255, 255, 255, 1];
  for (let k = layers.length - 1; k >= 0; k--) bg = over(layers[k], bg);
  return bg;
}
function opacity(e) { let o = 1; for (let n = e; n && n.nodeType === 1; n = n.parentElement) o *= +getComputedStyle(n).opacity; return o; }
const hex = c => '#' + c.slice(0, 3).map(v => Math.round(v).toString(16).padStart(2, '0')).join('');
function where(e) {
  let s = e.tagName.toLowerCase() + (e.id ? '#' + e.id : '') + (e.className && typeof e.className === 'string' ? '.' + e.className.trim().split(/\s+/).join('.') : '');
  if (e.parentElement && e.parentElement !== document.body && !e.id) s = where(e.parentElement) + ' > ' + s;
  return s;
}
// the contrast of the text drawn by e (colour over its background, its opacity applied)
function measure(e, text) {
  const cs = getComputedStyle(e), bg = background(e);
  let fg = parse(cs.color);
  if (!fg) return null;
  fg = over([fg[0], fg[1], fg[2], fg[3] * opacity(e)], bg);
  const px = parseFloat(cs.fontSize), bold = (+cs.fontWeight || 400) >= 700;
  const large = px >= 24 || (px >= 18.66 && bold);
  const r = ratio(fg, bg);
  return { text: text.trim().slice(0, 40), where: where(e), fg: hex(fg), bg: hex(bg), ratio: +r.toFixed(2), need: large ? 3 : 4.5, px };
}
function shown(rects) {
  const W = document.documentElement.scrollWidth, H = document.documentElement.scrollHeight;
  return Array.from(rects).some(r => r.width > 1 && r.height > 1 && r.right + scrollX > 0 && r.bottom + scrollY > 0
    && r.left + scrollX < W && r.top + scrollY < H);
}
function exempt(e) {
  return !!e.closest('svg, option, :disabled, script, style, noscript, template');
}
function contrast() {
  const out = [], walk = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
  const range = document.createRange();
  let disabled = 0;
  for (let t = walk.nextNode(); t; t = walk.nextNode()) {
    if (!t.nodeValue.trim()) continue;
    const e = t.parentElement;
    if (!e || e.closest('svg, option, script, style, noscript, template')) continue;
    if (!e.checkVisibility({ visibilityProperty: true, opacityProperty: true })) continue;
    range.selectNodeContents(t);
    if (!shown(range.getClientRects())) continue;
    if (exempt(e)) { disabled++; continue; }
    const m = measure(e, t.nodeValue);
    if (m) out.push(m);
  }
  for (const e of document.querySelectorAll('input[type=text], select')) {
    if (!e.checkVisibility({ visibilityProperty: true, opacityProperty: true }) || !shown(e.getClientRects())) continue;
    if (exempt(e)) { disabled++; continue; }
    const text = e.tagName === 'SELECT' ? (e.selectedOptions[0] || {}).textContent || '' : e.value;
    if (!text.trim()) continue;
    const m = measure(e, text);
    if (m) out.push(m);
  }
  out.sort((a, b) => a.ratio / a.need - b.ratio / b.need);
  return { n: out.length, disabled, fails: out.filter(m => m.ratio < m.need), lowest: out.slice(0, 4),
    of: sel => out.filter(m => m.where.includes(sel)) };
}
// the focused element: where it is, and its ring (outline) against what the ring is drawn on
function focused() {
  const e = document.activeElement;
  if (!e || e === document.body || e === document.documentElement) return { body: true };
  const cs = getComputedStyle(e), w = parseFloat(cs.outlineWidth) || 0, off = parseFloat(cs.outlineOffset) || 0;
  const col = parse(cs.outlineColor), on = off < 0 ? background(e) : background(e.parentElement || e);
  const region = e.closest('.skip') ? 'skip' : e.closest('#controls, #anim, form#controls, #presets, #pins') ? 'controls'
    : e.closest('#figure, #figbox') ? 'figure' : e.closest('nav') ? 'catalogue' : e.closest('header') ? 'header' : 'other';
  const b = e.getBoundingClientRect();
  return { where: where(e), region, tag: e.tagName, type: e.type || '', key: e.dataset.key || '',
    ring: cs.outlineStyle !== 'none' && w >= 2 && col && col[3] > 0 ? +ratio(over(col, on), on).toFixed(2) : 0,
    ringWidth: w, ringColor: cs.outlineColor, on: hex(on),
    inView: b.width > 0 && b.height > 0 && b.bottom > 0 && b.right > 0 && b.top < innerHeight && b.left < innerWidth };
}
window.a11y = { contrast: () => { const c = contrast(); delete c.of; return c; },
  of: sel => contrast().of(sel), focused, ratio: (a, b) => ratio(parse(a), parse(b)) };
return true; })()"""

INTERACTIVE = {"slider", "button", "checkbox", "link", "combobox", "textbox", "spinbutton", "searchbox",
               "switch", "radio", "menuitem", "tab", "listbox", "PopUpButton", "ToggleButton", "disclosuretriangle"}


def viewport(dt, w, h):
    dt.call("Emulation.setDeviceMetricsOverride", width=w, height=h, deviceScaleFactor=1, mobile=False)


def open_scene(dt, base, frag, what):
    dt.call("Page.navigate", url="about:blank")
    dt.call("Page.navigate", url=base + "#" + frag)
    scene = frag.split("?")[0]
    ok = dt.wait(f"window.hv && hv.info && hv.info.file === '{scene}' && hv.renders >= 1 && hv.svg "
                 "&& !hv.inflight && !hv.pending", 60, what)
    dt.js(A11Y_JS)
    return ok


def backend_id(dt, expr):
    r = dt.call("Runtime.evaluate", expression=expr)
    oid = r.get("result", {}).get("objectId")
    if not oid:
        return None
    return dt.call("DOM.describeNode", objectId=oid)["node"]["backendNodeId"]


def ax_tree(dt, what):
    """Every interactive node not ignored has a name: {role: count}, and the
    nodes by their DOM node (backendDOMNodeId)."""
    nodes = dt.call("Accessibility.getFullAXTree")["nodes"]
    counts, nameless, by_dom = {}, [], {}
    for n in nodes:
        if "backendDOMNodeId" in n:
            by_dom[n["backendDOMNodeId"]] = n
        if n.get("ignored"):
            continue
        role = n.get("role", {}).get("value", "")
        if role not in INTERACTIVE:
            continue
        name = str(n.get("name", {}).get("value", "")).strip()
        counts[role] = counts.get(role, 0) + 1
        if not name:
            nameless.append((role, n.get("backendDOMNodeId")))
    where = []
    for role, bid in nameless[:5]:
        try:
            d = dt.call("DOM.describeNode", backendNodeId=bid)["node"]
            where.append(f"{role} <{d.get('localName')} {' '.join(d.get('attributes', [])[:6])}>")
        except Exception:  # noqa: BLE001 (a description for the message only)
            where.append(role)
    total = sum(counts.values())
    check(total > 0 and not nameless, f"{what}: {total} interactive nodes in the accessibility tree "
          f"({', '.join(f'{v} {k}' for k, v in sorted(counts.items()))}), {len(nameless)} without a name"
          + (f": {where}" if where else ""))
    return by_dom, counts


def prop(node, name):
    for p in node.get("properties", []):
        if p.get("name") == name:
            return p.get("value", {}).get("value")
    return None


def figure_node(dt, by_dom, sel, what):
    bid = backend_id(dt, f"document.querySelector('{sel}')")
    n = by_dom.get(bid) if bid else None
    role = n and n.get("role", {}).get("value")
    name = n and str(n.get("name", {}).get("value", ""))
    desc = n and str(n.get("description", {}).get("value", ""))
    check(n is not None and not n.get("ignored") and role == "image" and name.strip() != "",
          f"{what}: the figure is one node of role image with a name: {role}, '{(name or '')[:90]}'")
    return name or "", desc or ""


def contrast(dt, what, least=10):
    c = dt.js("a11y.contrast()")
    low = ", ".join(f"'{m['text']}' {m['ratio']}:1 ({m['fg']} on {m['bg']})" for m in c["lowest"][:3])
    check(c["n"] >= least and not c["fails"], f"{what}: {c['n']} texts measured, {len(c['fails'])} below WCAG AA"
          + (f": {[(m['text'], m['where'][-60:], m['ratio'], m['fg'], m['bg']) for m in c['fails'][:6]]}" if c["fails"]
             else f"; lowest {low}") + (f"; {c['disabled']} in disabled controls (exempt)" if c["disabled"] else ""))
    return c


def tab(dt, shift=False):
    for kind in ("rawKeyDown", "keyUp"):
        dt.call("Input.dispatchKeyEvent", type=kind, key="Tab", code="Tab", windowsVirtualKeyCode=9,
                modifiers=8 if shift else 0)
    return dt.js("a11y.focused()")


def enter(dt):
    dt.call("Input.dispatchKeyEvent", type="rawKeyDown", key="Enter", code="Enter", windowsVirtualKeyCode=13)
    dt.call("Input.dispatchKeyEvent", type="char", key="Enter", code="Enter", text="\r", windowsVirtualKeyCode=13)
    dt.call("Input.dispatchKeyEvent", type="keyUp", key="Enter", code="Enter", windowsVirtualKeyCode=13)


def from_top(dt):
    """The focus at the top of the document, as after a page load: on an
    element put before everything (focusable by script only, tabindex -1), so
    that the next Tab goes to the page's first focusable element (blur() would
    leave chromium's starting point where the focus was)."""
    dt.js("""(() => { let t = document.getElementById('a11y-top');
        if (!t) { t = document.createElement('span'); t.id = 'a11y-top'; t.tabIndex = -1; document.body.prepend(t); }
        t.focus(); window.scrollTo(0, 0); return true; })()""")


def keyboard(dt, what, controls_first=True, order=("controls", "figure", "catalogue"), limit=400):
    """Tab from the top: the skip link first; followed, a control within 3
    presses; then every element in order, each with a ring, round to the top."""
    from_top(dt)
    f = tab(dt)
    check(f.get("region") == "skip" and f.get("ring", 0) >= 3 and f.get("inView"),
          f"{what}: the first Tab reaches the skip link, shown, with a focus ring ({f.get('where')}, ring {f.get('ring')}:1)")
    enter(dt)
    dt.wait("document.activeElement && document.activeElement.id !== 'skip'", 5, "the skip link followed")
    presses = None
    for k in range(1, 4):
        f = tab(dt)
        if f.get("region") == "controls" and f.get("tag") in ("INPUT", "BUTTON", "SELECT"):
            presses = k
            break
    check(presses is not None, f"{what}: after the skip link, a control within 3 Tab presses ({presses}: {f.get('where')})")
    # the whole sequence from the top
    from_top(dt)
    seen, first, bad_ring, hidden = [], {}, [], []
    for k in range(limit):
        f = tab(dt)
        if f.get("body") or (k > 0 and f.get("region") == "skip"):
            break
        seen.append(f["where"])
        first.setdefault(f["region"], k)
        if f["ring"] < 3:
            bad_ring.append((f["where"][-50:], f["ring"], f["ringColor"], f["on"]))
        if not f["inView"]:
            hidden.append(f["where"][-50:])
    n = len(seen)
    check(n < limit - 1, f"{what}: Tab goes through {n} elements and out of the page (no trap)")
    regions = [r for r in order if r in first]
    check(regions == list(order) and [first[r] for r in regions] == sorted(first[r] for r in regions),
          f"{what}: the Tab order reaches {' → '.join(order)} in that order (first at press "
          + ", ".join(f"{r} {first.get(r)}" for r in order) + ")")
    check(not bad_ring, f"{what}: each of the {n} elements Tab reaches shows a focus ring >= 3:1"
          + (f"; {len(bad_ring)} do not: {bad_ring[:5]}" if bad_ring else ""))
    check(not hidden, f"{what}: each element Tab reaches is scrolled into view" + (f"; not: {hidden[:5]}" if hidden else ""))
    # and back: Shift+Tab from the first control reaches the skip link's neighbourhood, not a trap
    return first


def shot(dt, shots, name):
    if not shots:
        return
    data = dt.call("Page.captureScreenshot", format="png")
    path = os.path.join(shots, name + ".png")
    with open(path, "wb") as f:
        f.write(base64.b64decode(data["data"]))
    print(f"   screenshot: {path}")


def focus_control(dt):
    """The focus on the first slider, by the keyboard (skip link, Tab...)."""
    from_top(dt)
    tab(dt)
    enter(dt)
    for _ in range(30):
        f = tab(dt)
        if f.get("type") == "range":
            return f
    return f


# ---- the live page ---------------------------------------------------------------

def test_names(dt, base):
    viewport(dt, 1400, 1000)
    check(open_scene(dt, base, F15 + ".scene", "Fig. 15"), "Fig. 15 opens")
    dt.js("addPin()")
    dt.js("""(() => { const r = document.querySelector('input[type=range][data-key="model.sigma0"]');
        r.value = 700; r.dispatchEvent(new Event('input')); r.dispatchEvent(new Event('change')); })()""")
    bt.settle(dt)
    dt.js("addPin()")
    by_dom, counts = ax_tree(dt, "Fig. 15 with two pins")
    check(counts.get("slider", 0) >= 5 and counts.get("button", 0) >= 10 and counts.get("link", 0) >= 20,
          f"... sliders, buttons and the catalogue's links are among them: {counts}")
    name, desc = figure_node(dt, by_dom, "#figure", "Fig. 15")
    # the server's SVG (the page takes its <title> out of its own copy once read)
    svg_title, svg_desc = (x.strip() for x in dt.js("""(() => { const d = new DOMParser().parseFromString(hv.svg, 'image/svg+xml');
        return [(d.querySelector('svg > title') || {}).textContent || '', (d.querySelector('svg > desc') || {}).textContent || '']; })()"""))
    caption = dt.js("document.getElementById('caption').textContent").strip()
    want = svg_title or caption
    check(want and name.startswith(want) and "pinned for comparison: σ0 = " in name,
          f"the figure's name is the SVG's {'<title>' if svg_title else 'caption (the SVG has no <title>)'}, "
          f"then the pins: '{name[:120]}…'")
    check(desc == svg_desc if svg_desc else True,
          "the figure's description is the SVG's <desc>" if svg_desc else "(the SVG has no <desc>: no description)")
    # an SVG with <title> and <desc> (as the renderer writes them once it does): the page says them
    got = dt.js("""(() => { const f = document.getElementById('figure'), svg = f.querySelector('svg');
        const NS = 'http://www.w3.org/2000/svg', t = document.createElementNS(NS, 'title'), d = document.createElementNS(NS, 'desc');
        t.textContent = 'A test title'; d.textContent = 'A test description: three series';
        svg.prepend(t, d); labelFigure();
        const r = [f.getAttribute('aria-label'), document.getElementById(f.getAttribute('aria-describedby') || 'none')];
        return [r[0], r[1] && r[1].textContent, !!svg.querySelector('title')]; })()""")
    check(got[0].startswith("A test title;") and got[1] == "A test description: three series" and not got[2],
          f"with an SVG <title> and <desc>, the figure is named by the title (taken out of the inline copy: no "
          f"tooltip) and described by the desc: {got}")
    got = dt.js("""(() => { const f = document.getElementById('figure'), NS = 'http://www.w3.org/2000/svg';
        const svg = f.querySelector('svg'), ds = [...svg.querySelectorAll('desc')];
        ds.forEach(d => d.remove()); labelFigure(); const r = f.getAttribute('aria-describedby');
        for (const d of ds.reverse()) svg.prepend(d);
        labelFigure();
        return r; })()""")
    check(got == "caption", f"named by its <title> with no <desc>, the figure is described by the caption: {got}")
    by_dom, _ = ax_tree(dt, "Fig. 15, its SVG given a <title> and <desc>")
    name, desc = figure_node(dt, by_dom, "#figure", "Fig. 15 with <title>")
    check(name.startswith("A test title") and desc == "A test description: three series",
          f"... and chromium's tree says them: name '{name[:40]}', description '{desc}'")
    # sliders: symbol and unit, the value as text; pins' x
    s = dt.js("""(() => { const r = document.querySelector('input[type=range][data-key="model.sigma0"]');
        return [r.getAttribute('aria-label'), r.getAttribute('aria-valuetext'), hv.sets['model.sigma0'] || ctlOf('model.sigma0').value,
                ctlOf('model.sigma0').unit]; })()""")
    check(s[0].startswith("σ0") and (not s[3] or s[0].endswith(")")) and s[1].startswith(str(s[2])),
          f"the σ0 slider is named '{s[0]}' and says its value '{s[1]}' (not its position)")
    x = dt.js("Array.from(document.querySelectorAll('.pinchip button')).map(b => b.getAttribute('aria-label'))")
    check(len(x) == 2 and x[0].startswith("remove pin σ0 = 6") and x[1].startswith("remove pin σ0 = "),
          f"the pins' × buttons are named: {x}")
    # a figure whose parameters have units (Bouc-Wen: N, mm, s): each slider says its unit
    BW = "bw_fig1a_quasistatic_loop"
    check(open_scene(dt, base, BW + ".scene", BW), f"{BW} opens")
    u = dt.js("""hv.info.controls.filter(c => c.unit).map(c => {
        const r = document.querySelector('input[type=range][data-key="' + c.key + '"]');
        return [c.key, c.unit, r.getAttribute('aria-label'), r.getAttribute('aria-valuetext')]; })""")
    bad = [x for x in u if not (x[2].endswith(")") and "(" in x[2] and x[3].split(" ", 1)[-1] == x[2][x[2].rindex("(") + 1:-1])]
    check(u and not bad, f"{BW}: {len(u)} sliders with a unit, each named with it and saying it with the value "
          f"(e.g. {u[0][2:] if u else None})" + (f"; not: {bad[:3]}" if bad else ""))


def set_sigma1(dt, v):
    dt.js(f"""(() => {{ const b = document.querySelector('input[type=text][data-key="model.sigma1"]');
        b.value = '{v}'; b.dispatchEvent(new Event('change')); }})()""")
    if v < 0:
        dt.wait("hv.error !== null && !hv.inflight", 20, "the error")
    else:
        bt.settle(dt)


def test_contrast(dt, base, shots):
    for w, h in ((1024, 768), (1920, 1080)):
        viewport(dt, w, h)
        check(open_scene(dt, base, F15 + ".scene", f"Fig. 15 at {w}x{h}"), f"Fig. 15 opens at {w}x{h}")
        if w == 1024:
            file6 = dt.js("a11y.of('span.file')")
            cap = [m for m in dt.js("a11y.of('nav')") if "small" in m["where"]]
            if file6 and cap:
                print(f"   'file: 6' {file6[0]['ratio']}:1 ({file6[0]['fg']} on {file6[0]['bg']}); catalogue captions "
                      f"{min(m['ratio'] for m in cap)}:1 and more")
        dt.js("addPin()")
        for theme in ("default", "slides"):
            if theme == "slides":
                dt.js("setTheme(true)")
                dt.wait("document.body.classList.contains('slides') && !hv.inflight && !hv.pending", 20, "slides")
            # an error next to a control and in the message box; the key list open
            set_sigma1(dt, -1)
            dt.js("toggleKeys(true)")
            contrast(dt, f"{w}x{h}, {theme} theme (a pin, an error, the keys shown)")
            dt.js("setPresent(true)")
            contrast(dt, f"{w}x{h}, {theme} theme, presentation view (a pin, an error, the keys shown)")
            dt.js("toggleKeys(false)")
            set_sigma1(dt, 1)
            # as a person sees it: the focus on a slider, by the keyboard
            for present in (True, False):
                dt.js(f"setPresent({'true' if present else 'false'})")
                f = focus_control(dt)
                tag = ("present-" if present else "page-") + theme
                check(f.get("type") == "range" and f.get("ring", 0) >= 3, f"{w}x{h} {tag}: a slider has the focus "
                      f"by the keyboard, with a ring {f.get('ring')}:1 ({f.get('ringColor')} on {f.get('on')})")
                shot(dt, shots, f"a11y-{w}x{h}-{tag}")
        dt.js("setTheme(false)")
        bt.settle(dt)


def test_anim(dt, base, hv, tmp):
    """An animation scene: its player's controls are named, its text is
    legible in both themes and the presentation view (the frames need GL; the
    controls and their text do not)."""
    viewport(dt, 1024, 768)
    dt.call("Page.navigate", url="about:blank")
    dt.call("Page.navigate", url=base + "#" + ANIM_SCENE)
    ok = dt.wait(f"window.hv && hv.info && hv.info.file === '{ANIM_SCENE}' && hv.info.anim && !hv.frameInflight "
                 "&& document.getElementById('frameinfo').textContent !== ''", 90, "the animation scene")
    dt.js(A11Y_JS)
    check(ok, "the animation scene opens")
    by_dom, counts = ax_tree(dt, "an animation scene")
    check(counts.get("combobox", 0) >= 1 and counts.get("checkbox", 0) >= 1,
          f"... the player's speed (combobox) and loop (checkbox) among them: {counts}")
    lab = dt.js("[document.getElementById('frame').getAttribute('role'), document.getElementById('frame').getAttribute('aria-label'), "
                "document.getElementById('scrub').getAttribute('aria-valuetext')]")
    check(lab[0] == "img" and lab[1].startswith("animation ") and (lab[2] or "").startswith("frame ")
          or "could not" in dt.js("document.getElementById('frameinfo').textContent"),
          f"the clip's canvas is an image named with the frame shown, the scrubber says the frame: {lab}")
    # a frame's note reaches the polite live region
    dt.js("frameWarn('frame 5 skipped: it came from the server, but this browser cannot decode its PNG (test)')")
    said = dt.js("document.getElementById('say').textContent")
    check("frame 5 skipped" in said, f"a frame's note is said in the polite live region: '{said[:60]}'")
    for theme in ("default", "slides"):
        if theme == "slides":
            dt.js("setTheme(true)")
            dt.wait("document.body.classList.contains('slides') && !hv.inflight && !hv.pending", 20)
        contrast(dt, f"the animation scene, {theme} theme")
        dt.js("setPresent(true)")
        contrast(dt, f"the animation scene, {theme} theme, presentation view")
        dt.js("setPresent(false)")
    dt.js("setTheme(false); frameWarn('')")


def test_keyboard(dt, base, shots):
    viewport(dt, 1024, 768)
    check(open_scene(dt, base, F15 + ".scene", "Fig. 15"), "Fig. 15 opens")
    if shots:  # the skip link and the figure as the keyboard shows them
        from_top(dt)
        tab(dt)
        shot(dt, shots, "a11y-1024x768-skip")
        dt.js("document.getElementById('figure').focus()")
        shot(dt, shots, "a11y-1024x768-figure")
    keyboard(dt, "Fig. 15 at 1024x768")
    dt.js("setTheme(true)")
    dt.wait("document.body.classList.contains('slides') && !hv.inflight && !hv.pending", 20, "slides")
    keyboard(dt, "Fig. 15, slides theme")
    dt.js("setTheme(false)")
    check(open_scene(dt, base, F15 + ".scene?view=present", "the presentation view"), "the presentation view opens")
    keyboard(dt, "Fig. 15, presentation view", order=("controls", "figure"))
    # the sliders still step with ← →, and Tab leaves them (no trap): checked above;
    # live regions: an error is said at once (assertive), and stays in the tree
    dt.js("""(() => { const b = document.querySelector('input[type=text][data-key="model.sigma1"]');
        b.value = '-1'; b.dispatchEvent(new Event('change')); })()""")
    dt.wait("hv.error !== null && !hv.inflight", 20, "the error")
    said = dt.js("[document.getElementById('alert').textContent, hv.error]")
    check(said[1] and said[0].strip() == said[1].strip(), f"an error is said in the assertive live region: '{said[0][:60]}'")
    by_dom, _ = ax_tree(dt, "the presentation view with an error")
    for sel, want in (("#alert", "assertive"), ("#say", "polite")):
        n = by_dom.get(backend_id(dt, f"document.querySelector('{sel}')"))
        check(n is not None and not n.get("ignored") and prop(n, "live") == want,
              f"{sel} is a live region ({want}) in the accessibility tree: {n and prop(n, 'live')}")
    dt.js("""(() => { const b = document.querySelector('input[type=text][data-key="model.sigma1"]');
        b.value = '1'; b.dispatchEvent(new Event('change')); })()""")
    bt.settle(dt)


# ---- the exported pages ------------------------------------------------------------

def export(hv, args):
    return subprocess.run([hv, "export"] + args, capture_output=True, text=True, timeout=300)


def test_export(dt, hv, scenes, tmp, shots):
    page = os.path.join(tmp, "grid.html")
    r = export(hv, [os.path.join(scenes, F15 + ".scene"), "--grid", "model.sigma0=1,6,20", "--grid", "input.umin2=0.2,0.5",
                    "-o", page, "-q"])
    check(r.returncode == 0, "export of a 3 x 2 grid of Fig. 15 " + r.stderr.strip()[:200])
    if r.returncode:
        return
    for w, h in ((1024, 768), (1920, 1080)):
        viewport(dt, w, h)
        dt.call("Page.navigate", url="about:blank")
        dt.call("Page.navigate", url="file://" + page)
        check(dt.wait("window.hv && hv.ready && hv.svg", 60, "the export"), f"the exported page opens at {w}x{h}")
        dt.js(A11Y_JS)
        dt.js("document.dispatchEvent(new KeyboardEvent('keydown', {key: 'g'}))")  # a pin
        if w == 1024:
            by_dom, counts = ax_tree(dt, "the exported grid")
            check(counts.get("slider", 0) == 2, f"... its two sliders among them: {counts}")
            name, _ = figure_node(dt, by_dom, "#figure", "the exported grid")
            title = dt.js("(new DOMParser().parseFromString(hv.svg, 'image/svg+xml').querySelector('svg > title') || {}).textContent || ''")
            check(name.startswith(title.strip()) if title.strip() else name.startswith("fig15_minor_loop_ex4, σ0 = 1, u_min,2 = "),
                  f"the exported figure's name: '{name[:100]}'")
            s = dt.js("Array.from(document.querySelectorAll('input[type=range]')).map(r => [r.getAttribute('aria-label'), r.getAttribute('aria-valuetext')])")
            check(s and s[0][0].startswith("σ0") and (s[0][1] or "").startswith("1"),
                  f"the exported sliders are named with symbol and unit and say their value: {s}")
            x = dt.js("Array.from(document.querySelectorAll('.pinchip button')).map(b => b.getAttribute('aria-label'))")
            check(len(x) == 1 and x[0].startswith("remove pin σ0 = 1"), f"the pin's × is named: {x}")
            keyboard(dt, "the exported grid", order=("controls", "figure"))
        contrast(dt, f"the exported grid at {w}x{h}")
        dt.js("document.dispatchEvent(new KeyboardEvent('keydown', {key: 't'}))")
        contrast(dt, f"the exported grid at {w}x{h}, dark page")
        f = focus_control(dt)
        check(f.get("type") == "range" and f.get("ring", 0) >= 3, f"export {w}x{h}, dark page: a slider has the "
              f"focus, ring {f.get('ring')}:1")
        shot(dt, shots, f"a11y-export-{w}x{h}-dark")
        dt.js("document.dispatchEvent(new KeyboardEvent('keydown', {key: 'p'}))")
        contrast(dt, f"the exported grid at {w}x{h}, dark page, presentation view")
        dt.js("document.dispatchEvent(new KeyboardEvent('keydown', {key: 't'}))")
        contrast(dt, f"the exported grid at {w}x{h}, presentation view")
        focus_control(dt)
        shot(dt, shots, f"a11y-export-{w}x{h}-present")
    # an animation, where hystviz-animate renders here
    r = subprocess.run([hv, "animate", "minor-loop-ex4", "--frames", "0:1", "-o", os.path.join(tmp, "gl"), "--quiet"],
                       capture_output=True, text=True, timeout=120)
    if r.returncode != 0:
        print("SKIP (exported animation): hystviz-animate cannot render here: " + r.stderr.strip()[:200])
        return
    page = os.path.join(tmp, "anim.html")
    r = export(hv, ["minor-loop-ex4", "--size", "160x90", "-j", "2", "-o", page, "-q"])
    check(r.returncode == 0, "export of a built-in animation at 160x90 " + r.stderr.strip()[:200])
    if r.returncode:
        return
    viewport(dt, 1024, 768)
    dt.call("Page.navigate", url="about:blank")
    dt.call("Page.navigate", url="file://" + page)
    check(dt.wait("window.hv && hv.ready && hv.frame >= 0", 60, "the exported animation"), "the exported animation opens")
    dt.js(A11Y_JS)
    by_dom, counts = ax_tree(dt, "the exported animation")
    name, _ = figure_node(dt, by_dom, "#figure", "the exported animation")
    check("frame 1 of" in name, f"the exported frame is named with its number: '{name}'")
    keyboard(dt, "the exported animation", order=("controls", "figure"))
    contrast(dt, "the exported animation", 5)
    dt.js("document.dispatchEvent(new KeyboardEvent('keydown', {key: 'p'}))")
    contrast(dt, "the exported animation, presentation view", 5)


def main():
    hv, src = os.path.realpath(sys.argv[1]), os.path.realpath(sys.argv[2])
    shots = os.path.realpath(sys.argv[sys.argv.index("--screenshots") + 1]) if "--screenshots" in sys.argv else None

    def body(dt, base, scenes, tmp):
        dt.call("DOM.enable")
        dt.call("Accessibility.enable")
        test_names(dt, base)
        test_keyboard(dt, base, shots)
        test_contrast(dt, base, shots)
        test_anim(dt, base, hv, tmp)
        test_export(dt, hv, scenes, tmp, shots)
    rc = bt.run_session(hv, src, "hystviz-a11y-", body)
    if rc == 0:
        print("all accessibility tests passed")
    return rc


if __name__ == "__main__":
    sys.exit(main())
