#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Calibrates the work budget's cost model (src/pipeline/hy_cost.h, issue 36
item 1) on adversarial scenes: history-heavy Preisach minor loops (300, 600,
1,200 nested extrema; a long input file), Jiles-Atherton at large amplitude
and stiff, 200-3200 annotations asking for one place, PNGs at high dpi,
Dahl/LuGre/Bouc-Wen at many points and cycles, the play operator, FORC.

For each case: `hystviz render --print-work` (the estimate and each kind's
count, nothing computed), then the real render, its CPU time (user + sys
of the process, /usr/bin/time's %U %S) the median of RUNS runs taken in
rounds over all cases (alternating, so a burst of load hits every case).
Prints per case the estimate, the estimate in seconds (/ units a second),
the measured CPU seconds, their ratio, and the load average; then fits a
weight per kind (least squares of log time: Gauss-Newton from the
relative-error fit, numpy) and prints them in units (HY_COST_UNITS_PER_S
a second) for hy_cost.h.  With -o FILE it writes the cases, counts and
times (the file tests/scene/test_cost.py checks the estimator against).

usage: bench_cost.py HYSTVIZ SCENES_DIR [--runs N] [-o FILE] [--only NAME...]
       bench_cost.py HYSTVIZ SCENES_DIR --write-scene NAME DIR   (the case's scene, for the test)
"""
import argparse
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

UNITS_PER_S = 1e7  # HY_COST_UNITS_PER_S (hy_cost.h); checked against --print-work's line


def nested_extrema(n):
    """n extrema, each pair inside the last: every minor loop stays on the memory stack."""
    ex = []
    for i in range(n // 2):
        a = 1 - i / (n / 2 + 1.0)
        ex += [-a, a]
    return ("[model]\nkind = preisach\n\n[input]\nkind = multimodal\nextrema = %s\n\n"
            "[compute]\npoints = 400\n\n[figure]\nkind = loop\n\n[series major]\ndata = major\n\n"
            "[series minor]\ndata = minor\n" % ", ".join("%.6g" % e for e in ex))


def file_input(n):
    """A 'measured' input file of n samples: a random walk of reversals (seeded)."""
    rng = np.random.default_rng(36)
    u = np.cumsum(rng.uniform(-1, 1, n))
    u = 2 * (u - u.min()) / (u.max() - u.min()) - 1
    data = "".join("%d %.9g\n" % (i, x) for i, x in enumerate(u))
    scene = ("[model]\nkind = preisach\n\n[input]\nkind = file\nfile = \"u.txt\"\n\n[compute]\npoints = 400\n\n"
             "[figure]\nkind = loop\n\n[series major]\ndata = major\n\n[series minor]\ndata = minor\n")
    return scene, {"u.txt": data}


def with_annotations(src, n):
    """Fig. 15 with n long annotations all asking for one place (bench_annotations.sh's pile)."""
    text = open(src).read()
    text = re.sub(r"(?m)^\[output\][\s\S]*", "", text)
    return text + "".join("\n[annotation a%d]\ntext = \"a long annotation number %d\"\nx = 0.5\ny = 0.1\n" % (i, i)
                          for i in range(n))


JA = ("[model]\nkind = jiles-atherton\nja_ms = 1.6e6\nja_a = 1100\nja_k = %s\nja_c = 0.2\nja_alpha = %s\n\n"
      "[input]\nkind = multimodal\nextrema = -%s, %s, -%s, %s\n\n[compute]\npoints = %d\n\n[figure]\nkind = loop\n\n"
      "[series major]\ndata = major\n\n[series minor]\ndata = minor\n")
PLAY = ("[model]\nkind = play\n\n[input]\nkind = multimodal\nextrema = %s\n\n[compute]\npoints = %d\ncycles = 3\n\n"
        "[figure]\nkind = loop\n\n[series y]\ndata = ystar\n\n[series minor]\ndata = minor\n")


def cases(scenes):
    """(name, scene text or (text, files), render arguments, checked by test_cost.py)."""
    fig15 = os.path.join(scenes, "fig15_minor_loop_ex4.scene")
    out = []
    for n in (300, 600, 1200):
        out.append(("preisach_nested_%d" % n, nested_extrema(n), ["--format", "svg"], n >= 600))
    out.append(("preisach_file_1500", file_input(1500), ["--format", "svg"], False))
    out.append(("ja_large", JA % ("400", "1.6e-3", "1e6", "1e6", "5e5", "5e5", 20000), ["--format", "svg"], False))
    out.append(("ja_stiff", JA % ("1e-6", "2e-3", "2000", "2000", "1000", "1000", 400), ["--format", "svg"], False))
    for n in (200, 800, 3200):
        out.append(("annotations_%d" % n, with_annotations(fig15, n), ["--format", "svg"], n == 800))
    out.append(("png_600dpi", open(fig15).read(), ["--format", "png", "--set", "figure.size=30cm,20cm",
                                                   "--set", "figure.dpi=600"], True))
    out.append(("dahl_filter_solves", open(os.path.join(scenes, "fig04_example1_gamma_loops.scene")).read(),
                ["--format", "svg", "--set", "compute.points=200000"], False))
    out.append(("lugre_solves", open(os.path.join(scenes, "fig11_ygamma_ex3.scene")).read(),
                ["--format", "svg", "--set", "compute.points=300000"], True))
    out.append(("boucwen_cycles", open(os.path.join(scenes, "bw_fig2a_output_periods.scene")).read(),
                ["--format", "svg", "--set", "compute.cycles=20"], True))
    out.append(("play_points", PLAY % (", ".join("%g" % ((-1) ** i * (1 - i / 200.0)) for i in range(100)), 200000),
                ["--format", "svg"], False))
    out.append(("forc_preisach", open(os.path.join(scenes, "forc_preisach.scene")).read(),
                ["--format", "svg", "--set", "forc.curves=300"], False))
    return out


def write_scene(case, scenes, d):
    name, text, args, _ = case
    files = {}
    if isinstance(text, tuple):
        text, files = text
    for inc in ("style.scene", "ex2_model.scene", "ex3_model.scene"):  # what the cases include
        shutil.copy(os.path.join(scenes, inc), d)
    for f, body in files.items():
        with open(os.path.join(d, f), "w") as fh:
            fh.write(body)
    path = os.path.join(d, name + ".scene")
    with open(path, "w") as fh:
        fh.write(text)
    return path


def estimate(hv, path, args, timeout=120):
    """(total units, {kind: count}) from render --print-work."""
    p = subprocess.run([hv, "render", path, "--print-work", "--max-work", "1e15"] + args,
                       capture_output=True, text=True, timeout=timeout)
    if p.returncode != 0:
        raise RuntimeError("%s: --print-work failed (%d): %s" % (path, p.returncode, p.stderr.strip()))
    m = re.search(r"work (\S+) units, about \S+ s of CPU \((\S+) units a second\)", p.stdout)
    if not m or float(m.group(2)) != UNITS_PER_S:
        raise RuntimeError("%s: unexpected --print-work output: %s" % (path, p.stdout))
    counts = {k: float(c) for k, c in re.findall(r"(?m)^  ([\w-]+) +(\S+) x ", p.stdout)}
    if not counts:
        raise RuntimeError("%s: --print-work listed no kind of work: %s" % (path, p.stdout))
    return float(m.group(1)), counts


def measure(hv, path, args, outdir, timeout=600):
    """CPU seconds (user + sys) of one real render, or None when it was refused or failed."""
    tf = os.path.join(outdir, "time")
    p = subprocess.run(["/usr/bin/time", "-f", "%U %S", "-o", tf, hv, "render", path, "-o", outdir,
                        "--max-work", "1e15"] + args, capture_output=True, text=True, timeout=timeout)
    if p.returncode != 0:
        return None, p.stderr.strip().splitlines()[-1] if p.stderr.strip() else "exit %d" % p.returncode
    user, sys_ = open(tf).read().split()[-2:]
    return float(user) + float(sys_), ""


def load():
    return " ".join(open("/proc/loadavg").read().split()[:3])


def fit(rows, kinds):
    """Per-kind weights minimising sum (log est - log t)^2 over the cases, est = sum w_k c_k (units),
    t in units: the relative-error linear fit, then Gauss-Newton in log w (weights stay > 0)."""
    C = np.array([[r["counts"].get(k, 0.0) for k in kinds] for r in rows])
    t = np.array([r["cpu"] * UNITS_PER_S for r in rows])
    used = C.sum(axis=0) > 0
    C, ks = C[:, used], [k for k, u in zip(kinds, used) if u]
    w, *_ = np.linalg.lstsq(C / t[:, None], np.ones(len(t)), rcond=None)
    w = np.where(w > 0, w, np.median(t / C.sum(axis=1)))
    lw = np.log(w)
    for _ in range(50):
        e = C @ np.exp(lw)
        res = np.log(e) - np.log(t)
        J = C * np.exp(lw)[None, :] / e[:, None]
        step, *_ = np.linalg.lstsq(J, -res, rcond=None)
        lw += np.clip(step, -2, 2)
        if np.max(np.abs(step)) < 1e-9:
            break
    return dict(zip(ks, np.exp(lw))), np.exp(np.abs(np.log(C @ np.exp(lw)) - np.log(t)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("hystviz")
    ap.add_argument("scenes")
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("-o", "--out")
    ap.add_argument("--only", nargs="*")
    ap.add_argument("--write-scene", nargs=2, metavar=("NAME", "DIR"))
    a = ap.parse_args()
    all_cases = cases(a.scenes)
    if a.write_scene:
        c = [c for c in all_cases if c[0] == a.write_scene[0]]
        if not c:
            sys.exit("bench_cost: no case %s" % a.write_scene[0])
        print(write_scene(c[0], a.scenes, a.write_scene[1]))
        print(" ".join(c[0][2]))
        return
    todo = [c for c in all_cases if not a.only or c[0] in a.only]
    tmp = tempfile.mkdtemp(prefix="bench_cost.")
    try:
        rows = []
        loads = [load()]
        for c in todo:
            d = os.path.join(tmp, c[0])
            os.mkdir(d)
            path = write_scene(c, a.scenes, d)
            try:
                est, counts, why = *estimate(a.hystviz, path, c[2]), ""
            except RuntimeError as e:  # refused before computing (JA's step budget): nothing to time
                est, counts, why = float("nan"), {}, "refused before computing: " + str(e).split(": ", 2)[-1]
            rows.append({"name": c[0], "path": path, "args": c[2], "check": c[3], "est": est, "counts": counts,
                         "times": [], "why": why})
        for _ in range(a.runs):  # rounds over the cases: alternating runs
            for r in rows:
                if r["why"]:
                    continue
                cpu, why = measure(a.hystviz, r["path"], r["args"], os.path.dirname(r["path"]))
                if cpu is None:
                    r["why"] = why
                else:
                    r["times"].append(cpu)
            loads.append(load())
        machine = "%s, %d cores, %s" % (os.uname().machine, os.cpu_count(), os.uname().release)
        print("bench_cost: %s; load average (1, 5, 15 min) at each round: %s" % (machine, " | ".join(loads)))
        print("%-20s %12s %10s %10s %7s" % ("case", "estimate", "est s", "CPU s", "ratio"))
        done = []
        for r in rows:
            if r["why"]:
                print("%-20s %12.4g %10.3g %10s %7s  refused or failed: %s" % (r["name"], r["est"], r["est"] / UNITS_PER_S,
                                                                              "-", "-", r["why"][:100]))
                continue
            r["cpu"] = float(np.median(r["times"]))
            done.append(r)
            print("%-20s %12.4g %10.3g %10.3g %7.2f" % (r["name"], r["est"], r["est"] / UNITS_PER_S, r["cpu"],
                                                       r["est"] / UNITS_PER_S / r["cpu"]))
        if a.out:
            with open(a.out, "w") as fh:
                fh.write("# written by tests/bench/bench_cost.py (%s)\n# %s; load average per round: %s\n"
                         "# case check cpu_seconds estimate_units_at_the_run (the weights then in hy_cost.h) runs\n"
                         % (time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), machine, " | ".join(loads)))
                for r in done:
                    fh.write("%s %d %.4g %.6g %d\n" % (r["name"], 1 if r["check"] else 0, r["cpu"], r["est"],
                                                       len(r["times"])))
        kinds = sorted({k for r in done for k in r["counts"]})
        if done:
            w, factor = fit(done, kinds)
            print("fitted weights (units a count, %g units a second; least squares of log CPU time):" % UNITS_PER_S)
            for k, v in sorted(w.items()):
                print("  %-12s %.4g" % (k, v))
            print("with them the estimate is within a factor %.2f of the measured time on every case (worst)"
                  % float(np.max(factor)))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
