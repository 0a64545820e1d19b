# SPDX-License-Identifier: MIT
"""bench_python.py SOURCE_ROOT LIB BENCH_LIB: the Python package's figures
(issues 24, 35), printed in docs/PERFORMANCE.md's units:
  1. call overhead: hystviz.steady_loop (200 points) against a C program
     (bench_lib) making the call it makes, hy_steady_loop, on the same [model]
     and [input] texts and points: CPU time (user + system) per call, the
     medians of 7 rounds each of N calls, C and Python alternating round by
     round so that load on the machine falls on both; the difference is the
     figure (issue 35: goal <= 5 us);
  2. the same in this process: the bare ctypes call (arguments made once)
     against hystviz.steady_loop, single calls alternating, CPU time, median
     of the differences: the wrapper's own cost;
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

src, lib, bench_lib = sys.argv[1:4]
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


def py_round():
    """CPU microseconds per call of one round of N steady_loop calls."""
    c0 = cpu()
    for _ in range(N):
        hystviz.steady_loop(m, u, points=POINTS)
    return (cpu() - c0) / N * 1e6


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

# the wrapper's own cost, in this process: the one C call through ctypes with
# its arguments made once (arrays allocated once) against
# hystviz.steady_loop, single calls alternating so that the process's caches
# and the load fall on both alike; CPU time, median of the differences
fn = hystviz._lib.steady_loop
mt, ut = m.scene_text().encode(), u.scene_text().encode()
buf = np.empty(3 * (POINTS + 1))
a = buf.ctypes.data


def c_call():
    if fn(b"<python>/scene.scene", mt, ut, None, 0, POINTS, a, a + 8 * (POINTS + 1), a + 16 * (POINTS + 1), None):
        raise RuntimeError("hy_steady_loop failed")


load0 = os.getloadavg()[0]
diffs, cs = [], []
for _ in range(10 * N):
    t0 = cpu()
    c_call()
    t1 = cpu()
    hystviz.steady_loop(m, u, points=POINTS)
    t2 = cpu()
    diffs.append((t2 - t1) - (t1 - t0))
    cs.append(t1 - t0)
diffs.sort()
cs.sort()
print(f"python call overhead (in process) | steady_loop {POINTS} points against the bare ctypes call of "
      f"hy_steady_loop, CPU time: {diffs[len(diffs) // 2] * 1e6:.1f} us extra per call (median of {len(diffs)} "
      f"alternating pairs; the bare call {cs[len(cs) // 2] * 1e6:.1f} us; load {load0:.1f}-{os.getloadavg()[0]:.1f}; "
      f"goal <= 5)")

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
