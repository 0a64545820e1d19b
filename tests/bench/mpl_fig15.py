#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""The matplotlib yardstick for `hystviz serve` (issue 16): Fig. 15 redrawn for
a new sigma0 inside one warm Python process, as an interactive matplotlib
session would: NumPy recompute of the steady loop, set_data on the lines,
the annotation's text, canvas draw, and the SVG written to memory.

usage: /usr/bin/python3 tests/bench/mpl_fig15.py [HYSTVIZ SCENE] [N]
       python3 tests/bench/mpl_fig15.py --rows

The loop is the closed form hystviz draws (docs/ARCHITECTURE.md: a run of
variation D maps y to e^(-aD) y + s g(0) (1 - e^(-aD)), a = sigma0/g(0),
at the fixed point of the period map), on the bimodal input 0 -> 1 -> 0.5
-> 1.5 -> 0 with 2000 points per unit of variation as the scene samples.
With HYSTVIZ and SCENE given it first checks its circle and square markers
against `hystviz data` (printed).  Prints median and 95th percentile with
and without the SVG as docs/PERFORMANCE.md's table (tests/cli/test_readme_bench.sh
checks its rows and format; --rows prints the header and first cells only,
without matplotlib); asserts nothing.  Needs python3-matplotlib (Debian)."""
import io
import os
import subprocess
import sys
import time

try:
    import numpy as np
except ImportError:                         # --rows needs neither NumPy nor matplotlib
    np = None

G0 = 2.0                                   # g(0) = Fs of Example 4
RUNS = [(1, 0.0, 1.0), (-1, 1.0, 0.5), (1, 0.5, 1.5), (-1, 1.5, 0.0)]   # sign, from, to
PTS = 2000                                 # points per unit of variation


def loop(sigma0):
    a = sigma0 / G0
    A, B = 1.0, 0.0
    for s, u0, u1 in RUNS:
        e = np.exp(-a * abs(u1 - u0))
        A, B = A * e, e * B + s * G0 * (1 - e)
    y = B / (1 - A)                         # y°(0), the fixed point
    us, ys = [], []
    for s, u0, u1 in RUNS:
        d = np.linspace(0.0, abs(u1 - u0), int(PTS * abs(u1 - u0)) + 1)
        us.append(u0 + s * d)
        ys.append(s * G0 + (y - s * G0) * np.exp(-a * d))
        y = ys[-1][-1]
    return us, ys


# the benchmark's table, docs/PERFORMANCE.md's
TABLE_HEADER = ("| yardstick (`tests/bench/mpl_fig15.py`, one warm process) | redraw + SVG to memory, median / p95 | "
                "without the SVG, median / p95 | SVG | load |\n|---|---|---|---|---|")
ROW = "| matplotlib: Fig. 15 for a new sigma0 (NumPy recompute, set_data, draw) |"


def pct(v, q):
    v = sorted(v)
    return v[min(len(v) - 1, int(round(q / 100 * (len(v) - 1))))]


def main():
    if sys.argv[1:2] == ["--rows"]:
        print(TABLE_HEADER)
        print(ROW)
        return
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    n = int(sys.argv[3]) if len(sys.argv) > 3 else 60
    if len(sys.argv) > 2:
        out = subprocess.run([sys.argv[1], "data", sys.argv[2]], capture_output=True, text=True, check=True).stdout
        mk = {l.split(",")[0]: float(l.split(",")[2]) for l in out.splitlines() if "@marker" in l}
        us, ys = loop(6.0)
        t1 = ys[0][-1]                      # rho = 1: end of the first run
        t5 = ys[2][len(ys[2]) // 2]         # rho = 2: half-way up the third run
        print(f"mpl-fig15 check against hystviz data: circle {abs(t1 - mk['t1@marker']):.1e}, "
              f"square {abs(t5 - mk['t5@marker']):.1e}")
    fig, ax = plt.subplots(figsize=(12 / 2.54, 9 / 2.54), dpi=200)
    us, ys = loop(6.0)
    major, = ax.plot(np.concatenate([us[0], us[3]]), np.concatenate([ys[0], ys[3]]), "k--", lw=1, label="major loop")
    minor, = ax.plot(np.concatenate([us[1], us[2]]), np.concatenate([ys[1], ys[2]]), color="#D55E00", lw=1.5,
                     label="minor loop")
    t1m, = ax.plot([us[0][-1]], [ys[0][-1]], "ko", mfc="none")
    t5m, = ax.plot([us[2][len(us[2]) // 2]], [ys[2][len(ys[2]) // 2]], "ks", mfc="none")
    txt = ax.text(0.05, 1.6, "")
    ax.set_xlabel("u")
    ax.set_ylabel(r"$y^\circ_u$")
    ax.legend(loc="lower right")
    times, times_nosvg = [], []
    for i in range(n + 3):
        sigma0 = 1.0 * (60.0 / 1.0) ** ((i % 50) / 49)
        t0 = time.perf_counter()
        us, ys = loop(sigma0)
        major.set_data(np.concatenate([us[0], us[3]]), np.concatenate([ys[0], ys[3]]))
        mu, my = np.concatenate([us[1], us[2]]), np.concatenate([ys[1], ys[2]])
        minor.set_data(mu, my)
        t1m.set_data([us[0][-1]], [ys[0][-1]])
        t5m.set_data([us[2][len(us[2]) // 2]], [ys[2][len(ys[2]) // 2]])
        txt.set_text(f"minor loop area {abs(np.trapz(my, mu)):.4g}")
        ax.relim()
        ax.autoscale_view()
        fig.canvas.draw()
        t_draw = time.perf_counter()
        buf = io.BytesIO()
        fig.savefig(buf, format="svg")
        t1 = time.perf_counter()
        if i >= 3:                          # the first draws load fonts and caches
            times.append(t1 - t0)
            times_nosvg.append(t_draw - t0)
    print(f"mpl-fig15: {n} changes", file=sys.stderr)
    print(TABLE_HEADER)
    print(f"{ROW} {1e3 * pct(times, 50):.1f} / {1e3 * pct(times, 95):.1f} ms | "
          f"{1e3 * pct(times_nosvg, 50):.1f} / {1e3 * pct(times_nosvg, 95):.1f} ms | {len(buf.getvalue())} bytes | "
          f"{os.getloadavg()[0]:.1f} |", flush=True)


if __name__ == "__main__":
    main()
