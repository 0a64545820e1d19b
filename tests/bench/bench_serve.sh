#!/bin/sh
# SPDX-License-Identifier: MIT
# tests/bench/bench_serve.sh BENCH_SERVE HYSTVIZ SCENES_DIR: `hystviz serve`
# benchmark (issue 16): a control change -> the updated SVG, for Fig. 15
# (analytic), Fig. 11 (GSL) and bw_fig1a (Newmark): (1) the server's render
# in one warm process (bench_serve), (2) in chromium, server render and
# end-to-end time from the input event to the new SVG in the DOM, and the
# reload after a rename-save, (3) the matplotlib yardstick (Fig. 15 redrawn
# for a new sigma0 in one Python process).  Prints; asserts nothing.
bench=$1 hv=$2 scenes=$3
here=$(dirname "$0")
"$bench" "$scenes" 200
if command -v chromium >/dev/null && command -v python3 >/dev/null; then
    python3 "$here/../serve/browser_test.py" "$hv" "$scenes" --bench 100
else
    echo "bench-serve-browser: SKIP (chromium or python3 missing)"
fi
if /usr/bin/python3 -c "import matplotlib, numpy" 2>/dev/null; then
    /usr/bin/python3 "$here/mpl_fig15.py" "$hv" "$scenes/fig15_minor_loop_ex4.scene" 100
else
    echo "mpl-fig15: SKIP (python3-matplotlib missing)"
fi
