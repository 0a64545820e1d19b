#!/bin/sh
# SPDX-License-Identifier: MIT
# Command-line tests of hystviz: --help, --version, loop CSV, clear errors with
# non-zero exit status and no partial output.
set -u
hv=$1
. "$(dirname "$0")/../lib.sh"

"$hv" --help > "$tmp/h" 2>&1 && grep -q 'usage: hystviz COMMAND' "$tmp/h" && grep -q 'loop' "$tmp/h" && ok || bad "--help"
"$hv" --version | grep -Eq '^hystviz [0-9]+\.[0-9]+\.[0-9]+$' && ok || bad "--version"
"$hv" loop --help | grep -q 'input SPEC' && ok || bad "loop --help"

# the issue's example: 200 rows plus a header, t,u,y, %.17g, periodic loop
"$hv" loop --model lugre --sigma0 6 --fc 1 --fs 2 --vs 1 --beta 1 --input bimodal:0,0.5,1,1.5 --points 200 > "$tmp/loop.csv"
[ "$(head -1 "$tmp/loop.csv")" = "t,u,y" ] && ok || bad "loop header"
[ "$(wc -l < "$tmp/loop.csv")" -eq 201 ] && ok || bad "loop rows: $(wc -l < "$tmp/loop.csv")"
first=$(sed -n 2p "$tmp/loop.csv" | cut -d, -f3)
last=$(tail -1 "$tmp/loop.csv" | cut -d, -f3)
[ "$first" = "$last" ] && ok || bad "loop not closed: $first vs $last"
# %.17g: the first output value is printed with 17 significant digits
echo "$first" | grep -Eq '^-?[0-9]\.[0-9]{16}$' && ok || bad "not %.17g: $first"

# -o writes atomically and deterministically
"$hv" loop --input bimodal:0,0.2,1,1.5 -o "$tmp/a.csv" && "$hv" loop --input bimodal:0,0.2,1,1.5 -o "$tmp/b.csv" &&
    cmp -s "$tmp/a.csv" "$tmp/b.csv" && ok || bad "deterministic -o"
"$hv" loops --model lugre --sigma0 6 --input bimodal:0,0.5,1,1.5 | grep -q '^minor,1,1,1.5,2,' && ok || bad "loops: Example 4 minor loop [1, 2]"

# errors: message, exit status 2, no output file
expect_err() { # expected-text, args...
    want=$1
    shift
    "$hv" "$@" > "$tmp/out" 2> "$tmp/err"
    st=$?
    if [ $st -ne 0 ] && grep -qF -- "$want" "$tmp/err" && [ ! -s "$tmp/out" ]; then ok; else
        bad "hystviz $* -> status $st, stderr: $(cat "$tmp/err")"
    fi
}
expect_err "sigma0 must be > 0" loop --sigma0 -1 --input bimodal:0,0.5,1,1.5
expect_err "'nan' is not a finite number" loop --sigma0 nan --input bimodal:0,0.5,1,1.5
expect_err "u_min,2 < u_max,1" loop --input bimodal:0,1.2,1,1.5
expect_err "unknown command 'lop'" lop
expect_err "unknown option '--sigma'" loop --sigma 3 --input bimodal:0,0.5,1,1.5
expect_err "--input SPEC is required" loop
expect_err "unknown model 'lugr'" loop --model lugr --input bimodal:0,0.5,1,1.5
expect_err "gamma must be a finite number > 0" loop --gamma 0 --input bimodal:0,0.5,1,1.5
expect_err "cannot write" loop --input bimodal:0,0.5,1,1.5 -o /nonexistent/dir/x.csv
[ ! -e /nonexistent/dir/x.csv ] && ok || bad "partial file"

# the option parser (src/app/cli_opt.c): the forms of a value, '--', and one
# line naming the command and the option for each kind of mistake
"$hv" loop --input=bimodal:0,0.2,1,1.5 --points=200 -o "$tmp/eq.csv" && cmp -s "$tmp/a.csv" "$tmp/eq.csv" && ok ||
    bad "--name=VALUE differs from --name VALUE"
[ "$("$hv" render --version)" = "$("$hv" --version)" ] && [ "$("$hv" serve x.scene --version)" = "$("$hv" --version)" ] &&
    ok || bad "COMMAND --version"
expect_err "hystviz loop: option --points needs a value (N) (see hystviz loop --help)" loop --input sine:1,1 --points
expect_err "hystviz check: option --quick takes no value" check --quick=1
expect_err "hystviz check: unexpected argument 'x'" check x
expect_err "hystviz: unknown option '--bogus' (see hystviz --help)" --bogus
expect_err "hystviz data: unknown option '--format'" data x.scene --format svg
# checked whole before anything acts: the bad option at the end stops the render
expect_err "hystviz render: unknown option '--bogus'" render "$tmp/none.scene" -o "$tmp/r" --bogus
[ ! -e "$tmp/r" ] && ok || bad "render acted before its line was checked"
# after '--' every argument is a scene, even one named like an option
expect_err "--help: cannot read scene file" render -- --help

# hystviz itself never loads OpenGL (animations run in hystviz-animate) nor
# the HTTP and TLS libraries (serve runs in hystviz-serve)
if command -v ldd > /dev/null; then
    ldd "$hv" | grep -qiE 'osmesa|llvm' && bad "hystviz links OpenGL/LLVM" || ok
    ldd "$hv" | grep -qiE 'microhttpd|gnutls' && bad "hystviz links libmicrohttpd/gnutls" || ok
fi
"$hv" serve --help > "$tmp/serve" 2>&1; rc=$?
{ [ $rc -eq 0 ] && grep -q 'usage: hystviz serve' "$tmp/serve"; } ||
    { [ $rc -eq 3 ] && grep -q 'libmicrohttpd' "$tmp/serve"; } || bad "hystviz serve --help (exit $rc): $(cat "$tmp/serve")"
"$hv" animate --help > "$tmp/anim" 2>&1 && grep -q 'animate' "$tmp/anim" && ok || bad "hystviz animate --help: $(cat "$tmp/anim")"

# the helpers beside hystviz (libexec when installed) answer --version and
# --help like every command (issue 36 item 7: "which animation?", "scenes: No
# such file or directory")
for helper in hystviz-animate hystviz-serve; do
    h=$(dirname "$hv")/$helper
    [ -x "$h" ] || continue
    [ "$("$h" --version 2> "$tmp/h.err")" = "$("$hv" --version)" ] && ok ||
        bad "$helper --version: $(cat "$tmp/h.err")"
    "$h" --help > "$tmp/h.out" 2>&1
    rc=$?
    { [ $rc -eq 0 ] && grep -q "^usage: hystviz ${helper#hystviz-}" "$tmp/h.out"; } ||
        { [ $rc -eq 3 ] && grep -q 'libmicrohttpd' "$tmp/h.out"; } || bad "$helper --help (exit $rc): $(head -c 300 "$tmp/h.out")"
done

finish "cli"
