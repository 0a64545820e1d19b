# SPDX-License-Identifier: MIT
"""bench_import.py SOURCE_ROOT LIB: what `import hystviz` costs beyond NumPy's
own import (issue 35: budget 50 ms), from `python3 -X importtime -c "import
numpy, hystviz"` run 11 times, each a fresh interpreter: hystviz's cumulative
time (numpy is already imported then, so it is not counted in it) and
numpy's own, medians; and the CPU time of the import (time.process_time()
around it), which load on the machine does not inflate.  The package and library are the build tree's
(PYTHONPATH, HYSTVIZ_LIB); a wheel loads the library from its own directory,
the same dlopen."""
import os
import subprocess
import sys
import tempfile


def run(env):
    """(hystviz's, numpy's) cumulative import time in ms, one fresh interpreter."""
    err = subprocess.run([sys.executable, "-X", "importtime", "-c", "import numpy, hystviz"], env=env, check=True,
                         capture_output=True, text=True, timeout=120).stderr
    cum = {ln.split("|")[2].strip(): int(ln.split("|")[1]) for ln in err.splitlines() if ln.startswith("import time:")
           and ln.split("|")[1].strip().isdigit()}
    return cum["hystviz"] / 1e3, cum["numpy"] / 1e3


def cpu(env):
    """The CPU time of `import hystviz` after numpy, in ms (what a loaded machine does not inflate)."""
    out = subprocess.run([sys.executable, "-c", "import time, numpy\nc = time.process_time()\nimport hystviz\n"
                          "print((time.process_time() - c) * 1e3)"], env=env, check=True, capture_output=True,
                         text=True, timeout=120).stdout
    return float(out)

src, lib = sys.argv[1:3]
hv, npy, cpus = [], [], []
with tempfile.TemporaryDirectory() as tmp:
    # bytecode compiled once, into the benchmark's own directory, as pip
    # compiles a wheel's modules when it installs them
    env = dict(os.environ, PYTHONPATH=os.path.join(src, "src", "python"), HYSTVIZ_LIB=lib,
               PYTHONPYCACHEPREFIX=os.path.join(tmp, "pycache"))
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    subprocess.run([sys.executable, "-c", "import numpy, hystviz"], env=env, check=True, timeout=120)
    for _ in range(11):
        hv_ms, np_ms = run(env)
        hv.append(hv_ms)
        npy.append(np_ms)
        cpus.append(cpu(env))
med = sorted(hv)[5]
load = os.getloadavg()[0]
print(f"import hystviz | beyond numpy: {med:.1f} ms (budget 50), numpy itself {sorted(npy)[5]:.1f} ms; "
      f"median of 11 fresh interpreters, min {min(hv):.1f} max {max(hv):.1f} ms, load {load:.1f}; "
      f"CPU time {sorted(cpus)[5]:.1f} ms")
