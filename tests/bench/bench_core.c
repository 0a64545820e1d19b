/* SPDX-License-Identifier: MIT */
/* bench_core.c: speed of the hysteresis core (prints figures, asserts nothing).
 *  1. steady-loop evaluation on a dense grid (points per second, one core);
 *  2. exact y_γ over 100 periods at 1e5 output points;
 *  3. GSL integration of Example 3 at γ = 10: time to reach 1e-8 max error,
 *     per stepper (tolerance tightened by decades until the error is met). */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "hy_gamma.h"
#include "hy_limit.h"
#include "hy_ode.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static int cmpd(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int n)
{
    qsort(v, n, sizeof *v, cmpd);
    return v[n / 2];
}

int main(void)
{
    gsl_set_error_handler_off();
    hy_model m;
    hy_input in;
    hy_error err;
    hy_model_lugre_init(&m, 1, 1, 1, 2, 1, 1);
    hy_input_bimodal(&in, 0, 0.2, 1, 1.5, NULL, HY_SHAPE_LINEAR, &err);

    /* 1. dense steady loop */
    hy_steady st;
    hy_steady_init(&st, &m, &in, &err);
    size_t n = 20000000;
    double *y = malloc(n * sizeof *y), rep[7];
    for (int r = 0; r < 7; r++) {
        double t0 = now();
        hy_steady_sample(&st, n, NULL, y);
        rep[r] = now() - t0;
    }
    double tm = median(rep, 7);
    printf("steady loop, dense grid: %zu points in %.2f ms: %.0f million points/s (target >= 100)\n", n, 1e3 * tm,
           n / tm / 1e6);
    for (int r = 0; r < 7; r++) {
        double t0 = now();
        hy_steady_sample(&st, 4096, NULL, y);
        rep[r] = now() - t0;
    }
    printf("steady loop, 4096 points (in cache): %.0f million points/s\n", 4096 / median(rep, 7) / 1e6);
    free(y);

    /* 2. exact y_γ, 100 periods, 1e5 points */
    enum { M = 100000 };
    double *t = malloc(M * sizeof *t), *yy = malloc(M * sizeof *yy);
    for (int j = 0; j < M; j++)
        t[j] = 100 * in.period * j / (M - 1.0);
    for (int r = 0; r < 7; r++) {
        double t0 = now();
        hy_gamma_exact(&m, &in, 10, t, M, yy, NULL, &err);
        rep[r] = now() - t0;
    }
    printf("exact y_gamma, 100 periods, 1e5 points: %.3f ms (target < 5 ms)\n", 1e3 * median(rep, 7));

    /* 3. GSL steppers on Example 3 at γ = 10, 5 periods, to 1e-8 max error */
    enum { K = 201 };
    double tt[K], yex[K], yg[K];
    for (int j = 0; j < K; j++)
        tt[j] = 5 * in.period * j / (K - 1.0);
    hy_gamma_exact(&m, &in, 10, tt, K, yex, NULL, &err);
    printf("GSL odeiv2 on Example 3, gamma = 10, 5 periods, restarts at breakpoints: time to 1e-8 max error\n");
    printf("  %-8s %-9s %-10s %-10s %-8s %s\n", "stepper", "rtol", "error", "time_ms", "steps", "rhs_evals");
    for (const char *const *s = hy_ode_stepper_names(); *s; s++) {
        int done = 0;
        for (double tol = 1e-4; tol >= 1e-14 && !done; tol /= 10) {
            hy_ode_opts o = hy_ode_defaults();
            o.stepper = *s;
            o.rtol = tol;
            o.atol = tol * 1e-2;
            o.max_steps = 200000; /* first-order rk1imp would need millions of steps */
            o.work_limit = 0;     /* the cap and the 2 s stop decide here, as before */
            hy_ode_stats stats;
            double t_try = now();
            int rc = hy_ode_solve(&m, &in, 10, &o, tt, K, yg, &stats, &err);
            if (rc || now() - t_try > 2.0) /* hit the cap, or too slow to chase further */
                break;
            double e = 0;
            for (int j = 0; j < K; j++)
                e = fmax(e, fabs(yg[j] - yex[j]));
            if (e <= 1e-8) {
                for (int r = 0; r < 5; r++) {
                    double t0 = now();
                    hy_ode_solve(&m, &in, 10, &o, tt, K, yg, &stats, &err);
                    rep[r] = now() - t0;
                }
                printf("  %-8s %-9.0e %-10.2e %-10.3f %-8lu %lu\n", *s, tol, e, 1e3 * median(rep, 5), stats.steps, stats.nfev);
                done = 1;
            }
        }
        if (!done)
            printf("  %-8s did not reach 1e-8 within 2e5 steps and 2 s per run\n", *s);
    }
    free(t);
    free(yy);
    hy_steady_free(&st);
    hy_input_free(&in);
    return 0;
}
