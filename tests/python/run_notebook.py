# SPDX-License-Identifier: MIT
"""run_notebook.py NOTEBOOK SCENES_DIR: executes the notebook top to bottom
with nbclient and its python3 kernel in a temporary directory, without
HYSTVIZ_SCENES (each cell's asserts must hold; a cell that raises fails the
test), and checks the repository copy has its outputs stripped and uses
public API only, NumPy-2 clean (no hystviz._*, no np.trapz)."""
import os
import sys
import tempfile

import nbclient
import nbformat

path, scenes = sys.argv[1], sys.argv[2]
nb = nbformat.read(path, as_version=4)
stripped = all(not c.get("outputs") and c.get("execution_count") is None for c in nb.cells if c.cell_type == "code")
if not stripped:
    print(f"FAIL: {path}: outputs are not stripped (clear them before committing)")
    sys.exit(1)
# public API only, NumPy-2 clean (issue 35): no hystviz._name, no np.trapz
code = "\n".join(c.source for c in nb.cells if c.cell_type == "code")
private = [w for w in ("hystviz._", "np.trapz(", "HYSTVIZ_SCENES") if w in code]
if private:
    print(f"FAIL: {path}: uses {', '.join(private)} (public API and NumPy 2 only)")
    sys.exit(1)
os.environ.pop("HYSTVIZ_SCENES", None)  # the notebook finds its scenes itself (hystviz.scene_path)
os.environ["PYDEVD_DISABLE_FILE_VALIDATION"] = "1"
with tempfile.TemporaryDirectory() as tmp:  # the kernel's files, removed after
    os.environ["JUPYTER_RUNTIME_DIR"] = os.path.join(tmp, "runtime")
    os.environ["IPYTHONDIR"] = os.path.join(tmp, "ipython")
    os.environ["MPLCONFIGDIR"] = os.path.join(tmp, "mpl")
    work = os.path.join(tmp, "work")  # the kernel's directory: not the source tree
    os.mkdir(work)
    client = nbclient.NotebookClient(nb, timeout=120, kernel_name="python3", allow_errors=False,
                                     resources={"metadata": {"path": work}})
    try:
        client.execute()
    except Exception as e:  # nbclient.exceptions.CellExecutionError and kernel failures
        print(f"FAIL: {path}: {e}")
        sys.exit(1)
last = nb.cells[-1]["outputs"]
has_svg = any("image/svg+xml" in o.get("data", {}) for o in last)
print(("ok" if has_svg else "FAIL") + f": {path} ran top to bottom; the last cell shows the figure as SVG: {has_svg}")
sys.exit(0 if has_svg else 1)
