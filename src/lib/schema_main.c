/* SPDX-License-Identifier: MIT */
/* schema_main.c: prints the scene schema as JSON (hy_schema_json), for the
 * generators of bash completion and docs at build time (tools/gen_docs.py). */
#include <stdio.h>
#include <stdlib.h>

#include "hystviz.h"

int main(void)
{
    char *js = hy_schema_json();
    if (!js) {
        fputs("hy_schema_json: out of memory\n", stderr);
        return 1;
    }
    int bad = fputs(js, stdout) == EOF || fflush(stdout) != 0;
    free(js);
    return bad;
}
