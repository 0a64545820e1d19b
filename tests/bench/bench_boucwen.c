/* SPDX-License-Identifier: MIT */
/* bench_boucwen.c: the benchmark's example synthesis timed: a 50 N multisine
 * period (8192 x 20 samples at 15 kHz), 4 periods + 1 extra = 5 periods =
 * 819,200 Newmark steps, then 2-2-5 decimation.  Prints figures only. */
#include "hy_boucwen.h"
#include "hy_signal.h"

#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int main(void)
{
    const size_t r = 20, periods = 4;
    hy_multisine ms;
    hy_boucwen_params p;
    hy_newmark_opts o;
    hy_error err;
    hy_multisine_default(&ms);
    hy_boucwen_params_default(&p);
    hy_newmark_opts_default(&o);
    size_t np = ms.n * r, steps = (periods + 1) * np;
    double *u = malloc(np * sizeof *u), *y = malloc(periods * ms.n * sizeof *y);
    double *u5 = malloc(steps * sizeof *u5), *y5 = malloc(steps * sizeof *y5);
    if (!u || !y || !u5 || !y5 || hy_multisine_design(&ms, r, u, &err)) {
        fprintf(stderr, "bench_boucwen: setup failed\n");
        return 1;
    }
    double best = 1e30, best_int = 1e30, best_dec = 1e30;
    double *yd = malloc(steps / r * sizeof *yd);
    size_t nyd;
    for (int rep = 0; rep < 5; rep++) {
        double t0 = now();
        if (hy_boucwen_synth_periodic(&p, &o, ms.fs, r, 1, u, np, periods, y, &err)) {
            fprintf(stderr, "bench_boucwen: %s\n", err.msg);
            return 1;
        }
        double t1 = now();
        for (size_t q = 0; q <= periods; q++)
            for (size_t i = 0; i < np; i++)
                u5[q * np + i] = u[i];
        double t2 = now();
        if (hy_boucwen_simulate(&p, &o, 1.0 / (ms.fs * (double)r), u5, steps, NULL, y5, NULL, &err)) {
            fprintf(stderr, "bench_boucwen: %s\n", err.msg);
            return 1;
        }
        double t3 = now();
        if (hy_signal_decimate_stages(y5, steps, r, 1, yd, &nyd, &err)) {
            fprintf(stderr, "bench_boucwen: %s\n", err.msg);
            return 1;
        }
        double t4 = now();
        if (t4 - t3 < best_dec)
            best_dec = t4 - t3;
        if (t1 - t0 < best)
            best = t1 - t0;
        if (t3 - t2 < best_int)
            best_int = t3 - t2;
    }
    printf("boucwen synthesis: %zu Newmark steps (5 periods x 8192 x 20) + 2-2-5 decimation\n", steps);
    printf("  total     %.4f s  (%.3g steps/s, best of 5)\n", best, (double)steps / best);
    printf("  integrate %.4f s  (%.3g steps/s, %.0f ns/step)\n", best_int,
           (double)steps / best_int, 1e9 * best_int / (double)steps);
    printf("  decimate  %.4f s  (2-2-5 stages, %zu -> %zu samples)\n", best_dec, steps, nyd);
    free(u);
    free(y);
    free(u5);
    free(y5);
    free(yd);
    return 0;
}
