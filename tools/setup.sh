#!/bin/sh
# tools/setup.sh: one command from a fresh Debian 12 (as root) to a built hystviz.
#   sh tools/setup.sh gallery   install what is missing, build, render the gallery
#   sh tools/setup.sh test      install what is missing, build, run every test suite
#                               (again without OSMesa, and again under ASan+UBSan)
# With CI=true the build uses -Dwerror=true.
set -eu
cd "$(dirname "$0")/.."
what=${1:-gallery}

pkgs="gcc meson ninja-build pkg-config libgsl-dev libcairo2-dev libpng-dev libosmesa6-dev fonts-dejavu-core fonts-stix"
missing=""
for p in $pkgs; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing="$missing $p"
done
if [ -n "$missing" ]; then
    echo "setup: installing$missing"
    if [ "$(id -u)" -ne 0 ]; then
        echo "setup: missing packages:$missing; run as root or install them" >&2
        exit 1
    fi
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $missing >/dev/null
fi

werror=false
[ "${CI:-}" = "true" ] && werror=true

configure() { # dir, extra options...
    dir=$1; shift
    if [ -d "$dir" ]; then
        meson setup --reconfigure "$dir" -Dwerror=$werror "$@" >/dev/null
    else
        meson setup "$dir" -Dwerror=$werror "$@" >/dev/null
    fi
    meson compile -C "$dir"
}

case "$what" in
gallery)
    configure build
    ./build/src/app/hystviz gallery
    ;;
test)
    configure build
    meson test -C build --print-errorlogs --num-processes 2
    # the build without OSMesa: cairo figures work, GL tests report SKIP
    configure build-noosm -Dosmesa=disabled
    meson test -C build-noosm --no-suite check --print-errorlogs --num-processes 2
    # GCC's -fsanitize=undefined leaves out float-cast-overflow (a double too large
    # for the integer it is converted to); it is added, and made fatal, here
    san="-fsanitize=float-cast-overflow -fno-sanitize-recover=undefined,float-cast-overflow"
    configure build-san -Db_sanitize=address,undefined -Db_lundef=false -Dbuildtype=debug \
        -Dc_args="$san" -Dc_link_args="$san"
    # every suite but the benchmarks-like ones again under ASan + UBSan
    # (fontconfig keeps a process-lifetime cache: suppressed in tests/render/lsan.supp)
    UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 ASAN_OPTIONS=detect_leaks=1 \
        LSAN_OPTIONS=suppressions="$PWD/tests/render/lsan.supp" \
        meson test -C build-san --no-suite check --print-errorlogs --num-processes 2
    ;;
bench)
    configure build
    meson test -C build --benchmark --verbose
    ;;
*)
    echo "usage: sh tools/setup.sh gallery|test|bench" >&2
    exit 2
    ;;
esac
