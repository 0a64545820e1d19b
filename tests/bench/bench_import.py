# SPDX-License-Identifier: MIT
"""bench_import.py SOURCE_ROOT LIB: what `import hystviz` costs beyond NumPy's
own import (issue 35: budget 50 ms), each figure the median of 11 fresh
interpreters:
  - wall, from `python3 -X importtime -c "import hystviz"`: hystviz's
    cumulative time minus numpy's (numpy is imported inside it);
  - CPU time (user + system, time.process_time()) and wall around `import
    hystviz` in an interpreter that has imported numpy just before: the CPU
    figure is the one load on the machine does not inflate, and the one the
    budget is checked against.
The package and library are the build tree's (PYTHONPATH, HYSTVIZ_LIB); a
wheel loads the library from its own directory, the same dlopen.  Bytecode
is compiled once first, into the benchmark's own directory, as pip compiles
a wheel's modules when it installs them."""
import os
import subprocess
import sys
import tempfile

ROUNDS = 11
TIMED = ("import time\nc0, w0 = time.process_time(), time.perf_counter()\nimport numpy\n"
         "c1, w1 = time.process_time(), time.perf_counter()\nimport hystviz\n"
         "c2, w2 = time.process_time(), time.perf_counter()\n"
         "print((c2 - c1) * 1e3, (w2 - w1) * 1e3, (c1 - c0) * 1e3)")


def importtime(env):
    """hystviz's cumulative -X importtime minus numpy's, in ms (one fresh interpreter)."""
    err = subprocess.run([sys.executable, "-X", "importtime", "-c", "import hystviz"], env=env, check=True,
                         capture_output=True, text=True, timeout=120).stderr
    cum = {ln.split("|")[2].strip(): int(ln.split("|")[1]) for ln in err.splitlines() if ln.startswith("import time:")
           and ln.split("|")[1].strip().isdigit()}
    return (cum["hystviz"] - cum["numpy"]) / 1e3


def timed(env):
    """(CPU ms, wall ms) of `import hystviz` after numpy, and numpy's own CPU ms."""
    out = subprocess.run([sys.executable, "-c", TIMED], env=env, check=True, capture_output=True, text=True,
                         timeout=120).stdout.split()
    return tuple(float(x) for x in out)


def med(v):
    return sorted(v)[len(v) // 2]


src, lib = sys.argv[1:3]
load0 = os.getloadavg()[0]
it, cpu, wall, np_cpu = [], [], [], []
with tempfile.TemporaryDirectory() as tmp:
    env = dict(os.environ, PYTHONPATH=os.path.join(src, "src", "python"), HYSTVIZ_LIB=lib,
               PYTHONPYCACHEPREFIX=os.path.join(tmp, "pycache"))
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    subprocess.run([sys.executable, "-c", "import hystviz"], env=env, check=True, timeout=120)
    for _ in range(ROUNDS):  # the two measurements alternate, so that load falls on both
        it.append(importtime(env))
        c, w, n = timed(env)
        cpu.append(c)
        wall.append(w)
        np_cpu.append(n)
print(f"import hystviz | beyond numpy: {med(cpu):.1f} ms CPU (budget 50), {med(wall):.1f} ms wall, "
      f"-X importtime {med(it):.1f} ms; numpy itself {med(np_cpu):.1f} ms CPU; medians of {ROUNDS} fresh "
      f"interpreters (CPU min {min(cpu):.1f} max {max(cpu):.1f}), load {load0:.1f}-{os.getloadavg()[0]:.1f}")
