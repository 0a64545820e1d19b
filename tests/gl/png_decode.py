# SPDX-License-Identifier: MIT
"""tests/gl/png_decode.py FILE.png...: each PNG decoded by Python's zlib (the
IDAT stream, to exactly h rows of 1 + 3 w bytes, filter bytes 0..4) and by
PIL (Image.open + load, its size and mode RGB/RGBA), the two independent of
hystviz's encoder and of tests/render/png_strict.c.  Prints one line per
failure and "png_decode: N files, N ok, N failed"; exit 0 only when all are ok;
exit 77 when PIL is missing (the caller decides whether that may SKIP)."""
import struct
import sys
import zlib

try:
    from PIL import Image
except ImportError:
    print("png_decode: PIL is not installed (python3-pil)")
    sys.exit(77)


def check(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        return "not a PNG"
    p, idat, w = 8, b"", None
    while p < len(data):
        n, kind = struct.unpack(">I4s", data[p:p + 8])
        body = data[p + 8:p + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
            ch = {2: 3, 6: 4}.get(ctype)
        elif kind == b"IDAT":
            idat += body
        p += 12 + n
    if w is None or ch is None or depth != 8:
        return "no IHDR, or not 8-bit RGB/RGBA"
    d = zlib.decompressobj()
    raw = d.decompress(idat)
    if not d.eof or d.unused_data:
        return "zlib: the stream does not end where the IDAT data ends"
    rb = 1 + w * ch
    if len(raw) != h * rb:
        return f"zlib: {len(raw)} bytes, want {h * rb}"
    if any(raw[y * rb] > 4 for y in range(h)):
        return "zlib: a filter byte over 4"
    im = Image.open(path)
    im.load()
    if im.size != (w, h) or im.mode not in ("RGB", "RGBA"):
        return f"PIL: size {im.size}, mode {im.mode}"
    return None


def main():
    files = sys.argv[1:]
    bad = 0
    for path in files:
        try:
            why = check(path)
        except Exception as e:  # noqa: BLE001 - any decoder error is a failure of that file
            why = f"{type(e).__name__}: {e}"
        if why:
            bad += 1
            print(f"FAIL {path}: {why}")
    print(f"png_decode: {len(files)} files, {len(files) - bad} ok, {bad} failed")
    sys.exit(1 if bad or not files else 0)


main()
