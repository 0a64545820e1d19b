/* SPDX-License-Identifier: MIT */
/* bench_pyloop.c: the C side of the same-process call-overhead figure
 * (tests/bench/bench_python.py, issue 35): a shared module the benchmark
 * loads with ctypes into the Python process itself, whose one function makes
 * count calls of hy_steady_loop (the one call hystviz.steady_loop makes) with
 * the same arguments and buffers as Python's calls, through the address of
 * the library Python loaded (so both sides call one copy of the library, in
 * one process, with one memory layout).  The Python side times it with the
 * clock it times its own calls with (CPU time), one ctypes call per round.
 * bench_pyloop_noop has hy_steady_loop's type and does nothing: bound in its
 * place, it leaves the Python wrapper's own cost. */
#include <stddef.h>

#include "hystviz.h"

typedef int steady_fn(const char *name, const char *model, const char *input, const char *const *sets,
                      size_t nsets, size_t points, double *t, double *u, double *y, hy_error *err);

int bench_pyloop_steady(steady_fn *fn, const char *name, const char *model, const char *input, size_t points,
                        double *out, size_t count);
steady_fn bench_pyloop_noop;

/* count calls of fn (hy_steady_loop) writing t, u, y one after the other into
 * out (3 (points + 1) doubles); returns how many calls failed (0 expected). */
int bench_pyloop_steady(steady_fn *fn, const char *name, const char *model, const char *input, size_t points,
                        double *out, size_t count)
{
    size_t n = points + 1;
    int failed = 0;
    for (size_t i = 0; i < count; i++)
        failed += fn(name, model, input, NULL, 0, points, out, out + n, out + 2 * n, NULL) != 0;
    return failed;
}

/* hy_steady_loop's type, nothing done: returns 0 (HY_OK), writes nothing. */
int bench_pyloop_noop(const char *name, const char *model, const char *input, const char *const *sets, size_t nsets,
                      size_t points, double *t, double *u, double *y, hy_error *err)
{
    (void)name, (void)model, (void)input, (void)sets, (void)nsets, (void)points, (void)t, (void)u, (void)y, (void)err;
    return 0;
}
