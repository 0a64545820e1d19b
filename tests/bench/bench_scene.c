/* SPDX-License-Identifier: MIT */
/* bench_scene.c: parse time of large scenes (16,000 to 96,000 named sections; 64,000 is the
 * size of issue 10's quadratic-parser reproducer; 4 MiB is the cap): with hashed section
 * and key lookups the time grows linearly.  Prints; asserts nothing. */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "hy_scene.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int main(void)
{
    static const int sizes[] = {16000, 32000, 64000, 96000};
    for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++) {
        int n = sizes[k];
        size_t cap = (size_t)n * 48, o = 0;
        char *text = malloc(cap);
        if (!text)
            return 1;
        for (int i = 0; i < n; i++)
            o += (size_t)snprintf(text + o, cap - o, "[series s%d]\ndata = input\nat = %d\n", i, i);
        hy_scene *s;
        hy_error err;
        double t0 = now();
        int rc = hy_scene_parse_buffer("bench.scene", text, o, &s, &err);
        double t1 = now();
        if (rc) {
            fprintf(stderr, "bench_scene: %s\n", err.msg);
            free(text);
            return 1;
        }
        size_t cnt = hy_scene_count(s, "series");
        double at = 0;
        for (int i = 0; i < n; i++) { /* every section by name, as a figure's series loop does */
            double v;
            hy_scene_get_num(s, "series", hy_scene_name_at(s, "series", (size_t)i), "at", &v);
            at += v;
        }
        double t2 = now();
        printf("scene parse: %6d sections, %7.2f MB: parse %8.1f ms, %zu sections read back by name in %6.1f ms (sum %g)\n", n,
               (double)o / 1e6, 1e3 * (t1 - t0), cnt, 1e3 * (t2 - t1), at);
        hy_scene_free(s);
        free(text);
    }
    return 0;
}
