# SPDX-License-Identifier: MIT
"""test_dask.py HYSTVIZ SCENES_DIR: the Dask recipe of docs/STUDIES.md (the
code block after its "dask-recipe" marker, run as written) on a LocalCluster
on loopback gives the one-process hystviz.sweep's records byte for byte
(the same library computes both: no tolerance).  Exit 77 (SKIP) when
dask.distributed is missing (Debian python3-distributed).  Dask's files go to
this test's own temporary directory; every wait has a deadline (the cluster
is in-process; run.sh runs this under `timeout 300`)."""
import os
import sys
import tempfile

try:
    import dask
    import dask.distributed  # noqa: F401
except ImportError as e:
    print(f"SKIP: dask.distributed is missing ({e}); apt-get install python3-distributed")
    sys.exit(77)

import numpy as np

import hystviz

hv, scenes = sys.argv[1], sys.argv[2]
scene = os.path.join(scenes, "fig15_minor_loop_ex4.scene")
doc = os.path.join(scenes, "..", "docs", "STUDIES.md")
with open(doc, encoding="utf-8") as f:
    text = f.read()
start = text.index("<!-- dask-recipe")
begin = text.index("```python\n", start) + 10
code = text[begin:text.index("\n```\n", begin)]
fails = 0


def check(cond, what):
    global fails
    print(("ok: " if cond else "FAIL: ") + what, flush=True)
    fails += 0 if cond else 1


grid = {"model.sigma0": np.logspace(0, 2, 40), "input.umin2": np.linspace(0.1, 0.5, 30)}  # 1,200 points
with tempfile.TemporaryDirectory(prefix="hystviz-test-dask-") as tmp:
    os.chdir(tmp)
    with dask.config.set({"temporary-directory": tmp, "distributed.comm.timeouts.connect": "30s"}):
        ns = {}
        exec(compile(code, doc + " (dask-recipe)", "exec"), ns)
        whole = hystviz.sweep(scene, grid=grid, jobs=2)
        d = ns["dask_sweep"](scene, grid, parts=7, workers=2)
        check(d.dtype == whole.dtype and d.tobytes() == whole.tobytes(),
              f"dask_sweep in 7 shards = the one-process sweep, byte for byte ({len(d)} records)")
        cols = ["model.sigma0", "minor1_area", "energy"]
        d = ns["dask_sweep"](scene, grid, columns=cols, parts=3, workers=2)
        one = hystviz.sweep(scene, grid=grid, columns=cols)
        check(d.tobytes() == one.tobytes(), "with columns=, 3 shards: the same")
    os.chdir("/")
sys.exit(1 if fails else 0)
