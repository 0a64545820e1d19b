/* SPDX-License-Identifier: MIT */
/* bench_lib.c MODEL_FILE INPUT_FILE POINTS N: the C side of the Python
 * call-overhead figure (tests/bench/bench_python.py): N calls of
 * hy_steady_loop, the one call hystviz.steady_loop makes, on the [model] and
 * [input] texts of the two files (what the Python package passes) at POINTS
 * samples, into arrays allocated once; prints the CPU time (user + system)
 * per call in microseconds of this one round (the Python side alternates
 * rounds with it and takes the medians). */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "hystviz.h"

static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The whole file at path as a NUL-terminated text in buf (size bytes), or 0. */
static int slurp(const char *path, char *buf, size_t size)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return 0;
    size_t len = fread(buf, 1, size - 1, f);
    int whole = feof(f) && !ferror(f);
    fclose(f);
    buf[len] = '\0';
    return whole && len > 0;
}

int main(int argc, char **argv)
{
    static char model[1 << 14], input[1 << 14];
    if (argc != 5)
        return fprintf(stderr, "usage: bench_lib MODEL_FILE INPUT_FILE POINTS N\n"), 2;
    if (!slurp(argv[1], model, sizeof model) || !slurp(argv[2], input, sizeof input))
        return fprintf(stderr, "bench_lib: cannot read %s or %s (or one is empty or over 16 kB)\n", argv[1], argv[2]),
               2;
    long points = atol(argv[3]), n = atol(argv[4]);
    if (points < 2 || n < 1)
        return fprintf(stderr, "bench_lib: POINTS >= 2 and N >= 1, got %s and %s\n", argv[3], argv[4]), 2;
    double *buf = malloc(3 * ((size_t)points + 1) * sizeof *buf);
    if (!buf)
        return fprintf(stderr, "bench_lib: out of memory\n"), 1;
    double *t = buf, *u = buf + points + 1, *y = buf + 2 * (points + 1);
    double c0 = cpu_now();
    for (long i = 0; i < n; i++) {
        hy_error err;
        if (hy_steady_loop("<python>/scene.scene", model, input, NULL, 0, (size_t)points, t, u, y, &err))
            return fprintf(stderr, "bench_lib: %s\n", err.msg), free(buf), 1;
    }
    printf("%.3f\n", (cpu_now() - c0) / (double)n * 1e6);
    free(buf);
    return 0;
}
