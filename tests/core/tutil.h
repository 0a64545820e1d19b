/* SPDX-License-Identifier: MIT */
/* tutil.h: the core tests' checks (tests/hy_test.h under their short names:
 * CHECK counts and reports; tu_finish prints "N passed, M failed" and returns
 * the exit code) and a fixed-seed random generator. */
#ifndef HY_TUTIL_H
#define HY_TUTIL_H

#include <stdint.h>

#include "../hy_test.h"

/* the core tests' names for tests/hy_test.h's checks */
#define CHECK HY_CHECK
#define CHECK_CLOSE HY_CHECK_CLOSE

#define CHECK_MSG(rc, err, expect_code, needle)                                 \
    CHECK((rc) == (expect_code) && strstr((err).msg, (needle)) != NULL,         \
          "expected code %d with message containing '%s', got %d: '%s'",       \
          (expect_code), (needle), (rc), (err).msg)

static inline int tu_finish(const char *name)
{
    return hy_test_finish(name);
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
