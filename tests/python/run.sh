#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/python/run.sh SOURCE_ROOT LIB HYSTVIZ [notebook|api|SCRIPT.py]: runs test_python.py
# (or tests/python/SCRIPT.py with the same arguments; with "notebook",
# docs/examples/minor_loops.ipynb through nbclient; with "api", test_api.py:
# docstrings, doctests, units, file errors) with a
# Python 3 that has NumPy (Debian's python3-numpy is for /usr/bin/python3,
# which may not be the first python3 on PATH).  Without one: SKIP, or FAIL
# when CI=true (the README's set-up installs it).
set -u
src=$1 lib=$2 hv=$3
for py in /usr/bin/python3 python3; do
    if [ "${4:-}" = notebook ]; then
        "$py" -c "import numpy, nbclient, ipykernel" 2>/dev/null || continue
        PYTHONPATH="$src/src/python" HYSTVIZ_LIB="$lib" exec timeout 300 "$py" "$src/tests/python/run_notebook.py" \
            "$src/docs/examples/minor_loops.ipynb" "$src/scenes"
    fi
    if [ "${4:-}" = api ] && "$py" -c "import numpy" 2>/dev/null; then
        PYTHONPATH="$src/src/python" HYSTVIZ_LIB="$lib" exec timeout 300 "$py" "$src/tests/python/test_api.py"
    fi
    if "$py" -c "import numpy" 2>/dev/null; then
        PYTHONPATH="$src/src/python" HYSTVIZ_LIB="$lib" exec timeout 300 "$py" "$src/tests/python/${4:-test_python.py}" "$hv" "$src/scenes"
    fi
done
# (tests/lib.sh only here: the runs above exec, which would leave its $tmp behind)
. "$(dirname "$0")/../lib.sh"
[ "${CI:-}" = true ] &&
    fatal "no python3 with NumPy (and nbclient, ipykernel for the notebook: apt-get install python3-numpy python3-nbclient python3-ipykernel)"
skip "no python3 with NumPy (and nbclient, ipykernel for the notebook)"
