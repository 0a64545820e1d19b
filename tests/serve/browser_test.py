#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""tests/serve/browser_test.py HYSTVIZ SCENES_DIR [--screenshot PNG] [--bench N]

The page of `hystviz serve` in a real browser: Debian's chromium, headless,
driven over the DevTools protocol (a WebSocket client in the standard
library; no network, no packages).  It drags Fig. 15's sigma0 slider with
mouse events and checks that the SVG the page shows is byte for byte what
`hystviz render --set model.sigma0=V --format svg` writes; types a refused
sigma1 and checks the CLI's message appears next to the control while the
figure stays; hovers a curve; saves an edit of style.scene by renaming (as
Vim does) and checks the page followed without a click; scrubs the
animation to frame 10 and checks the PNG equals `hystviz animate --frames
10:11`; plays a built-in animation for 3 s (>= 10 frames/s shown) and
checks the paused frame i equals `hystviz animate --frames i:i+1`, and that
a slider moved while a scene animation plays changes the frames that follow
(== `animate --set`).  Exit 77 (SKIP) with a message where chromium is absent; the frame
check is skipped where hystviz-animate was built without OSMesa.

--bench-play S: instead, plays every built-in animation and animation scene
for S seconds at 1280x720 and prints the frames shown per second.

--bench N: instead, N slider moves per figure (Fig. 15, Fig. 11, bw_fig1a),
printing the median and 95th percentile of the server's render time and of
the page's time from the input event to the new SVG in the DOM.
"""
import atexit
import base64
import json
import os
import re
import shlex
import shutil
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import time
import urllib.parse
import urllib.request

FAILS = []


def check(cond, what):
    print(("ok: " if cond else "FAIL: ") + what, flush=True)
    if not cond:
        FAILS.append(what)


# ---- a minimal WebSocket client (RFC 6455), enough for DevTools -------------

class WebSocket:
    def __init__(self, url):
        m = re.match(r"ws://([^/:]+):(\d+)(/.*)", url)
        self.sock = socket.create_connection((m.group(1), int(m.group(2))), timeout=60)
        key = base64.b64encode(os.urandom(16)).decode()
        req = (f"GET {m.group(3)} HTTP/1.1\r\nHost: {m.group(1)}:{m.group(2)}\r\nUpgrade: websocket\r\n"
               f"Connection: Upgrade\r\nSec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\n\r\n")
        self.sock.sendall(req.encode())
        head = b""
        while b"\r\n\r\n" not in head:
            chunk = self.sock.recv(1)
            if not chunk:
                raise OSError("websocket handshake: connection closed")
            head += chunk
        if b" 101 " not in head.split(b"\r\n")[0]:
            raise OSError("websocket handshake refused: " + head.decode(errors="replace"))

    def send(self, text):
        data = text.encode()
        hdr = bytes([0x81])
        n = len(data)
        if n < 126:
            hdr += bytes([0x80 | n])
        elif n < 65536:
            hdr += bytes([0x80 | 126]) + struct.pack(">H", n)
        else:
            hdr += bytes([0x80 | 127]) + struct.pack(">Q", n)
        mask = os.urandom(4)
        self.sock.sendall(hdr + mask + bytes(b ^ mask[i % 4] for i, b in enumerate(data)))

    def _read(self, n):
        buf = b""
        while len(buf) < n:
            chunk = self.sock.recv(n - len(buf))
            if not chunk:
                raise OSError("websocket closed")
            buf += chunk
        return buf

    def recv(self):
        msg = b""
        while True:
            b0, b1 = self._read(2)
            n = b1 & 0x7F
            if n == 126:
                n = struct.unpack(">H", self._read(2))[0]
            elif n == 127:
                n = struct.unpack(">Q", self._read(8))[0]
            if b1 & 0x80:
                mask = self._read(4)
                data = bytes(b ^ mask[i % 4] for i, b in enumerate(self._read(n)))
            else:
                data = self._read(n)
            op = b0 & 0x0F
            if op == 0x9:  # ping: answer, keep reading
                continue
            if op == 0x8:
                raise OSError("websocket closed by the browser")
            msg += data
            if b0 & 0x80:
                return msg.decode()


class DevTools:
    def __init__(self, ws_url):
        self.ws = WebSocket(ws_url)
        self.id = 0

    def call(self, method, **params):
        self.id += 1
        self.ws.send(json.dumps({"id": self.id, "method": method, "params": params}))
        t0 = time.time()
        while True:
            # each read waits 60 s at most (the socket's timeout); events that
            # keep coming without our answer end after 120 s
            if time.time() - t0 > 120:
                raise OSError(f"{method}: no answer from chromium within 120 s")
            m = json.loads(self.ws.recv())
            if m.get("id") == self.id:
                if "error" in m:
                    raise RuntimeError(f"{method}: {m['error']}")
                return m.get("result", {})

    def js(self, expr, timeout=30):
        r = self.call("Runtime.evaluate", expression=expr, awaitPromise=True, returnByValue=True,
                      timeout=timeout * 1000)
        if "exceptionDetails" in r:
            raise RuntimeError(f"{expr[:80]}...: {r['exceptionDetails']}")
        return r["result"].get("value")

    def wait(self, cond, timeout=20, what=""):
        """Waits until the JS expression cond is true; returns whether it became true."""
        t0 = time.time()
        while time.time() - t0 < timeout:
            if self.js(f"(() => {{ try {{ return !!({cond}); }} catch (e) {{ return false; }} }})()"):
                return True
            time.sleep(0.02)
        print(f"   (timed out after {timeout} s waiting for {what or cond})")
        return False

    def mouse(self, kind, x, y, buttons=0, button="none"):
        self.call("Input.dispatchMouseEvent", type=kind, x=x, y=y, button=button, buttons=buttons, clickCount=1)

    def key(self, code, key):
        for kind in ("rawKeyDown", "keyUp"):
            self.call("Input.dispatchKeyEvent", type=kind, key=key, code=code, windowsVirtualKeyCode=39 if key == "ArrowRight" else 0)


# ---- helpers ------------------------------------------------------------------

def render_svg(hv, scene, sets, out):
    args = [hv, "render", scene, "--format", "svg", "-o", out]
    for s in sets:
        args += ["--set", s]
    subprocess.run(args, check=True, capture_output=True, timeout=120)
    name = re.search(r"^name = (\S+)", open(scene).read(), re.M)
    base = name.group(1) if name else os.path.basename(scene)[:-len(".scene")]  # default: the file's name
    with open(os.path.join(out, base + ".svg"), encoding="utf-8") as f:
        return f.read()


def rename_save(path, old, new):
    text = open(path).read()
    assert old in text, f"{old!r} not in {path}"
    tmp = os.path.join(os.path.dirname(path), ".edit.swp")
    with open(tmp, "w") as f:
        f.write(text.replace(old, new))
    os.rename(tmp, path)


def settle(dt):
    """Waits until the page has no render running or queued."""
    return dt.wait("hv.renders > 0 && !hv.inflight && !hv.pending", 30, "the renders to settle")


def slider_box(dt, key):
    return dt.js(f"""(() => {{ const r = document.querySelector('input[type=range][data-key="{key}"]');
        r.scrollIntoView({{block: 'center'}}); const b = r.getBoundingClientRect();
        return [b.left, b.top, b.width, b.height]; }})()""")


def key_focus_body(dt):
    """Takes the focus from any control, so that a key goes to the page's own handler."""
    dt.js("document.activeElement && document.activeElement.blur && document.activeElement.blur()")


def drag(dt, key, frac_from, frac_to, steps=8):
    x, y, w, h = slider_box(dt, key)
    cy = y + h / 2
    x0, x1 = x + 8 + (w - 16) * frac_from, x + 8 + (w - 16) * frac_to
    dt.mouse("mouseMoved", x0, cy)
    dt.mouse("mousePressed", x0, cy, 1, "left")
    for i in range(1, steps + 1):
        dt.mouse("mouseMoved", x0 + (x1 - x0) * i / steps, cy, 1, "left")
        time.sleep(0.01)
    dt.mouse("mouseReleased", x1, cy, 0, "left")


def wait_line(path, pattern, proc, deadline, what):
    """The first match of pattern in the file path, which proc writes; None
    when proc exits first or after deadline seconds (with a message)."""
    t0 = time.time()
    while time.time() - t0 < deadline:
        with open(path, encoding="utf-8", errors="replace") as f:
            m = re.search(pattern, f.read())
        if m:
            return m
        if proc.poll() is not None:
            return None
        time.sleep(0.05)
    print(f"   (timed out after {deadline} s waiting for {what})", flush=True)
    return None


def stop_group(p):
    """Kills p and every process it started (its own session) and reaps p."""
    try:
        os.killpg(p.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    p.wait(timeout=30)


def remove_tree(path):
    """Removes path; a process that was just killed may still be ending (chromium's
    renderers write into its profile until they are gone), so it tries again
    for up to 10 s rather than leave a directory behind in $TMPDIR."""
    deadline = time.monotonic() + 10
    while True:
        shutil.rmtree(path, ignore_errors=True)
        if not os.path.exists(path) or time.monotonic() > deadline:
            return
        time.sleep(0.2)


def need_chromium():
    """Whether a browser that cannot be had fails the test instead of SKIPping it:
    in CI (CI=true), where tools/setup.sh installs chromium, a SKIP would hide
    the browser tests (as a too-long socket path once did)."""
    return os.environ.get("CI") == "true"


def start_chromium(tmp):
    """chromium headless with DevTools on a free port: (process, page WebSocket URL),
    or (None, None) where it is absent or does not start (after a second try);
    under CI (need_chromium) that raises instead."""
    exe = shutil.which("chromium") or shutil.which("chromium-browser")
    if not exe:
        if need_chromium():
            raise RuntimeError("chromium is not installed (CI=true: tools/setup.sh test installs it)")
        return None, None
    for attempt in (1, 2):
        p, ws = start_chromium_once(exe, tmp, attempt)
        if p:
            return p, ws
    if need_chromium():
        raise RuntimeError("chromium did not start headless (twice; its messages are above)")
    return None, None


def start_chromium_once(exe, tmp, attempt):
    prof = os.path.join(tmp, f"profile{attempt}")
    log = os.path.join(tmp, f"chromium{attempt}.err")
    # its temporaries (org.chromium.Chromium.*, left when it is killed) in tmp,
    # whose name must stay short: chromium's SingletonSocket below it is a Unix
    # socket (108 bytes at most; a nested $TMPDIR once made it too long and the
    # test SKIPped); where tmp is too deep, a directory of its own in /tmp
    ctmp = os.path.join(tmp, f"c{attempt}")
    if len(ctmp) > 56:
        ctmp = tempfile.mkdtemp(prefix="hyc", dir="/tmp")
        atexit.register(remove_tree, ctmp)
    else:
        os.mkdir(ctmp)
    # its own session: stop_group ends its renderer and GPU processes too; its
    # messages go to a file (a pipe nobody reads would block it once full)
    with open(log, "w") as err:
        p = subprocess.Popen([exe, "--headless=new", "--no-sandbox", "--disable-gpu", "--no-first-run",
                              "--disable-extensions", "--disable-background-networking", "--disable-sync",
                              "--remote-debugging-port=0", f"--user-data-dir={prof}", "--window-size=1400,1000",
                              "about:blank"], stdout=subprocess.DEVNULL, stderr=err, start_new_session=True,
                             env=dict(os.environ, TMPDIR=ctmp))
    m = wait_line(log, r"DevTools listening on (ws://\S+)", p, 60, "chromium's DevTools URL")
    if not m:
        stop_group(p)
        with open(log, encoding="utf-8", errors="replace") as f:
            print(f"   (chromium, status {p.returncode}, said: {f.read()[-1500:]})", flush=True)
        return None, None
    url = m.group(1)
    port = re.match(r"ws://[^:]+:(\d+)/", url).group(1)
    targets = json.load(urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list", timeout=30))
    page = next(t for t in targets if t["type"] == "page")
    return p, page["webSocketDebuggerUrl"]


def start_server(hv, scenes):
    out, err = os.path.abspath("serve.out"), os.path.abspath("serve.err")
    with open(out, "w") as o, open(err, "w") as e:
        p = subprocess.Popen([hv, "serve", scenes, "--port", "0"], stdout=o, stderr=e, stdin=subprocess.DEVNULL)
    m = wait_line(out, r"(http://127\.0\.0\.1:\d+/)", p, 30, "serve's URL")
    if m:
        return p, m.group(1)
    try:
        rc = p.wait(timeout=10)
    except subprocess.TimeoutExpired:
        p.kill()
        p.wait()
        rc = None
    if rc == 3:
        return p, None  # built without libmicrohttpd
    with open(err, encoding="utf-8", errors="replace") as f:
        raise RuntimeError(f"serve printed no URL within 30 s (status {rc}): " + f.read())


def pct(v, q):
    v = sorted(v)
    return v[min(len(v) - 1, int(round(q / 100 * (len(v) - 1))))]


# ---- the tests -----------------------------------------------------------------

def test_page(dt, hv, base, scenes, tmp, screenshot):
    F = "fig15_minor_loop_ex4"
    scene = os.path.join(scenes, F + ".scene")
    dt.call("Page.navigate", url=base + "#" + F + ".scene")
    check(dt.wait("window.hv && hv.renders >= 1 && hv.svg", 30, "the first figure"), "the page shows Fig. 15")
    first = dt.js("hv.svg")
    check(first == render_svg(hv, scene, [], os.path.join(tmp, "r0")), "first figure == hystviz render")
    check(dt.js("document.querySelector('#figure svg') !== null && document.querySelectorAll('.ctl').length > 5"),
          "inline SVG and the controls are in the DOM")

    # drag sigma0 from the left quarter to 3/4 of the slider: several renders while dragging
    n0 = dt.js("hv.renders")
    drag(dt, "model.sigma0", 0.25, 0.75)
    dt.wait("!hv.holding", 30, "the limits of the slider's range")
    settle(dt)
    val = dt.js("hv.sets['model.sigma0']")
    check(val is not None and dt.js("hv.renders") > n0, f"dragging sigma0 re-rendered (sigma0 = {val}, "
          f"{dt.js('hv.renders') - n0} renders while dragging)")
    # the drag may hold the axes (figure.xlim/ylim, issue 38) if it lasted until their limits came
    sets = dt.js("Object.entries(hv.sets).map(([k, v]) => k + '=' + v)")
    want = render_svg(hv, scene, sets, os.path.join(tmp, "r1"))
    check(dt.js("hv.svg") == want, f"page SVG == hystviz render --set {' --set '.join(sets)} --format svg")
    check(dt.js("hv.svg") != first, "the figure changed")
    check(dt.js("document.getElementById('figure').innerHTML.length > 1000"), "the DOM holds the new SVG")
    cmd = dt.js("document.getElementById('cmd').textContent")
    words = shlex.split(cmd)
    check(words[:3] == ["hystviz", "render", scene] and words[-2:] == ["--format", "svg"] and f"--set model.sigma0={val}" in cmd
          and words[3:-2:2] == ["--set"] * len(sets) and sorted(words[4:-2:2]) == sorted(sets),
          f"the page shows the command: {cmd}")

    # hover: the nearest drawn point of a curve
    dt.wait("hv.hover !== null", 10, "the hover data")
    pos = dt.js("""(() => { const m = hv.hover.map, s = hv.hover.series.find(s => s.name === 'minor');
        let i = s.x.findIndex(v => v !== null) + 7; const svg = document.querySelector('#figure svg');
        const p = svg.createSVGPoint();
        p.x = m.x0 + (s.x[i] - m.xlo) / (m.xhi - m.xlo) * m.w; p.y = m.y0 + m.h - (s.y[i] - m.ylo) / (m.yhi - m.ylo) * m.h;
        const q = p.matrixTransform(svg.getScreenCTM()); return [q.x, q.y, s.x[i], s.y[i]]; })()""")
    dt.mouse("mouseMoved", pos[0], pos[1])
    tip = dt.js("document.getElementById('tip').hidden ? '' : document.getElementById('tip').textContent")
    check(tip.startswith("minor: u = ") and f"{pos[2]:.5g}"[:4] in tip, f"hover shows the series and point: '{tip}'")

    # a value the CLI refuses: its message (without the "--set KEY=VALUE: " the
    # control already tells) next to the control, the figure stays
    good = dt.js("hv.svg")
    dt.js("""(() => { const b = document.querySelector('input[type=text][data-key="model.sigma1"]');
        b.value = '-1'; b.dispatchEvent(new Event('change')); })()""")
    dt.wait("hv.error !== null && !hv.inflight", 20, "the error")
    cli = subprocess.run([hv, "render", scene, "--set", f"model.sigma0={val}", "--set", "model.sigma1=-1", "-o",
                          os.path.join(tmp, "rx")], capture_output=True, text=True, timeout=120).stderr.strip()
    msg = dt.js("document.querySelector('.err[data-key=\"model.sigma1\"]').textContent")
    prefix = "hystviz: --set model.sigma1=-1: "
    check(cli.startswith(prefix) and msg == cli[len(prefix):], f"the CLI's message next to the control: '{msg}'")
    check(dt.js("hv.svg") == good and dt.js("document.getElementById('figure').innerHTML.length > 1000"),
          "the last good figure stays")
    dt.js("""(() => { const b = document.querySelector('input[type=text][data-key="model.sigma1"]');
        b.value = '1'; b.dispatchEvent(new Event('change')); })()""")
    settle(dt)
    check(dt.js("hv.error") is None and dt.js("hv.svg") == good, "a valid value again: the figure is back")

    if screenshot:
        shot = dt.call("Page.captureScreenshot", format="png")
        with open(screenshot, "wb") as f:
            f.write(base64.b64decode(shot["data"]))
        print(f"   screenshot: {screenshot}")

    # an edit of style.scene saved by rename: the page follows with no click
    n1, c1 = dt.js("hv.renders"), dt.js("hv.changes")
    t0 = time.time()
    rename_save(os.path.join(scenes, "style.scene"), "fontsize = 9pt", "fontsize = 11pt")
    followed = dt.wait(f"hv.changes > {c1} && hv.renders > {n1} && !hv.inflight && !hv.pending", 10, "the reload")
    dt_ms = 1000 * (time.time() - t0)
    want = render_svg(hv, scene, [f"model.sigma0={val}"], os.path.join(tmp, "r2"))
    check(followed and dt.js("hv.svg") == want and want != good,
          "after saving style.scene the page shows the new figure, with no click and the sliders kept")
    # the one-second target is the benchmark's to measure (a loaded CI machine may be slower)
    print(f"   the page followed the save in {dt_ms:.0f} ms")


def test_anim(dt, hv, base, scenes, tmp, screenshot=None):
    A = "anim_minor_loop_ex4"
    scene = os.path.join(scenes, A + ".scene")
    out = os.path.join(tmp, "anim")
    r = subprocess.run([hv, "animate", scene, "--frames", "10:11", "-o", out, "--quiet"], capture_output=True, text=True,
                       timeout=120)
    if r.returncode == 3:
        print("SKIP (frame check): hystviz-animate was built without OSMesa: " + r.stderr.strip())
        return
    check(r.returncode == 0, "hystviz animate --frames 10:11 " + r.stderr.strip())
    want = open(os.path.join(out, A, "frame_00010.png"), "rb").read()
    dt.call("Page.navigate", url=base + "#" + A + ".scene")
    check(dt.wait("hv.info && hv.info.file === '" + A + ".scene' && hv.frame === 0 && !hv.frameInflight", 60,
                  "frame 0"), "the scrubber shows frame 0")
    # scrub with the keyboard: ten steps to the right, latest wins
    dt.js("document.getElementById('scrub').focus()")
    for _ in range(10):
        dt.key("ArrowRight", "ArrowRight")
    check(dt.wait("hv.frame === 10 && !hv.frameInflight && hv.framePending < 0", 60, "frame 10"),
          "scrubbed to frame 10")
    got = base64.b64decode(dt.js("hv.frameB64") or "")
    check(got == want, f"frame 10 in the page == hystviz animate --frames 10:11 ({len(got)} bytes)")
    test_play(dt, hv, base, scenes, tmp, screenshot)


def animate_frame(hv, tmp, what, i, sets=()):
    """The PNG `hystviz animate WHAT --frames i:i+1 --set ...` writes."""
    out = tempfile.mkdtemp(dir=tmp)
    args = [hv, "animate", what, "--frames", f"{i}:{i + 1}", "-o", out, "--quiet"]
    for s in sets:
        args += ["--set", s]
    subprocess.run(args, check=True, capture_output=True, timeout=120)
    sub = next(d for d in os.listdir(out) if os.path.isdir(os.path.join(out, d)))
    with open(os.path.join(out, sub, f"frame_{i:05d}.png"), "rb") as f:
        return f.read()


SERVE_PID = None  # the serve under test (main sets it)


def animate_children(pid):
    """The pids of hystviz-animate processes whose parent is pid."""
    out = set()
    if not pid:
        return out
    for d in os.listdir("/proc"):
        if not d.isdigit():
            continue
        try:
            with open(f"/proc/{d}/stat") as f:
                st = f.read()
            with open(f"/proc/{d}/cmdline", "rb") as f:
                cmd = f.read()
        except OSError:
            continue
        if int(st.rsplit(")", 1)[1].split()[1]) == pid and b"hystviz-animate" in cmd:
            out.add(int(d))
    return out


def play_for(dt, seconds):
    """Plays the open animation: waits for its first played frame, then counts the
    frames shown in `seconds` of play; returns frames per second, timed by the
    page's clock from the frame shown first in the window to the one shown last
    (a player that keeps the clip's rate reads the rate itself, not +-1 frame
    of the window's edges)."""
    dt.js("document.getElementById('play').click()")
    dt.wait("hv.anim.shown > 0", 60, "the first played frame")
    n0, t0 = dt.js("[hv.anim.shown, hv.anim.shownAt]")
    time.sleep(seconds)
    n1, t1 = dt.js("[hv.anim.shown, hv.anim.shownAt]")
    return 1000 * (n1 - n0) / max(t1 - t0, 1e-3)


def pause(dt):
    dt.js("hv.frameB64 = null; document.getElementById('play').click()")
    dt.wait("!hv.playing && hv.frameB64 !== null", 20, "the paused frame")
    return dt.js("hv.frame"), base64.b64decode(dt.js("hv.frameB64") or "")


def test_play(dt, hv, base, scenes, tmp, screenshot):
    """Playback: a built-in animation at its frame rate (>= 10 frames/s asserted, 30
    is the benchmark's), the paused frame == animate --frames i:i+1; a slider moved
    while a scene animation plays changes the frames that follow."""
    B = "minor-loop-ex4"
    dt.call("Page.navigate", url=base + "#@" + B)
    check(dt.wait(f"hv.info && hv.info.file === '@{B}' && hv.frame === 0 && !hv.frameInflight", 60, "frame 0"),
          f"@{B}: frame 0 shown")
    # the frames come from warm workers, not a process per frame: the
    # hystviz-animate children serve starts while 3 s play (polled in /proc)
    seen, stop = set(), threading.Event()

    def watch():
        while not stop.is_set():
            seen.update(animate_children(SERVE_PID))
            stop.wait(0.02)
    w = threading.Thread(target=watch, daemon=True)
    w.start()
    shown0 = dt.js("hv.anim.shown") or 0
    fps = play_for(dt, 3)
    shown = (dt.js("hv.anim.shown") or 0) - shown0
    stop.set()
    w.join(5)
    check(shown > len(seen) + 2, f"@{B}: {shown} frames shown from {len(seen)} hystviz-animate process(es) "
                                 "(warm workers, not one process per frame)")
    if screenshot:
        dt.js("document.getElementById('anim').scrollIntoView()")
        shot = dt.call("Page.captureScreenshot", format="png")
        with open(screenshot.replace(".png", "") + "-play.png", "wb") as f:
            f.write(base64.b64decode(shot["data"]))
    stalls = dt.js("hv.anim.stalls")
    what = f"@{B} plays at {fps:.1f} frames/s over 3 s (>= 10; {stalls} display frames waited for a frame)"
    load = os.getloadavg()[0]
    if os.environ.get("HYSTVIZ_SLOW_BUILD"):  # sanitizers, -O0: the rate is the build's, not asserted
        print(f"   (not asserted in a sanitizer or unoptimised build) {what}")
    elif load >= (os.cpu_count() or 1):  # a busy machine: the rate is the machine's (the benchmark's figure)
        print(f"   (not asserted at load {load:.1f} on {os.cpu_count()} cores) {what}")
    else:
        check(fps >= 10, what)
    i, got = pause(dt)
    check(got == animate_frame(hv, tmp, B, i), f"paused on frame {i}: the PNG == hystviz animate --frames {i}:{i + 1}")
    check(dt.js("document.getElementById('scrub').value") == str(i), "the scrubber follows the played frame")

    A = "anim_gamma_sweep_ex3"
    scene = os.path.join(scenes, A + ".scene")
    dt.call("Page.navigate", url=base + "#" + A + ".scene")
    check(dt.wait(f"hv.info && hv.info.file === '{A}.scene' && hv.frame === 0 && !hv.frameInflight", 60, "frame 0"),
          f"{A}: frame 0 shown")
    play_for(dt, 0.5)
    # a new sigma0 while it plays: the frames not yet shown use it
    dt.js("""(() => { const b = document.querySelector('input[type=text][data-key="model.sigma0"]');
        b.value = '2'; b.dispatchEvent(new Event('change')); })()""")
    n0 = dt.js("hv.anim.shown")
    check(dt.wait(f"hv.anim.shown > {n0} + 10", 30, "frames with the new sigma0"), "frames go on after the slider moved")
    i, got = pause(dt)
    want = animate_frame(hv, tmp, scene, i, ["model.sigma0=2"])
    check(got == want, f"moved while playing: paused frame {i} == hystviz animate --set model.sigma0=2 --frames {i}:{i + 1}")
    check(got != animate_frame(hv, tmp, scene, i), "... and differs from the frame without the override")


def bench_play(dt, base, seconds, scenes):
    """Playback in the page at 1280x720: frames shown per second over `seconds`
    (after the first), per built-in animation and animation scene."""
    dt.call("Page.navigate", url=base)
    dt.wait("window.hv && hv.scenes.length > 0", 30, "the catalogue")
    names = ["@" + n for n in dt.js("hv.scenes.filter(s => s.builtin).map(s => s.file.slice(1))")]
    names += sorted(f for f in os.listdir(scenes) if f.startswith("anim_") and f.endswith(".scene"))
    for f in names:
        dt.call("Page.navigate", url=base + "#" + f)
        if not dt.wait(f"hv.info && hv.info.file === '{f}' && hv.frame === 0 && !hv.frameInflight", 60, "frame 0"):
            continue
        info = dt.js("[hv.anim.n, hv.anim.fps]")
        # the server alone: every frame of the clip through one /api/frames stream
        t0 = time.time()
        with urllib.request.urlopen(f"{base}api/frames?scene={urllib.parse.quote(f)}&from=0&to={info[0]}"
                                    f"&page=bench&seq={int(t0 * 1000)}", timeout=300) as r:
            body = r.read()
        srv_fps, i = 0, 0
        while i < len(body):  # records "TAG NUM LEN\n<bytes>"
            nl = body.index(b"\n", i)
            tag, _, n = body[i:nl].split()
            srv_fps += tag == b"frame"
            i = nl + 1 + int(n)
        srv_fps /= time.time() - t0
        fps = play_for(dt, seconds)
        stalls, gap = dt.js("[hv.anim.stalls, hv.anim.maxGap]")
        dt.js("document.getElementById('play').click()")
        print(f"bench-serve-play {f}: {fps:.1f} frames/s shown over {seconds} s at 1280x720 (clip: {info[0]} frames "
              f"at {info[1]} fps; {stalls} display frames waited for a frame to decode, the longest time between two "
              f"frames shown {gap:.0f} ms); the server streams {srv_fps:.1f} "
              f"frames/s (the whole clip, one client, no browser); load {os.getloadavg()[0]:.1f} on "
              f"{os.cpu_count()} CPUs", flush=True)


BENCH_FIGS = [("fig15_minor_loop_ex4", "model.sigma0"), ("fig11_ygamma_ex3", "model.sigma0"),
              ("bw_fig1a_quasistatic_loop", "input.amp")]
# the benchmark's table, the README's (tests/cli/test_readme_bench.sh checks its rows and format)
BENCH_HEADER = ("| figure (control) | in chromium: server render wall / CPU, median | "
                "input event → new SVG in the DOM, back to back: median / p95 | "
                "one change at a time (100 ms apart): median / p95 | load |\n|---|---|---|---|---|")


def bench_rows():
    print(BENCH_HEADER)
    for f, key in BENCH_FIGS:
        print(f"| {f} ({key}) |")


def bench(dt, base, n, scenes):
    print(BENCH_HEADER, flush=True)
    for f, key in BENCH_FIGS:
        dt.call("Page.navigate", url=base + "#" + f + ".scene")
        dt.wait(f"hv.info && hv.info.file === '{f}.scene' && hv.renders >= 1 && !hv.inflight", 60)
        if key is None or not dt.js(f"!!document.querySelector('input[type=range][data-key=\"{key}\"]')"):
            key = dt.js("hv.info.controls[0].key")
        # back to back (the next change as soon as the figure is in: a fast drag,
        # each change meeting the page's work for the one before), then one
        # change at a time (a step of the keyboard or a click: the page idle)
        srv, e2e, one, cpu, refused = [], [], [], [], 0
        for i in range(2 * n):
            if i >= n:
                time.sleep(0.1)
            # one control change: an input event, then the time until the new SVG is in the DOM
            # (or the scene's error is shown: counted, not timed)
            r = dt.js(f"""new Promise(res => {{
                const el = document.querySelector('input[type=range][data-key="{key}"]');
                const t0 = performance.now();
                const ok = () => {{ document.removeEventListener('hv-error', bad); res([hv.serverMs, performance.now() - t0, hv.serverCpuMs]); }};
                const bad = () => {{ document.removeEventListener('hv-rendered', ok); res(null); }};
                document.addEventListener('hv-rendered', ok, {{once: true}});
                document.addEventListener('hv-error', bad, {{once: true}});
                el.value = {470 + (i * 7) % 60}; el.dispatchEvent(new Event("input"));
            }})""", timeout=60)
            if r is None:
                refused += 1
                continue
            srv.append(r[0])
            (e2e if i < n else one).append(r[1])
            cpu.append(r[2])
        if not srv:
            print(f"bench-serve-browser {f}: every change refused", file=sys.stderr)
            continue
        if not e2e or not one:
            print(f"bench-serve-browser {f}: too many changes refused", file=sys.stderr)
            continue
        print(f"| {f} ({key}) | {pct(srv, 50):.1f} / {pct(cpu, 50):.1f} ms | {pct(e2e, 50):.1f} / {pct(e2e, 95):.1f} ms | "
              f"{pct(one, 50):.1f} / {pct(one, 95):.1f} ms | {os.getloadavg()[0]:.1f} |", flush=True)
        print(f"bench-serve-browser {f}: {len(srv)} changes, {refused} refused", file=sys.stderr, flush=True)
    # reload on save: rename-save of style.scene -> the new figure in the page
    f = "fig15_minor_loop_ex4"
    dt.call("Page.navigate", url=base + "#" + f + ".scene")
    dt.wait(f"hv.info && hv.info.file === '{f}.scene' && hv.renders >= 1 && !hv.inflight", 60)
    lat = []
    sizes = ["fontsize = 9pt", "fontsize = 9.5pt"]
    for i in range(10):
        n0 = dt.js("hv.renders")
        t0 = time.time()
        rename_save(os.path.join(scenes, "style.scene"), sizes[i % 2], sizes[(i + 1) % 2])
        if dt.wait(f"hv.renders > {n0} && !hv.inflight && !hv.pending", 10, "the reload"):
            lat.append(1000 * (time.time() - t0))
        time.sleep(0.2)
    if lat:
        print(f"bench-serve-reload rename-save of style.scene -> new Fig. 15 in the page ({len(lat)} saves): "
              f"median {pct(lat, 50):.0f} ms, max {max(lat):.0f} ms (80 ms of it is the debounce)", flush=True)


def run_session(hv, src, prefix, body, check_exit=True):
    """The frame of a browser test: the scenes of src copied into a fresh
    directory, serve on it, chromium headless over DevTools at 1400x1000;
    body(dt, base, scenes, tmp) runs the tests (in that directory); then
    chromium and serve are stopped and the directory removed, also when
    meson's timeout (SIGTERM) or Ctrl-C ends it.  Returns 77 (SKIP) where
    chromium or libmicrohttpd is missing (a missing chromium fails under CI), else
    1 if a check failed, else 0."""
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(1))
    if not (shutil.which("chromium") or shutil.which("chromium-browser")):
        if need_chromium():
            print("FAIL: chromium is not installed (CI=true: sh tools/setup.sh test installs it)")
            return 1
        print("SKIP: chromium is not installed (Debian: apt-get install chromium; sh tools/setup.sh test does)")
        return 77
    tmp = tempfile.mkdtemp(prefix=prefix)
    scenes = os.path.join(tmp, "scenes")
    os.mkdir(scenes)
    for f in os.listdir(src):
        if f.endswith(".scene"):
            shutil.copy(os.path.join(src, f), scenes)
    os.chdir(tmp)
    scenes = "scenes"
    srv = chrome = None
    try:
        srv, base = start_server(hv, scenes)
        global SERVE_PID
        SERVE_PID = srv.pid if srv else None
        if base is None:
            srv = None
            print("SKIP: hystviz was built without libmicrohttpd (serve exits 3)")
            return 77
        chrome, ws = start_chromium(tmp)
        if not chrome:
            print("SKIP: chromium did not start headless")
            return 77
        dt = DevTools(ws)
        dt.call("Page.enable")
        dt.call("Runtime.enable")
        dt.call("Emulation.setDeviceMetricsOverride", width=1400, height=1000, deviceScaleFactor=1, mobile=False)
        body(dt, base, scenes, tmp)
    finally:
        if chrome:
            stop_group(chrome)
        if srv:
            srv.send_signal(signal.SIGINT)
            try:
                rc = srv.wait(timeout=10)
                if check_exit:
                    check(rc == 0, f"serve exited {rc} on SIGINT")
            except subprocess.TimeoutExpired:
                srv.kill()
                check(False, "serve did not stop within 10 s of SIGINT")
        remove_tree(tmp)
    if FAILS:
        print(f"{len(FAILS)} failure(s)")
        return 1
    return 0


def main():
    if sys.argv[1:] == ["--rows"]:
        bench_rows()
        return 0
    hv, src = os.path.realpath(sys.argv[1]), os.path.realpath(sys.argv[2])
    screenshot = sys.argv[sys.argv.index("--screenshot") + 1] if "--screenshot" in sys.argv else None
    nbench = int(sys.argv[sys.argv.index("--bench") + 1]) if "--bench" in sys.argv else 0
    play_s = float(sys.argv[sys.argv.index("--bench-play") + 1]) if "--bench-play" in sys.argv else 0

    def body(dt, base, scenes, tmp):
        if play_s:
            bench_play(dt, base, play_s, scenes)
        elif nbench:
            bench(dt, base, nbench, scenes)
        else:
            test_page(dt, hv, base, scenes, tmp, screenshot)
            test_anim(dt, hv, base, scenes, tmp, screenshot)
    rc = run_session(hv, src, "hystviz-browser-", body, check_exit=not (nbench or play_s))
    if rc == 0:
        print("all browser tests passed")
    return rc


if __name__ == "__main__":
    sys.exit(main())
