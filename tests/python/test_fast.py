# SPDX-License-Identifier: MIT
"""test_fast.py HYSTVIZ SCENES_DIR: steady_loop's compiled fast path
(hystviz._fast, src/python/_fast.c) against the ctypes path it replaces, and
GSL's error handler off in a process that imported hystviz (issue 35).

  - with HYSTVIZ_EXPECT_FAST=1 (meson sets it where it built the module) the
    package must have found the fast path (else a broken build would pass
    unseen through the fallback);
  - the two paths give the same bytes (the library is deterministic and both
    call the one loaded copy of it: exact equality, no tolerance), for models
    with typed keys only and with string keys (overrides), at several points;
  - a scene the library refuses raises the same SceneError through both;
  - the GIL is released for the call (a thread runs during it);
  - HYSTVIZ_CTYPES=1 turns the fast path off;
  - the module refuses arguments of the wrong kind and a short or read-only
    buffer with an exception, writing nothing;
  - GSL's own error call (gsl_error, what GSL_ERROR calls inside GSL) returns
    in a child process that imported hystviz, where GSL's default handler
    would abort it (SIGABRT).
"""
import ctypes
import os
import subprocess
import sys
import threading
import time

import numpy as np

import hystviz

fails = 0


def check(cond, what):
    global fails
    print(("ok: " if cond else "FAIL: ") + what, flush=True)
    fails += 0 if cond else 1


def both(model, inp, points):
    """steady_loop through the fast path and through ctypes: ((t, u, y) or the SceneError) of each."""
    out = []
    for fast in (hystviz._steady_fast, None):
        saved, hystviz._steady_fast = hystviz._steady_fast, fast
        try:
            out.append(np.stack(hystviz.steady_loop(model, inp, points=points)).tobytes())
        except hystviz.SceneError as e:
            out.append(str(e))
        finally:
            hystviz._steady_fast = saved
    return out


fast = hystviz._steady_fast
if os.environ.get("HYSTVIZ_EXPECT_FAST") == "1":
    check(fast is not None, "the package found the compiled fast path hystviz._fast (built by meson here)")
if fast is None:
    print("SKIP: hystviz._fast not built or not loadable here; the comparisons need it")
else:
    bim = hystviz.Input("bimodal", umin1=0, umin2=0.5, umax1=1, umax2=1.5)
    cases = [(hystviz.Model("lugre", sigma0=6, sigma1=1, fc=1, fs=2, vs=1, beta=1), bim, 200),
             (hystviz.Model("dahl", rho=2.5), hystviz.Input("sine"), 37),
             (hystviz.Model("preisach", pr_density="lorentzian", pr_support="triangle"), hystviz.Input("sine"), 500)]
    check(bool(cases[2][0]._sets), "the Preisach case passes string keys as overrides (the sets argument)")
    for model, inp, points in cases:
        a, b = both(model, inp, points)
        check(isinstance(a, bytes) and a == b, f"{model.kind} at {points} points: the same bytes through both paths")
    a, b = both(hystviz.Model("lugre", sigma0=-1), bim, 200)
    check(isinstance(a, str) and a == b and "sigma0" in a, f"a refused model: the same SceneError ({a!r})")

    # the module's own checks: an exception, nothing written
    m, name = cases[0][0], hystviz._PY_NAME
    buf = np.full(3 * 201, 7.0)
    for args, exc, what in [((name, m._btext, "[input]\n", [], [], 200, buf), TypeError, "a str text"),
                            ((name, m._btext, bim._btext, [b"x", 1], [], 200, buf), TypeError, "a non-bytes set"),
                            ((name, m._btext, bim._btext, None, [], 200, buf), TypeError, "sets None"),
                            ((name, m._btext, bim._btext, [], [], 201, buf), ValueError, "a buffer too short"),
                            ((name, m._btext, bim._btext, [], [], -1, buf), OverflowError, "negative points"),
                            ((name, m._btext, bim._btext, [], [], 200, bytes(8 * 603)), BufferError, "a read-only buffer"),
                            ((name, m._btext), TypeError, "2 arguments")]:
        try:
            fast(*args)
            check(False, f"_fast.steady_loop refuses {what}")
        except exc as e:
            check(True, f"_fast.steady_loop refuses {what}: {type(e).__name__}: {e}")
    check(bool(np.all(buf == 7.0)), "nothing written on a refused call")
    check(fast(name, m._btext, bim._btext, [], [], 200, buf) == 0 and not np.all(buf == 7.0),
          "the same buffer written by a good call (status 0)")
    # more overrides than the module keeps on its stack (SETS_ON_STACK 32): the
    # model's own sigma0 40 times over, the same result
    many = np.empty(3 * 201)
    check(fast(name, m._btext, bim._btext, [b"model.sigma0=6"] * 20, [b"model.sigma0=6"] * 20, 200, many) == 0
          and many.tobytes() == buf.tobytes(), "40 overrides (past the stack array): the same bytes")

    # the GIL is released for the library call: a Python thread ticks during
    # one long call (a million points, about 0.7 s); only the ticks in the
    # call's middle 80 % count, so ticks before and after it do not (with the
    # GIL held there would be none)
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            stop.wait(0.001)
    th = threading.Thread(target=tick)
    th.start()
    t0 = time.perf_counter()
    hystviz.steady_loop(cases[0][0], bim, points=1000000)
    t1 = time.perf_counter()
    stop.set()
    th.join(10)
    inside = sum(t0 + 0.1 * (t1 - t0) < t < t1 - 0.1 * (t1 - t0) for t in ticks)
    check(inside > 5, f"a Python thread ran {inside} times inside a {t1 - t0:.2f} s steady_loop call (GIL released)")

# HYSTVIZ_CTYPES=1 forces the ctypes path (docs/LIBRARY.md)
p = subprocess.run([sys.executable, "-c", "import hystviz; print(hystviz._steady_fast is None)"], capture_output=True,
                   text=True, timeout=120, env=dict(os.environ, HYSTVIZ_CTYPES="1"))
check(p.stdout.strip() == "True", f"HYSTVIZ_CTYPES=1: no fast path ({p.stdout.strip()} {p.stderr.strip()[-120:]})")

# GSL's handler: in a child (an abort must not take this test with it), with
# a deadline
child = r"""
import ctypes, hystviz
gsl = next(ln.split()[-1] for ln in open("/proc/self/maps") if "/libgsl.so" in ln)
g = ctypes.CDLL(gsl)
g.gsl_error.argtypes = [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_int, ctypes.c_int]
g.gsl_error(b"test error", b"test_fast.py", 1, 1)  # GSL_EDOM, as GSL_ERROR raises it
print("returned")
"""
p = subprocess.run([sys.executable, "-c", child], capture_output=True, text=True, timeout=120)
check(p.returncode == 0 and p.stdout.strip() == "returned",
      f"a GSL error in a process that imported hystviz returns (status {p.returncode}, {p.stderr.strip()[-120:]!r})")

print("FAILED" if fails else "all passed", fails)
sys.exit(1 if fails else 0)
