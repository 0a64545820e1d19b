#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""The NumPy yardstick for `hystviz sweep --formats none` (issue 23): the Fig. 15
study's table computed by a plain Python loop over the grid with NumPy, from
the same closed form hystviz uses (docs/ARCHITECTURE.md: a monotone run of
variation d maps y to e^(-a d) y + s g(0) (1 - e^(-a d)), a = sigma0/g(0);
y°(0) is the fixed point B/(1 - A) of the period map y -> A y + B; the
integral of y du over a run is g(0) d + s (y0 - s g(0)) (1 - e^(-a d))/a).

Scalars per point, as sweep.csv's: y° min and max (at the run ends), the
major loop's area (the whole period from its start, as hystviz's
major_area), the minor loop's (the run 1 -> u_min,2 and the way back to 1),
the energy (the period's integral).  The table is written as %.17g CSV.

usage: /usr/bin/python3 tests/bench/np_sweep.py [--vector csv|npy] SIGMA0_FROM SIGMA0_TO NSIGMA UMIN2_FROM UMIN2_TO NUMIN2 OUT [HYSTVIZ_CSV]

--vector (issue 37): the same closed form vectorised over the whole grid
(one NumPy expression per quantity, no Python loop), written as %.17g CSV
with np.savetxt or as a structured .npy with np.save (fields index <i8, then
<f8: model.sigma0, input.umin2, ysteady_min, ysteady_max, major_area,
minor1_area, energy); prints "numpy-vector ...".  With HYSTVIZ_CSV both the
loop's and the vector's scalars are checked against hystviz's table.

The grid is hystviz's --grid model.sigma0=FROM:TO:logN --grid
input.umin2=FROM:TO:N (row-major, sigma0 outer).  Prints one line:
"numpy-loop POINTS points WALL s wall CPU s cpu" (the loop and the table
only: the interpreter's start and NumPy's import are not counted).  With
HYSTVIZ_CSV (sweep.csv of the same grid) it first checks every scalar
against it (relative 1e-9) and exits 1 on a mismatch, so that the two sides
compute the same thing.  Needs python3-numpy (Debian)."""
import csv
import sys
import time

import numpy as np

G0 = 2.0                          # g(0) = Fs of Example 4 (fs = 2)
UMIN1, UMAX1, UMAX2 = 0.0, 1.0, 1.5


def point(sigma0, umin2):
    a = sigma0 / G0
    s = np.array([1.0, -1.0, 1.0, -1.0])
    d = np.array([UMAX1 - UMIN1, UMAX1 - umin2, UMAX2 - umin2, UMAX2 - UMIN1])
    em = -np.expm1(-a * d)        # 1 - e^(-a d), without cancellation
    A, B = 1.0, 0.0
    for i in range(4):
        A, B = A * (1.0 - em[i]), (1.0 - em[i]) * B + s[i] * G0 * em[i]
    y = np.empty(5)
    y[0] = B / (1.0 - A)
    for i in range(4):
        y[i + 1] = s[i] * G0 + (y[i] - s[i] * G0) * (1.0 - em[i])
    area = G0 * d + s * (y[:4] - s * G0) * em / a
    energy = float(area.sum())
    # minor loop: down 1 -> umin2, then up umin2 -> 1 (part of the third run)
    dm = UMAX1 - umin2
    emm = -np.expm1(-a * dm)
    minor = float(area[1] + G0 * dm + (y[2] - G0) * emm / a)
    return float(y.min()), float(y.max()), energy, minor, energy


def points_vec(S0, U2):
    """point() over whole arrays: ymin, ymax, major, minor, energy."""
    a = S0 / G0
    s = np.array([1.0, -1.0, 1.0, -1.0])[:, None]
    d = np.stack([np.full_like(U2, UMAX1 - UMIN1), UMAX1 - U2, UMAX2 - U2, np.full_like(U2, UMAX2 - UMIN1)])
    em = -np.expm1(-a * d)
    A, B = np.ones_like(a), np.zeros_like(a)
    for i in range(4):
        A, B = A * (1.0 - em[i]), (1.0 - em[i]) * B + s[i] * G0 * em[i]
    y = np.empty((5,) + a.shape)
    y[0] = B / (1.0 - A)
    for i in range(4):
        y[i + 1] = s[i] * G0 + (y[i] - s[i] * G0) * (1.0 - em[i])
    area = G0 * d + s * (y[:4] - s * G0) * em / a
    energy = area.sum(axis=0)
    dm = UMAX1 - U2
    minor = area[1] + G0 * dm + (y[2] - G0) * (-np.expm1(-a * dm)) / a
    return y.min(axis=0), y.max(axis=0), energy, minor, energy


def mesh(s0, u2):
    """The grid's points in row-major order (sigma0 outer)."""
    S0, U2 = np.meshgrid(s0, u2, indexing="ij")
    return S0.ravel(), U2.ravel()


def check_vec(s0, u2, path):
    rows = list(csv.DictReader(open(path)))  # at the table's own grid values (logspace differs in the last bits)
    got = points_vec(np.array([float(r["model.sigma0"]) for r in rows]), np.array([float(r["input.umin2"]) for r in rows]))
    worst = 0.0
    for k, col in enumerate(("ysteady_min", "ysteady_max", "major_area", "minor1_area", "energy")):
        t = np.array([float(r[col]) for r in rows])
        worst = max(worst, float(np.max(np.abs(got[k] - t) / np.maximum(np.abs(t), 1e-300))))
    print("np_sweep: the vectorised scalars agree with hystviz's table to %.1e (relative)" % worst)
    if worst > 1e-9:
        sys.exit("np_sweep: they differ: the two sides do not compute the same thing")


def vector(fmt, s0, u2, out):
    w0, c0 = time.perf_counter(), time.process_time()
    S0, U2 = mesh(s0, u2)
    ymin, ymax, major, minor, energy = points_vec(S0, U2)
    n = S0.size
    if fmt == "csv":
        t = np.column_stack([np.arange(n, dtype=np.float64), S0, U2, ymin, ymax, major, minor, energy])
        np.savetxt(out, t, fmt=["%d"] + ["%.17g"] * 7, delimiter=",", comments="",
                   header="index,model.sigma0,input.umin2,ysteady_min,ysteady_max,major_area,minor1_area,energy")
    else:
        names = ["model.sigma0", "input.umin2", "ysteady_min", "ysteady_max", "major_area", "minor1_area", "energy"]
        t = np.empty(n, dtype=[("index", "<i8")] + [(k, "<f8") for k in names])
        t["index"] = np.arange(n)
        for k, v in zip(names, (S0, U2, ymin, ymax, major, minor, energy)):
            t[k] = v
        np.save(out, t)
    w, c = time.perf_counter() - w0, time.process_time() - c0
    print("numpy-vector %d points %.4f s wall %.4f s cpu" % (n, w, c))


def grid(a):
    s0 = np.logspace(np.log10(float(a[0])), np.log10(float(a[1])), int(a[2]))
    u2 = np.linspace(float(a[3]), float(a[4]), int(a[5]))
    return s0, u2


def check(s0, u2, path):
    rows = list(csv.DictReader(open(path)))
    if len(rows) != len(s0) * len(u2):
        sys.exit("np_sweep: %s has %d rows, expected %d" % (path, len(rows), len(s0) * len(u2)))
    worst = 0.0
    for r in rows:
        mine = point(float(r["model.sigma0"]), float(r["input.umin2"]))
        theirs = [float(r[k]) for k in ("ysteady_min", "ysteady_max", "major_area", "minor1_area", "energy")]
        for m, t in zip(mine, theirs):
            worst = max(worst, abs(m - t) / max(abs(t), 1e-300))
    print("np_sweep: the NumPy loop's scalars agree with hystviz's table to %.1e (relative)" % worst)
    if worst > 1e-9:
        sys.exit("np_sweep: they differ: the two sides do not compute the same thing")


def main():
    fmt = None
    if len(sys.argv) > 2 and sys.argv[1] == "--vector" and sys.argv[2] in ("csv", "npy"):
        fmt = sys.argv[2]
        del sys.argv[1:3]
    if len(sys.argv) < 8:
        sys.exit(__doc__)
    s0, u2 = grid(sys.argv[1:7])
    if fmt:
        if len(sys.argv) > 8:
            check_vec(s0, u2, sys.argv[8])
        with open(sys.argv[7], "wb") as f:
            vector(fmt, s0, u2, f)
        return
    if len(sys.argv) > 8:
        check(s0, u2, sys.argv[8])
    w0, c0 = time.perf_counter(), time.process_time()
    with open(sys.argv[7], "w") as f:
        f.write("index,model.sigma0,input.umin2,ysteady_min,ysteady_max,major_area,minor1_area,energy\n")
        i = 0
        for a in s0:
            for b in u2:
                v = point(a, b)
                f.write("%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n" % ((i, a, b) + v))
                i += 1
    w, c = time.perf_counter() - w0, time.process_time() - c0
    print("numpy-loop %d points %.4f s wall %.4f s cpu" % (i, w, c))


if __name__ == "__main__":
    main()
