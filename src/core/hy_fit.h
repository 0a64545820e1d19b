/* SPDX-License-Identifier: MIT */
/* hy_fit.h: bounded nonlinear least squares over a residual callback, with
 * several starts, standard errors and identifiability (issue 32 item 2's
 * engine; docs/FIT.md).
 *
 * Minimises sum_i r_i(theta)^2 with GSL's gsl_multifit_nlinear (trust region,
 * Levenberg-Marquardt with geodesic acceleration, SVD solver, More scaling).
 * Each parameter stays inside its bounds through a smooth map from an
 * unbounded coordinate u (logistic between two finite bounds, exp past one;
 * on log theta for log-scale parameters), so the solver never proposes a
 * value outside them.  Several starts (the caller's, then a scrambled Latin
 * hypercube over the bounds, deterministic for a seed) run on `jobs` threads;
 * the start with the least residual sum of squares wins (ties: the lower
 * index), so the result is the same for any number of threads.
 *
 *     static int resid(const double *th, double *r, void *ctx) { ... return 0; }
 *     hy_fit_param prm[2] = {{"a", 0.1, 10, HY_FIT_LOG}, {"b", -5, 5, HY_FIT_LINEAR}};
 *     double x0[2] = {1, 0};
 *     hy_fit_problem pb = {.n = n, .p = 2, .param = prm, .f = resid, .ctx = &data,
 *                          .start = x0, .data = y};
 *     hy_fit_opts o;  hy_fit_result res;  hy_error err;
 *     hy_fit_opts_default(&o);
 *     o.starts = 8; o.jobs = 2;
 *     if (hy_fit_run(&pb, &o, &res, &err)) fprintf(stderr, "%s\n", err.msg);
 *     else { hy_fit_report(stdout, &pb, &res); hy_fit_result_free(&res); }
 *
 * The residual callback works in the parameters' own units and may be called
 * from several threads at once with the same ctx (it must be reentrant).  A
 * non-zero return or a non-finite residual is a failed evaluation: a failed
 * trial step is rejected (the trust region shrinks), a start whose first
 * evaluation fails is reported and skipped; only when every start fails does
 * hy_fit_run fail.  hy_fit_run and hy_fit_evaluate turn GSL's aborting error
 * handler off (gsl_set_error_handler_off, for the process) and check every
 * GSL status.
 */
#ifndef HY_FIT_H
#define HY_FIT_H

#include "hy_cancel.h"
#include "hy_status.h"

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/* A parameter's scale: the design and the bound map work on theta or log theta. */
enum { HY_FIT_LINEAR = 0, HY_FIT_LOG = 1 };

/* Why a parameter is flagged unidentifiable (hy_fit_result.unident, bits). */
enum {
    HY_FIT_NULLDIR = 1, /* it carries a direction the Jacobian does not see:
                           a right singular vector v of the column-
                           equilibrated Jacobian whose relative singular
                           value is below rank_tol, with |v_j| >=
                           HY_FIT_SHARE x the largest |v| of it */
    HY_FIT_WIDE = 2     /* its standard error exceeds its range hi - lo */
};
/* rank_tol = max(HY_FIT_RANK_TOL, HY_FIT_RANK_ERR x jac_err / s_1): jac_err
 * is ||J(h) - J(h/4)||_F of the column-equilibrated Jacobian central-
 * differenced at h and h/4, for the first h = eps^(1/3) 4^-k (k = 0 ..
 * HY_FIT_LEVELS - 2) where it is below HY_FIT_RANK_TOL, else the k where it
 * is least (J(h) is the one used); s_1 is J's largest singular value.  A
 * singular value the Jacobian's own error could make (Weyl: an error E moves
 * them by at most ||E||_2 <= ||E||_F) is not information. */
#define HY_FIT_RANK_TOL 1e-8
#define HY_FIT_RANK_ERR 3.0
#define HY_FIT_LEVELS 5
#define HY_FIT_SHARE 0.3

/* The residual vector r (n values) at theta (p values, inside the bounds).
 * 0 on success; non-zero (or a non-finite r_i) means the model refused or
 * failed there. */
typedef int (*hy_fit_residual)(const double *theta, double *r, void *ctx);

typedef struct hy_fit_param {
    const char *name;
    double lo, hi; /* lo < hi; linear: may be -INFINITY / INFINITY; log: 0 <= lo,
                      hi may be INFINITY (lo = 0: no lower bound on log theta) */
    int scale;     /* HY_FIT_LINEAR or HY_FIT_LOG */
} hy_fit_param;

typedef struct hy_fit_problem {
    size_t n, p;               /* residuals, parameters (n > p for errors) */
    const hy_fit_param *param; /* p of them */
    hy_fit_residual f;
    void *ctx;
    const double *start; /* p values inside the bounds, or NULL (design only) */
    const double *data;  /* n measured values behind r, or NULL: only for the
                            normalised RMS and the fit index */
} hy_fit_problem;

/* What the progress callback hears: after each iteration of a start, and
 * once when it ends (done = 1, status HY_OK or the start's failure). */
typedef struct hy_fit_progress {
    size_t start, nstarts, iter, nevals;
    double rss;
    int done, status;
} hy_fit_progress;

typedef struct hy_fit_opts {
    size_t starts;   /* design points besides problem.start (default 0; with
                        no start given at least 1 is used) */
    uint64_t seed;   /* of the design (default 1) */
    int jobs;        /* threads (default 1); the result does not depend on it */
    double fd_step;  /* relative forward-difference step of the iterations'
                        Jacobian in u: h_j = fd_step max(|u_j|, 1)
                        (default sqrt(DBL_EPSILON) = 1.49e-8) */
    double xtol, gtol; /* gsl_multifit_nlinear_test's (1e-12, 1e-12), on
                        residuals divided by the start's initial RMS */
    double ftol;     /* stop when a step lowers the RSS by less than ftol of
                        itself (default 0: off) */
    size_t max_iter; /* iterations per start (default 200) */
    int accel;       /* geodesic acceleration (default 1) */
    void (*progress)(const hy_fit_progress *pr, void *ctx); /* NULL: silent;
                        called from the worker threads */
    void *progress_ctx;
    const hy_cancel *cancel; /* NULL: never; polled before each start and each
                        iteration: when it says stop, hy_fit_run returns
                        HY_ECANCEL (no result) after the iteration running */
} hy_fit_opts;

/* One start: where it began and ended and how. */
typedef struct hy_fit_start {
    double *x0, *x;  /* p values each (owned by the result) */
    int status;      /* HY_OK, or HY_ENUM: evaluation failed at x0 / while
                        differencing (msg says which) */
    int gsl_status;  /* 0 (a test passed), GSL_EMAXITER, GSL_ENOPROG */
    int info;        /* 1: small step (xtol), 2: small gradient (gtol),
                        3: small RSS change (ftol) */
    size_t iter, nevals, nfailed; /* nfailed: failed trial evaluations */
    double rss;      /* at x (NAN if the start failed) */
    char msg[160];
} hy_fit_start;

typedef struct hy_fit_result {
    size_t n, p, dof; /* dof = n - p */
    double *theta;    /* p: the best start's estimate */
    double *se;       /* p: sqrt(diag(s^2 (J^T J)^-1)), s^2 = rss/dof; NAN for
                         a parameter flagged HY_FIT_NULLDIR */
    double *ci_lo, *ci_hi; /* p: theta -+ t(0.975, dof) se */
    double *corr;     /* p x p, row-major; NAN in a NULLDIR row or column */
    int *unident;     /* p: 0, or HY_FIT_NULLDIR | HY_FIT_WIDE bits */
    double *sv;       /* p: singular values of the column-equilibrated J, descending */
    double *resid;    /* n: r at theta */
    double rss, s2, rms, nrms, max_abs, fit_index, cond, t975;
    double jac_err, rank_tol; /* the Jacobian's estimated error and the
                                 relative rank tolerance it gave (above) */
    double jac_step;          /* the relative difference step J was taken at */
    size_t best, nstarts, nfailed; /* best start, starts run, starts failed */
    size_t iter, nevals;           /* the best start's iterations; evaluations
                                      of all starts and the statistics */
    double seconds;                /* wall time of hy_fit_run */
    hy_fit_start *start;           /* nstarts records */
} hy_fit_result;

/* Sets o to the defaults above (o NULL: nothing done). */
void hy_fit_opts_default(hy_fit_opts *o);

/* Fits pb.  On success res holds the estimate and statistics (release with
 * hy_fit_result_free) and HY_OK is returned.  HY_EINVAL: a bad problem or
 * option (bounds, start outside them, design over infinite bounds); HY_ENUM:
 * every start failed (res is zeroed and needs no free; the message quotes
 * the first start's reason); HY_ECANCEL: o->cancel said stop (res zeroed);
 * HY_ENOMEM.  pb, o and res must not be NULL (HY_EINVAL; res, when given, is
 * zeroed), nor pb->param and pb->f; pb->start and pb->data may be NULL (as
 * said there); a tolerance that is not finite is refused (HY_EINVAL). */
int hy_fit_run(const hy_fit_problem *pb, const hy_fit_opts *o, hy_fit_result *res, hy_error *err);

/* The statistics of hy_fit_run at a given theta, without fitting (res->start
 * empty, nstarts 0).  Errors as hy_fit_run; HY_ENUM if an evaluation fails.
 * pb, theta and res must not be NULL (HY_EINVAL). */
int hy_fit_evaluate(const hy_fit_problem *pb, const double *theta, hy_fit_result *res, hy_error *err);

/* Releases what a successful hy_fit_run / hy_fit_evaluate allocated; res is
 * zeroed (res may be NULL: nothing done). */
void hy_fit_result_free(hy_fit_result *res);

/* npts points (row-major, npts x p) of a scrambled Latin hypercube over the
 * bounds (on log theta for log parameters), deterministic for seed: in each
 * coordinate, one point in each of npts equal strata, at a uniform position
 * in it, strata permuted independently.  HY_EINVAL on an infinite bound, and
 * when param (p > 0) or x (p and npts > 0) is NULL or npts x p values do not
 * fit in memory. */
int hy_fit_design(size_t p, const hy_fit_param *param, size_t npts, uint64_t seed, double *x, hy_error *err);

/* The bound map of one parameter: theta from the unbounded u (hy_fit_theta),
 * and back (hy_fit_u)
 * (a theta on a finite bound maps to the u of a point 1e-12 of the range
 * inside it).  q NULL: NaN. */
double hy_fit_theta(const hy_fit_param *q, double u);
double hy_fit_u(const hy_fit_param *q, double theta);

/* Prints the estimates, errors, intervals, flags, correlations |r| > 0.95,
 * condition number and fit statistics as a table.  f, pb (with its param) and
 * res (a result of a successful call) must not be NULL: else nothing is
 * printed. */
void hy_fit_report(FILE *f, const hy_fit_problem *pb, const hy_fit_result *res);

#ifdef __cplusplus
}
#endif

#endif
