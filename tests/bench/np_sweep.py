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

usage: /usr/bin/python3 tests/bench/np_sweep.py SIGMA0_FROM SIGMA0_TO NSIGMA UMIN2_FROM UMIN2_TO NUMIN2 OUT.csv [HYSTVIZ_CSV]

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
    if len(sys.argv) < 8:
        sys.exit(__doc__)
    s0, u2 = grid(sys.argv[1:7])
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
