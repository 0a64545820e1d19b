#!/bin/bash
# SPDX-License-Identifier: MIT
# tests/libhystviz/test_cxx.sh LIB LIST-TOOL HEADER...: every installed header
# serves C++: a C++17 program that includes them all (-Wall -Wextra -pedantic
# -Werror) and takes the address of every function they declare links with
# libhystviz, which it only can when each declaration is inside the header's
# extern "C" (a C++ name would be mangled and undefined).  The headers are the
# install list (src/lib/meson.build: lib_public_headers).
set -u
. "$(dirname "$0")/../lib.sh"
lib=$1 tool=$2
shift 2
command -v c++ >/dev/null || skip "no C++ compiler (c++) is installed"
T=$tmp
inc=()
n=0
{
    echo "#include <cstdio>"
    for h in "$@"; do
        echo "#include \"$(basename "$h")\""
        inc+=("-I$(dirname "$h")")
    done
    echo "using fn = void (*)();"
    echo "static const fn all[] = {"
    for f in $(python3 "$tool" --list "$@"); do
        echo "    reinterpret_cast<fn>(&$f),"
        n=$((n + 1))
    done
    echo "};"
    echo "int main() { std::printf(\"%zu\\n\", sizeof all / sizeof all[0]); return 0; }"
} >"$T/all.cpp"
[ "$n" -ge 100 ] || fatal "only $n functions found in the headers"
if ! timeout 120 c++ -std=c++17 -Wall -Wextra -pedantic -Werror "${inc[@]}" "$T/all.cpp" "$lib" \
    -Wl,-rpath,"$(dirname "$lib")" -o "$T/all" 2>"$T/err"; then
    head -40 "$T/err"
    grep -q "undefined reference" "$T/err" &&
        bad "a C++ program does not link: a header above declares functions outside extern \"C\""
    fatal "the installed headers do not compile or link as C++17"
fi
got=$(timeout 30 "$T/all") || fatal "the C++ program exited non-zero"
[ "$got" = "$n" ] || fatal "the C++ program saw $got functions, the headers declare $n"
ok "$# headers compile as C++17 and all $n functions link unmangled"
finish lib-cxx
