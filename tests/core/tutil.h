/* SPDX-License-Identifier: MIT */
/* tutil.h: tiny assertion helpers for hystviz's C tests.  CHECK counts and
 * reports; tu_finish prints "N passed, M failed" and returns the exit code. */
#ifndef HY_TUTIL_H
#define HY_TUTIL_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

static int tu_pass, tu_fail;

#define CHECK(cond, ...)                                                        \
    do {                                                                        \
        if (cond)                                                               \
            tu_pass++;                                                          \
        else {                                                                  \
            tu_fail++;                                                          \
            if (tu_fail <= 25) {                                                \
                fprintf(stderr, "FAIL %s:%d: ", __FILE__, __LINE__);            \
                fprintf(stderr, __VA_ARGS__);                                   \
                fputc('\n', stderr);                                            \
            }                                                                   \
        }                                                                       \
    } while (0)

#define CHECK_CLOSE(a, b, tol, what)                                            \
    CHECK(fabs((double)(a) - (double)(b)) <= (tol), "%s: %.17g vs %.17g (diff %.3g > tol %.3g)", \
          what, (double)(a), (double)(b), fabs((double)(a) - (double)(b)), (double)(tol))

#define CHECK_MSG(rc, err, expect_code, needle)                                 \
    CHECK((rc) == (expect_code) && strstr((err).msg, (needle)) != NULL,         \
          "expected code %d with message containing '%s', got %d: '%s'",       \
          (expect_code), (needle), (rc), (err).msg)

static inline int tu_finish(const char *name)
{
    printf("%s: %d passed, %d failed\n", name, tu_pass, tu_fail);
    return tu_fail ? 1 : 0;
}

/* splitmix64: a fixed-seed generator so random cases are reproducible */
static uint64_t tu_state = 0x9E3779B97F4A7C15ULL;
static inline uint64_t tu_next(void)
{
    uint64_t z = (tu_state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}
static inline double tu_unif(double a, double b)
{
    return a + (b - a) * ((double)(tu_next() >> 11) * 0x1.0p-53);
}
static inline double tu_logunif(double a, double b)
{
    return exp(tu_unif(log(a), log(b)));
}

#endif
