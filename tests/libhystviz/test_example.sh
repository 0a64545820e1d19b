#!/bin/bash
# SPDX-License-Identifier: MIT
# tests/libhystviz/test_example.sh BUILD_ROOT SOURCE_ROOT HYSTVIZ: docs/examples/minor_loop_area.c
# builds with `pkg-config --cflags --libs hystviz` (the uninstalled .pc meson
# writes) and prints Fig. 15's minor-loop area, the very number (%.17g, bit
# for bit) that `hystviz loops` prints for Example 4 (issue 24).
set -u
. "$(dirname "$0")/../lib.sh"
build=$1 src=$2 hv=$3
command -v pkg-config >/dev/null || skip "pkg-config is not installed"
command -v cc >/dev/null || skip "no C compiler"
T=$tmp
export PKG_CONFIG_PATH="$build/meson-uninstalled"
flags=$(pkg-config --cflags --libs hystviz) || fatal "pkg-config --cflags --libs hystviz"
timeout 120 cc -std=c11 -Wall -Wextra -Werror "$src/docs/examples/minor_loop_area.c" $flags -o "$T/area" ||
    fatal "the example does not build with: $flags"
got=$(LD_LIBRARY_PATH="$build/src/lib" timeout 60 "$T/area") || fatal "the example exited non-zero"
want=$(timeout 60 "$hv" loops --sigma0 6 --input bimodal:0,0.5,1,1.5 | awk -F, '$1 == "minor" {print $10; exit}')
[ -n "$want" ] && [ "$got" = "$want" ] || fatal "example printed '$got', hystviz loops '$want'"
ok "the pkg-config example prints $got, as hystviz loops"
finish lib-example
