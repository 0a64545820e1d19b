#!/bin/sh
# SPDX-License-Identifier: MIT
# test_names_strcmp.sh ROOT: no strcmp chain on a name that an X-macro table owns (issue 34,
# item 3): line styles, markers, legend places, themes, easings (src/core/hy_figure_names.h),
# the GSL steppers (HY_ODE_STEPPERS, src/core/hy_ode.h), the input kinds (HY_INPUT_KINDS,
# src/scene/hy_scene_schema.h) and the figure formats (src/core/hy_formats.h).  Code compares
# the decoded value with the generated HY_*_<ID> value, or asks the table, instead.
# Allowed, by file and line text: serve's slider domains (src/serve/serve_util.c, which issue 34
# item 2 moves into the schema's rows).
set -u
. "$(dirname "$0")/../lib.sh"
root=$1
names='solid|dashed|dotted|dashdot|circle|square|best|top-left|top-right|bottom-left|bottom-right'
names="$names|paper|slides|linear|smooth|bimodal|multimodal|triangle|sine|pwl|file|multisine|sweep|data"
names="$names|rk2|rk4|rkf45|rkck|rk8pd|rk1imp|rk2imp|rk4imp|bsimp|msadams|msbdf|svg|pdf|png"
vars='kind|kind_s|stepper|o->stepper|solver|style|marker|legend|theme|easing|ease|fmt|format'
pat="strcmp\\(($vars), \"($names)\"\\)"
allowed='src/serve/serve_util.c:.*strcmp\(sec, "input"\) && !strcmp\(kind, "bimodal"\)'
hits=$(cd "$root" && grep -rnE "$pat" src --include='*.c' --include='*.h' | grep -vE "$allowed")
if [ -n "$hits" ]; then
    echo "$hits"
    bad "a strcmp chain on a table's names (above): compare the decoded value with its HY_*_<ID> (or ask the table)"
else
    ok "no strcmp chain on the tables' names under $root/src"
fi
finish names-strcmp
