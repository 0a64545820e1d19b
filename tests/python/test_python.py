# SPDX-License-Identifier: MIT
"""test_python.py HYSTVIZ SCENES_DIR: the Python package (src/python/hystviz)
against the hystviz command: the same scene gives the same numbers bit for
bit (floats parsed from `hystviz data`'s %.17g round-trip exactly), the same
SVG bytes, the same minor-loop area as `hystviz loops`, the same Bouc-Wen
output as `hystviz boucwen data`; errors are exceptions with file:line:col.
"""
import math
import os
import stat
import subprocess
import sys
import tempfile
import threading

import numpy as np

import hystviz

hv, scenes = sys.argv[1], sys.argv[2]
fails = 0


def check(cond, what):
    global fails
    print(("ok: " if cond else "FAIL: ") + what, flush=True)
    fails += 0 if cond else 1


def cli(*args, **kw):
    return subprocess.run([hv, *args], check=True, capture_output=True, timeout=120, **kw).stdout


def data_csv(text):
    """series name -> (x, y) from `hystviz data` output."""
    out = {}
    for line in text.decode().splitlines()[1:]:
        name, x, y = line.rsplit(",", 2)
        out.setdefault(name, ([], []))
        out[name][0].append(float(x))
        out[name][1].append(float(y))
    return {k: (np.array(a), np.array(b)) for k, (a, b) in out.items()}


with tempfile.TemporaryDirectory() as tmp:
    fig15 = os.path.join(scenes, "fig15_minor_loop_ex4.scene")
    # a scene file: CSV, SVG and loops as the CLI's
    r = hystviz.run(fig15, model__sigma0=2.5)
    check(r.csv().encode() == cli("data", fig15, "--set", "model.sigma0=2.5"), "run(fig15).csv() == hystviz data")
    svgdir = os.path.join(tmp, "svg")
    cli("render", fig15, "--set", "model.sigma0=2.5", "--format", "svg", "-o", svgdir)
    with open(os.path.join(svgdir, "fig15_minor_loop_ex4.svg"), "rb") as f:
        check(r.render("svg") == f.read(), "render('svg') == hystviz render's SVG bytes")
    fig = hystviz.render(fig15, **{"model.sigma0": 2.5})
    check(fig._repr_svg_().startswith("<?xml"), "Figure._repr_svg_ for Jupyter")
    png = os.path.join(tmp, "f.png")
    fig.save(png)
    with open(png, "rb") as f:
        check(f.read(8) == b"\x89PNG\r\n\x1a\n", "Figure.save(.png) writes a PNG")

    # steady_loop's arrays == hystviz data of the same scene, bit for bit
    m = hystviz.Model("lugre", sigma0=6, sigma1=1, fc=1, fs=2, vs=1, beta=1)
    u = hystviz.Input("bimodal", umin1=0, umin2=0.5, umax1=1, umax2=1.5)
    t, uu, y = hystviz.steady_loop(m, u, points=200)
    path = os.path.join(tmp, "steady.scene")
    with open(path, "w") as f:
        f.write(hystviz._scene(m, u, "[series y]\ndata = ysteady\n", 200))
    d = data_csv(cli("data", path))
    check(np.array_equal(t, d["y"][0]) and np.array_equal(y, d["y"][1]) and np.array_equal(uu, d["u"][1]),
          f"steady_loop: {t.size} points equal hystviz data's bit for bit")
    for name, fn in (("limit", lambda: hystviz.limit(m, u, points=100)),
                     ("ygamma", lambda: hystviz.ygamma(m, u, 10, points=100)),
                     ("kcycles", lambda: hystviz.kcycles(m, u, 2, points=100))):
        tt, _, yy = fn()
        check(tt.size == 101 and np.all(np.isfinite(tt)) and np.all(np.isfinite(yy)), f"{name}: 101 finite samples")
    # steady_loop is one call of hy_steady_loop (issue 35): bit for bit what
    # its previous implementation returned, the scene of the same sections
    # through hy_result_from_text (_tuy over _scene_bytes, which limit, ygamma
    # and kcycles still use): exact equality, as both must be the one
    # computation of the library; every model kind with a steady state,
    # inputs of every shape, a string key (input file), point counts from
    # the least the schema allows; a refused one raises the same SceneError
    upath2 = os.path.join(tmp, "u2.csv")
    with open(upath2, "w") as f:
        f.write("0,0\n0.5,1\n1,0.25\n1.5,0.75\n2,0\n")
    bim = hystviz.Input("bimodal", umin1=0, umin2=0.5, umax1=1, umax2=1.5)
    cases = [(m, bim), (hystviz.Model("lugre", sigma0=1e5), hystviz.Input("sine", amp=2)),
             (hystviz.Model("dahl", rho=3, fc=0.7), hystviz.Input("multimodal", extrema=[0, 1, 0.3, 0.8])),
             (hystviz.Model("dahl-filter", rho=2, fc=1, tau=0.3), hystviz.Input("triangle")),
             (hystviz.Model("jiles-atherton", ja_ms=1.6e6, ja_a=1100, ja_k=400, ja_c=0.2, ja_alpha=1.6e-3),
              hystviz.Input("bimodal", umin1=-1500, umin2=-1100, umax1=500, umax2=1500, t=[1, 2.2, 3.2, 5],
                            shape="cosine")),
             (hystviz.Model("preisach"), bim), (hystviz.Model("preisach"), hystviz.Input("file", file=upath2)),
             (hystviz.Model("boucwen-operator", bw_beta=1, bw_gamma=0.5, delta=0.5), hystviz.Input("sine")),
             (hystviz.Model("play", play_r=0.2), hystviz.Input("file", file=upath2)),
             (hystviz.Model("lugre", sigma0=-1), bim), (m, hystviz.Input("multisine"))]
    same = refused_same = 0
    for mm, ii in cases:
        for pts in (2, 37, 200):
            try:
                new = hystviz.steady_loop(mm, ii, points=pts)
            except hystviz.SceneError as e:
                new = e
            try:
                old = hystviz._tuy(hystviz._scene_bytes(mm.scene_text(), ii.scene_text(), "[series y]\ndata = ysteady\n",
                                                        pts), pts, hystviz._sets_of(mm, ii))
            except hystviz.SceneError as e:
                old = e
            if isinstance(old, Exception) or isinstance(new, Exception):
                ok = type(old) is type(new) and str(old) == str(new) and old.code == new.code
                refused_same += ok
            else:
                ok = all(a.shape == (pts + 1,) and a.tobytes() == b.tobytes() for a, b in zip(new, old))
                same += ok
            check(ok, f"steady_loop({mm!r}, {ii!r}, points={pts}) as before: "
                      f"{'refused alike' if isinstance(old, Exception) else 'bit for bit'}")
    check(same >= 24 and refused_same == 6, f"{same} computed cases bit for bit, {refused_same} refused alike")
    for bad in (1, -5, 10**7 + 1, 10**15):  # the schema's range 2 to 10^7, checked before any array is made
        try:
            hystviz.steady_loop(m, bim, points=bad)
            check(False, f"points = {bad} refused")
        except hystviz.SceneError as e:
            check("'points'" in str(e) and "2 to 10000000" in str(e), f"points = {bad} refused: {e}")
    # the copy retries with the size the library reports when its first guess is short
    t2, u2, y2 = hystviz._tuy(hystviz._scene(m, u, "[series y]\ndata = ysteady\n", 200), 10)
    check(np.array_equal(t2, t) and np.array_equal(u2, uu) and np.array_equal(y2, y),
          "a short first buffer: the retried copy equals steady_loop's arrays")

    # minor loops: hystviz loops' area, %.17g, bit for bit
    loops = hystviz.minor_loops(m, u)
    want = [l.split(",") for l in cli("loops", "--sigma0", "6", "--input", "bimodal:0,0.5,1,1.5").decode().splitlines()
            if l.startswith("minor,")]
    check(len(loops) == len(want) == 1 and loops[0].area == float(want[0][9]),
          f"minor_loops area {loops[0].area!r} == hystviz loops {want[0][9] if want else None}")

    # Figure.save through libhystviz's output writer, as the CLI writes (issue
    # 36 item 3): it wrote to a predictable path.tmp<pid>, followed a link
    # planted there, and replaced whatever was at the target (a link, a FIFO,
    # a device); strings went into scene text as they were
    sd = os.path.join(tmp, "save")
    os.mkdir(sd)
    victim = os.path.join(tmp, "victim.txt")
    with open(victim, "w") as f:
        f.write("victim\n")

    def victim_intact():
        with open(victim) as f:
            return f.read() == "victim\n"
    target = os.path.join(sd, "fig.svg")
    planted = f"{target}.tmp{os.getpid()}"
    os.symlink(victim, planted)
    fig.save(target)
    with open(target, "rb") as f:
        check(victim_intact() and f.read() == fig.svg and not os.path.islink(target),
              "a link planted at the old temporary name path.tmp<pid> is not followed")
    if os.path.lexists(planted):
        os.unlink(planted)
    with open(victim, "w") as f:  # (the old code wrote through the link: the next checks start afresh)
        f.write("victim\n")
    out_link = os.path.join(sd, "out.svg")
    os.symlink(victim, out_link)
    try:
        fig.save(out_link)
        check(False, "a link at the target that leads out of its directory is refused")
    except OSError as e:
        check(os.path.islink(out_link) and victim_intact(), f"a link out at the target: refused, left as it was: {e}")
    if os.path.lexists(out_link):
        os.unlink(out_link)
    fifo = os.path.join(sd, "pipe.svg")
    os.mkfifo(fifo)
    got = []

    def drain():
        with open(fifo, "rb") as f:
            got.append(f.read())
    th = threading.Thread(target=drain, daemon=True)  # daemon: with the old code it waits on a FIFO no one opens
    th.start()
    fig.save(fifo)
    th.join(20)
    check(stat.S_ISFIFO(os.lstat(fifo).st_mode) and got == [fig.svg],
          "a FIFO at the target is written as it is, not replaced by a regular file")
    os.unlink(fifo)
    check(sorted(os.listdir(sd)) == ["fig.svg"], f"no temporary left beside the target: {sorted(os.listdir(sd))}")
    for name in os.listdir(sd):
        os.unlink(os.path.join(sd, name))

    def refused(what, fn):
        try:
            fn()
            check(False, f"{what}: refused")
        except ValueError as e:
            check(("NUL" in str(e) or "newline" in str(e) or "carriage" in str(e)) and "victim" not in os.listdir(sd),
                  f"{what}: ValueError naming it: {e}")
    refused("a NUL in Figure.save's format", lambda: fig.save(os.path.join(sd, "x.png"), format="svg\0png"))
    refused("a newline in Figure.save's format", lambda: fig.save(os.path.join(sd, "x"), format="svg\n"))
    refused("a NUL in Figure.save's path", lambda: fig.save(os.path.join(sd, "x.svg\0.png")))
    refused("a NUL in render's format", lambda: r.render("svg\0"))
    refused("a newline in a string parameter", lambda: hystviz.Input("file", file="u.csv\n[model]\nkind = dahl"))
    refused("a NUL in a string parameter", lambda: hystviz.Input("file", file="u.csv\0x"))
    refused("a newline in an override", lambda: hystviz.run(fig15, sets={"figure.title": "x\n[model]\nsigma0 = -1"}))
    refused("a NUL in an override", lambda: hystviz.run(fig15, figure__title="x\0y"))
    refused("a newline in an override's key", lambda: hystviz.run(fig15, sets={"figure.title\n[x]": "t"}))
    refused("a newline in ygamma's solver", lambda: hystviz.ygamma(m, u, 10, points=10, solver="exact\n[series z]"))
    check(len(os.listdir(sd)) == 0, f"nothing written by a refused save: {os.listdir(sd)}")
    # a string parameter reaches the library through its --set parser
    upath = os.path.join(tmp, "u 2 #.csv")  # a space and a '#': the value's own characters (quoted for the parser)
    with open(upath, "w") as f:
        f.write("0,0\n0.5,1\n1,0\n")
    ufile = hystviz.Input("file", file=upath)
    check(ufile.scene_sets() == [f'input.file="{upath}"'.encode()] and upath not in ufile.scene_text(),
          "a string parameter goes to the --set parser, not into scene text")
    tf, uf, yf = hystviz.steady_loop(m, ufile, points=20)
    check(tf.size == 21 and np.all(np.isfinite(yf)) and abs(uf.max() - 1) < 1e-12, "steady_loop on an input file (a string key)")
    title = 'a "quoted" title \\ with #'
    svg = hystviz.render(fig15, figure__title=title).svg
    tdir = os.path.join(tmp, "titled")
    cli("render", fig15, "--set", 'figure.title="a \\"quoted\\" title \\\\ with #"', "--format", "svg", "-o", tdir)
    with open(os.path.join(tdir, "fig15_minor_loop_ex4.svg"), "rb") as f:
        want = f.read()
    check(svg == want and svg != fig.svg, "a text override is quoted for the --set parser: the SVG equals hystviz render's with the quoted title")

    # Bouc-Wen: the CLI's output for a force file at the integration rate
    n = 3000
    force = 50 * np.sin(2 * np.pi * 5 * np.arange(n) / 750)
    fpath = os.path.join(tmp, "u.csv")
    with open(fpath, "w") as f:
        f.write("".join(f"{i / 750!r},{v!r}\n" for i, v in enumerate(force)))
    rows = [l.split(",") for l in cli("boucwen", "data", "--input", fpath, "--upsample", "1", "--fs", "750", "--noise", "0")
            .decode().splitlines()[1:]]
    yb = hystviz.boucwen.simulate(force, fs=750)
    check(len(rows) == n and np.array_equal(yb, np.array([float(r[2]) for r in rows])),
          f"boucwen.simulate: {n} samples == hystviz boucwen data bit for bit")

    # errors: exceptions with the C message and its location
    try:
        hystviz.run("[model]\nkind = lugre\nsigma0 = -1\n")
        check(False, "a refused scene raises")
    except hystviz.SceneError as e:
        check(":3:" in str(e) and "sigma0" in str(e), f"SceneError names line 3 and sigma0: {e}")
    try:
        hystviz.Model("lugre", sigmaO=1)
        check(False, "an unknown key raises")
    except hystviz.SceneError as e:
        check("sigmaO" in str(e), f"unknown key named: {e}")
    check("sigma0" in hystviz.Model.__doc__ and "> 0" in hystviz.Model.__doc__,
          "help(Model) lists sigma0 with its range from the schema")
    # the model table: a class per kind with exactly its parameters
    check(set(hystviz.models) >= {"dahl", "lugre", "boucwen", "jiles-atherton", "preisach"},
          f"a class per model kind: {sorted(hystviz.models)}")
    check("ja_ms" in hystviz.models["jiles-atherton"].__doc__ and "sigma0" not in hystviz.models["jiles-atherton"].__doc__,
          "help(models['jiles-atherton']) lists its parameters only")
    try:
        hystviz.models["preisach"](sigma0=1)
        check(False, "a parameter of another model raises")
    except hystviz.SceneError as e:
        check("preisach" in str(e) and "sigma0" in str(e), f"another model's parameter refused: {e}")
    ja = hystviz.models["jiles-atherton"](ja_ms=1.6e6, ja_a=1100, ja_k=400, ja_c=0.2, ja_alpha=1.6e-3)
    jl = hystviz.minor_loops(ja, hystviz.Input("bimodal", umin1=-1500, umin2=-1100, umax1=500, umax2=1500))
    check(len(jl) == 1 and jl[0].area > 0, f"Jiles-Atherton minor loop from Python: {jl}")

    # the GIL is released during a computation: another thread runs meanwhile
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(1)
            stop.wait(0.001)
    th = threading.Thread(target=tick)
    th.start()
    hystviz.run(fig15, compute__points=400000)
    stop.set()
    th.join(10)
    check(len(ticks) > 5, f"a Python thread ran {len(ticks)} times during a long computation")

# read_data: the reader of a scene's [data] (the ferrite's four loops), the same
# doubles as `hystviz data` prints for the scene's measured series; a bad file
# raises SceneError with FILE:LINE:COL
ferrite = os.path.join(scenes, "data", "magnetic", "mnzn_ferrite.csv")
d = hystviz.read_data(ferrite, u="H_A_per_m", y="B_T", split="loop")
check(d["u"].shape == (516,) and list(d["records"]) == [0, 129, 258, 387, 516], f"read_data: {d['u'].shape} rows, records {list(d['records'])}")
rows = [ln.split(",") for ln in cli("data", os.path.join(scenes, "ferrite_measured.scene")).decode().splitlines()[1:]]
meas = np.array([[float(r[1]), float(r[2])] for r in rows if r[0] == "measured"])
check(meas.shape == (516, 2) and np.array_equal(meas[:, 0], d["u"]) and np.array_equal(meas[:, 1], d["y"]),
      "read_data = hystviz data's measured rows, bit for bit")
check(bool(np.all(d["area"] > 0)) and np.all(np.diff(d["area"]) > 0), f"loop areas grow with amplitude, > 0: {d['area']}")
d4 = hystviz.read_data(ferrite, u=2, y=3, split=1, y_scale=1e3, record=4)
check(d4["u"].shape == (129,) and d4["y"][0] == d["y"][387] * 1e3, "record 4, columns by index, y in mT")
check(hystviz.loop_area([0, 1, 1, 0], [0, 0, 1, 1]) == 1.0, "loop_area: the unit square counter-clockwise is +1")
with tempfile.TemporaryDirectory() as td:
    bad = os.path.join(td, "bad.csv")
    with open(bad, "w") as f:
        f.write("H,B\n1,2\n3,nan\n")
    try:
        hystviz.read_data(bad, u="H", y="B")
        check(False, "read_data accepted nan")
    except hystviz.SceneError as e:
        check(str(e).startswith(bad + ":3:3: column 2 is not a finite number"), f"read_data refusal: {e}")

# fit: hystviz.fit against `hystviz fit -o` (issue 32 item 6): the same estimates,
# standard errors and RMS bit for bit (the fitted scene writes them %.17g), the
# same fitted scene text; the residuals are model - measured; a bad key raises
with tempfile.TemporaryDirectory() as td:
    with open(os.path.join(td, "p.csv"), "w") as f:
        f.write("u,y\n")
        y = 0.0
        for i in range(61):
            x = i / 60 * 4
            u = x if x < 1 else 2 - x if x < 3 else x - 4
            y = u - 0.3 if u - y > 0.3 else u + 0.3 if y - u > 0.3 else y
            f.write(f"{u!r},{y + 0.01 * math.sin(7 * i)!r}\n")
    sc = os.path.join(td, "p.scene")
    with open(sc, "w") as f:
        f.write("[model]\nkind = play\nplay_r = 0.2\nplay_y0 = 0.1\n[data d]\nfile = \"p.csv\"\nu = u\ny = y\n"
                "[input]\nkind = data\ndata = d\n[figure]\nkind = loop\n[series m]\ndata = modelled\nof = d\n")
    out = os.path.join(td, "fitted.scene")
    cli("fit", sc, "--free", "play_r,play_y0", "--starts", "3", "--seed", "5", "-j", "1", "-q", "-o", out)
    with open(out) as f:
        text = f.read()
    fr = hystviz.fit(sc, free=["play_r", "play_y0"], starts=3, seed=5)
    vals = {ln.split(" = ")[0]: float(ln.split(" = ")[1]) for ln in text.splitlines() if " = " in ln and
            ln.startswith("play_")}
    ses = {ln.split()[1]: float(ln.split()[2]) for ln in text.splitlines() if ln.startswith("#   play_")}
    rms = float(text.splitlines()[0].split("RMS ")[1].split()[0])
    check(fr.keys == ["play_r", "play_y0"], f"fit keys {fr.keys}")
    check([vals[k] for k in fr.keys] == list(fr.estimates), f"fit estimates = hystviz fit's bit for bit: {fr.estimates}")
    check([ses[k] for k in fr.keys] == list(fr.std_errors), f"fit standard errors bit for bit: {fr.std_errors}")
    check(rms == fr.rms and fr.scene_text == text, f"fit RMS {fr.rms} and the fitted scene's text = the CLI's")
    check(abs(fr.estimates[0] - 0.3) < 3 * fr.std_errors[0], f"play_r {fr.estimates[0]} within 3 SE of 0.3")
    check(np.array_equal(fr.residuals, fr.model - fr.measured) and fr.u.shape == (61,) and fr.correlation.shape == (2, 2)
          and list(fr.offsets) == [0, 61] and fr.data == ["d"], "fit residuals = model - measured; shapes")
    try:
        hystviz.fit(sc, free="nosuch")
        check(False, "fit accepted an unknown key")
    except hystviz.SceneError as e:
        check("[model] has no key 'nosuch'" in str(e), f"fit refusal: {e}")
# ---- FORC (issue 33 item 6): hystviz.forc and hystviz.read_forc against `hystviz forc` bit for bit ----
forc_file = os.path.join(scenes, "data", "forc", "conventional_example.forc")
with tempfile.TemporaryDirectory() as td:
    rho_csv, curves_csv = os.path.join(td, "rho.csv"), os.path.join(td, "curves.csv")
    cli("forc", forc_file, "-o", rho_csv, "--curves-out", curves_csv)
    f = hystviz.forc(forc_file)
    rows = ["hc,hu,rho"]
    for iu, hu in enumerate(f["hu"]):
        for ic, hc in enumerate(f["hc"]):
            r = f["rho"][iu, ic]
            rows.append("%.10g,%.10g,%s" % (hc, hu, "%.17g" % r if math.isfinite(r) else "nan"))
    with open(rho_csv) as fh:
        check("\n".join(rows) + "\n" == fh.read(), f"forc(file): rho ({f['rho'].shape}) = hystviz forc -o, bit for bit")
    rows = ["ha,hb,m"] + ["%.17g,%.17g,%.17g" % t for t in zip(f["ha"], f["hb"], f["m"])]
    with open(curves_csv) as fh:
        check("\n".join(rows) + "\n" == fh.read(), "forc(file): curves = hystviz forc --curves-out, bit for bit")
    d = hystviz.read_forc(forc_file)
    check(len(d["curves"]) == 121 and len(d["m"]) == 8394 and d["field_unit"] == "T" and d["moment_unit"] == "A m2",
          f"read_forc: 120 curves, 8394 points, T and A m2 ({len(d['curves']) - 1}, {len(d['m'])})")
    # arrays in give the same distribution as the file
    g = hystviz.forc(ha=d["ha"], hb=d["hb"], m=d["m"])
    check(np.array_equal(g["rho"], f["rho"], equal_nan=True), "forc(ha=, hb=, m=) = forc(file)")
    # a truncated file: SceneError at its line
    cut = os.path.join(td, "cut.forc")
    with open(forc_file, "rb") as a, open(cut, "wb") as b:
        b.write(b"".join(a.readlines()[:1999]))
    try:
        hystviz.read_forc(cut)
        check(False, "read_forc accepted a truncated file")
    except hystviz.SceneError as e:
        check(str(e).startswith(cut + ":1999:") and "NCrv = 120" in str(e), f"read_forc refusal: {e}")

# the protocol on a Python model: the y*_u limit of docs/FORC.md (a = 2, g0 = 2):
# M(H_a, H_b) = e^{-a(H_b - H_a)} M(H_a) + g0 (1 - e^{-a(H_b - H_a)}) along each curve
state = {"u": 6.0, "y": 2.0}


def ystar(u, a=2.0, g0=2.0):
    d = u - state["u"]
    s = 1.0 if d > 0 else -1.0
    state["y"] = math.exp(-a * abs(d)) * state["y"] + s * g0 * (-math.expm1(-a * abs(d)))
    state["u"] = u
    return state["y"]


p = hystviz.forc(model=ystar, protocol=dict(hsat=6, ha_lo=-2, ha_hi=2, ncurves=30), sf=3)
i0, i1 = p["curves"][5], p["curves"][6]
ha, hb, m = p["ha"][i0], p["hb"][i0:i1], p["m"][i0:i1]
want = np.exp(-2 * (hb - ha)) * m[0] + 2 * -np.expm1(-2 * (hb - ha))
# 1e-12: the model's own steps compound one exp per point (about 60 roundings) against one closed form
check(np.max(np.abs(m - want)) < 1e-12 and len(p["curves"]) == 31, "forc(model=): the protocol through a Python callable")
# rho beyond the ridge is negative (-g0 a^2 e^{-2 a H_c}): no Preisach density
hc_col = np.searchsorted(p["hc"], 0.5)
check(np.nanmax(p["rho"][:, hc_col]) < 0, "forc(model=): the y* limit's rho < 0 at H_c = 0.5")
try:
    hystviz.forc(model=lambda u: 1 / 0, protocol=dict(hsat=6, ha_lo=-2, ha_hi=2, ncurves=30))
    check(False, "a failing model passed")
except ZeroDivisionError:
    check(True, "forc(model=): the model's exception raised again")

sys.exit(1 if fails else 0)
