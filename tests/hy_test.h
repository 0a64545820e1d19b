/* SPDX-License-Identifier: MIT */
/* tests/hy_test.h: the C tests' vocabulary.  Checks that count and say what
 * failed, with tolerances; a summary whose status is the test's; the test's
 * own temporary directory (tests/tmpdir.h); a whole file read into memory.
 *
 *     HY_CHECK(n == 3, "rows: %d, want 3", n);
 *     HY_CHECK_CLOSE(area, 4.0, 1e-12, "loop area");   (absolute tolerance)
 *     HY_CHECK_REL(e, e_ref, 1e-9, "energy");          (relative tolerance)
 *     char *text = hy_test_slurp(test_tmppath(p, sizeof p, "out.svg"), &len);
 *     return hy_test_finish("test_name");  ("NAME: P passed, F failed"; 0 or 1)
 *
 * The first 25 failures are printed on stderr as "FAIL file:line: message". */
#ifndef HY_TEST_H
#define HY_TEST_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tmpdir.h"

static int hy_test_pass, hy_test_fail;

#define HY_CHECK(cond, ...)                                                     \
    do {                                                                        \
        if (cond)                                                               \
            hy_test_pass++;                                                     \
        else {                                                                  \
            hy_test_fail++;                                                     \
            if (hy_test_fail <= 25) {                                           \
                fprintf(stderr, "FAIL %s:%d: ", __FILE__, __LINE__);            \
                fprintf(stderr, __VA_ARGS__);                                   \
                fputc('\n', stderr);                                            \
            }                                                                   \
        }                                                                       \
    } while (0)

/* |a - b| <= tol (a NaN on either side fails) */
#define HY_CHECK_CLOSE(a, b, tol, what)                                         \
    HY_CHECK(fabs((double)(a) - (double)(b)) <= (tol),                          \
             "%s: %.17g vs %.17g (diff %.3g > tol %.3g)", what, (double)(a),    \
             (double)(b), fabs((double)(a) - (double)(b)), (double)(tol))

/* |a - b| <= rtol |b| (a NaN on either side fails) */
#define HY_CHECK_REL(a, b, rtol, what)                                          \
    HY_CHECK(fabs((double)(a) - (double)(b)) <= (rtol) * fabs((double)(b)),     \
             "%s: %.17g vs %.17g (relative diff %.3g > %.3g)", what,            \
             (double)(a), (double)(b),                                          \
             fabs((double)(a) - (double)(b)) / fabs((double)(b)), (double)(rtol))

/* Prints "name: P passed, F failed"; returns the test's exit status (0 or 1). */
static inline int hy_test_finish(const char *name)
{
    printf("%s: %d passed, %d failed\n", name, hy_test_pass, hy_test_fail);
    return hy_test_fail ? 1 : 0;
}

/* The whole of path, NUL-terminated, in a malloc'd buffer the caller frees;
 * *len (when len is not NULL) gets its size.  NULL, with a message naming the
 * file, when it cannot be read. */
static inline char *hy_test_slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        fprintf(stderr, "hy_test_slurp: cannot open %s\n", path);
        return NULL;
    }
    size_t cap = 4096, n = 0;
    char *buf = malloc(cap);
    for (size_t got; buf && (got = fread(buf + n, 1, cap - n - 1, f)) > 0;) {
        n += got;
        if (cap - n - 1 == 0) {
            char *bigger = realloc(buf, cap * 2);
            if (!bigger) {
                free(buf);
                buf = NULL;
                break;
            }
            buf = bigger;
            cap *= 2;
        }
    }
    int bad = ferror(f);
    fclose(f);
    if (!buf || bad) {
        fprintf(stderr, "hy_test_slurp: cannot read %s\n", path);
        free(buf);
        return NULL;
    }
    buf[n] = '\0';
    if (len)
        *len = n;
    return buf;
}

#endif
