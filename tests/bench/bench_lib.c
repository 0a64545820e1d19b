/* SPDX-License-Identifier: MIT */
/* bench_lib.c SCENE_TEXT_FILE N: the C side of the Python call-overhead figure
 * (tests/bench/bench_python.py): N calls of hy_result_from_text on the scene
 * text (the 200-point steady loop hystviz.steady_loop writes), each taking its
 * series and freeing the result; prints the median microseconds per call of
 * 7 rounds. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hystviz.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv)
{
    if (argc != 3)
        return fprintf(stderr, "usage: bench_lib SCENE_TEXT_FILE N\n"), 2;
    FILE *f = fopen(argv[1], "r");
    static char text[1 << 16];
    size_t len = f ? fread(text, 1, sizeof text - 1, f) : 0;
    if (f)
        fclose(f);
    long n = atol(argv[2]);
    if (!len || n < 1)
        return fprintf(stderr, "bench_lib: no scene text or N\n"), 2;
    double rounds[7];
    for (int k = 0; k < 7; k++) {
        double t0 = now();
        for (long i = 0; i < n; i++) {
            hy_result *r;
            hy_error err;
            if (hy_result_from_text("<python>/scene.scene", text, len, NULL, 0, 0, &r, &err))
                return fprintf(stderr, "bench_lib: %s\n", err.msg), 1;
            const double *x, *y;
            volatile size_t m = hy_result_series(r, 1, &x, &y);
            (void)m;
            hy_result_free(r);
        }
        rounds[k] = (now() - t0) / (double)n * 1e6;
    }
    qsort(rounds, 7, sizeof *rounds, cmp);
    printf("%.3f\n", rounds[3]);
    return 0;
}
