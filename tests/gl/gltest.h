/* SPDX-License-Identifier: MIT */
/* gltest.h: helpers shared by the GL tests (checks, SKIP when there is no GL context). */
#ifndef HY_GLTEST_H
#define HY_GLTEST_H

#include <stdio.h>
#include <stdlib.h>

#include "hy_gl.h"

#include "../render/rcheck.h"

/* Creates a context or exits 77 (SKIP) with the reason. */
static inline hy_gl *gl_or_skip(int w, int h)
{
    hy_gl *g;
    hy_error err;
    if (hy_gl_create(&g, w, h, &err)) {
        printf("SKIP: no GL context: %s\n", err.msg);
        exit(77);
    }
    return g;
}

#endif
