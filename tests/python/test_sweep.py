# SPDX-License-Identifier: MIT
"""test_sweep.py HYSTVIZ SCENES_DIR: hystviz.sweep (a study as a NumPy
structured array, computed in C, issue 37) against `hystviz sweep --table npy`
of the same grid: the records are the same bytes (bit for bit: the values are
the library's own doubles, so no tolerance), for any number of threads and
with points the scene refuses; columns= selects fields; a bad key, value or
column raises SweepError naming it.  Files only in its own temporary
directory; every command has a timeout."""
import os
import subprocess
import sys
import tempfile

import numpy as np

import hystviz
from hystviz._sweep import grid_text

hv, scenes = sys.argv[1], sys.argv[2]
scene = os.path.join(scenes, "fig15_minor_loop_ex4.scene")
fails = 0


def check(cond, what):
    global fails
    print(("ok: " if cond else "FAIL: ") + what, flush=True)
    fails += 0 if cond else 1


def raises(what, needle, **kw):
    try:
        hystviz.sweep(scene, **kw)
    except hystviz.SweepError as e:
        check(needle in str(e), f"{what}: SweepError naming {needle!r} ({e})")
        return
    check(False, f"{what}: no SweepError")


# 30 x 7 points; umin2 = 1.2 > umax1 = 1 makes its points invalid (status 1)
sigma0 = np.logspace(0, 2, 30)
umin2 = np.append(np.linspace(0.1, 0.5, 6), 1.2)
grid = {"model.sigma0": sigma0, "input.umin2": umin2}
a = hystviz.sweep(scene, grid=grid, jobs=2)
check(a.shape == (sigma0.size * umin2.size,), f"one record per point ({a.shape})")
with tempfile.TemporaryDirectory(prefix="hystviz-test-sweep-") as tmp:
    args = [hv, "sweep", scene, "--formats", "none", "--table", "npy", "-o", tmp, "-q", "-j", "2"]
    for k, v in grid.items():
        args += ["--grid", k + "=" + ",".join(grid_text(x) for x in v)]
    rc = subprocess.run(args, capture_output=True, timeout=120).returncode
    check(rc == 2, f"the CLI sweep exits 2 (invalid points) (got {rc})")
    with open(os.path.join(tmp, "sweep.npy"), "rb") as f:
        raw = f.read()
    b = np.load(os.path.join(tmp, "sweep.npy"))
check(a.dtype == b.dtype, "the same fields and types as sweep.npy")
check(raw[-a.nbytes:] == a.tobytes() and len(raw) - a.nbytes < 65536 + 64,
      "the records are sweep.npy's bytes, bit for bit")
check((a["status"] == 1).sum() == sigma0.size and (a["status"] == 0).sum() == 6 * sigma0.size,
      "the umin2 = 1.2 points are invalid, the others ok")
check(all(len(m) > 0 for m in a["message"][a["status"] == 1]), "invalid points carry a message")
s = a["model.sigma0"].reshape(sigma0.size, umin2.size)
check(np.array_equal(s[:, 0].view(np.uint64), sigma0.view(np.uint64)), "the first axis is the outermost, values bit for bit")
one = hystviz.sweep(scene, grid=grid, jobs=1)
check(one.tobytes() == a.tobytes(), "jobs=1 gives the bytes of jobs=2")
sh = hystviz.sweep(scene, grid=grid, jobs=2, shard=(1, 3))
check(sh.tobytes() == a[1::3].tobytes(), "shard=(1, 3) gives the whole study's records 1, 4, 7, ...")
cols = ["minor1_area", "model.sigma0", "energy"]
c = hystviz.sweep(scene, grid=grid, columns=cols, jobs=2)
check(c.dtype.names == tuple(cols) and all(c[k].tobytes() == a[k].tobytes() for k in cols),
      "columns= returns those fields, in that order, with the same values")
raises("an unknown grid key", "model.nope", grid={"model.nope": [1.0]})
raises("a value the scene refuses", "sigma0", grid={"model.sigma0": [-1.0]})
raises("a non-finite value", "model.sigma0", grid={"model.sigma0": [np.inf]})
raises("an unknown column", "zz", grid={"model.sigma0": [1.0]}, columns=["zz"])
raises("an empty axis", "model.sigma0", grid={"model.sigma0": []})
sys.exit(1 if fails else 0)
