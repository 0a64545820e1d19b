# SPDX-License-Identifier: MIT
"""test_api.py: the package's public API as a researcher reads it.

  1. every public function and class (hystviz.__all__, hystviz.boucwen.simulate,
     each class of hystviz.models) has a numpydoc docstring with Parameters
     (when it takes any), Returns and Raises (functions) and Examples sections;
  2. those Examples run as doctests (their expected outputs are exact: the
     minor-loop area 0.199107 is Fig. 15's, the fitted play radius 0.3 is the
     one the data were made with, a unit square's shoelace area is 1);
  3. help() shows the schema's units: a [model] key with a unit in the schema
     has it in help(hystviz.Model) and in help(hystviz.models[kind]);
  4. plot(result, ax=ax) draws each series with its own points (when
     matplotlib is installed; otherwise that part is skipped with a message);
  5. files: a missing scene is FileNotFoundError, an unreadable one
     PermissionError (skipped as root, who reads any file), a bad scene SceneError.
plot()'s example needs matplotlib: without it that example is left out with
a message (the rest still runs).
"""
import doctest
import inspect
import os
import sys
import tempfile

import numpy as np

import hystviz

fails = 0


def check(cond, what):
    global fails
    print(("ok: " if cond else "FAIL: ") + what, flush=True)
    fails += 0 if cond else 1


# the library is found without ctypes.util.find_library (ldconfig and a
# compiler run at each import: 0.15-0.5 s), and nothing it runs
check("ctypes.util" not in sys.modules and "subprocess" not in sys.modules,
      "import hystviz imports neither ctypes.util nor subprocess")

try:
    import matplotlib
    matplotlib.use("Agg")
    have_mpl = True
except ImportError:
    have_mpl = False
    print("note: matplotlib is not installed (apt-get install python3-matplotlib): plot()'s example is skipped")

public = [(n, getattr(hystviz, n)) for n in hystviz.__all__ if callable(getattr(hystviz, n))]
public += [("boucwen.simulate", hystviz.boucwen.simulate)] + [(f"models[{k!r}]", c) for k, c in hystviz.models.items()]
for name, obj in public:
    doc = inspect.getdoc(obj) or ""
    need = ["Examples\n--------\n>>> "]
    if inspect.isclass(obj) or inspect.signature(obj).parameters:
        need.append("Parameters\n----------")
    if inspect.isfunction(obj):  # a class's constructor raises only what its docstring's Raises says, if any
        need += ["Returns\n-------", "Raises\n------"]
    missing = [n.split("\n")[0] for n in need if n not in doc]
    check(not missing, f"{name}: numpydoc sections" + (f" missing: {', '.join(missing)}" if missing else ""))

with tempfile.TemporaryDirectory() as tmp:
    os.environ["MPLCONFIGDIR"] = os.path.join(tmp, "mpl")
    cwd = os.getcwd()
    os.chdir(tmp)  # the examples' relative files (none expected) land here
    try:
        finder = doctest.DocTestFinder()
        runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS)
        ran = 0
        for mod in (hystviz, hystviz.boucwen):
            for t in finder.find(mod, globs={"hystviz": hystviz, "np": np, "os": os}):
                if not t.examples or (t.name == "hystviz.plot" and not have_mpl):
                    continue
                r = runner.run(t, out=sys.stdout.write)
                ran += r.attempted
                check(r.failed == 0, f"doctest {t.name}: {r.attempted - r.failed} of {r.attempted} examples")
        check(ran >= 60, f"{ran} doctest examples ran")
    finally:
        os.chdir(cwd)

    # units: the schema's, in help()
    units = {k["name"]: k["unit"] for k in hystviz.schema()["sections"][0]["keys"] if k["unit"]}
    check(units.get("c") == "N s/m", f"schema: [model] c has unit N s/m ({units.get('c')!r})")
    check(all(f"{k} : number, {u}" in hystviz.Model.__doc__ for k, u in units.items()),
          f"help(hystviz.Model) shows each of {len(units)} units")
    bw = [k for k, spec in hystviz._MODELS.items() if "c" in spec["params"]]
    check(bool(bw) and "c : number, N s/m" in hystviz.models[bw[0]].__doc__,
          f"help(hystviz.models[{bw[0] if bw else None!r}]) shows c's unit N s/m")
    check(bool(bw) and hystviz.models[bw[0]].units.get("c") == "N s/m" and hystviz.Model.units == units | {
          k: None for k in hystviz.Model.units if k not in units},
          f"hystviz.models[{bw[0] if bw else None!r}].units['c'] == 'N s/m'; Model.units the schema's")

    # plot: one line a series, its points the Result's own (bit for bit)
    if have_mpl:
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots()
        res = hystviz.run(hystviz.scene_path("fig15_minor_loop_ex4"))
        back = hystviz.plot(res, ax=ax)
        lines = {ln.get_label(): ln for ln in ax.get_lines()}
        same = back is ax and set(lines) == set(res.series) and all(
            np.array_equal(lines[k].get_xdata(), x, equal_nan=True) and
            np.array_equal(lines[k].get_ydata(), y, equal_nan=True) for k, (x, y) in res.series.items())
        check(same, f"plot(Result, ax=ax) draws each of {len(res.series)} series with its own points into ax")
        try:
            hystviz.plot(res, ax=ax, model__sigma0=2)
            check(False, "plot(Result, overrides) raised nothing")
        except ValueError as e:
            check("overrides" in str(e), f"plot(Result, overrides) is a ValueError ({e})")
        plt.close(fig)
    else:
        print("SKIP (part): plot(): matplotlib is not installed (apt-get install python3-matplotlib)")

    # files: the OS's exceptions; scenes: SceneError
    missing = os.path.join(tmp, "nosuch.scene")
    for fn, what in ((lambda: hystviz.run(missing), "run"), (lambda: hystviz.render(missing), "render"),
                     (lambda: hystviz.fit(missing, "sigma0"), "fit"), (lambda: hystviz.read_data(missing), "read_data"),
                     (lambda: hystviz.read_forc(missing), "read_forc"),
                     (lambda: hystviz.scene_path("nosuch_scene"), "scene_path")):
        try:
            fn()
            check(False, f"{what}: a missing file raised nothing")
        except FileNotFoundError as e:
            check("nosuch" in str(e), f"{what}: a missing file is FileNotFoundError ({e})")
    locked = os.path.join(tmp, "locked.scene")
    with open(locked, "w") as f:
        f.write("[model]\nkind = lugre\n")
    os.chmod(locked, 0)
    if os.geteuid() != 0:
        try:
            hystviz.run(locked)
            check(False, "run: an unreadable scene raised nothing")
        except PermissionError as e:
            check("locked.scene" in str(e), f"run: an unreadable scene is PermissionError ({e})")
    else:
        print("note: running as root, who reads any file: the PermissionError check is skipped")
    bad = os.path.join(tmp, "bad.scene")
    with open(bad, "w") as f:
        f.write("[model]\nkind = lugre\nsigma0 = -1\n")
    try:
        hystviz.run(bad)
        check(False, "run: a bad scene raised nothing")
    except hystviz.SceneError as e:
        check(str(e).startswith(bad + ":3:"), f"run: a bad scene is SceneError with file:line ({e})")
sys.exit(1 if fails else 0)
