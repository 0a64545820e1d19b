/* gltest.h: helpers shared by the GL tests (checks, SKIP when there is no GL context). */
#ifndef HY_GLTEST_H
#define HY_GLTEST_H

#include <stdio.h>
#include <stdlib.h>

#include "hy_gl.h"

static int fails;
#define CHECK(c, ...)                                                      \
    do {                                                                   \
        if (!(c)) {                                                        \
            fails++;                                                       \
            printf("FAIL %s:%d: ", __FILE__, __LINE__);                    \
            printf(__VA_ARGS__);                                           \
            printf("\n");                                                  \
        }                                                                  \
    } while (0)

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
