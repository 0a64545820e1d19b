# SPDX-License-Identifier: MIT
"""tests/serve/png_browser.py [--deadline S] FILE.png...: each PNG decoded in
Debian's chromium, headless (DevTools, browser_test.py's client), the way the
page decodes animation frames: createImageBitmap(new Blob([png])), and as an
<img> (img.decode() of a blob URL); both must give the PNG's IHDR size.
chromium's createImageBitmap refused frames that zlib, libpng, PIL and <img>
took (an incomplete Huffman code in hy_zfast's last block: issue 38).
Bounded: each decode 30 s at most, all of them --deadline seconds (default
120); what is left then fails.  Prints one line per failure and
"png_browser: N files, N ok, N failed"; exit 77 (SKIP) where chromium is
absent or does not start (a failure under CI=true, as browser_test.py)."""
import base64
import os
import signal
import struct
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import browser_test as bt  # noqa: E402

DECODE = """(async () => {
  const s = atob(%s), b = new Uint8Array(s.length);
  for (let i = 0; i < s.length; i++) b[i] = s.charCodeAt(i);
  const blob = new Blob([b], {type: 'image/png'}), r = {};
  try { const bm = await createImageBitmap(blob); r.bitmap = [bm.width, bm.height]; bm.close(); }
  catch (e) { r.bitmap = String(e); }
  const u = URL.createObjectURL(blob);
  try { const im = new Image(); im.src = u; await im.decode(); r.img = [im.naturalWidth, im.naturalHeight]; }
  catch (e) { r.img = String(e); }
  URL.revokeObjectURL(u);
  return r;
})()"""


def main():
    args = sys.argv[1:]
    deadline = 120.0
    if args[:1] == ["--deadline"]:
        deadline, args = float(args[1]), args[2:]
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(1))
    if not (bt.shutil.which("chromium") or bt.shutil.which("chromium-browser")):
        if bt.need_chromium():
            print("FAIL: chromium is not installed (CI=true: sh tools/setup.sh test installs it)")
            return 1
        print("SKIP: chromium is not installed (Debian: apt-get install chromium)")
        return 77
    tmp = tempfile.mkdtemp(prefix="hypng")
    chrome = None
    bad = done = 0
    try:
        chrome, ws = bt.start_chromium(tmp)
        if not chrome:
            print("SKIP: chromium did not start headless")
            return 77
        dt = bt.DevTools(ws)
        dt.call("Runtime.enable")
        t0 = time.monotonic()
        for path in args:
            if time.monotonic() - t0 > deadline:
                print(f"FAIL: the {deadline:.0f} s deadline passed with {len(args) - done} files left")
                bad += len(args) - done
                break
            with open(path, "rb") as f:
                png = f.read()
            size = list(struct.unpack(">II", png[16:24])) if png[12:16] == b"IHDR" else None
            try:
                r = dt.js(DECODE % repr(base64.b64encode(png).decode()), timeout=30)
            except (RuntimeError, OSError) as e:
                r = {"bitmap": str(e), "img": str(e)}
            done += 1
            if r.get("bitmap") != size or r.get("img") != size:
                bad += 1
                print(f"FAIL {path}: IHDR {size}, createImageBitmap {r.get('bitmap')}, <img> {r.get('img')}", flush=True)
    finally:
        if chrome:
            bt.stop_group(chrome)
        bt.remove_tree(tmp)
    print(f"png_browser: {len(args)} files, {len(args) - bad} ok, {bad} failed")
    return 1 if bad or not args else 0


if __name__ == "__main__":
    sys.exit(main())
