#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The γ-sweep animation of Example 3 made with matplotlib's FuncAnimation,
timed against `hystviz animate` making the same clip (benchmark, issue 5).

usage: /usr/bin/python3 tests/bench/mpl_gamma_sweep.py BUILD/src/app/hystviz [OUTDIR]

Both draw, per frame, the limit loop y°_u, the loop of y_γ over the last of
three input periods and a caption (hystviz: γ and max|y_γ − y*_u|; matplotlib:
γ, as y*_u is not exported by the scene), axes, ticks and legend, at 1280x720,
30 fps, 120 frames (γ from 1 towards 1000, log-spaced, as the scene's
keyframe says).  The data come from hystviz (`hystviz data`, one call per γ)
before any timing starts, so matplotlib is timed on drawing and writing only.
Timed: (1) a PNG sequence (what FuncAnimation's file writers do: draw, then
savefig per frame), (2) an MP4 through FuncAnimation.save with the ffmpeg
writer, when ffmpeg is on PATH; hystviz with -j 1 and -j 2 for both.
Prints the figures; asserts nothing.  Needs python3-matplotlib (Debian)."""
import csv
import io
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.animation import FuncAnimation  # noqa: E402

FRAMES, FPS, W, H, DPI = 120, 30, 1280, 720, 100
SCENE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scenes", "anim_gamma_sweep_ex3.scene")


def gamma_at(i):
    # the scene's keyframe (log-linear from 1 at 0 s to 1000 at 5 s) at the time
    # frame i of a 4 s clip shows, i/(n-1) x 4 s (docs/SCENES.md, Animations)
    t = min(i / (FRAMES - 1) * 4.0 / 5.0, 1.0)
    return math.exp(t * math.log(1000.0))


def series(hystviz, gamma):
    out = subprocess.run([hystviz, "data", SCENE, "--set", "series.g.gamma=%.17g" % gamma],
                         check=True, capture_output=True, text=True).stdout
    data = {}
    for row in csv.DictReader(io.StringIO(out)):
        data.setdefault(row["series"], ([], []))
        data[row["series"]][0].append(float(row["x"]))
        data[row["series"]][1].append(float(row["y"]))
    return data


def run(cmd):
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - t0


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        return 2
    hystviz = os.path.abspath(sys.argv[1])
    outdir = sys.argv[2] if len(sys.argv) > 2 else tempfile.mkdtemp(prefix="mpl_bench_")
    os.makedirs(outdir, exist_ok=True)
    t0 = time.perf_counter()
    data = [series(hystviz, gamma_at(i)) for i in range(FRAMES)]
    print("data for %d frames from hystviz: %.2f s (not timed below)" % (FRAMES, time.perf_counter() - t0))

    fig, ax = plt.subplots(figsize=(W / DPI, H / DPI), dpi=DPI)
    lim = data[-1]["limit"]
    ax.plot(lim[0], lim[1], color="black", lw=1.0, label="y°_u")
    (line,) = ax.plot([], [], color="#D55E00", lw=1.5, label="y_γ")
    text = ax.text(0.0, 1.1, "")
    ax.set_xlim(-0.1, 1.6)
    ax.set_ylim(-1.3, 1.3)
    ax.set_xlabel("u")
    ax.set_ylabel("y")
    ax.legend(loc="lower right")

    def update(i):
        g = data[i]["g"]
        line.set_data(g[0], g[1])
        text.set_text("γ = %.4g" % gamma_at(i))
        return line, text

    anim = FuncAnimation(fig, update, frames=FRAMES, blit=False)
    png_dir = os.path.join(outdir, "mpl_png")
    os.makedirs(png_dir, exist_ok=True)
    t0 = time.perf_counter()
    for i in range(FRAMES):          # what FuncAnimation's file writers do per frame
        update(i)
        fig.savefig(os.path.join(png_dir, "frame_%05d.png" % i), dpi=DPI)
    t_png = time.perf_counter() - t0
    print("matplotlib %s, %d PNG frames %dx%d: %.2f s (%.1f frames/s)" % (matplotlib.__version__, FRAMES, W, H,
                                                                         t_png, FRAMES / t_png))
    hv = {}
    for j in (1, 2):
        hv[j] = run([hystviz, "animate", SCENE, "-o", os.path.join(outdir, "hv_png_j%d" % j), "--quality", "720p30",
                     "--duration", "4", "-j", str(j), "--quiet"])
        print("hystviz animate, same %d PNG frames, -j %d: %.2f s (%.1f frames/s; %.1fx matplotlib)" %
              (FRAMES, j, hv[j], FRAMES / hv[j], t_png / hv[j]))
    if shutil.which("ffmpeg"):
        mp4 = os.path.join(outdir, "mpl.mp4")
        t0 = time.perf_counter()
        anim.save(mp4, writer="ffmpeg", fps=FPS, dpi=DPI)
        t_mp4 = time.perf_counter() - t0
        print("matplotlib FuncAnimation.save(writer='ffmpeg') MP4: %.2f s" % t_mp4)
        for j in (1, 2):
            t = run([hystviz, "animate", SCENE, "-o", os.path.join(outdir, "hv_mp4_j%d" % j), "--quality", "720p30",
                     "--duration", "4", "-j", str(j), "--quiet", "--video", "mp4"])
            print("hystviz animate --video mp4 (PNG frames too), -j %d: %.2f s (%.1fx matplotlib)" % (j, t, t_mp4 / t))
            t = run([hystviz, "animate", SCENE, "-o", os.path.join(outdir, "hv_mp4only_j%d" % j), "--quality",
                     "720p30", "--duration", "4", "-j", str(j), "--quiet", "--video", "mp4", "--no-frames"])
            print("hystviz animate --video mp4 --no-frames, -j %d: %.2f s (%.1fx matplotlib)" % (j, t, t_mp4 / t))
    else:
        print("ffmpeg not on PATH: MP4 comparison skipped")
    return 0


if __name__ == "__main__":
    sys.exit(main())
