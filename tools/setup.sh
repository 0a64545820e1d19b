#!/bin/sh
# tools/setup.sh: one command from a fresh Debian 12 (as root) to a built hystviz.
#   sh tools/setup.sh gallery   install what is missing, build, render the gallery
#   sh tools/setup.sh test      install what is missing, build, run every test suite
#                               (the gl suite on each GL backend: both in build/,
#                               -Dgl=osmesa, -Dgl=egl; again without GL, and again
#                               under ASan+UBSan)
#   sh tools/setup.sh bench     build, run the benchmarks
#   sh tools/setup.sh fuzz MIN  build the libFuzzer target with clang in build-fuzz/ and
#                               fuzz the scene parser and `data` path for MIN minutes
#                               (default 10); new inputs go to build-fuzz/fuzz-corpus/,
#                               failing ones to build-fuzz/fuzz-crashes/ (tests/fuzz/README.md)
# With CI=true the build uses -Dwerror=true.
set -eu
cd "$(dirname "$0")/.."
what=${1:-gallery}

pkgs="gcc meson ninja-build pkg-config libgsl-dev libcairo2-dev libpng-dev libdeflate-dev fonts-dejavu-core fonts-stix parallel time libmicrohttpd-dev"
# GL backends (OSMesa; EGL with Mesa's software device) and ffmpeg for the video tests
pkgs="$pkgs libgl-dev libosmesa6-dev libegl-dev libegl-mesa0 ffmpeg"
# the fuzzer needs clang and its runtime libraries (libFuzzer, ASan, UBSan)
[ "$what" = fuzz ] && pkgs="$pkgs clang libclang-rt-dev"
# what the tests need besides: curl and bash (serve over HTTP), python3 and
# chromium (the page in a real browser, headless); slurm-wlm, munge and
# iproute2 (a single-node Slurm on loopback: tests/cli/test_slurm.sh)
case "$what" in test) pkgs="$pkgs curl bash python3 chromium pngcheck slurm-wlm munge iproute2" ;; bench) pkgs="$pkgs curl bash python3 chromium python3-matplotlib python3-numpy" ;; esac
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
    # the README's Slurm example on a real single-node Slurm of its own
    # (tools/cluster/slurm-local.sh); once, not per build configuration
    sh tests/cli/test_slurm.sh build/src/app/hystviz .
    # each GL backend alone (build/ has both: its gl suite ran on each, and
    # compared their frames); -Dgl=egl is the machine without OSMesa
    for gl in osmesa egl; do
        configure build-$gl -Dgl=$gl
        meson test -C build-$gl --suite gl --print-errorlogs --num-processes 2
    done
    # the build without GL and libmicrohttpd: cairo figures work, GL tests
    # report SKIP, serve exits 3 naming what is missing
    configure build-nogl -Dgl=disabled -Dmicrohttpd=disabled
    meson test -C build-nogl --no-suite check --print-errorlogs --num-processes 2
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
fuzz)
    minutes=${2:-10}
    case "$minutes" in ''|*[!0-9]*) echo "setup: fuzz MINUTES takes a whole number of minutes" >&2; exit 2;; esac
    # clang: libFuzzer instruments every library (coverage), ASan + UBSan with
    # float-cast-overflow abort at the first report; only the fuzz target is built
    fuzz_cflags="-fsanitize=fuzzer-no-link,float-cast-overflow -fno-sanitize-recover=all -fno-omit-frame-pointer"
    if [ -d build-fuzz ]; then
        meson setup --reconfigure build-fuzz >/dev/null
    else
        CC=clang meson setup build-fuzz -Dfuzz=true -Dgl=disabled -Db_sanitize=address,undefined \
            -Db_lundef=false -Dc_args="$fuzz_cflags" >/dev/null
    fi
    meson compile -C build-fuzz fuzz_scene fuzz_dict
    mkdir -p build-fuzz/fuzz-corpus build-fuzz/fuzz-crashes
    build-fuzz/tests/fuzz/fuzz_dict --write build-fuzz/scene.dict
    before=$(ls build-fuzz/fuzz-crashes | wc -l)
    start=$(date +%s)
    # one job; a failing input is saved and the fuzzing goes on (-fork=1 -ignore_*)
    ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 \
    build-fuzz/tests/fuzz/fuzz_scene -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
        -max_total_time=$((minutes * 60)) -timeout=10 -rss_limit_mb=2048 -max_len=8192 \
        -dict=build-fuzz/scene.dict -artifact_prefix=build-fuzz/fuzz-crashes/ \
        build-fuzz/fuzz-corpus tests/fuzz/corpus tests/fuzz/repro >build-fuzz/fuzz.log 2>&1 || true
    last=$(grep -E '^#[0-9]+: cov:' build-fuzz/fuzz.log | tail -n 1)
    echo "fuzz: ran $(($(date +%s) - start)) s of $minutes min, log build-fuzz/fuzz.log"
    echo "fuzz: last status: ${last:-none (see the log)}"
    echo "fuzz: executions $(echo "$last" | sed -n 's/^#\([0-9]*\):.*/\1/p'), coverage: edges (cov) $(echo "$last" |
        sed -n 's/.* cov: \([0-9]*\).*/\1/p'), features (ft) $(echo "$last" | sed -n 's/.* ft: \([0-9]*\).*/\1/p'),"\
        "corpus $(ls build-fuzz/fuzz-corpus | wc -l) files"
    after=$(ls build-fuzz/fuzz-crashes | wc -l)
    echo "fuzz: findings: $((after - before)) new in build-fuzz/fuzz-crashes/ ($after in all)"
    ls -t build-fuzz/fuzz-crashes | head -n $((after - before)) | sed 's|^|  build-fuzz/fuzz-crashes/|'
    echo "fuzz: replay one: build-fuzz/tests/fuzz/fuzz_scene FILE (or build/tests/fuzz/fuzz_replay -v FILE)"
    ;;
*)
    echo "usage: sh tools/setup.sh gallery|test|bench|fuzz [MINUTES]" >&2
    exit 2
    ;;
esac
