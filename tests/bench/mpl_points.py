#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""The matplotlib yardstick for large series (issue 23 item 2): Fig. 15 of
Example 4 with N points on the minor loop and 2N on the major loop, as
`hystviz render scenes/fig15_minor_loop_ex4.scene --set compute.points=N`
draws it, written as SVG, PDF and a PNG at 300 dpi (12 cm x 9 cm) by one
process; tests/bench/bench_points.sh times the process and its peak memory
beside hystviz's.  The loop is mpl_fig15.py's closed form (the same runs and
g(0)), sampled here per run: N on each of the major loop's two runs, N split
by variation over the minor loop's two.

usage: /usr/bin/python3 tests/bench/mpl_points.py N OUTDIR"""
import os
import sys

import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mpl_fig15 import G0, RUNS  # noqa: E402


def loop_n(sigma0, counts):
    a = sigma0 / G0
    A, B = 1.0, 0.0
    for s, u0, u1 in RUNS:
        e = np.exp(-a * abs(u1 - u0))
        A, B = A * e, e * B + s * G0 * (1 - e)
    y = B / (1 - A)
    us, ys = [], []
    for (s, u0, u1), n in zip(RUNS, counts):
        d = np.linspace(0.0, abs(u1 - u0), n)
        us.append(u0 + s * d)
        ys.append(s * G0 + (y - s * G0) * np.exp(-a * d))
        y = ys[-1][-1]
    return us, ys


def main():
    n, out = int(sys.argv[1]), sys.argv[2]
    os.makedirs(out, exist_ok=True)
    us, ys = loop_n(6.0, [n, n // 3, n - n // 3, n])
    fig, ax = plt.subplots(figsize=(12 / 2.54, 9 / 2.54), dpi=300)
    ax.plot(np.concatenate([us[0], us[3]]), np.concatenate([ys[0], ys[3]]), "k--", lw=1, label="major loop")
    mu, my = np.concatenate([us[1], us[2]]), np.concatenate([ys[1], ys[2]])
    ax.plot(mu, my, color="#D55E00", lw=1.5, label="minor loop")
    ax.plot([us[0][-1]], [ys[0][-1]], "ko", mfc="none")
    ax.plot([us[2][len(us[2]) // 2]], [ys[2][len(ys[2]) // 2]], "ks", mfc="none")
    ax.text(0.05, 1.6, f"minor loop area {abs(np.trapz(my, mu)):.4g}")
    ax.set_xlabel("u")
    ax.set_ylabel(r"$y^\circ_u$")
    ax.legend(loc="lower right")
    for ext in ("svg", "pdf", "png"):
        fig.savefig(os.path.join(out, "fig15." + ext), format=ext)


if __name__ == "__main__":
    main()
