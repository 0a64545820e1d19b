# SPDX-License-Identifier: MIT
"""bench_python.py SOURCE_ROOT LIB BENCH_LIB BENCH_PYLOOP: the Python package's figures
(issues 24, 35), printed in docs/PERFORMANCE.md's units:
  1. call overhead: hystviz.steady_loop (200 points) against a C program
     (bench_lib) making the call it makes, hy_steady_loop, on the same [model]
     and [input] texts and points: CPU time (user + system) per call, the
     medians of 7 rounds each of N calls, C and Python alternating round by
     round so that load on the machine falls on both; the difference is the
     figure (issue 35: goal <= 5 us);
  2. the same in this process (the figure of issue 35's goal): C making
     the same calls of hy_steady_loop in this process (BENCH_PYLOOP, a
     module loaded with ctypes that loops in C) against hystviz.steady_loop
     through its compiled fast path (hystviz._fast) and through ctypes (the
     fallback without it), and the extension's call alone: CPU time per
     call, 101 rounds of 100 calls each, alternating; the medians of the
     round-by-round differences are the figures (the quartiles say how far
     the load moved them); then the wrapper alone (the library call replaced
     by a C function that returns at once);
  3. the steady loop of Example 4 as a researcher would compute it with
     SciPy: solve_ivp (RK45, rtol 1e-10, atol 1e-12) of the limit system
     dz/dt = u' - sigma0 |u'| z / g(0), y = sigma0 z, period after period
     until two periods agree to 1e-12, against hystviz's exact y°: time and
     the largest error of each against the exact closed form (hystviz's
     error is measured by the library against its long-double reference)."""
import ctypes
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

src, lib, bench_lib, bench_pyloop = sys.argv[1:5]
sys.path.insert(0, os.path.join(src, "src", "python"))
os.environ["HYSTVIZ_LIB"] = lib
import hystviz  # noqa: E402

m = hystviz.Model("lugre", sigma0=6, sigma1=1, fc=1, fs=2, vs=1, beta=1)
u = hystviz.Input("bimodal", umin1=0, umin2=0.5, umax1=1, umax2=1.5)
N, POINTS = 2000, 200
cpu = time.process_time


def median_us(fn, n):
    rounds = []
    for _ in range(7):
        t0 = time.perf_counter()
        for _ in range(n):
            fn()
        rounds.append((time.perf_counter() - t0) / n * 1e6)
    return sorted(rounds)[3]


def py_round(n=N):
    """CPU microseconds per call of one round of n steady_loop calls."""
    c0 = cpu()
    for _ in range(n):
        hystviz.steady_loop(m, u, points=POINTS)
    return (cpu() - c0) / n * 1e6


load0 = os.getloadavg()[0]
with tempfile.TemporaryDirectory() as tmp:
    mpath, upath = os.path.join(tmp, "model.txt"), os.path.join(tmp, "input.txt")
    with open(mpath, "w") as f:
        f.write(m.scene_text())
    with open(upath, "w") as f:
        f.write(u.scene_text())
    py_round()  # warm: the first calls fill caches (both sides start warm)
    # NumPy loads libquadmath (LAPACK -> libgfortran), which registers a
    # printf hook: glibc then formats every printf the slow way, in the
    # library too. The C program runs as it is and with libquadmath loaded
    # as in this process (its path from this process's own map), to tell the
    # wrapper's cost from the process's
    with open("/proc/self/maps") as f:
        qm = sorted({ln.split()[-1] for ln in f if "/libquadmath.so" in ln})
    cmd = [bench_lib, mpath, upath, str(POINTS), str(N)]
    c_rounds, q_rounds, py_rounds = [], [], []
    for _ in range(7):
        c_rounds.append(float(subprocess.run(cmd, capture_output=True, text=True, check=True, timeout=300).stdout))
        py_rounds.append(py_round())
        if qm:
            q_rounds.append(float(subprocess.run(cmd, capture_output=True, text=True, check=True, timeout=300,
                                                 env=dict(os.environ, LD_PRELOAD=qm[0])).stdout))
c_us, py_us = sorted(c_rounds)[3], sorted(py_rounds)[3]
load = f"load {load0:.1f}-{os.getloadavg()[0]:.1f}"
print(f"python call overhead | steady_loop {POINTS} points, CPU time per call: {py_us:.1f} us from Python, "
      f"{c_us:.1f} us in a C program (hy_steady_loop; medians of 7 alternating rounds of {N} calls, {load}; "
      f"C rounds {min(c_rounds):.1f}-{max(c_rounds):.1f}, Python {min(py_rounds):.1f}-{max(py_rounds):.1f}): "
      f"{py_us - c_us:.1f} us extra per call (goal <= 5)")
if q_rounds:
    q_us = sorted(q_rounds)[3]
    print(f"python call overhead (C with libquadmath) | the same C program with {os.path.basename(qm[0])} loaded "
          f"as NumPy loads it: {q_us:.1f} us (rounds {min(q_rounds):.1f}-{max(q_rounds):.1f}); Python "
          f"{py_us - q_us:.1f} us extra per call against it")
else:
    print("python call overhead (C with libquadmath) | SKIP: this NumPy did not load libquadmath")

# the same calls in this process (issue 35's figure): bench_pyloop's C loop
# makes N calls of hy_steady_loop through the address of the library this
# process loaded, with the same texts, points and one output buffer, timed by
# the clock Python's rounds are timed with (CPU time; one ctypes call a
# round); short rounds alternate C, Python (the compiled fast path where it
# is built), Python through ctypes (the fallback), so that load falls on all
# alike; the figure is the median of the round-by-round differences, with
# their quartiles
loop = ctypes.CDLL(bench_pyloop).bench_pyloop_steady
loop.restype = ctypes.c_int
loop.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_char_p, ctypes.c_char_p, ctypes.c_size_t,
                 ctypes.c_void_p, ctypes.c_size_t]
fn_addr = ctypes.cast(hystviz._lib.lib.hy_steady_loop, ctypes.c_void_p).value
mt, ut = m._btext, u._btext
buf = np.empty(3 * (POINTS + 1))
fast = hystviz._steady_fast


def c_round(n):
    c0 = cpu()
    if loop(fn_addr, hystviz._PY_NAME, mt, ut, POINTS, buf.ctypes.data, n):
        raise RuntimeError("hy_steady_loop failed")
    return (cpu() - c0) / n * 1e6


def bare_round(n):
    """The extension's call alone: arguments made once, one buffer (no
    wrapper, no array made per call)."""
    c0 = cpu()
    for _ in range(n):
        fast(hystviz._PY_NAME, mt, ut, [], [], POINTS, buf)
    return (cpu() - c0) / n * 1e6


def ctypes_round(n):
    hystviz._steady_fast = None  # the package's fallback path (as without the extension)
    try:
        return py_round(n)
    finally:
        hystviz._steady_fast = fast


def extra(rounds, base):
    """The median of the round-by-round differences and their quartiles."""
    d = sorted(r - c for r, c in zip(rounds, base))
    return f"{d[len(d) // 2]:.1f} us extra per call (quartiles {d[len(d) // 4]:.1f} to {d[3 * len(d) // 4]:.1f})"


def wrapper_us(n=20000):
    """hystviz.steady_loop's own CPU cost per call, fast path and ctypes: the
    library call replaced by bench_pyloop_noop (same type, does nothing)."""
    pyloop = ctypes.CDLL(bench_pyloop)
    noop_addr = ctypes.cast(pyloop.bench_pyloop_noop, ctypes.c_void_p).value
    noop = ctypes.CFUNCTYPE(ctypes.c_int)(noop_addr)
    noop.argtypes, noop.restype = hystviz._steady.argtypes, ctypes.c_int
    got, real = [], hystviz._steady
    try:
        if fast is not None:
            fast.__self__.bind(noop_addr)
        hystviz._steady = noop
        got = [py_round(n) if fast is not None else float("nan"), ctypes_round(n)]
    finally:
        hystviz._steady = real
        if fast is not None:
            fast.__self__.bind(fn_addr)
    return got


load0 = os.getloadavg()[0]
ROUNDS, NR = 101, 100
cr, fr, br, tr = [], [], [], []
for _ in range(ROUNDS):
    cr.append(c_round(NR))
    if fast is not None:
        fr.append(py_round(NR))
        br.append(bare_round(NR))
    tr.append(ctypes_round(NR))
load = f"load {load0:.1f}-{os.getloadavg()[0]:.1f}"
if fast is not None:
    path = (f"its compiled fast path (hystviz._fast) {extra(fr, cr)} (goal <= 5); the extension's call alone "
            f"(arguments made once, one buffer) {extra(br, cr)}")
else:
    path = "its compiled fast path: SKIP, hystviz._fast not built"
print(f"python call overhead (same process) | steady_loop {POINTS} points against C making the same calls in the "
      f"same process (tests/bench/bench_pyloop.c), CPU time per call, {ROUNDS} rounds of {NR} calls alternating "
      f"({load}; C median {sorted(cr)[ROUNDS // 2]:.1f} us, rounds {min(cr):.1f}-{max(cr):.1f}): Python through "
      f"{path}; through ctypes (the fallback) {extra(tr, cr)}")
w_fast, w_ct = wrapper_us()
print(f"python call overhead (wrapper alone) | steady_loop with the library call replaced by a C function that "
      f"returns at once (bench_pyloop_noop), CPU time per call of 20000: {w_fast:.2f} us through the fast path, "
      f"{w_ct:.2f} us through ctypes (load {os.getloadavg()[0]:.1f}): the rest of the extra above is the call's "
      f"own slowdown next to Python's work (caches), not the wrapper's")

try:
    from scipy.integrate import solve_ivp
except ImportError:
    print("python vs scipy | SKIP: no scipy (apt-get install python3-scipy)")
    sys.exit(0)

# the bimodal input of Definition 1, slopes ±1: 0 -> 1 -> 0.5 -> 1.5 -> 0
knots_t = np.array([0, 1.0, 1.5, 2.5, 4.0])  # hystviz's Definition 1, normalised (slopes ±1)
knots_u = np.array([0, 1.0, 0.5, 1.5, 0.0])
T = knots_t[-1]
sigma0, g0 = 6.0, 2.0


def rhs(t, z):
    k = min(np.searchsorted(knots_t, t % T, side="right") - 1, 3)
    du = (knots_u[k + 1] - knots_u[k]) / (knots_t[k + 1] - knots_t[k])
    return [du - sigma0 * abs(du) * z[0] / g0]


def scipy_steady(npts=200):
    z0, periods = 0.0, 0
    ts = np.linspace(0, T, npts + 1)
    piece = np.minimum(np.searchsorted(knots_t, ts, side="right") - 1, 3)  # each sample's piece
    while True:
        ys = np.empty(ts.size)
        z = z0
        for k, (a, b) in enumerate(zip(knots_t[:-1], knots_t[1:])):  # piece by piece: the kinks are breakpoints
            idx = np.nonzero(piece == k)[0]
            te = np.clip(ts[idx], a, b)
            sol = solve_ivp(rhs, (a, b), [z], method="RK45", rtol=1e-10, atol=1e-12,
                            t_eval=te if te[-1] == b else np.append(te, b))
            ys[idx] = sol.y[0][:idx.size]
            z = sol.y[0][-1]
        periods += 1
        if abs(z - z0) < 1e-12 or periods > 200:
            return ts, sigma0 * ys, periods
        z0 = z


t_h, u_h, y_h = hystviz.steady_loop(m, u, points=200)
assert np.allclose(u_h, np.interp(t_h, knots_t, knots_u), atol=1e-15), "the input is not hystviz's"
h_us = median_us(lambda: hystviz.steady_loop(m, u, points=200), 50)
t0 = time.perf_counter()
ts, ys, periods = scipy_steady()
sp_s = time.perf_counter() - t0
res = hystviz.run(hystviz._scene(m, u, "[series y]\ndata = ysteady\n", 200))
h_err, h_ref = res.errors["y"]
sp_err = np.max(np.abs(ys - y_h))
print(f"python vs scipy | Example 4 steady loop, 200 points: hystviz {h_us / 1e3:.3f} ms "
      f"(error {h_err:.1e} against {h_ref}); solve_ivp RK45 rtol 1e-10 {sp_s * 1e3:.1f} ms "
      f"({periods} periods to settle, error {sp_err:.1e} against hystviz's exact y°); "
      f"hystviz {sp_s * 1e6 / h_us:.0f}x faster")
