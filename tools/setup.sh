#!/bin/sh
# SPDX-License-Identifier: MIT
# tools/setup.sh: one command from a fresh Debian 12 (as root) to a built hystviz.
#   sh tools/setup.sh gallery   install what is missing, build, render the gallery
#   sh tools/setup.sh test      install what is missing, build, run every test suite
#                               (the gl suite on each GL backend: both in build/,
#                               -Dgl=osmesa, -Dgl=egl; the suites that depend on
#                               the configuration again without GL, and every
#                               suite again under ASan+UBSan), each run with
#                               $TMPDIR a fresh directory that must stay empty
#   sh tools/setup.sh bench     build, run the benchmarks
#   sh tools/setup.sh fuzz MIN  build the libFuzzer target with clang in build-fuzz/ and
#                               fuzz the scene parser and `data` path for MIN minutes
#                               (default 10); new inputs go to build-fuzz/fuzz-corpus/,
#                               failing ones to build-fuzz/fuzz-crashes/ (tests/fuzz/README.md)
#   sh tools/setup.sh fuzz MIN zfast  the same for hy_zfast, the PNG frames' deflate encoder
#                               (fuzz_zfast: images against zlib and a strict inflater);
#                               build-fuzz/zfast-corpus/, build-fuzz/zfast-crashes/
#   sh tools/setup.sh fuzz MIN readers  the same for the data file readers ([data]'s table,
#                               FORC files, Preisach density files: fuzz_readers)
# With CI=true the build uses -Dwerror=true.
set -eu
cd "$(dirname "$0")/.."
what=${1:-gallery}

pkgs="gcc meson ninja-build pkg-config python3-dev libgsl-dev libcairo2-dev libpng-dev libdeflate-dev fonts-dejavu-core fonts-stix parallel time libmicrohttpd-dev"
# python3-dev: the Python package's compiled fast path hystviz._fast (without it, ctypes alone)
# GL backends (OSMesa; EGL with Mesa's software device) and ffmpeg for the video tests
pkgs="$pkgs libgl-dev libosmesa6-dev libegl-dev libegl-mesa0 ffmpeg"
# the fuzzer needs clang and its runtime libraries (libFuzzer, ASan, UBSan)
[ "$what" = fuzz ] && pkgs="$pkgs clang libclang-rt-dev"
# the test command's build directories share their compilations through ccache (see "test)" below)
[ "$what" = test ] && pkgs="$pkgs ccache"
# what the tests need besides: curl and bash (serve over HTTP), python3 and
# chromium (the page in a real browser, headless); slurm-wlm, munge and
# iproute2 (a single-node Slurm on loopback: tests/cli/test_slurm.sh);
# python3-numpy, python3-nbclient and python3-ipykernel (the Python package and
# its notebook: tests/python); python3-distributed (the Dask recipe of
# docs/STUDIES.md: tests/python/test_dask.py); cmake and g++ (a CMake project
# and a C++17 program against the installed library: tests/libhystviz/test_cmake.sh);
# python3-mesonpy and python3-venv (pip wheel . into a venv), mypy (mypy
# --strict) and python3-matplotlib (hystviz.plot's example); universal-ctags
# (function lengths: tests/design/long_functions.txt, tools/long_functions.py)
case "$what" in test) pkgs="$pkgs curl bash python3 python3-numpy python3-nbclient python3-ipykernel python3-distributed python3-pip python3-wheel python3-mesonpy python3-venv mypy python3-matplotlib chromium pngcheck python3-pil slurm-wlm munge iproute2 cmake g++ universal-ctags" ;; bench) pkgs="$pkgs curl bash python3 chromium pngcheck python3-pil python3-matplotlib python3-numpy python3-scipy" ;; esac
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

# binutils' gold links where it is there (Debian's binutils has it) and no
# linker is chosen (CC_LD): the GL programs link against Mesa's libraries,
# where ld.bfd took 0.8 s of CPU a program and gold 0.08 s (build/'s 96 links:
# 13.4 CPU s against 3.8 s).  Read by meson when a directory is first set up
ld=${CC_LD:-}
[ -z "$ld" ] && command -v ld.gold >/dev/null 2>&1 && ld=gold
setup_dir() { # dir, extra options...
    dir=$1; shift
    if [ -d "$dir" ]; then
        meson setup --reconfigure "$dir" -Dwerror=$werror "$@" >/dev/null
    elif [ -n "$ld" ]; then
        CC_LD=$ld meson setup "$dir" -Dwerror=$werror "$@" >/dev/null
    else
        meson setup "$dir" -Dwerror=$werror "$@" >/dev/null
    fi
}
configure() { # dir, extra options...: set up and build everything
    setup_dir "$@"
    meson compile -C "$1"
}
# configure_for DIR "SUITE..." OPTIONS...: set up DIR and build only what the
# tests of those suites run (their executables and the targets they name,
# from meson's introspection), not the whole project; a suite written !SUITE
# leaves its tests out ("!check !no-san": every test but those)
configure_for() {
    dir=$1 suites=$2; shift 2
    setup_dir "$dir" "$@"
    # shellcheck disable=SC2046,SC2086 # the targets and suites are words
    meson compile -C "$dir" $( (cd "$dir" && meson introspect --tests --targets) | python3 -c '
import json, sys
j = json.load(sys.stdin)
want = {s for s in sys.argv[1:] if not s.startswith("!")}
skip = {s[1:] for s in sys.argv[1:] if s.startswith("!")}
def chosen(suites):
    return (not want or want & suites) and not skip & suites
import os
src = os.getcwd()
def qualified(t):  # path/name:type: names alone are ambiguous (the hystviz program and library)
    d = os.path.relpath(os.path.dirname(t["defined_in"]), src)
    return ("" if d == "." else d + "/") + t["name"] + ":" + t["type"].replace(" ", "_")
names = {t["id"]: qualified(t) for t in j["targets"]}
need = {names[d] for t in j["tests"] if chosen({s.split(":")[-1] for s in t["suite"]}) for d in t["depends"]}
print(" ".join(sorted(need)))' $suites)
}
# run_tests DIR MESON-TEST-OPTIONS...: the tests with $TMPDIR a fresh directory,
# which must be empty afterwards: a test leaves nothing behind
run_tests() {
    dir=$1; shift
    tmp=$(mktemp -d "${TMPDIR:-/tmp}/hystviz-tests.XXXXXX")
    # Mesa's shader cache for this run only: nothing under ~/.cache, and
    # each shader variant compiled once for all the tests' processes
    shaders=$(mktemp -d "${TMPDIR:-/tmp}/hystviz-shaders.XXXXXX")
    # one test more than the cores: part of the tests' time is waiting on a
    # server, a browser or a child (the sanitizer stage of a fresh clone's
    # .ci/run: 214 s at one per core, 200 s at one more)
    st=0
    TMPDIR=$tmp MESA_SHADER_CACHE_DIR=$shaders meson test -C "$dir" --print-errorlogs \
        --num-processes $(($(getconf _NPROCESSORS_ONLN) + 1)) "$@" || st=$?
    left=$(ls -A "$tmp")
    rm -rf "$tmp" "$shaders"
    if [ -n "$left" ]; then
        echo "setup: the tests in $dir left in \$TMPDIR: $(echo "$left" | tr '\n' ' ')" >&2
        [ "$st" -ne 0 ] || st=1
    fi
    return "$st"
}

# dist_check: build/'s `meson dist` tarball, unpacked in a temporary
# directory, configured and built for suite 'dist', whose tests run there
dist_check() {
    rm -rf build/meson-dist
    meson dist -C build --no-tests --formats gztar >/dev/null
    d=$(mktemp -d "${TMPDIR:-/tmp}/hystviz-dist.XXXXXX")
    tar -xzf build/meson-dist/hystviz-*.tar.gz -C "$d"
    st=0
    (cd "$d"/hystviz-* && configure_for build dist && run_tests build --no-rebuild --suite dist) || st=$?
    rm -rf "$d"
    return "$st"
}

# wait_job PID SECONDS: the background job's exit status; past SECONDS it is
# stopped (TERM, then KILL, it and its children) and the status is 124, so a
# hung job cannot hold the test command forever
wait_job() {
    n=$2
    while [ "$n" -gt 0 ] && kill -0 "$1" 2>/dev/null; do
        sleep 1
        n=$((n - 1))
    done
    if kill -0 "$1" 2>/dev/null; then
        echo "setup: a background job ran past $2 s: stopped" >&2
        pkill -TERM -P "$1" 2>/dev/null; kill -TERM "$1" 2>/dev/null
        sleep 2
        pkill -KILL -P "$1" 2>/dev/null; kill -KILL "$1" 2>/dev/null
        wait "$1" 2>/dev/null
        return 124
    fi
    wait "$1"
}

# stage NAME: say how long the last stage took and the whole command so far
# (the test command's budget is 10 minutes on 2 cores), and the CPU time
# (user + sys) its processes used: on a loaded machine the wall time says
# little.  The CPU time counts only processes that were waited for: servers,
# daemons and browsers a test leaves to its process group are missed (on 2
# quiet cores the whole command keeps both busy: /proc/stat sampled every
# 2 s: 1,258 s of CPU in 639 s, against 1,141 s counted here)
t_start=$(date +%s); t_stage=$t_start
t_times=$(mktemp "${TMPDIR:-/tmp}/hystviz-times.XXXXXX")
ccache_dir=""
trap 'rm -f "$t_times"; [ -z "$ccache_dir" ] || rm -rf "$ccache_dir"' EXIT
cpu_s() { # the children's user + sys seconds, from the shell's own `times` (no subshell: it would count none)
    awk 'NR == 2 { s = 0; for (i = 1; i <= 2; i++) { split($i, a, "m"); s += a[1] * 60 + a[2] } printf "%.0f", s }' "$t_times"
}
times >"$t_times"; c_start=$(cpu_s); c_stage=$c_start
stage() {
    now=$(date +%s)
    times >"$t_times"; c_now=$(cpu_s)
    echo "setup: $1 took $((now - t_stage)) s ($((now - t_start)) s in all; CPU $((c_now - c_stage)) s, $((c_now - c_start)) s in all)"
    t_stage=$now c_stage=$c_now
}

case "$what" in
gallery)
    configure build
    ./build/src/app/hystviz gallery
    ;;
test)
    # ccache within this run only (issue 36 item 7): build-osmesa, -egl, -nogl
    # and the dist tarball's build compile most of build/'s sources with the
    # same flags (meson uses ccache when it finds it; the command lines name
    # the sources relative to the build directory, so with the directory left
    # out of the hash they hit across build directories).  Its own cache in
    # $TMPDIR, removed at exit: nothing under ~/.cache, nothing from another run
    if command -v ccache >/dev/null 2>&1; then
        ccache_dir=$(mktemp -d "${TMPDIR:-/tmp}/hystviz-ccache.XXXXXX")
        export CCACHE_DIR="$ccache_dir" CCACHE_NOHASHDIR=1 CCACHE_BASEDIR="$PWD"
    fi
    configure build
    stage "building build/"
    # build/'s tests leave a core idle about a third of the time (serial tests,
    # waits on servers and browsers): meanwhile, in the background, the Slurm
    # example (mostly waiting on its daemons) and the builds of build-osmesa,
    # -egl, -nogl and -san (their tests run below, after these).  Each job's
    # output is shown when it ends, its exit status counted.  The builds run at
    # the tests' own priority: at nice 19 (as they did) any CPU-bound process of
    # normal priority in the same scheduling group starved them (beside
    # `stress-ng --cpu 4` in the same session, three runs' builds made 1.5 of
    # their 4 directories in 38 minutes and would have met wait_job's deadline)
    bg_log=$(mktemp -d "${TMPDIR:-/tmp}/hystviz-bg.XXXXXX")
    # the README's Slurm example on a real single-node Slurm of its own
    # (tools/cluster/slurm-local.sh); once, not per build configuration
    sh tests/cli/test_slurm.sh build/src/app/hystviz . >"$bg_log/slurm" 2>&1 &
    bg_slurm=$!
    (
        set -e
        # each GL backend alone (build/ has both: its gl suite ran on each, and
        # compared their frames); -Dgl=egl is the machine without OSMesa; only
        # what the gl suite runs is built
        for gl in osmesa egl; do
            configure_for build-$gl "gl !gl-once" -Dgl=$gl
        done
        # the build without GL and libmicrohttpd: only what its suites run
        configure_for build-nogl "gl serve config" -Dgl=disabled -Dmicrohttpd=disabled
        # GCC's -fsanitize=undefined leaves out float-cast-overflow (a double too large
        # for the integer it is converted to); it is added, and made fatal, here.
        # -O1, as ASan's documentation advises for speed; -g1 keeps the stacks readable
        # (line tables: every frame's file and line) and compiles a fifth faster than
        # the debug buildtype's full -g (40 of its sources: 23.1-24.5 s against
        # 18.6-20.2 s of CPU); only what its tests run is built (not the benchmarks,
        # man pages, ...)
        san="-fsanitize=float-cast-overflow -fno-sanitize-recover=undefined,float-cast-overflow"
        # without ccache: build-san's flags are its own, so no directory hits its
        # compilations, and each miss costs ccache a preprocessor run and a
        # compressed store (cold cache 146.8-158.5 CPU s, without 129.2-137.6)
        export CCACHE_DISABLE=1
        configure_for build-san "!check !no-san" -Db_sanitize=address,undefined -Db_lundef=false -Dbuildtype=debug \
            -Doptimization=1 -Dc_args="$san -g1" -Dc_link_args="$san"
    ) >"$bg_log/builds" 2>&1 </dev/null &
    bg_builds=$!
    st=0
    run_tests build || st=$?
    bg_st=0
    wait_job "$bg_slurm" 900 || bg_st=$?
    echo "setup: the Slurm example (run beside build/'s tests):"
    cat "$bg_log/slurm"
    [ "$bg_st" -eq 0 ] || { echo "setup: the Slurm example failed (exit $bg_st)" >&2; st=1; }
    bg_st=0
    wait_job "$bg_builds" 2400 || bg_st=$?
    echo "setup: building build-osmesa, build-egl, build-nogl and build-san (beside build/'s tests):"
    tail -n 40 "$bg_log/builds"
    [ "$bg_st" -eq 0 ] || { echo "setup: building them failed (exit $bg_st; the whole log above was cut to 40 lines)" >&2; st=1; }
    rm -rf "$bg_log"
    [ "$st" -eq 0 ] || exit "$st"
    stage "the tests in build/, beside them the Slurm example and building build-osmesa, -egl, -nogl, -san"
    # the gl suite on each GL backend alone (built above), but for the tests
    # whose result does not depend on the backends compiled in (gl-once:
    # tests/gl/meson.build), which ran in build/ on each backend
    for gl in osmesa egl; do
        run_tests build-$gl --no-rebuild --suite gl --no-suite gl-once
        stage "build-$gl (its gl suite)"
    done
    # the build without GL and libmicrohttpd: cairo figures work, GL tests
    # report SKIP, serve exits 3 naming what is missing.  Only the suites whose
    # code depends on the configuration run again (gl, serve, and the tests
    # tagged 'config': tests/meson.build); the rest ran in build/
    run_tests build-nogl --no-rebuild --suite gl --suite serve --suite config
    stage "build-nogl (its gl, serve and config suites)"
    # beside them (at the tests' priority, as the builds above), the release tarball passes its own
    # tests (issue 35 item 5): `meson dist` makes it from git (--no-tests: its
    # own check rebuilds everything and runs every test, too long for the
    # budget); it is unpacked outside any checkout, built for the tests of
    # suite 'dist' only and those run: the licence lines without git, the build
    # tree's files against a decoy install, the library's symbols, ABI,
    # reference and pipeline
    bg_log=$(mktemp "${TMPDIR:-/tmp}/hystviz-dist-log.XXXXXX")
    (dist_check) >"$bg_log" 2>&1 </dev/null &
    bg_dist=$!
    # every suite again under ASan + UBSan but the full check and the tests
    # tagged no-san (tests/meson.build: their C paths run here in other tests)
    # (fontconfig keeps a process-lifetime cache: suppressed in tests/render/lsan.supp)
    export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 ASAN_OPTIONS=detect_leaks=1 \
        LSAN_OPTIONS=suppressions="$PWD/tests/render/lsan.supp"
    st=0
    run_tests build-san --no-rebuild --no-suite check --no-suite no-san || st=$?
    bg_st=0
    wait_job "$bg_dist" 1800 || bg_st=$?
    echo "setup: the dist tarball (run beside build-san/'s tests):"
    cat "$bg_log"
    rm -f "$bg_log"
    [ "$bg_st" -eq 0 ] || { echo "setup: the dist tarball failed (exit $bg_st)" >&2; st=1; }
    [ "$st" -eq 0 ] || exit "$st"
    if [ -n "$ccache_dir" ]; then
        echo "setup: ccache of this run: $(ccache -s | grep -E '^ *(Hits|Misses):' | head -n 2 | tr -s ' ' | tr '\n' ' ')"
    fi
    stage "the tests in build-san/, beside them the dist tarball (building, its dist suite)"
    ;;
bench)
    configure build
    meson test -C build --benchmark --verbose
    ;;
fuzz)
    minutes=${2:-10}
    # at least 1 (libFuzzer's -max_total_time=0 would mean no limit)
    case "$minutes" in ''|*[!0-9]*) minutes=0;; esac
    [ "$minutes" -ge 1 ] 2>/dev/null || { echo "setup: fuzz MINUTES takes a whole number of minutes, at least 1" >&2; exit 2; }
    target=${3:-scene}
    case "$target" in scene|zfast|readers) ;; *) echo "setup: fuzz MINUTES [scene|zfast|readers]" >&2; exit 2;; esac
    # clang: libFuzzer instruments every library (coverage), ASan + UBSan with
    # float-cast-overflow abort at the first report; only the fuzz target is built
    fuzz_cflags="-fsanitize=fuzzer-no-link,float-cast-overflow -fno-sanitize-recover=all -fno-omit-frame-pointer"
    if [ -d build-fuzz ]; then
        meson setup --reconfigure build-fuzz >/dev/null
    else
        CC=clang meson setup build-fuzz -Dfuzz=true -Dgl=disabled -Db_sanitize=address,undefined \
            -Db_lundef=false -Dc_args="$fuzz_cflags" >/dev/null
    fi
    # fuzz_report NAME LOG CORPUS CRASHES BEFORE START: what the round did
    fuzz_report() {
        last=$(grep -E '^#[0-9]+: cov:' "$2" | tail -n 1)
        echo "fuzz $1: ran $(($(date +%s) - $6)) s of $minutes min, log $2"
        echo "fuzz $1: last status: ${last:-none (see the log)}"
        echo "fuzz $1: executions $(echo "$last" | sed -n 's/^#\([0-9]*\):.*/\1/p'), coverage: edges (cov) $(echo "$last" |
            sed -n 's/.* cov: \([0-9]*\).*/\1/p'), features (ft) $(echo "$last" | sed -n 's/.* ft: \([0-9]*\).*/\1/p'),"\
            "corpus $(ls "$3" | wc -l) files"
        after=$(ls "$4" | wc -l)
        echo "fuzz $1: findings: $((after - $5)) new in $4/ ($after in all)"
        ls -t "$4" | head -n $((after - $5)) | sed "s|^|  $4/|"
    }
    if [ "$target" != scene ]; then
        # zfast: an image from each input (tests/fuzz/zfast_harness.h), up to 2^16 pixels;
        # readers: byte 0 picks [data]'s table, a FORC or a density file, the rest is its text
        # (tests/fuzz/readers_harness.h); seeds tests/fuzz/TARGET-corpus, TARGET-repro
        maxlen=16384
        [ "$target" = readers ] && maxlen=65537
        meson compile -C build-fuzz fuzz_$target
        mkdir -p build-fuzz/$target-corpus build-fuzz/$target-crashes
        before=$(ls build-fuzz/$target-crashes | wc -l)
        start=$(date +%s)
        ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 \
        build-fuzz/tests/fuzz/fuzz_$target -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
            -max_total_time=$((minutes * 60)) -timeout=10 -rss_limit_mb=2048 -max_len=$maxlen \
            -artifact_prefix=build-fuzz/$target-crashes/ \
            build-fuzz/$target-corpus tests/fuzz/$target-corpus tests/fuzz/$target-repro >build-fuzz/$target.log 2>&1 || true
        fuzz_report $target build-fuzz/$target.log build-fuzz/$target-corpus build-fuzz/$target-crashes "$before" "$start"
        echo "fuzz $target: replay one: build-fuzz/tests/fuzz/fuzz_$target FILE (or build/tests/fuzz/${target}_replay DIR)"
        exit 0
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
    fuzz_report scene build-fuzz/fuzz.log build-fuzz/fuzz-corpus build-fuzz/fuzz-crashes "$before" "$start"
    echo "fuzz scene: replay one: build-fuzz/tests/fuzz/fuzz_scene FILE (or build/tests/fuzz/fuzz_replay -v FILE)"
    ;;
*)
    echo "usage: sh tools/setup.sh gallery|test|bench|fuzz [MINUTES [scene|zfast|readers]]" >&2
    exit 2
    ;;
esac
