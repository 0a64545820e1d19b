#!/bin/bash
# SPDX-License-Identifier: MIT
# tests/cli/test_decoy.sh PROG DECOY_PREFIX SOURCE_ROOT BUILD_ROOT HYSTVIZ: the
# tests use the build tree's programs, library and files, never an installed
# hystviz (issue 35 item 5: `meson dist` ran 5 tests against an install in
# the configured prefix).  DECOY_PREFIX is the prefix PROG (hy_file.c's
# lookup, tests/cli/decoyprefix) was configured with; this test fills it
# with a decoy install (scenes, Bouc-Wen data, hystviz-animate, bin/hystviz,
# lib/libhystviz.so.0) and puts its bin/ first in PATH and its lib/ in
# LIBRARY_PATH.  Then:
#   - a copy of PROG outside the build tree finds the decoy (so the decoy is
#     where an install would be: the test can fail);
#   - PROG in the build tree finds none of them, as where nothing is
#     installed (a scene's include is not looked up among installed scenes,
#     the Bouc-Wen data come from the source tree: cmd_boucwen.c);
#   - the pkg-config example's test (tests/libhystviz/test_example.sh), run as
#     the suite runs it, never runs the decoy hystviz and passes against the
#     build tree's library.
set -u
. "$(dirname "$0")/../lib.sh"
prog=$1 prefix=$2 src=$3 build=$4 hv=$5
T=$tmp
trap 'rm -rf "$prefix"; lib_cleanup' EXIT
rm -rf "$prefix"
mkdir -p "$prefix/share/hystviz/scenes" "$prefix/share/hystviz/boucwen" "$prefix/libexec" "$prefix/bin" "$prefix/lib"
echo "# decoy" >"$prefix/share/hystviz/scenes/style.scene"
printf '#!/bin/sh\necho "decoy $0 $*" >>"%s"\nexit 99\n' "$T/decoy-ran" >"$prefix/bin/hystviz"
cp "$prefix/bin/hystviz" "$prefix/libexec/hystviz-animate"
chmod +x "$prefix/bin/hystviz" "$prefix/libexec/hystviz-animate"
echo "not a library" >"$prefix/lib/libhystviz.so.0"
ln -s libhystviz.so.0 "$prefix/lib/libhystviz.so"
out=$(timeout 30 "$prog") || bad "$prog exited non-zero"
[ "$(sed -n 's/^configured //p' <<<"$out")" = "$prefix/share/hystviz" ] ||
    bad "PROG was not configured with the decoy prefix: $out"
# the same program outside any build tree: an installed program's lookup
mkdir -p "$T/outside/bin"
cp "$prog" "$T/outside/bin/prog"
outside=$(timeout 30 "$T/outside/bin/prog")
[ "$(sed -n 's/^scenes //p' <<<"$outside")" = "$prefix/share/hystviz/scenes" ] &&
    [ "$(sed -n 's/^hystviz-animate //p' <<<"$outside")" = "$prefix/libexec/hystviz-animate" ] &&
    ok "outside the build tree the lookup finds the decoy install" ||
    bad "outside the build tree the decoy install was not found (the test cannot tell): $outside"
# in the build tree: nothing found, as where nothing is installed
[ "$(grep -v '^configured ' <<<"$out")" = "$(printf 'scenes -\nboucwen -\nhystviz-animate -')" ] &&
    ok "build tree: no scenes, data or helper of the decoy install found" ||
    bad "build tree: found in an install: $out"
# a suite helper with the decoy first in PATH and in the linker's path
PATH="$prefix/bin:$PATH" LIBRARY_PATH="$prefix/lib" timeout 100 bash "$src/tests/libhystviz/test_example.sh" \
    "$build" "$src" "$hv" >"$T/example.log" 2>&1 &&
    ok "the pkg-config example's test passes with the decoy first in PATH and LIBRARY_PATH" ||
    { cat "$T/example.log"; bad "the pkg-config example's test with the decoy in PATH and LIBRARY_PATH"; }
[ ! -e "$T/decoy-ran" ] && ok "the decoy hystviz never ran" || bad "the decoy ran: $(cat "$T/decoy-ran")"
finish decoy
