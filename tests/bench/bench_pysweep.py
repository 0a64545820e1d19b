# SPDX-License-Identifier: MIT
"""bench_pysweep.py SCENES_DIR [ROUNDS] | bench_pysweep.py --rows: hystviz.sweep
(the study as a structured array, in C, issue 37) against NumPy vectorised
over the whole grid (b: tests/bench/np_sweep.py's points_vec, the same
closed form) for the same columns (the grid values, ysteady_min,
ysteady_max, major_area, minor1_area, energy) of the Fig. 15 table-only
study, in one process, nothing written: ROUNDS (default 3) alternating
rounds at 1e4, 1e5, 1e6 points, medians of wall and CPU time
(time.process_time: every thread of the process).  The two sides are first
checked to agree (relative 1e-9).  Prints docs/PERFORMANCE.md's rows, with
the load (1, 5, 15 min) before and after; --rows prints the labels only.
Needs python3-numpy and libhystviz (HYSTVIZ_LIB, PYTHONPATH as
tests/python/run.sh sets them)."""
import os
import statistics
import sys
import time

KINDS = [("hv1", "`hystviz.sweep`, `jobs=1`"), ("hv2", "`hystviz.sweep`, `jobs=2`"),
         ("vec", "NumPy vectorised over the grid (b), the arithmetic only")]
SIZES = [10000, 100000, 1000000]


def label(kind, n):
    return f"Fig. 15 table only, {n:,} points, in Python: {dict(KINDS)[kind]}"


if len(sys.argv) > 1 and sys.argv[1] == "--rows":
    print("| Python sweep | wall | points/s | points per CPU second | CPU time / NumPy's |")
    print("|---|---|---|---|---|")
    for n in SIZES:
        for k, _ in KINDS:
            print(f"| {label(k, n)} |")
    sys.exit(0)

import numpy as np  # noqa: E402

import hystviz  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import np_sweep  # noqa: E402

scene = os.path.join(sys.argv[1], "fig15_minor_loop_ex4.scene")
rounds = int(sys.argv[2]) if len(sys.argv) > 2 else 3
cols = ["model.sigma0", "input.umin2", "ysteady_min", "ysteady_max", "major_area", "minor1_area", "energy"]


def load():
    with open("/proc/loadavg") as f:
        return " ".join(f.read().split()[:3])


def grid(n):
    return {"model.sigma0": np.logspace(0, 2, n // 50), "input.umin2": np.linspace(0.1, 0.5, 50)}


def run(kind, g):
    w0, c0 = time.perf_counter(), time.process_time()
    if kind == "vec":
        S0, U2 = np_sweep.mesh(g["model.sigma0"], g["input.umin2"])
        out = np_sweep.points_vec(S0, U2)
    else:
        out = hystviz.sweep(scene, grid=g, columns=cols, jobs=1 if kind == "hv1" else 2)
    return time.perf_counter() - w0, time.process_time() - c0, out


g = grid(10000)
t = run("hv2", g)[2]
v = run("vec", g)[2]
worst = max(float(np.max(np.abs(v[k] - t[c]) / np.maximum(np.abs(t[c]), 1e-300)))
            for k, c in enumerate(["ysteady_min", "ysteady_max", "major_area", "minor1_area", "energy"]))
if worst > 1e-9:
    sys.exit(f"bench_pysweep: hystviz.sweep and NumPy differ by {worst:.1e} (relative): not the same computation")
l0 = load()
print("| Python sweep | wall | points/s | points per CPU second | CPU time / NumPy's |")
print("|---|---|---|---|---|")
for n in SIZES:
    g = grid(n)
    times = {k: [] for k, _ in KINDS}
    for r in range(rounds if n < 1000000 else 1):
        for k, _ in KINDS:
            w, c, _ = run(k, g)
            times[k].append((w, c))
    vc = statistics.median(c for _, c in times["vec"])
    for k, _ in KINDS:
        w = statistics.median(x for x, _ in times[k])
        c = statistics.median(x for _, x in times[k])
        print(f"| {label(k, n)} | {w:.3f} s | {n / w:,.0f} | {n / c:,.0f} | {c / vc:.2f} |")
print(f"\n{rounds} alternating rounds (1 at 1,000,000 points), medians, one process; the two sides agree to "
      f"{worst:.1e} (relative); load (1, 5, 15 min) before: {l0}, after: {load()}")
