/* SPDX-License-Identifier: MIT */
/* rcheck.h: the failure counter and CHECK macro shared by the render and GL
 * tests (each test file prints its own summary from `fails`). */
#ifndef HY_RCHECK_H
#define HY_RCHECK_H

#include <stdio.h>

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

#endif
