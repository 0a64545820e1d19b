#!/bin/bash
# SPDX-License-Identifier: MIT
# tests/cli/test_spdx_modes.sh SPDX_TEST: test_spdx.sh judges the right files
# in a small tree of its own (three files with their SPDX line, one without,
# a build directory's generated file without one) placed three ways: alone
# (an unpacked tarball), untracked inside another git checkout (the tarball
# `meson dist` unpacks under build/meson-private: issue 35 item 5), and as a
# git checkout of its own (only tracked files count).  Each time it must
# name exactly the file without the line, and pass once that file has it.
set -u
. "$(dirname "$0")/../lib.sh"
spdx=$1
need git
T=$tmp
export GIT_CONFIG_GLOBAL=/dev/null GIT_CONFIG_NOSYSTEM=1 GIT_AUTHOR_NAME=t GIT_AUTHOR_EMAIL=t@t \
    GIT_COMMITTER_NAME=t GIT_COMMITTER_EMAIL=t@t
make_tree() { # DIR
    mkdir -p "$1/src" "$1/build/meson-private"
    printf '/* SPDX-License-Identifier: MIT */\nint x;\n' >"$1/src/a.c"
    printf '#!/bin/sh\n# SPDX-License-Identifier: MIT\n' >"$1/run.sh"
    printf '# SPDX-License-Identifier: MIT\nproject(%s)\n' "'t'" >"$1/meson.build"
    printf 'print("no licence line")\n' >"$1/src/bad.py"
    printf 'int generated;\n' >"$1/build/gen.c"
}
expect() { # WHERE DIR: fails naming src/bad.py alone, passes once it has its line
    out=$(sh "$spdx" "$2" 3 2>&1)
    # (its output: the FAIL line, the files, and tests/lib.sh's summary line)
    if [ $? -ne 0 ] && [ "$(printf '%s\n' "$out" | sed -n '2,$p' | sed '$d')" = "src/bad.py" ]; then
        ok "$1: names src/bad.py alone"
    else
        bad "$1: expected a failure naming src/bad.py alone, got: $out"
    fi
    sed -i '1i # SPDX-License-Identifier: MIT' "$2/src/bad.py"
    out=$(sh "$spdx" "$2" 3 2>&1) && ok "$1: passes once it has its line ($out)" || bad "$1: still fails: $out"
}
make_tree "$T/alone"
expect "no git checkout" "$T/alone"
git init -q "$T/repo" && echo x >"$T/repo/README" && git -C "$T/repo" add README && git -C "$T/repo" commit -qm x
make_tree "$T/repo/build/meson-private/dist-unpack/t-1.0"
expect "untracked inside another checkout" "$T/repo/build/meson-private/dist-unpack/t-1.0"
make_tree "$T/own"
git -C "$T/own" init -q && git -C "$T/own" add src/a.c src/bad.py run.sh meson.build && git -C "$T/own" commit -qm x
printf 'int untracked;\n' >"$T/own/src/scratch.c"
expect "its own checkout (untracked files do not count)" "$T/own"
finish spdx-modes
