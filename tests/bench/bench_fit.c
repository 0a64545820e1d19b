/* SPDX-License-Identifier: MIT */
/* bench_fit.c [cheap N | boucwen K]: do hy_fit's standard errors describe
 * the estimates' scatter?  The same problem fitted under N (K) independent
 * noise draws: for each parameter the standard deviation of the estimates
 * against the root-mean-square of the printed standard errors.
 *
 *   cheap N (default 1000): the damped oscillation of tests/fit/
 *     test_synth.c (200 samples, sigma 0.05, five parameters); passes when
 *     every ratio is within 30 %.  The sample standard deviation of N
 *     estimates has a relative standard error of 1/sqrt(2 (N - 1)): 10 % at
 *     N = 50, where 30 % is 3 of them and one of five parameters (c, seeds
 *     1000..1049) came out at 1.34; at N = 1000 (2 s) every ratio is within
 *     6 % (docs/FIT.md).
 *   boucwen K (default 10): the Bouc-Wen identification of hy_bwfit.c on the
 *     reduced record of tests/boucwen/test_fit.c (1024 samples a period, the
 *     multisine of seed 1 every time, noise seeds 101.., seven parameters);
 *     K is what a few minutes allow, so the bound is 3 sampling standard
 *     errors, 3 / sqrt(2 (K - 1)) (71 % for K = 10), and the ratios are
 *     printed for a reader to judge.
 * Exit status 1 when a ratio is outside its bound. */
#include "hy_bwfit.h"
#include "hy_signal.h"

#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define NS 200
typedef struct osc {
    double t[NS], y[NS];
} osc;

static double model(const double *th, double t) { return th[0] * exp(-th[1] * t) * cos(th[2] * t + th[3]) + th[4]; }

static int resid(const double *th, double *r, void *ctx)
{
    const osc *d = ctx;
    for (size_t i = 0; i < NS; i++)
        r[i] = model(th, d->t[i]) - d->y[i];
    return 0;
}

/* Accumulates estimates and SE; prints and judges the ratios. */
typedef struct tally {
    size_t p, k;
    double sum[8], sum2[8], se2[8];
} tally;

static void tally_add(tally *t, const double *theta, const double *se)
{
    for (size_t j = 0; j < t->p; j++) {
        t->sum[j] += theta[j];
        t->sum2[j] += theta[j] * theta[j];
        t->se2[j] += se[j] * se[j];
    }
    t->k++;
}

static int tally_judge(const tally *t, const char *const *names, double bound)
{
    int bad = 0;
    printf("%-12s %14s %14s %8s\n", "parameter", "scatter (sd)", "rms of SE", "ratio");
    for (size_t j = 0; j < t->p; j++) {
        double k = (double)t->k, mean = t->sum[j] / k;
        double sd = sqrt(fmax(0, (t->sum2[j] - k * mean * mean) / (k - 1))), se = sqrt(t->se2[j] / k);
        double ratio = se / sd;
        bad |= !(fabs(ratio - 1) <= bound);
        printf("%-12s %14.4g %14.4g %8.3f%s\n", names[j], sd, se, ratio, fabs(ratio - 1) <= bound ? "" : "  OUTSIDE");
    }
    printf("%zu fits; bound |SE/sd - 1| <= %.0f %%: %s\n", t->k, 100 * bound, bad ? "FAIL" : "pass");
    return bad;
}

static int cheap(size_t N)
{
    static const double truth[5] = {2.5, 0.7, 6.0, 0.4, -0.3}, x0[5] = {1.5, 1.0, 5.0, 0.0, 0.0};
    static const hy_fit_param prm[5] = {{"A", 0.1, 100, HY_FIT_LOG}, {"k", 0.01, 10, HY_FIT_LOG},
                                        {"w", 1, 20, HY_FIT_LINEAR},  {"phi", -3, 3, HY_FIT_LINEAR},
                                        {"c", -5, 5, HY_FIT_LINEAR}};
    const char *names[5] = {"A", "k", "w", "phi", "c"};
    tally t = {.p = 5};
    printf("== SE against scatter: damped oscillation, 200 samples, sigma 0.05, %zu noise seeds\n", N);
    for (size_t s = 0; s < N; s++) {
        osc d;
        hy_rng rng;
        hy_rng_seed(&rng, 1000 + s);
        for (size_t i = 0; i < NS; i++) {
            d.t[i] = 4.0 * (double)i / NS;
            d.y[i] = model(truth, d.t[i]) + 0.05 * hy_rng_normal(&rng);
        }
        hy_fit_problem pb = {NS, 5, prm, resid, &d, x0, d.y};
        hy_fit_opts o;
        hy_fit_opts_default(&o);
        hy_fit_result res;
        hy_error err = {0};
        if (hy_fit_run(&pb, &o, &res, &err)) {
            printf("seed %zu: %s\n", s, err.msg);
            return 1;
        }
        tally_add(&t, res.theta, res.se);
        hy_fit_result_free(&res);
    }
    return tally_judge(&t, names, 0.30);
}

static int boucwen(size_t K)
{
    hy_bwfit_opts o;
    hy_bwfit_opts_default(&o);
    o.n = 1024;
    o.fit.jobs = 2;
    hy_boucwen_params truth;
    hy_boucwen_params_default(&truth);
    hy_fit_param prm[8];
    size_t p = hy_bwfit_params(&o, prm, NULL, NULL);
    const char *names[8];
    for (size_t j = 0; j < p; j++)
        names[j] = prm[j].name;
    tally t = {.p = p};
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    printf("== SE against scatter: Bouc-Wen identification, 1024 samples, noise 8e-6 m, %zu noise seeds\n", K);
    for (size_t s = 0; s < K; s++) {
        o.noise_seed = 101 + s;
        hy_bwfit_train tr;
        hy_fit_result res;
        hy_error err = {0};
        if (hy_bwfit_make_train(&o, &truth, &tr, &err) || hy_bwfit_run(&o, &tr, NULL, &res, &err)) {
            printf("noise seed %zu: %s\n", 101 + s, err.msg);
            return 1;
        }
        tally_add(&t, res.theta, res.se);
        printf("noise seed %zu: %zu evaluations, %.1f s\n", 101 + s, res.nevals, res.seconds);
        fflush(stdout);
        hy_fit_result_free(&res);
        hy_bwfit_train_free(&tr);
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    int bad = tally_judge(&t, names, 3 / sqrt(2.0 * (double)(K - 1)));
    printf("%.0f s for %zu Bouc-Wen fits\n", (double)(t1.tv_sec - t0.tv_sec), K);
    return bad;
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    const char *what = argc > 1 ? argv[1] : "cheap";
    long k = argc > 2 ? atol(argv[2]) : 0;
    if (!strcmp(what, "cheap"))
        return cheap(k >= 3 ? (size_t)k : 1000);
    if (!strcmp(what, "boucwen"))
        return boucwen(k >= 3 ? (size_t)k : 10);
    fprintf(stderr, "usage: bench_fit [cheap N | boucwen K]\n");
    return 2;
}
