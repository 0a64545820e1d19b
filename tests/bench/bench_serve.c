/* SPDX-License-Identifier: MIT */
/* bench_serve.c SCENES_DIR [N]: the server side of a control change in
 * `hystviz serve`, in one warm process as the server runs it: scene text +
 * one override -> parse, plan, compute, draw, SVG bytes in memory
 * (hy_scene_run_load/compute/render), figure_only and with serve's
 * allocator settings (serve_malloc.h).  Fig. 15 (analytic), Fig. 11 (GSL)
 * and bw_fig1a (Newmark); a new value per change, as a slider drag sends.
 * Prints a Markdown table, the README's (tests/cli/test_readme_bench.sh
 * checks its rows and format): median, 95th percentile and minimum of the
 * wall time, the median CPU time and the load average; asserts nothing.
 * `bench_serve --rows` prints the header and first cells only;
 * `bench_serve SCENES_DIR N FILE` times only the figure FILE (profiling). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <gsl/gsl_errno.h>

#include "scene_run.h"
#include "serve_malloc.h"

static double clock_s(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static double now(void) { return clock_s(CLOCK_MONOTONIC); }

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double pct(double *v, int n, double q)
{
    qsort(v, (size_t)n, sizeof *v, cmp);
    int i = (int)lround(q / 100 * (n - 1));
    return v[i];
}

/* One change: key=value(i); returns seconds (or -1 on error, printed), its
 * CPU seconds in *cpu. */
static double change(const char *path, const char *key, double value, size_t *bytes, double *cpu)
{
    char set[128];
    snprintf(set, sizeof set, "%s=%.4g", key, value);
    char *sets[1] = {set};
    double t0 = now(), c0 = clock_s(CLOCK_PROCESS_CPUTIME_ID);
    hy_scene_run r;
    hy_error err;
    int lrc = hy_scene_run_load(&r, path, sets, 1, &err);
    if (!lrc)
        r.figure_only = 1; /* as serve computes a figure */
    if (lrc || (hy_scene_run_compute(&r, NULL, &err) && (hy_scene_run_free(&r), 1))) {
        fprintf(stderr, "bench_serve: %s\n", err.msg);
        return -1;
    }
    unsigned char *buf;
    size_t len;
    int rc = hy_scene_run_render(&r, HY_FORMAT_SVG, &buf, &len, NULL, &err);
    hy_scene_run_free(&r);
    if (rc) {
        fprintf(stderr, "bench_serve: %s\n", err.msg);
        return -1;
    }
    free(buf);
    *bytes = len;
    *cpu = clock_s(CLOCK_PROCESS_CPUTIME_ID) - c0;
    return now() - t0;
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    sv_malloc_tune();
    int rows_only = argc > 1 && !strcmp(argv[1], "--rows");
    const char *dir = argc > 1 ? argv[1] : "scenes";
    int n = argc > 2 ? atoi(argv[2]) : 100;
    const char *only = argc > 3 ? argv[3] : NULL;
    static const struct {
        const char *file, *key;
        double lo, hi;
        int n_div;
    } figs[] = {{"fig15_minor_loop_ex4.scene", "model.sigma0", 1, 60, 1},
                {"fig11_ygamma_ex3.scene", "model.sigma0", 1, 60, 2},
                {"bw_fig1a_quasistatic_loop.scene", "input.amp", 60, 180, 4}};
    printf("| figure (control) | server render, warm process (`bench_serve`): wall median / p95 (min) | CPU median | "
           "load |\n|---|---|---|---|\n");
    for (size_t f = 0; rows_only && f < sizeof figs / sizeof figs[0]; f++)
        printf("| %s (%s) |\n", figs[f].file, figs[f].key);
    for (size_t f = 0; !rows_only && f < sizeof figs / sizeof figs[0]; f++) {
        if (only && strcmp(only, figs[f].file))
            continue;
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", dir, figs[f].file);
        int m = n / figs[f].n_div > 5 ? n / figs[f].n_div : 5;
        double *t = malloc((size_t)m * sizeof *t), *cpu = malloc((size_t)m * sizeof *cpu), c;
        size_t bytes = 0;
        if (!t || !cpu || change(path, figs[f].key, figs[f].lo, &bytes, &c) < 0) /* warm: fonts, caches */
            return 1;
        int ok = 0, failed = 0;
        for (int i = 0; i < m; i++) {
            double v = figs[f].lo * pow(figs[f].hi / figs[f].lo, (double)(i % 50) / 49.0);
            double dt = change(path, figs[f].key, v, &bytes, &c);
            if (dt < 0)
                failed++; /* a scene error (printed): the page would show it */
            else
                cpu[ok] = c, t[ok++] = dt;
        }
        if (!ok)
            return 1;
        double med = pct(t, ok, 50), p95 = pct(t, ok, 95), mn = t[0], cmed = pct(cpu, ok, 50), load = NAN;
        FILE *la = fopen("/proc/loadavg", "r");
        if (la && fscanf(la, "%lf", &load) != 1)
            load = NAN;
        if (la)
            fclose(la);
        printf("| %s (%s) | %.2f / %.2f ms (min %.2f) | %.2f ms | %.1f |\n", figs[f].file, figs[f].key, 1e3 * med,
               1e3 * p95, 1e3 * mn, 1e3 * cmed, load);
        fprintf(stderr, "bench-serve-render %s: %d changes, %d refused, %zu-byte SVG\n", figs[f].file, ok, failed,
                bytes);
        free(t);
        free(cpu);
    }
    return 0;
}
