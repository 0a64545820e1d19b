/* SPDX-License-Identifier: MIT */
/* hy_fit.c: bounded multi-start nonlinear least squares (GSL multifit_nlinear,
 * Levenberg-Marquardt with geodesic acceleration) and the statistics at the
 * optimum: s^2 (J^T J)^-1 from a central-difference Jacobian in theta, its
 * SVD for the condition number and the unidentifiable directions (issue 32
 * item 2; docs/FIT.md). */
#include "hy_fit.h"

#include "hy_args.h"

#include "hy_signal.h"

#include <gsl/gsl_blas.h>
#include <gsl/gsl_cdf.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <float.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define FAIL_RESID 1e100 /* a failed trial evaluation: every residual this (rejected) */
#define EDGE 1e-12       /* a theta on a finite bound starts this fraction inside */

/* ---- the bound map ------------------------------------------------------ */

/* The bounds in the working coordinate s (theta, or log theta). */
static void s_bounds(const hy_fit_param *q, double *sl, double *sh)
{
    if (q->scale == HY_FIT_LOG) {
        *sl = q->lo > 0 ? log(q->lo) : -INFINITY;
        *sh = isfinite(q->hi) ? log(q->hi) : INFINITY;
    } else {
        *sl = q->lo;
        *sh = q->hi;
    }
}

double hy_fit_theta(const hy_fit_param *q, double u)
{
    double sl, sh, s;
    if (!q)
        return NAN;
    s_bounds(q, &sl, &sh);
    if (isfinite(sl) && isfinite(sh))
        s = sl + (sh - sl) / (1 + exp(-u));
    else if (isfinite(sl))
        s = sl + exp(u);
    else if (isfinite(sh))
        s = sh - exp(u);
    else
        s = u;
    if (s < sl) /* rounding at the edges */
        s = sl;
    if (s > sh)
        s = sh;
    return q->scale == HY_FIT_LOG ? exp(s) : s;
}

double hy_fit_u(const hy_fit_param *q, double theta)
{
    if (!q)
        return NAN;
    double sl, sh, s = q->scale == HY_FIT_LOG ? log(theta) : theta;
    s_bounds(q, &sl, &sh);
    if (isfinite(sl) && isfinite(sh)) {
        double f = (s - sl) / (sh - sl);
        f = f < EDGE ? EDGE : f > 1 - EDGE ? 1 - EDGE : f;
        return log(f / (1 - f));
    }
    double w = EDGE * (isfinite(s) ? fmax(fabs(s), 1) : 1);
    if (isfinite(sl))
        return log(fmax(s - sl, w));
    if (isfinite(sh))
        return log(fmax(sh - s, w));
    return s;
}

/* ---- checks ------------------------------------------------------------- */

static int check_param(const hy_fit_param *q, size_t j, hy_error *err)
{
    const char *nm = q->name ? q->name : "?";
    if (isnan(q->lo) || isnan(q->hi) || !(q->lo < q->hi))
        return hy_error_set(err, HY_EINVAL, "parameter %zu (%s): bounds [%g, %g] need lo < hi", j, nm, q->lo, q->hi);
    if (q->scale != HY_FIT_LINEAR && q->scale != HY_FIT_LOG)
        return hy_error_set(err, HY_EINVAL, "parameter %zu (%s): scale %d is neither linear nor log", j, nm, q->scale);
    if (q->scale == HY_FIT_LOG && !(q->lo >= 0))
        return hy_error_set(err, HY_EINVAL, "parameter %zu (%s): a log-scale parameter needs lo >= 0, got %g", j, nm,
                            q->lo);
    return HY_OK;
}

static int check_problem(const hy_fit_problem *pb, hy_error *err)
{
    if (!pb || !pb->f || !pb->param || pb->p == 0 || pb->n == 0)
        return hy_error_set(err, HY_EINVAL, "fit: the problem needs n >= 1 residuals, p >= 1 parameters and f");
    if (pb->n < pb->p)
        return hy_error_set(err, HY_EINVAL, "fit: %zu residuals cannot determine %zu parameters", pb->n, pb->p);
    for (size_t j = 0; j < pb->p; j++) {
        int rc = check_param(&pb->param[j], j, err);
        if (rc)
            return rc;
        double x = pb->start ? pb->start[j] : 0;
        const hy_fit_param *q = &pb->param[j];
        if (pb->start && !(x >= q->lo && x <= q->hi && (q->scale == HY_FIT_LINEAR || x > 0)))
            return hy_error_set(err, HY_EINVAL, "parameter %zu (%s): start %g is outside [%g, %g]", j,
                                q->name ? q->name : "?", x, q->lo, q->hi);
    }
    return HY_OK;
}

void hy_fit_opts_default(hy_fit_opts *o)
{
    if (!o)
        return;
    memset(o, 0, sizeof *o);
    o->seed = 1;
    o->jobs = 1;
    o->fd_step = sqrt(DBL_EPSILON);
    o->xtol = 1e-12;
    o->gtol = 1e-12;
    o->ftol = 0;
    o->max_iter = 200;
    o->accel = 1;
}

/* ---- the design --------------------------------------------------------- */

int hy_fit_design(size_t p, const hy_fit_param *param, size_t npts, uint64_t seed, double *x, hy_error *err)
{
    if (p && !param)
        return hy_error_set(err, HY_EINVAL, "%s: param must not be NULL (p is %zu)", __func__, p);
    if (p && npts && !x)
        return hy_error_set(err, HY_EINVAL, "%s: x must not be NULL (p and npts are not 0)", __func__);
    if (p && npts > SIZE_MAX / sizeof *x / p)
        return hy_error_set(err, HY_EINVAL, "%s: %zu x %zu values do not fit in memory", __func__, npts, p);
    for (size_t j = 0; j < p; j++) {
        int rc = check_param(&param[j], j, err);
        double sl, sh;
        s_bounds(&param[j], &sl, &sh);
        if (!rc && !(isfinite(sl) && isfinite(sh)))
            rc = hy_error_set(err, HY_EINVAL, "parameter %zu (%s): a design of starts needs finite bounds%s", j,
                              param[j].name ? param[j].name : "?", param[j].scale == HY_FIT_LOG ? " above 0" : "");
        if (rc)
            return rc;
    }
    size_t *perm = malloc((npts ? npts : 1) * sizeof *perm);
    if (!perm)
        return hy_error_set(err, HY_ENOMEM, "fit: out of memory for the design");
    hy_rng rng;
    hy_rng_seed(&rng, seed);
    for (size_t j = 0; j < p; j++) {
        for (size_t i = 0; i < npts; i++)
            perm[i] = i;
        for (size_t i = npts; i > 1; i--) { /* Fisher-Yates */
            size_t k = (size_t)(hy_rng_uniform(&rng) * (double)i);
            size_t t = perm[i - 1];
            perm[i - 1] = perm[k < i ? k : i - 1];
            perm[k < i ? k : i - 1] = t;
        }
        double sl, sh;
        s_bounds(&param[j], &sl, &sh);
        for (size_t i = 0; i < npts; i++) {
            double f = ((double)perm[i] + hy_rng_uniform(&rng)) / (double)npts;
            f = f < EDGE ? EDGE : f > 1 - EDGE ? 1 - EDGE : f;
            double s = sl + f * (sh - sl);
            x[i * p + j] = param[j].scale == HY_FIT_LOG ? exp(s) : s;
        }
    }
    free(perm);
    return HY_OK;
}

/* ---- one start ---------------------------------------------------------- */

typedef struct job {
    const hy_fit_problem *pb;
    const hy_fit_opts *o;
    size_t index, nstarts;
    double *theta;     /* p scratch */
    double scale;      /* residuals are divided by it (the start's initial RMS) */
    double *cache_u, *cache_r; /* the last successful evaluation (u, scaled r) */
    int cache_ok, last_failed;
    size_t col_jobs;   /* threads for the Jacobian's columns */
    size_t nevals, nfailed;
    hy_fit_start *rec;
} job;

/* r(theta(u)) / scale into r, theta (p scratch) the point; 0, or -1 when the
 * model failed (r then holds FAIL_RESID everywhere, so that a trust-region
 * step there is rejected).  No side effect on jb: columns run in parallel. */
static int eval_at(const job *jb, const double *u, double *theta, double *r)
{
    const hy_fit_problem *pb = jb->pb;
    for (size_t j = 0; j < pb->p; j++)
        theta[j] = hy_fit_theta(&pb->param[j], u[j]);
    int bad = pb->f(theta, r, pb->ctx) != 0;
    for (size_t i = 0; !bad && i < pb->n; i++)
        bad = !isfinite(r[i]);
    if (bad) {
        for (size_t i = 0; i < pb->n; i++)
            r[i] = FAIL_RESID;
        return -1;
    }
    for (size_t i = 0; i < pb->n; i++)
        r[i] /= jb->scale;
    return 0;
}

/* eval_at, counted, and remembered when it succeeds (gsl_df's r0). */
static int eval_u(job *jb, const double *u, double *r)
{
    jb->nevals++;
    if (eval_at(jb, u, jb->theta, r)) {
        jb->nfailed++;
        return -1;
    }
    memcpy(jb->cache_u, u, jb->pb->p * sizeof *u);
    memcpy(jb->cache_r, r, jb->pb->n * sizeof *r);
    jb->cache_ok = 1;
    return 0;
}

static int gsl_f(const gsl_vector *x, void *params, gsl_vector *f)
{
    job *jb = params;
    jb->last_failed = eval_u(jb, x->data, f->data) != 0;
    return GSL_SUCCESS; /* a failure is a huge residual: the step is rejected */
}

/* The forward-difference Jacobian's columns, shared by jb->col_jobs threads
 * (each column is the same arithmetic on any thread: the same bits). */
typedef struct columns {
    job *jb;
    const double *u, *r0;
    gsl_matrix *J;
    size_t next, nevals, nfailed;
    int rc;
    pthread_mutex_t mu;
} columns;

/* Column j: h_j = fd_step max(|u_j|, 1) forward, backward where the forward
 * point fails; -1 where both do. */
static int column(columns *cw, size_t j, double *u, double *theta, double *r1, size_t *nev, size_t *nfail)
{
    size_t n = cw->jb->pb->n;
    double uj = u[j], h = cw->jb->o->fd_step * fmax(fabs(uj), 1);
    volatile double up = uj + h; /* the step actually taken */
    h = up - uj;
    u[j] = up;
    int bad = eval_at(cw->jb, u, theta, r1);
    (*nev)++;
    if (bad) {
        (*nfail)++;
        u[j] = uj - h;
        h = -h;
        bad = eval_at(cw->jb, u, theta, r1);
        (*nev)++;
        *nfail += bad != 0;
    }
    u[j] = uj;
    for (size_t i = 0; !bad && i < n; i++)
        gsl_matrix_set(cw->J, i, j, (r1[i] - cw->r0[i]) / h);
    return bad ? -1 : 0;
}

static void *column_worker(void *arg)
{
    columns *cw = arg;
    size_t n = cw->jb->pb->n, p = cw->jb->pb->p, nev = 0, nfail = 0;
    double *u = malloc(p * sizeof *u), *theta = malloc(p * sizeof *theta), *r1 = malloc(n * sizeof *r1);
    int rc = u && theta && r1 ? GSL_SUCCESS : GSL_ENOMEM;
    if (u)
        memcpy(u, cw->u, p * sizeof *u);
    for (;;) {
        pthread_mutex_lock(&cw->mu);
        if (rc && !cw->rc)
            cw->rc = rc;
        size_t j = cw->rc ? p : cw->next++;
        pthread_mutex_unlock(&cw->mu);
        if (j >= p)
            break;
        if (column(cw, j, u, theta, r1, &nev, &nfail))
            rc = GSL_EBADFUNC;
    }
    pthread_mutex_lock(&cw->mu);
    cw->nevals += nev;
    cw->nfailed += nfail;
    pthread_mutex_unlock(&cw->mu);
    free(u);
    free(theta);
    free(r1);
    return NULL;
}

/* Forward differences in u (column); GSL_EBADFUNC where a column cannot be
 * evaluated on either side. */
static int gsl_df(const gsl_vector *x, void *params, gsl_matrix *J)
{
    job *jb = params;
    size_t n = jb->pb->n, p = jb->pb->p;
    double *r0 = malloc(n * sizeof *r0);
    if (!r0)
        return GSL_ENOMEM;
    if (jb->cache_ok && memcmp(jb->cache_u, x->data, p * sizeof *x->data) == 0)
        memcpy(r0, jb->cache_r, n * sizeof *r0);
    else if (eval_u(jb, x->data, r0)) {
        free(r0);
        snprintf(jb->rec->msg, sizeof jb->rec->msg, "the model failed at an accepted point");
        return GSL_EBADFUNC;
    }
    columns cw = {jb, x->data, r0, J, 0, 0, 0, GSL_SUCCESS, PTHREAD_MUTEX_INITIALIZER};
    size_t nt = jb->col_jobs < p ? jb->col_jobs : p, started = 0;
    pthread_t th[64];
    for (; started + 1 < nt && started < 64; started++)
        if (pthread_create(&th[started], NULL, column_worker, &cw))
            break; /* fewer threads: the same columns */
    column_worker(&cw);
    for (size_t t = 0; t < started; t++)
        pthread_join(th[t], NULL);
    jb->nevals += cw.nevals;
    jb->nfailed += cw.nfailed;
    free(r0);
    if (cw.rc == GSL_EBADFUNC)
        snprintf(jb->rec->msg, sizeof jb->rec->msg, "the model failed on both sides of a difference step");
    return cw.rc;
}

static double sumsq(const double *r, size_t n)
{
    double s = 0;
    for (size_t i = 0; i < n; i++)
        s += r[i] * r[i];
    return s;
}

static void report(job *jb, size_t iter, double rss, int done, int status)
{
    if (!jb->o->progress)
        return;
    hy_fit_progress pr = {jb->index, jb->nstarts, iter, jb->nevals, rss, done, status};
    jb->o->progress(&pr, jb->o->progress_ctx);
}

static void iter_cb(const size_t iter, void *params, const gsl_multifit_nlinear_workspace *w)
{
    job *jb = params;
    gsl_vector *f = gsl_multifit_nlinear_residual(w);
    double nrm = gsl_blas_dnrm2(f) * jb->scale;
    report(jb, iter, nrm * nrm, 0, HY_OK);
}

/* drive's status when o->cancel said stop (GSL's own are >= -2) */
#define FIT_STOPPED (-1000)

static int stopped(const hy_fit_opts *o)
{
    return o->cancel && o->cancel->fn && o->cancel->fn(o->cancel->ctx);
}

/* gsl_multifit_nlinear_driver's loop with the relative RSS test added:
 * iterate (one accepted step each) until GSL's xtol or gtol test passes
 * (info 1, 2), the RSS fell by less than ftol of itself in the last step
 * (info 3), no step can be found (GSL_ENOPROG) or max_iter steps were taken
 * (GSL_EMAXITER), or o->cancel says stop (FIT_STOPPED).  Returns 0 on the
 * tests, else that status. */
static int drive(job *jb, gsl_multifit_nlinear_workspace *w, int *info)
{
    const hy_fit_opts *o = jb->o;
    double prev = gsl_blas_dnrm2(gsl_multifit_nlinear_residual(w));
    iter_cb(0, jb, w);
    for (size_t it = 0; it < o->max_iter; it++) {
        if (stopped(o))
            return FIT_STOPPED;
        int st = gsl_multifit_nlinear_iterate(w);
        if (st)
            return st;
        iter_cb(it + 1, jb, w);
        double now = gsl_blas_dnrm2(gsl_multifit_nlinear_residual(w));
        st = gsl_multifit_nlinear_test(o->xtol, o->gtol, 0, info, w);
        if (st != GSL_CONTINUE)
            return st;
        if (o->ftol > 0 && prev * prev - now * now <= o->ftol * now * now) {
            *info = 3;
            return GSL_SUCCESS;
        }
        prev = now;
    }
    return GSL_EMAXITER;
}

/* The start's scale: its initial residual's RMS, evaluated in theta. */
static int start_scale(job *jb, double *r)
{
    const hy_fit_problem *pb = jb->pb;
    jb->nevals++;
    int bad = pb->f(jb->rec->x0, r, pb->ctx) != 0;
    for (size_t i = 0; !bad && i < pb->n; i++)
        bad = !isfinite(r[i]);
    if (bad) {
        jb->nfailed++;
        snprintf(jb->rec->msg, sizeof jb->rec->msg, "the model failed at the start");
        return -1;
    }
    double rms = sqrt(sumsq(r, pb->n) / (double)pb->n);
    jb->scale = rms > 0 && isfinite(rms) ? rms : 1;
    return 0;
}

/* The trust-region workspace for n residuals and p parameters (Levenberg-
 * Marquardt, with geodesic acceleration when o->accel); NULL when out of memory. */
static gsl_multifit_nlinear_workspace *new_workspace(const hy_fit_opts *o, size_t n, size_t p)
{
    gsl_multifit_nlinear_parameters prm = gsl_multifit_nlinear_default_parameters();
    prm.trs = o->accel ? gsl_multifit_nlinear_trs_lmaccel : gsl_multifit_nlinear_trs_lm;
    prm.solver = gsl_multifit_nlinear_solver_svd; /* robust where J loses rank */
    prm.scale = gsl_multifit_nlinear_scale_more;
    return gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &prm, n, p);
}

/* Records in jb->rec what the drive that returned st (and info) reached in w:
 * its status, iterations, message and, unless it failed or was stopped, the
 * optimum in theta and its residual sum of squares. */
static void record_result(job *jb, gsl_multifit_nlinear_workspace *w, int st, int info)
{
    const hy_fit_problem *pb = jb->pb;
    hy_fit_start *rec = jb->rec;
    rec->gsl_status = st;
    rec->info = info;
    rec->iter = gsl_multifit_nlinear_niter(w);
    if (st == FIT_STOPPED) {
        rec->status = HY_ECANCEL;
        snprintf(rec->msg, sizeof rec->msg, "stopped: the work is no longer wanted");
        return;
    }
    if (st && st != GSL_EMAXITER && st != GSL_ENOPROG) {
        if (!rec->msg[0])
            snprintf(rec->msg, sizeof rec->msg, "GSL: %s", gsl_strerror(st));
        return;
    }
    gsl_vector *u = gsl_multifit_nlinear_position(w);
    for (size_t j = 0; j < pb->p; j++)
        rec->x[j] = hy_fit_theta(&pb->param[j], gsl_vector_get(u, j));
    double nrm = gsl_blas_dnrm2(gsl_multifit_nlinear_residual(w)) * jb->scale;
    rec->rss = nrm * nrm;
    rec->status = HY_OK;
    if (st)
        snprintf(rec->msg, sizeof rec->msg, "%s", st == GSL_EMAXITER ? "stopped at the iteration limit"
                                                                     : "no further progress possible");
}

/* One start of the multi-start fit, from jb->rec->x0: its outcome, the
 * optimum or the reason there is none, in jb->rec (never fails otherwise). */
static void run_start(job *jb)
{
    const hy_fit_problem *pb = jb->pb;
    const hy_fit_opts *o = jb->o;
    size_t n = pb->n, p = pb->p;
    hy_fit_start *rec = jb->rec;
    rec->status = HY_ENUM;
    rec->rss = NAN;
    memcpy(rec->x, rec->x0, p * sizeof *rec->x);
    double *r = malloc(n * sizeof *r);
    jb->theta = malloc(p * sizeof *jb->theta);
    jb->cache_u = malloc(p * sizeof *jb->cache_u);
    jb->cache_r = malloc(n * sizeof *jb->cache_r);
    gsl_vector *u0 = gsl_vector_alloc(p);
    gsl_multifit_nlinear_workspace *w = NULL;
    if (!r || !jb->theta || !jb->cache_u || !jb->cache_r || !u0) {
        rec->status = HY_ENOMEM;
        snprintf(rec->msg, sizeof rec->msg, "out of memory");
        goto done;
    }
    if (stopped(o)) {
        rec->status = HY_ECANCEL;
        snprintf(rec->msg, sizeof rec->msg, "stopped: the work is no longer wanted");
        goto done;
    }
    if (start_scale(jb, r))
        goto done;
    gsl_multifit_nlinear_fdf fdf = {gsl_f, gsl_df, NULL, n, p, jb, 0, 0, 0};
    w = new_workspace(o, n, p);
    if (!w) {
        rec->status = HY_ENOMEM;
        snprintf(rec->msg, sizeof rec->msg, "out of memory for the GSL workspace");
        goto done;
    }
    for (size_t j = 0; j < p; j++)
        gsl_vector_set(u0, j, hy_fit_u(&pb->param[j], rec->x0[j]));
    int st = gsl_multifit_nlinear_init(u0, &fdf, w);
    if (st || jb->last_failed) {
        if (!rec->msg[0])
            snprintf(rec->msg, sizeof rec->msg, "the model failed at the start (%s)",
                     st ? gsl_strerror(st) : "mapped start");
        goto done;
    }
    int info = 0;
    st = drive(jb, w, &info);
    record_result(jb, w, st, info);
done:
    rec->nevals = jb->nevals;
    rec->nfailed = jb->nfailed;
    report(jb, rec->iter, rec->rss, 1, rec->status);
    gsl_multifit_nlinear_free(w);
    gsl_vector_free(u0);
    free(r);
    free(jb->theta);
    free(jb->cache_u);
    free(jb->cache_r);
}

/* ---- threads ------------------------------------------------------------ */

typedef struct pool {
    job *jobs;
    size_t njobs, next;
    pthread_mutex_t mu;
} pool;

static void *worker(void *arg)
{
    pool *pl = arg;
    for (;;) {
        pthread_mutex_lock(&pl->mu);
        size_t i = pl->next++;
        pthread_mutex_unlock(&pl->mu);
        if (i >= pl->njobs)
            return NULL;
        run_start(&pl->jobs[i]);
    }
}

static void run_all(pool *pl, int jobs)
{
    size_t nt = jobs > 1 ? (size_t)jobs : 1;
    if (nt > pl->njobs)
        nt = pl->njobs;
    pthread_t *th = nt > 1 ? calloc(nt - 1, sizeof *th) : NULL;
    size_t started = 0;
    for (size_t t = 0; th && t + 1 < nt; t++, started++)
        if (pthread_create(&th[t], NULL, worker, pl))
            break; /* fewer threads: the same results */
    worker(pl);
    for (size_t t = 0; t < started; t++)
        pthread_join(th[t], NULL);
    free(th);
}

/* ---- statistics at theta ------------------------------------------------ */

static void result_zero(hy_fit_result *res)
{
    memset(res, 0, sizeof *res);
}

void hy_fit_result_free(hy_fit_result *res)
{
    if (!res)
        return;
    free(res->theta); /* one block holds every p-sized array */
    free(res->resid);
    free(res->corr);
    free(res->unident);
    if (res->start)
        free(res->start[0].x0);
    free(res->start);
    result_zero(res);
}

static int result_alloc(hy_fit_result *res, size_t n, size_t p, hy_error *err)
{
    result_zero(res);
    res->n = n;
    res->p = p;
    res->theta = malloc(5 * p * sizeof *res->theta);
    res->resid = malloc(n * sizeof *res->resid);
    res->corr = malloc(p * p * sizeof *res->corr);
    res->unident = calloc(p, sizeof *res->unident);
    if (!res->theta || !res->resid || !res->corr || !res->unident) {
        hy_fit_result_free(res);
        return hy_error_set(err, HY_ENOMEM, "fit: out of memory for the result");
    }
    res->se = res->theta + p;
    res->ci_lo = res->theta + 2 * p;
    res->ci_hi = res->theta + 3 * p;
    res->sv = res->theta + 4 * p;
    return HY_OK;
}

/* Evaluates f at theta into r; 0 or -1 (failed or non-finite). */
static int eval_theta(const hy_fit_problem *pb, const double *theta, double *r, size_t *nevals)
{
    (*nevals)++;
    if (pb->f(theta, r, pb->ctx))
        return -1;
    for (size_t i = 0; i < pb->n; i++)
        if (!isfinite(r[i]))
            return -1;
    return 0;
}

/* Central differences in theta, h_j = step typ_j (typ_j = |theta_j|, or 1e-6
 * of the range, or 1, for theta_j = 0); one-sided (sqrt(eps) typ_j) where a
 * central point leaves the bounds.  J is n x p, row-major. */
static int jacobian_theta(const hy_fit_problem *pb, const double *theta, const double *r0, double step, double *J,
                          size_t *nevals, hy_error *err)
{
    size_t n = pb->n, p = pb->p;
    double *th = malloc(p * sizeof *th), *rp = malloc(n * sizeof *rp), *rm = malloc(n * sizeof *rm);
    int rc = th && rp && rm ? HY_OK : hy_error_set(err, HY_ENOMEM, "fit: out of memory for the Jacobian");
    if (!rc)
        memcpy(th, theta, p * sizeof *th);
    for (size_t j = 0; !rc && j < p; j++) {
        const hy_fit_param *q = &pb->param[j];
        double t = theta[j], range = q->hi - q->lo;
        double typ = t != 0 ? fabs(t) : isfinite(range) ? 1e-6 * range : 1;
        double h = step * typ;
        int central = t - h >= q->lo && t + h <= q->hi && (q->scale == HY_FIT_LINEAR || t - h > 0);
        if (!central)
            h = sqrt(DBL_EPSILON) * typ * (t + sqrt(DBL_EPSILON) * typ <= q->hi ? 1 : -1);
        volatile double tp = t + h, tm = t - h;
        th[j] = tp;
        int bad = eval_theta(pb, th, rp, nevals);
        if (!bad && central) {
            th[j] = tm;
            bad = eval_theta(pb, th, rm, nevals);
        }
        th[j] = t;
        if (bad) {
            rc = hy_error_set(err, HY_ENUM, "fit: the model failed beside the optimum (%s = %.17g) while "
                              "differencing", q->name ? q->name : "?", t);
            break;
        }
        for (size_t i = 0; i < n; i++)
            J[i * p + j] = central ? (rp[i] - rm[i]) / (tp - tm) : (rp[i] - r0[i]) / (tp - t);
    }
    free(th);
    free(rp);
    free(rm);
    return rc;
}

/* From J (n x p, row-major) and rss: SVD of the column-equilibrated J,
 * condition number, unidentifiable flags, covariance on the identified
 * directions, SE, CI, correlation. */
static int covariance(const hy_fit_problem *pb, const double *J, hy_fit_result *res, hy_error *err)
{
    size_t n = pb->n, p = pb->p;
    gsl_matrix *A = gsl_matrix_alloc(n, p), *V = gsl_matrix_alloc(p, p), *C = gsl_matrix_calloc(p, p);
    gsl_vector *S = gsl_vector_alloc(p), *wk = gsl_vector_alloc(p);
    double *D = malloc(p * sizeof *D);
    int rc = A && V && C && S && wk && D ? HY_OK : hy_error_set(err, HY_ENOMEM, "fit: out of memory for the SVD");
    for (size_t j = 0; !rc && j < p; j++) {
        double s = 0;
        for (size_t i = 0; i < n; i++)
            s += J[i * p + j] * J[i * p + j];
        D[j] = sqrt(s);
        for (size_t i = 0; i < n; i++)
            gsl_matrix_set(A, i, j, D[j] > 0 ? J[i * p + j] / D[j] : 0);
    }
    if (!rc && gsl_linalg_SV_decomp(A, V, S, wk))
        rc = hy_error_set(err, HY_ENUM, "fit: the SVD of the Jacobian failed");
    if (!rc) {
        double smax = gsl_vector_get(S, 0), smin = gsl_vector_get(S, p - 1);
        res->cond = smin > 0 ? smax / smin : INFINITY;
        /* Weyl: an error E moves each singular value by at most ||E||_2 <= ||E||_F */
        res->rank_tol = fmax(HY_FIT_RANK_TOL, HY_FIT_RANK_ERR * res->jac_err / smax);
        for (size_t k = 0; k < p; k++) {
            double sk = gsl_vector_get(S, k);
            res->sv[k] = sk;
            if (sk > res->rank_tol * smax) { /* identified: adds v v^T / s^2 */
                for (size_t a = 0; a < p; a++)
                    for (size_t b = 0; b < p; b++)
                        *gsl_matrix_ptr(C, a, b) += gsl_matrix_get(V, a, k) * gsl_matrix_get(V, b, k) / (sk * sk);
                continue;
            }
            double vmax = 0;
            for (size_t j = 0; j < p; j++)
                vmax = fmax(vmax, fabs(gsl_matrix_get(V, j, k)));
            for (size_t j = 0; j < p; j++)
                if (fabs(gsl_matrix_get(V, j, k)) >= HY_FIT_SHARE * vmax)
                    res->unident[j] |= HY_FIT_NULLDIR;
        }
        for (size_t j = 0; j < p; j++)
            if (D[j] == 0)
                res->unident[j] |= HY_FIT_NULLDIR;
        res->t975 = res->dof > 0 ? gsl_cdf_tdist_Pinv(0.975, (double)res->dof) : NAN;
        for (size_t a = 0; a < p; a++) {
            double cov = res->s2 * gsl_matrix_get(C, a, a) / (D[a] * D[a]);
            res->se[a] = res->unident[a] & HY_FIT_NULLDIR ? NAN : sqrt(cov);
            if (res->se[a] > pb->param[a].hi - pb->param[a].lo)
                res->unident[a] |= HY_FIT_WIDE;
            res->ci_lo[a] = res->theta[a] - res->t975 * res->se[a];
            res->ci_hi[a] = res->theta[a] + res->t975 * res->se[a];
        }
        for (size_t a = 0; a < p; a++)
            for (size_t b = 0; b < p; b++) {
                double cab = gsl_matrix_get(C, a, b), caa = gsl_matrix_get(C, a, a), cbb = gsl_matrix_get(C, b, b);
                int null = (res->unident[a] | res->unident[b]) & HY_FIT_NULLDIR;
                res->corr[a * p + b] = null ? NAN : a == b ? 1 : cab / sqrt(caa * cbb);
            }
    }
    gsl_matrix_free(A);
    gsl_matrix_free(V);
    gsl_matrix_free(C);
    gsl_vector_free(S);
    gsl_vector_free(wk);
    free(D);
    return rc;
}

/* Everything but the starts, at res->theta (set by the caller). */
static int statistics(const hy_fit_problem *pb, hy_fit_result *res, hy_error *err)
{
    size_t n = pb->n, p = pb->p;
    if (eval_theta(pb, res->theta, res->resid, &res->nevals))
        return hy_error_set(err, HY_ENUM, "fit: the model failed at the estimate");
    res->rss = sumsq(res->resid, n);
    res->dof = n - p;
    res->s2 = res->dof > 0 ? res->rss / (double)res->dof : NAN;
    res->rms = sqrt(res->rss / (double)n);
    res->max_abs = 0;
    for (size_t i = 0; i < n; i++)
        res->max_abs = fmax(res->max_abs, fabs(res->resid[i]));
    res->nrms = res->fit_index = NAN;
    if (pb->data) {
        double mean = 0, ss = 0;
        for (size_t i = 0; i < n; i++)
            mean += pb->data[i];
        mean /= (double)n;
        for (size_t i = 0; i < n; i++)
            ss += (pb->data[i] - mean) * (pb->data[i] - mean);
        res->nrms = res->rms / sqrt(ss / (double)n);
        res->fit_index = 100 * (1 - sqrt(res->rss) / sqrt(ss));
    }
    double *J = malloc(n * p * sizeof *J);
    if (!J)
        return hy_error_set(err, HY_ENOMEM, "fit: out of memory for the Jacobian");
    /* J at the steps h_k = eps^(1/3) 4^-k, k = 0, 1, ...: the difference of
       two neighbours estimates their error; the first pair that agrees to
       HY_FIT_RANK_TOL, else the best of HY_FIT_LEVELS, gives J (the larger
       step of the pair) and jac_err.  eps^(1/3) balances truncation and
       rounding for a smooth model (NIST's: the first pair agrees); a model
       only piecewise smooth in its parameters (a time-stepped one with |v|
       and sign(z)) has kinks that a step straddles now and then, less often
       the smaller the step (Bouc-Wen: 2e-3 at eps^(1/3), 1e-6 at 1/64 of it) */
    double *Jk[HY_FIT_LEVELS] = {J};
    int rc = HY_OK;
    size_t best = 0;
    res->jac_err = INFINITY;
    for (size_t k = 1; k < HY_FIT_LEVELS && !rc; k++)
        if (!(Jk[k] = malloc(n * p * sizeof *J)))
            rc = hy_error_set(err, HY_ENOMEM, "fit: out of memory for the Jacobian");
    if (!rc)
        rc = jacobian_theta(pb, res->theta, res->resid, cbrt(DBL_EPSILON), J, &res->nevals, err);
    for (size_t k = 1; k < HY_FIT_LEVELS && !rc; k++) {
        rc = jacobian_theta(pb, res->theta, res->resid, cbrt(DBL_EPSILON) * pow(0.25, (double)k), Jk[k],
                            &res->nevals, err);
        double e2 = 0; /* ||J_k-1 - J_k||_F with every column scaled to unit norm */
        for (size_t j = 0; !rc && j < p; j++) {
            double d = 0, s = 0;
            for (size_t i = 0; i < n; i++) {
                double a = Jk[k - 1][i * p + j], b = Jk[k][i * p + j];
                d += (a - b) * (a - b);
                s += a * a;
            }
            e2 += s > 0 ? d / s : 0;
        }
        if (!rc && sqrt(e2) < res->jac_err) {
            res->jac_err = sqrt(e2);
            best = k - 1;
        }
        if (res->jac_err <= HY_FIT_RANK_TOL)
            break;
    }
    if (!rc && best)
        memcpy(J, Jk[best], n * p * sizeof *J);
    res->jac_step = cbrt(DBL_EPSILON) * pow(0.25, (double)best);
    for (size_t k = 1; k < HY_FIT_LEVELS; k++)
        free(Jk[k]);
    if (!rc)
        rc = covariance(pb, J, res, err);
    free(J);
    return rc;
}

/* The statistics at res->theta and the wall time since t0; on failure res
 * is released. */
static int finish(const hy_fit_problem *pb, hy_fit_result *res, const struct timespec *t0, hy_error *err)
{
    struct timespec t1;
    int rc = statistics(pb, res, err);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    res->seconds = (double)(t1.tv_sec - t0->tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0->tv_nsec);
    if (rc)
        hy_fit_result_free(res);
    return rc;
}

int hy_fit_evaluate(const hy_fit_problem *pb, const double *theta, hy_fit_result *res, hy_error *err)
{
    struct timespec t0;
    gsl_set_error_handler_off(); /* every GSL status here is checked; none may abort */
    clock_gettime(CLOCK_MONOTONIC, &t0);
    HY_NONNULL(err, res);
    result_zero(res);
    HY_NONNULL(err, pb);
    HY_NONNULL(err, theta);
    int rc = check_problem(pb, err);
    if (!rc)
        rc = result_alloc(res, pb->n, pb->p, err);
    if (rc)
        return rc;
    memcpy(res->theta, theta, pb->p * sizeof *theta);
    return finish(pb, res, &t0, err);
}

/* ---- the fit ------------------------------------------------------------ */

/* res->start: nstarts records, x0 filled (the given start, then the design). */
static int starts_alloc(const hy_fit_problem *pb, const hy_fit_opts *o, hy_fit_result *res, hy_error *err)
{
    size_t p = pb->p, given = pb->start ? 1 : 0;
    size_t ndes = o->starts ? o->starts : given ? 0 : 1, ns = given + ndes;
    res->start = calloc(ns, sizeof *res->start);
    double *x = malloc(2 * ns * p * sizeof *x);
    if (!res->start || !x) {
        free(x);
        return hy_error_set(err, HY_ENOMEM, "fit: out of memory for %zu starts", ns);
    }
    res->nstarts = ns;
    for (size_t s = 0; s < ns; s++) {
        res->start[s].x0 = x + 2 * s * p;
        res->start[s].x = x + (2 * s + 1) * p;
    }
    if (given)
        memcpy(res->start[0].x0, pb->start, p * sizeof *x);
    if (!ndes)
        return HY_OK;
    double *d = malloc(ndes * p * sizeof *d);
    if (!d)
        return hy_error_set(err, HY_ENOMEM, "fit: out of memory for the design");
    int rc = hy_fit_design(p, pb->param, ndes, o->seed, d, err);
    for (size_t s = 0; !rc && s < ndes; s++)
        memcpy(res->start[given + s].x0, d + s * p, p * sizeof *d);
    free(d);
    return rc;
}

static int check_opts(const hy_fit_opts *o, hy_error *err)
{
    if (!(o->fd_step > 0 && o->fd_step < 0.1) || !(o->xtol >= 0) || !(o->gtol >= 0) || !(o->ftol >= 0) ||
        !isfinite(o->xtol) || !isfinite(o->gtol) || !isfinite(o->ftol) ||
        o->max_iter < 1 || o->jobs < 1)
        return hy_error_set(err, HY_EINVAL, "fit: options need 0 < fd_step < 0.1, tolerances >= 0, "
                            "max_iter >= 1 and jobs >= 1 (tolerances finite)");
    return HY_OK;
}

int hy_fit_run(const hy_fit_problem *pb, const hy_fit_opts *o, hy_fit_result *res, hy_error *err)
{
    struct timespec t0;
    gsl_set_error_handler_off(); /* before any thread starts: every GSL status is checked */
    clock_gettime(CLOCK_MONOTONIC, &t0);
    HY_NONNULL(err, res);
    result_zero(res);
    HY_NONNULL(err, pb);
    HY_NONNULL(err, o);
    int rc = check_problem(pb, err);
    if (!rc)
        rc = check_opts(o, err);
    if (!rc)
        rc = result_alloc(res, pb->n, pb->p, err);
    if (rc)
        return rc;
    rc = starts_alloc(pb, o, res, err);
    pool pl = {NULL, res->nstarts, 0, PTHREAD_MUTEX_INITIALIZER};
    if (!rc && !(pl.jobs = calloc(res->nstarts, sizeof *pl.jobs)))
        rc = hy_error_set(err, HY_ENOMEM, "fit: out of memory for the starts");
    if (rc) {
        hy_fit_result_free(res);
        return rc;
    }
    /* threads left over by the starts difference the Jacobian's columns */
    size_t col_jobs = (size_t)o->jobs > res->nstarts ? (size_t)o->jobs / res->nstarts : 1;
    for (size_t s = 0; s < res->nstarts; s++)
        pl.jobs[s] = (job){.pb = pb, .o = o, .index = s, .nstarts = res->nstarts, .rec = &res->start[s],
                           .col_jobs = col_jobs};
    run_all(&pl, o->jobs);
    free(pl.jobs);
    for (size_t s = 0; s < res->nstarts; s++)
        if (res->start[s].status == HY_ECANCEL || stopped(o)) {
            hy_fit_result_free(res);
            return hy_cancel_error(err);
        }
    size_t best = SIZE_MAX;
    for (size_t s = 0; s < res->nstarts; s++) {
        hy_fit_start *st = &res->start[s];
        res->nevals += st->nevals;
        if (st->status) {
            res->nfailed++;
            continue;
        }
        if (best == SIZE_MAX || st->rss < res->start[best].rss)
            best = s;
    }
    if (best == SIZE_MAX) {
        rc = hy_error_set(err, res->start[0].status == HY_ENOMEM ? HY_ENOMEM : HY_ENUM,
                          "fit: all %zu starts failed (start 0: %s)", res->nstarts, res->start[0].msg);
        hy_fit_result_free(res);
        return rc;
    }
    res->best = best;
    res->iter = res->start[best].iter;
    memcpy(res->theta, res->start[best].x, pb->p * sizeof *res->theta);
    return finish(pb, res, &t0, err);
}

/* ---- the table ---------------------------------------------------------- */

void hy_fit_report(FILE *f, const hy_fit_problem *pb, const hy_fit_result *res)
{
    if (!f || !pb || !pb->param || !res || !res->theta || !res->se || !res->unident)
        return;
    size_t p = res->p;
    fprintf(f, "%-12s %16s %12s %25s  %s\n", "parameter", "estimate", "std error", "95% interval", "");
    for (size_t j = 0; j < p; j++) {
        const char *nm = pb->param[j].name ? pb->param[j].name : "?";
        if (res->unident[j] & HY_FIT_NULLDIR)
            fprintf(f, "%-12s %16.9g %12s %25s  unidentifiable (the data do not determine it)\n", nm,
                    res->theta[j], "-", "-");
        else
            fprintf(f, "%-12s %16.9g %12.4g [%11.5g, %11.5g]  %s\n", nm, res->theta[j], res->se[j], res->ci_lo[j],
                    res->ci_hi[j], res->unident[j] & HY_FIT_WIDE ? "unidentifiable (error wider than its range)" : "");
    }
    int pairs = 0;
    for (size_t a = 0; a < p; a++)
        for (size_t b = a + 1; b < p; b++)
            if (fabs(res->corr[a * p + b]) > 0.95) {
                fprintf(f, "%s%s-%s %.4f", pairs++ ? ", " : "correlated |r| > 0.95: ", pb->param[a].name,
                        pb->param[b].name, res->corr[a * p + b]);
            }
    if (pairs)
        fputc('\n', f);
    fprintf(f, "condition number %.3g (column-equilibrated Jacobian; its estimated error %.2g, rank tolerance "
            "%.2g), %zu residuals, %zu degrees of freedom\n", res->cond, res->jac_err, res->rank_tol, res->n, res->dof);
    fprintf(f, "RSS %.6g, RMS %.6g, normalised RMS %.6g, max |error| %.6g, fit index %.4f %%\n", res->rss, res->rms,
            res->nrms, res->max_abs, res->fit_index);
    fprintf(f, "starts %zu (failed %zu, best %zu), iterations %zu, evaluations %zu, %.3f s\n", res->nstarts,
            res->nfailed, res->best, res->iter, res->nevals, res->seconds);
}
