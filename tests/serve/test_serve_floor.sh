#!/bin/sh
# SPDX-License-Identifier: MIT
# test_serve_floor.sh ROOT: serve is a floor of its own (issue 34 item 1,
# docs/ARCHITECTURE.md "hystviz serve and watch"): no file of src/serve
# includes a header of src/app, and no file of src/app names an HTTP
# endpoint (the routes are src/serve/serve_routes.c's table).
root=$1
fail=0
n=0
for f in "$root"/src/serve/*.c "$root"/src/serve/*.h; do
    n=$((n + 1))
    for h in $(sed -n 's/^#include "\([^"]*\)".*/\1/p' "$f"); do
        if [ -e "$root/src/app/$h" ]; then
            echo "src/serve/${f##*/} includes $h, a header of src/app: serve must not depend on app"
            fail=1
        fi
    done
done
if grep -rnE '"/(api/|events|scenes/|app\.js|app\.css|index\.html)' "$root/src/app"; then
    echo "a file of src/app names an HTTP endpoint: routes belong to src/serve/serve_routes.c"
    fail=1
fi
echo "serve floor: $n file(s) of src/serve checked, src/app names no endpoint"
exit $fail
