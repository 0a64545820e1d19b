#!/bin/bash
# SPDX-License-Identifier: MIT
# tests/libhystviz/test_cmake.sh BUILD_ROOT SOURCE_ROOT HYSTVIZ: a CMake
# project (tests/libhystviz/cmake) finds an installed libhystviz with
# find_package(hystviz 0.1) and builds the C++17 example
# docs/examples/minor_loop_area.cpp against hystviz::hystviz; it prints Fig. 15's
# minor-loop area, the very number (%.17g, bit for bit) that `hystviz loops`
# prints for Example 4.  The install (meson install --destdir, the devel and
# runtime files) is moved to another directory before CMake sees it, so the
# config must find it from its own place.  Asking for version 1.0 must fail.
set -u
. "$(dirname "$0")/../lib.sh"
build=$1 src=$2 hv=$3
command -v cmake >/dev/null || skip "cmake is not installed"
command -v c++ >/dev/null || skip "no C++ compiler (c++) is installed"
T=$tmp
timeout 300 meson install -C "$build" --no-rebuild --quiet --tags devel,runtime --destdir "$T/dest" >"$T/install.log" 2>&1 ||
    { cat "$T/install.log"; fatal "meson install --tags devel,runtime"; }
cfg=$(cd "$T/dest" && find . -name hystvizConfig.cmake)
[ -n "$cfg" ] || fatal "no hystvizConfig.cmake installed"
mv "$T/dest" "$T/moved"
conf_prefix=$(meson introspect "$build" --buildoptions |
    python3 -c 'import json, sys; print(next(o["value"] for o in json.load(sys.stdin) if o["name"] == "prefix"))') ||
    fatal "meson introspect --buildoptions gave no prefix"
prefix=$T/moved$conf_prefix
libdir=$(dirname "$(dirname "$(dirname "$T/moved/${cfg#./}")")")
[ -e "$libdir/libhystviz.so.0" ] || fatal "no libhystviz.so.0 in $libdir"
timeout 120 cmake -S "$src/tests/libhystviz/cmake" -B "$T/b" -DCMAKE_PREFIX_PATH="$prefix" \
    -DHYSTVIZ_EXAMPLE="$src/docs/examples/minor_loop_area.cpp" >"$T/cmake.log" 2>&1 ||
    { cat "$T/cmake.log"; fatal "cmake does not configure against the moved install at $prefix"; }
timeout 300 cmake --build "$T/b" >"$T/build.log" 2>&1 ||
    { cat "$T/build.log"; fatal "the C++17 example does not build with hystviz::hystviz"; }
got=$(LD_LIBRARY_PATH="$libdir" timeout 60 "$T/b/area") || fatal "the C++ example exited non-zero"
want=$(timeout 60 "$hv" loops --sigma0 6 --input bimodal:0,0.5,1,1.5 | awk -F, '$1 == "minor" {print $10; exit}')
[ -n "$want" ] && [ "$got" = "$want" ] || fatal "the C++ example printed '$got', hystviz loops '$want'"
ok "find_package(hystviz 0.1) in a moved install; the C++17 example prints $got, as hystviz loops"
if timeout 120 cmake -S "$src/tests/libhystviz/cmake" -B "$T/b1" -DCMAKE_PREFIX_PATH="$prefix" -DHYSTVIZ_WANT=1.0 \
    -DHYSTVIZ_EXAMPLE="$src/docs/examples/minor_loop_area.cpp" >"$T/cmake1.log" 2>&1; then
    fatal "find_package(hystviz 1.0) accepted version $(sed -n 's/^set(PACKAGE_VERSION "\(.*\)")$/\1/p' "$libdir/cmake/hystviz/hystvizConfigVersion.cmake")"
fi
tr -s ' \n' ' ' <"$T/cmake1.log" | grep -q 'compatible with requested version "1.0"' ||
    { cat "$T/cmake1.log"; fatal "find_package(hystviz 1.0) failed, but not on the version"; }
ok "find_package(hystviz 1.0) is refused by the version file"
finish lib-cmake
