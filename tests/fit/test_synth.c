/* SPDX-License-Identifier: MIT */
/* test_synth.c: hy_fit on synthetic truths: Gaussian noise (estimates within
 * 3 standard errors), no noise (1e-8 relative), a product of two parameters
 * (flagged unidentifiable), a model that refuses half of the starts (skipped,
 * not fatal), the same result for 1 and 2 threads, the bound map, refusals. */
#include "hy_fit.h"
#include "hy_signal.h"
#include "../core/tutil.h"

#include <gsl/gsl_errno.h>
#include <stdlib.h>

#define N 200

/* y = A exp(-k t) cos(w t + phi) + c on t in [0, 4): a damped oscillation,
 * parameters of both scales, one negative. */
typedef struct data {
    double t[N], y[N];
    double fail_above; /* refuse A above this (INFINITY: never) */
    int product;       /* 1: the amplitude is theta[0] * theta[4] */
} data;

static const double truth[5] = {2.5, 0.7, 6.0, 0.4, -0.3};
static const hy_fit_param prm[5] = {
    {"A", 0.1, 100, HY_FIT_LOG},     {"k", 0.01, 10, HY_FIT_LOG}, {"w", 1, 20, HY_FIT_LINEAR},
    {"phi", -3, 3, HY_FIT_LINEAR},   {"c", -5, 5, HY_FIT_LINEAR},
};

static double model(const double *th, double t, int product)
{
    double amp = product ? th[0] * th[4] : th[0];
    return amp * exp(-th[1] * t) * cos(th[2] * t + th[3]) + (product ? 0 : th[4]);
}

static int resid(const double *th, double *r, void *ctx)
{
    const data *d = ctx;
    if (th[0] > d->fail_above)
        return 1;
    for (size_t i = 0; i < N; i++)
        r[i] = model(th, d->t[i], d->product) - d->y[i];
    return 0;
}

static void make(data *d, const double *th, double sigma, uint64_t seed, int product)
{
    hy_rng rng;
    hy_rng_seed(&rng, seed);
    d->fail_above = INFINITY;
    d->product = product;
    for (size_t i = 0; i < N; i++) {
        d->t[i] = 4.0 * (double)i / N;
        d->y[i] = model(th, d->t[i], product) + sigma * hy_rng_normal(&rng);
    }
}

/* A start 40-60 % away from the truth, inside the bounds. */
static const double start[5] = {1.5, 1.0, 5.0, 0.0, 0.0};

static int fit(data *d, const double *x0, size_t starts, int jobs, hy_fit_result *res, hy_error *err)
{
    hy_fit_problem pb = {N, 5, prm, resid, d, x0, d->y};
    hy_fit_opts o;
    hy_fit_opts_default(&o);
    o.starts = starts;
    o.jobs = jobs;
    o.seed = 7;
    return hy_fit_run(&pb, &o, res, err);
}

/* sigma = 0.05 (the signal's amplitude is 2.5): with a correct covariance an
 * estimate is 3 SE off with probability 0.27 %; the seeds are fixed, so the
 * test is deterministic; a wrong s^2 or Jacobian scale by a factor 3 fails it. */
static void noisy(void)
{
    const uint64_t seeds[] = {1, 2, 3, 4, 5};
    double worst = 0;
    for (size_t s = 0; s < 5; s++) {
        data d;
        make(&d, truth, 0.05, seeds[s], 0);
        hy_fit_result res;
        hy_error err = {0};
        int rc = fit(&d, start, 0, 1, &res, &err);
        CHECK(rc == 0, "noisy seed %zu: %s", s, err.msg);
        if (rc)
            continue;
        for (size_t j = 0; j < 5; j++) {
            double z = fabs(res.theta[j] - truth[j]) / res.se[j];
            worst = fmax(worst, z);
            CHECK(z <= 3, "noisy seed %zu: %s = %.6g, truth %.6g, se %.3g (%.2f SE)", s, prm[j].name,
                  res.theta[j], truth[j], res.se[j], z);
            CHECK(res.ci_lo[j] < res.theta[j] && res.theta[j] < res.ci_hi[j], "CI around the estimate");
        }
        /* the residual RMS estimates sigma: within 15 % for 195 dof (its
           relative standard deviation is 1/sqrt(2 x 195) = 5 %) */
        CHECK(fabs(sqrt(res.s2) / 0.05 - 1) < 0.15, "s = %.4g for sigma 0.05", sqrt(res.s2));
        CHECK(res.fit_index > 90 && res.fit_index < 100, "fit index %.3f", res.fit_index);
        hy_fit_result_free(&res);
    }
    printf("noisy (sigma 0.05, 5 seeds): worst |estimate - truth| = %.2f SE\n", worst);
}

/* No noise: the minimum is the truth; LM with xtol 1e-12 gets there to
 * ~1e-10, so 1e-8 relative is the bound with margin. */
static void noise_free(void)
{
    data d;
    make(&d, truth, 0, 1, 0);
    hy_fit_result res;
    hy_error err = {0};
    int rc = fit(&d, start, 0, 1, &res, &err);
    CHECK(rc == 0, "noise-free: %s", err.msg);
    if (rc)
        return;
    double worst = 0;
    for (size_t j = 0; j < 5; j++) {
        double e = fabs(res.theta[j] / truth[j] - 1);
        worst = fmax(worst, e);
        CHECK(e <= 1e-8, "noise-free: %s = %.17g, truth %.17g (rel %.2g)", prm[j].name, res.theta[j], truth[j], e);
    }
    CHECK(res.rms < 1e-9, "noise-free RMS %.3g", res.rms);
    printf("noise-free: worst relative error %.2e, %zu iterations, %zu evaluations\n", worst, res.iter, res.nevals);
    hy_fit_result_free(&res);
}

/* A and c enter only as their product: both flagged, with no standard
 * error; k, w and phi stay identified with finite errors. */
static void unidentifiable(void)
{
    data d;
    double th[5] = {2.5, 0.7, 6.0, 0.4, 1.3};
    make(&d, th, 0.05, 3, 1);
    hy_fit_param q[5];
    memcpy(q, prm, sizeof q);
    q[4] = (hy_fit_param){"c", 0.1, 10, HY_FIT_LOG};
    double x0[5] = {1.5, 1.0, 5.0, 0.0, 1.0};
    hy_fit_problem pb = {N, 5, q, resid, &d, x0, d.y};
    hy_fit_opts o;
    hy_fit_opts_default(&o);
    hy_fit_result res;
    hy_error err = {0};
    int rc = hy_fit_run(&pb, &o, &res, &err);
    CHECK(rc == 0, "product: %s", err.msg);
    if (rc)
        return;
    CHECK(res.unident[0] & HY_FIT_NULLDIR, "A not flagged (%d)", res.unident[0]);
    CHECK(res.unident[4] & HY_FIT_NULLDIR, "c not flagged (%d)", res.unident[4]);
    CHECK(isnan(res.se[0]) && isnan(res.se[4]), "no standard error for A and c");
    for (size_t j = 1; j < 4; j++)
        CHECK(res.unident[j] == 0 && isfinite(res.se[j]) && fabs(res.theta[j] - th[j]) <= 3 * res.se[j],
              "%s: flag %d, %.6g +- %.3g (truth %.6g)", q[j].name, res.unident[j], res.theta[j], res.se[j], th[j]);
    CHECK(fabs(res.theta[0] * res.theta[4] / (th[0] * th[4]) - 1) < 0.02, "the product A c = %.6g, truth %.6g",
          res.theta[0] * res.theta[4], th[0] * th[4]);
    CHECK(res.sv[4] / res.sv[0] < HY_FIT_RANK_TOL, "smallest relative singular value %.3g", res.sv[4] / res.sv[0]);
    printf("product A c: flagged, relative singular value %.2e, condition %.3g\n", res.sv[4] / res.sv[0], res.cond);
    hy_fit_result_free(&res);
}

/* A > 6 refused: the design's starts there fail at once and are reported;
 * the fit goes on with the others. */
static void failing_starts(void)
{
    data d;
    make(&d, truth, 0.05, 1, 0);
    d.fail_above = 6;
    hy_fit_result res;
    hy_error err = {0};
    int rc = fit(&d, NULL, 12, 2, &res, &err);
    CHECK(rc == 0, "failing starts: %s", err.msg);
    if (rc)
        return;
    size_t expect = 0;
    for (size_t s = 0; s < res.nstarts; s++) {
        int bad = res.start[s].x0[0] > 6;
        expect += bad;
        CHECK(bad == (res.start[s].status != HY_OK), "start %zu (A = %g): status %d", s, res.start[s].x0[0],
              res.start[s].status);
        if (bad)
            CHECK(strstr(res.start[s].msg, "failed at the start") != NULL, "start %zu's message: %s", s,
                  res.start[s].msg);
    }
    CHECK(res.nfailed == expect && expect >= 3 && expect < res.nstarts, "%zu of %zu starts failed (expected %zu)",
          res.nfailed, res.nstarts, expect);
    CHECK(fabs(res.theta[0] - truth[0]) <= 3 * res.se[0], "A = %.6g +- %.3g", res.theta[0], res.se[0]);
    printf("failing starts: %zu of %zu refused and skipped; best start %zu\n", res.nfailed, res.nstarts, res.best);
    hy_fit_result_free(&res);
    /* every start refused: HY_ENUM with the reason, nothing to free */
    d.fail_above = 0;
    rc = fit(&d, NULL, 3, 1, &res, &err);
    CHECK_MSG(rc, err, HY_ENUM, "all 3 starts failed");
}

/* The same bits for jobs = 1 and jobs = 2 (and 3: more threads than cores),
 * for several starts and for one. */
static void determinism(void)
{
    data d;
    make(&d, truth, 0.05, 4, 0);
    hy_fit_result a, b;
    hy_error err = {0};
    int ra = fit(&d, start, 7, 1, &a, &err);
    for (int jobs = 2; jobs <= 3 && !ra; jobs++) {
        int rb = fit(&d, start, 7, jobs, &b, &err);
        CHECK(rb == 0, "jobs %d: %s", jobs, err.msg);
        if (rb)
            break;
        CHECK(!memcmp(a.theta, b.theta, 5 * sizeof *a.theta) && !memcmp(a.se, b.se, 5 * sizeof *a.se) &&
                  a.best == b.best && a.nevals == b.nevals && a.rss == b.rss,
              "jobs 1 and %d differ", jobs);
        for (size_t s = 0; s < a.nstarts; s++)
            CHECK(!memcmp(a.start[s].x, b.start[s].x, 5 * sizeof(double)) && a.start[s].nevals == b.start[s].nevals,
                  "start %zu differs between jobs 1 and %d", s, jobs);
        hy_fit_result_free(&b);
    }
    CHECK(ra == 0, "jobs 1: %s", err.msg);
    if (!ra)
        hy_fit_result_free(&a);
    /* one start: the spare threads difference the Jacobian's columns */
    ra = fit(&d, start, 0, 1, &a, &err);
    int rb = ra ? -1 : fit(&d, start, 0, 3, &b, &err);
    CHECK(ra == 0 && rb == 0, "one start: %s", err.msg);
    if (!ra && !rb)
        CHECK(!memcmp(a.theta, b.theta, 5 * sizeof *a.theta) && !memcmp(a.se, b.se, 5 * sizeof *a.se) &&
                  a.nevals == b.nevals && a.iter == b.iter,
              "one start: jobs 1 and 3 differ");
    if (!ra)
        hy_fit_result_free(&a);
    if (!rb)
        hy_fit_result_free(&b);
}

/* The map keeps every value inside its bounds and inverts; an optimum past
 * a bound ends at the bound. */
static void bounds(void)
{
    const hy_fit_param q[] = {{"l", -2, 3, HY_FIT_LINEAR}, {"g", 1e-3, 1e3, HY_FIT_LOG},
                              {"h", 0, INFINITY, HY_FIT_LOG}, {"o", -INFINITY, 4, HY_FIT_LINEAR},
                              {"f", -INFINITY, INFINITY, HY_FIT_LINEAR}};
    const double v[] = {0.7, 5.0, 2e-7, -30, 12};
    for (size_t j = 0; j < 5; j++) {
        double u = hy_fit_u(&q[j], v[j]), back = hy_fit_theta(&q[j], u);
        CHECK(fabs(back - v[j]) <= 1e-12 * fmax(fabs(v[j]), 1), "%s: %.17g -> u %.17g -> %.17g", q[j].name, v[j], u,
              back);
        for (double uu = -800; uu <= 800; uu += 40) {
            double t = hy_fit_theta(&q[j], uu);
            CHECK(t >= q[j].lo && t <= q[j].hi, "%s: theta(%g) = %g outside the bounds", q[j].name, uu, t);
        }
    }
    /* k's bounds [0.01, 0.5] exclude its truth 0.7: the estimate ends inside, near 0.5 */
    data d;
    make(&d, truth, 0.0, 1, 0);
    hy_fit_param qq[5];
    memcpy(qq, prm, sizeof qq);
    qq[1].hi = 0.5;
    double x0[5] = {2, 0.3, 6, 0.4, -0.3};
    hy_fit_problem pb = {N, 5, qq, resid, &d, x0, d.y};
    hy_fit_opts o;
    hy_fit_opts_default(&o);
    hy_fit_result res;
    hy_error err = {0};
    int rc = hy_fit_run(&pb, &o, &res, &err);
    CHECK(rc == 0, "bounded: %s", err.msg);
    if (!rc) {
        CHECK(res.theta[1] <= 0.5 && res.theta[1] > 0.49, "k = %.9g within (0.49, 0.5]", res.theta[1]);
        hy_fit_result_free(&res);
    }
}

static void refusals(void)
{
    data d;
    make(&d, truth, 0.05, 1, 0);
    hy_fit_param q[5];
    hy_fit_result res;
    hy_error err = {0};
    hy_fit_problem pb = {N, 5, q, resid, &d, start, d.y};
    hy_fit_opts o;
    hy_fit_opts_default(&o);
    memcpy(q, prm, sizeof q);
    q[2].lo = 30;
    CHECK_MSG(hy_fit_run(&pb, &o, &res, &err), err, HY_EINVAL, "need lo < hi");
    memcpy(q, prm, sizeof q);
    q[0].lo = -1;
    CHECK_MSG(hy_fit_run(&pb, &o, &res, &err), err, HY_EINVAL, "log-scale parameter needs lo >= 0");
    memcpy(q, prm, sizeof q);
    q[3].hi = -1;
    CHECK_MSG(hy_fit_run(&pb, &o, &res, &err), err, HY_EINVAL, "start 0 is outside");
    memcpy(q, prm, sizeof q);
    q[4].hi = INFINITY;
    o.starts = 2;
    CHECK_MSG(hy_fit_run(&pb, &o, &res, &err), err, HY_EINVAL, "needs finite bounds");
    pb.n = 4;
    CHECK_MSG(hy_fit_run(&pb, &o, &res, &err), err, HY_EINVAL, "cannot determine 5 parameters");
}

/* The design: one point per stratum in every coordinate, within the bounds,
 * the same for a seed and different for another. */
static void design(void)
{
    double a[10 * 5], b[10 * 5], c[10 * 5];
    hy_error err = {0};
    CHECK(hy_fit_design(5, prm, 10, 3, a, &err) == 0, "design: %s", err.msg);
    hy_fit_design(5, prm, 10, 3, b, &err);
    hy_fit_design(5, prm, 10, 4, c, &err);
    CHECK(!memcmp(a, b, sizeof a) && memcmp(a, c, sizeof a), "the design is a function of its seed");
    for (size_t j = 0; j < 5; j++) {
        int seen[10] = {0};
        double sl = prm[j].scale == HY_FIT_LOG ? log(prm[j].lo) : prm[j].lo;
        double sh = prm[j].scale == HY_FIT_LOG ? log(prm[j].hi) : prm[j].hi;
        for (size_t i = 0; i < 10; i++) {
            double s = prm[j].scale == HY_FIT_LOG ? log(a[i * 5 + j]) : a[i * 5 + j];
            int k = (int)floor((s - sl) / (sh - sl) * 10);
            CHECK(k >= 0 && k < 10, "%s: point %zu outside the bounds", prm[j].name, i);
            if (k >= 0 && k < 10)
                seen[k]++;
        }
        for (int k = 0; k < 10; k++)
            CHECK(seen[k] == 1, "%s: stratum %d holds %d points", prm[j].name, k, seen[k]);
    }
}

int main(void)
{
    gsl_set_error_handler_off();
    noisy();
    noise_free();
    unidentifiable();
    failing_starts();
    determinism();
    bounds();
    refusals();
    design();
    return tu_finish("fit-synth");
}
