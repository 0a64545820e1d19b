#!/bin/sh
# SPDX-License-Identifier: MIT
# test_serve_floor.sh ROOT: serve is a floor of its own (issue 34 item 1,
# docs/ARCHITECTURE.md "hystviz serve and watch"): no file of src/serve
# includes a header of src/app, and no file of src/app names an HTTP
# endpoint (the routes are src/serve/serve_routes.c's table).
set -u
. "$(dirname "$0")/../lib.sh"
root=$1
n=0
for f in "$root"/src/serve/*.c "$root"/src/serve/*.h; do
    n=$((n + 1))
    for h in $(sed -n 's/^#include "\([^"]*\)".*/\1/p' "$f"); do
        [ ! -e "$root/src/app/$h" ] ||
            bad "src/serve/${f##*/} includes $h, a header of src/app: serve must not depend on app"
    done
done
[ "$n" -gt 1 ] && ok "$n file(s) of src/serve checked for headers of src/app" || bad "no files in $root/src/serve"
if grep -rnE '"/(api/|events|scenes/|app\.js|app\.css|index\.html)' "$root/src/app"; then
    bad "a file of src/app names an HTTP endpoint (above): routes belong to src/serve/serve_routes.c"
else
    ok "src/app names no endpoint"
fi
finish serve-floor
