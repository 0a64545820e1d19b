#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""tests/gl/worker_test.py HYSTVIZ_ANIMATE SCENES_DIR

`hystviz-animate animate --worker` (src/io/anim_worker.h), the frame
worker hystviz serve keeps warm: every frame it answers is byte for byte
the PNG `animate NAME --frames I:I+1 [--set ...] [--size WxH]` writes (built-in
and scene animations, frames asked out of order, a range, overrides, another
size); a scene travels as text and its path is never opened (a path in a
directory that does not exist renders; includes still resolve below the
path's directory and one that leaves it is refused as `animate` refuses
it); a refused override, a frame past the end and an unknown name are
"error" records with the command line's message and status, after which
the worker goes on; a malformed request ends it with status 2.  SKIP (77)
where the program was built without GL.
"""
import os
import shutil
import subprocess
import sys
import tempfile

FAILS = []


def check(cond, what):
    print(("ok: " if cond else "FAIL: ") + what, flush=True)
    if not cond:
        FAILS.append(what)


class Worker:
    def __init__(self, exe):
        self.p = subprocess.Popen([exe, "animate", "--worker", "--quiet"], stdin=subprocess.PIPE,
                                  stdout=subprocess.PIPE)

    def ask(self, op, first, last, name, text=None, sets=(), size=(0, 0), raw=None):
        fields = [(b"name", name.encode())]
        if text is not None:
            fields.append((b"text", text))
        fields += [(b"set", s.encode()) for s in sets]
        req = f"hvw1 {op} {first} {last} {size[0]} {size[1]} {len(fields)}\n".encode()
        for tag, data in fields:
            req += tag + b" " + str(len(data)).encode() + b"\n" + data
        self.p.stdin.write(raw if raw is not None else req)
        self.p.stdin.flush()
        out = []
        while True:
            line = self.p.stdout.readline().decode()
            if not line:
                return out
            tag, num, n = line.split()
            out.append((tag, int(num), self.p.stdout.read(int(n))))
            if tag in ("end", "error"):
                return out

    def close(self, timeout=60):
        self.p.stdin.close()
        return self.p.wait(timeout=timeout)


def cli_frame(exe, tmp, name, i, sets=(), size=None):
    out = tempfile.mkdtemp(dir=tmp)
    args = [exe, "animate", name, "--frames", f"{i}:{i + 1}", "-o", out, "--quiet", "-j", "1"]
    for s in sets:
        args += ["--set", s]
    if size:
        args += ["--size", size]
    r = subprocess.run(args, capture_output=True, timeout=300)
    if r.returncode:
        return None, r.stderr.decode()
    sub = [d for d in os.listdir(out) if os.path.isdir(os.path.join(out, d))][0]
    with open(os.path.join(out, sub, f"frame_{i:05d}.png"), "rb") as f:
        data = f.read()
    shutil.rmtree(out)
    return data, ""


def main():
    exe, src = os.path.realpath(sys.argv[1]), os.path.realpath(sys.argv[2])
    r = subprocess.run([exe, "animate", "--list"], capture_output=True, timeout=120)
    if r.returncode == 3:
        print("SKIP: built without GL: " + r.stderr.decode().strip())
        return 77
    tmp = tempfile.mkdtemp(prefix="hystviz-worker-")
    w = Worker(exe)
    try:
        run(w, exe, src, tmp)
        check(w.close() == 0, "the worker ends with status 0 at the end of its input")
        # a malformed request: an error record, then the worker stops with status 2
        w = Worker(exe)
        got = w.ask(None, 0, 0, "", raw=b"hvw1 frames 0 1 0 0 1\nname 99999999999\n")
        check(len(got) == 1 and got[0][0] == "error" and w.close() == 2,
              f"a malformed request: an error record and status 2 ({got})")
    finally:
        if w.p.poll() is None:
            w.p.kill()
            w.p.wait()
        shutil.rmtree(tmp, ignore_errors=True)
    if FAILS:
        print(f"{len(FAILS)} failure(s)")
        return 1
    print("all worker tests passed")
    return 0


def run(w, exe, src, tmp):
    got = w.ask("info", 0, 0, "minor-loop-ex4")
    want = subprocess.run([exe, "animate", "minor-loop-ex4", "--info"], capture_output=True, timeout=60).stdout
    check(len(got) == 2 and got[0][0] == "info" and got[0][2] == want and got[1][0] == "end",
          f"info == animate --info ({want.decode().strip()})")
    # built-ins, asked out of order
    for name, i in (("minor-loop-ex4", 7), ("gamma-sweep-ex2", 40), ("minor-loop-ex4", 3), ("k-cycle-ex3", 100)):
        got = w.ask("frames", i, i + 1, name)
        ref, _ = cli_frame(exe, tmp, name, i)
        check(len(got) == 2 and got[0][:2] == ("frame", i) and got[0][2] == ref and got[1][:2] == ("end", 1),
              f"{name} frame {i} == animate --frames {i}:{i + 1}")
    # scenes: text with their own path, then with a path that does not exist
    scenes = os.path.join(tmp, "scenes")
    os.mkdir(scenes)
    for f in os.listdir(src):
        if f.endswith(".scene"):
            shutil.copy(os.path.join(src, f), scenes)
    g3 = os.path.join(scenes, "anim_gamma_sweep_ex3.scene")
    text = open(g3, "rb").read()
    got = w.ask("frames", 10, 13, g3, text, ["model.sigma0=3"])
    ok = len(got) == 4 and [g[:2] for g in got] == [("frame", 10), ("frame", 11), ("frame", 12), ("end", 3)]
    for k in (10, 12):
        ref, _ = cli_frame(exe, tmp, g3, k, ["model.sigma0=3"])
        ok = ok and got[k - 10][2] == ref
    check(ok, "scene frames 10..12 (one range) with --set model.sigma0=3 == animate --set ... --frames k:k+1")
    got = w.ask("frames", 4, 5, g3, text)
    ref, _ = cli_frame(exe, tmp, g3, 4)
    check(got[0][:2] == ("frame", 4) and got[0][2] == ref, "the override dropped again: frame 4 == animate")
    ml = os.path.join(scenes, "anim_minor_loop_ex4.scene")
    mtext = open(ml, "rb").read()
    got = w.ask("frames", 20, 21, ml, mtext, size=(320, 180))
    ref, _ = cli_frame(exe, tmp, ml, 20, size="320x180")
    check(got[0][:2] == ("frame", 20) and got[0][2] == ref, "frame 20 at 320x180 == animate --size 320x180")
    virt = os.path.join(scenes, "not_a_file.scene")
    got = w.ask("frames", 20, 21, virt, mtext, size=(320, 180))
    check(not os.path.exists(virt) and got[0][:2] == ("frame", 20) and got[0][2] == ref,
          "a scene path that is no file renders from the text (the worker never opens the scene)")
    nodir = os.path.join(tmp, "no", "such", "dir", "x.scene")
    got = w.ask("frames", 0, 1, nodir, mtext)
    check(got and got[0][0] == "error" and got[0][1] == 2 and b"style.scene" in got[0][2],
          f"includes resolve below the path's directory: none there, refused ({got[0][2][:120]!r})")
    outside = os.path.join(tmp, "outside.scene")
    with open(outside, "w") as f:
        f.write("[figure]\nfontsize = 10pt\n")
    esc = mtext.replace(b'include "style.scene"', b'include "../outside.scene"')
    check(esc != mtext, "the escaping scene differs from the original")
    with open(os.path.join(scenes, "escape.scene"), "wb") as f:
        f.write(esc)
    got = w.ask("frames", 0, 1, os.path.join(scenes, "escape.scene"), esc)
    _, cli_err = cli_frame(exe, tmp, os.path.join(scenes, "escape.scene"), 0)
    check(got and got[0][0] == "error" and got[0][1] == 2 and got[0][2].decode() == cli_err,
          f"an include out of the scene's directory is refused as animate refuses it: {cli_err.strip()[:160]}")
    # errors: a record with the command line's message; the worker goes on
    for what, args in (("a refused override", ("frames", 3, 4, g3, text, ["model.sigma0=-1"])),
                       ("a frame past the end", ("frames", 1000, 1001, "minor-loop-ex4")),
                       ("an unknown animation", ("frames", 0, 1, "no-such-animation")),
                       ("--set on a built-in", ("frames", 0, 1, "minor-loop-ex4", None, ["model.sigma0=2"]))):
        got = w.ask(*args)
        check(len(got) == 1 and got[0][0] == "error" and got[0][1] == 2 and got[0][2].startswith(b"hystviz animate: "),
              f"{what}: an error record, status 2: {got[0][2].decode().strip()[:120] if got else ''}")
    r = subprocess.run([exe, "animate", g3, "--frames", "3:4", "--set", "model.sigma0=-1", "-o", tmp, "--quiet"],
                       capture_output=True, timeout=120)
    got = w.ask("frames", 3, 4, g3, text, ["model.sigma0=-1"])
    check(r.returncode == 2 and got[0][2] == r.stderr, "the refused override's message is the command line's")
    got = w.ask("frames", 7, 8, "minor-loop-ex4")
    check(got[0][:2] == ("frame", 7), "after the errors the worker still renders")


if __name__ == "__main__":
    sys.exit(main())
