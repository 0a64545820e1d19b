/* SPDX-License-Identifier: MIT */
/* model_friction.c: Dahl, LuGre (seed 000, Eqs. 1-3) and the Example-1
 * system (16) in the model table; their numerics are src/core (hy_model,
 * hy_gamma, hy_ode, hy_limit, hy_loops); their stages (load, work estimate,
 * compute: the plan of γ solves, the steady state and loops, one function per
 * series kind) and table entries are this file. */
#include "scene_model.h"
#include "scene_run.h"

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hy_cost.h"
#include "hy_gamma.h"
#include "hy_ode.h"
#include "hy_os.h"
#include "scene_verify.h"

int hy_scene_run_build_model(hy_scene_run *r, hy_error *err)
{
    static const char *const keys[] = {"sigma0", "sigma1", "sigma2", "fc", "fs", "vs", "beta", "rho", "tau", "x0", NULL};
    const hy_decl_model *d = &r->doc.model;
    hy_model *m = &r->model;
    if (r->mtype == &hy_scene_model_dahl)
        hy_model_dahl_init(m, d->rho, d->fc);
    else if (r->mtype == &hy_scene_model_dahl_filter)
        hy_model_dahl_filter_init(m, d->rho, d->fc, d->tau);
    else {
        hy_model_lugre_init(m, d->sigma0, d->sigma1, d->fc, d->fs, d->vs, d->beta);
        m->sigma2 = d->sigma2;
    }
    m->x0 = d->x0;
    if (hy_model_validate(m, err))
        return hy_scene_located(&d->h, keys, err);
    return HY_OK;
}

/* ---- planning -------------------------------------------------------- */

typedef struct gamma_solve {
    double gamma;
    double *y;         /* on the shared grid */
    double err;        /* against the exact solution, or NaN */
    const char *ref;
    char refbuf[224];
    int exact;         /* solved by the exact solver */
    double seconds;
} gamma_solve;

typedef struct plan {
    double t0, t1;     /* the time span of every t-grid */
    size_t npts;       /* grid points over [t0, t1] */
    double *t;         /* the grid */
    long cycles;
    size_t per_period; /* points per period */
    gamma_solve *solves;
    size_t nsolves;
    int verbose;
} plan;

/* Appends a line to r->plan when the plan is logged (p->verbose): the
 * formatting is a good part of a table-only sweep point's time. */
static void plan_line(const plan *p, hy_scene_run *r, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void plan_line(const plan *p, hy_scene_run *r, const char *fmt, ...)
{
    if (!p->verbose)
        return;
    size_t len = strlen(r->plan);
    va_list ap;
    va_start(ap, fmt);
    if (len + 1 < sizeof r->plan)
        vsnprintf(r->plan + len, sizeof r->plan - len, fmt, ap);
    va_end(ap);
}

/* The GSL options of a solve at the scene's solver (rk8pd where it asks for
 * exact and exact does not apply); NULL when the exact solution serves. */
static const hy_ode_opts *solve_opts(const hy_scene_run *r, hy_ode_opts *o)
{
    const hy_decl_compute *dc = &r->doc.compute;
    const char *solver = hy_decl_enum_text(&dc->h, offsetof(hy_decl_compute, solver), dc->solver);
    if (!strcmp(solver, "exact") && hy_gamma_exact_applies(&r->model, &r->input))
        return NULL;
    *o = hy_ode_defaults();
    o->stepper = strcmp(solver, "exact") ? solver : "rk8pd";
    o->rtol = dc->rtol;
    o->atol = dc->atol;
    return o;
}

/* Refuses, at the solver's line, a scene whose GSL solves would pass their
 * work limit: every solve is checked before the first starts (issue 36
 * item 1: Fig. 4 at 7000 cycles computed for 15 s before its third γ was
 * refused). */
static int check_solves(const hy_scene_run *r, const plan *p, hy_error *err)
{
    const hy_decl_compute *dc = &r->doc.compute;
    for (size_t i = 0; i < p->nsolves; i++) {
        hy_ode_opts o;
        if (solve_opts(r, &o) && hy_ode_check_work(&r->model, &r->input, p->solves[i].gamma, &o, p->t1, err))
            return hy_decl_error(&dc->h, offsetof(hy_decl_compute, solver), err, HY_EINVAL, "gamma = %g: %s",
                                 p->solves[i].gamma, err->msg);
    }
    return HY_OK;
}

static int solve_gamma(hy_scene_run *r, plan *p, gamma_solve *g, hy_error *err)
{
    const hy_decl_compute *dc = &r->doc.compute;
    const char *solver = hy_decl_enum_text(&dc->h, offsetof(hy_decl_compute, solver), dc->solver);
    g->y = malloc(p->npts * sizeof *g->y);
    if (!g->y)
        return hy_error_set(err, HY_ENOMEM, "out of memory for %zu points", p->npts);
    g->err = NAN;
    double t0 = hy_now();
    int rc;
    int exact_ok = hy_gamma_exact_applies(&r->model, &r->input);
    if (!strcmp(solver, "exact") && exact_ok) {
        rc = hy_gamma_exact(&r->model, &r->input, g->gamma, p->t, p->npts, g->y, NULL, err);
        g->seconds = hy_now() - t0;
        g->exact = 1;
        if (!rc && !r->no_verify) /* measured against a long-double evaluation coded apart */
            hy_verify_gamma(r, g->gamma, p->t, g->y, p->npts, &g->err, g->refbuf, sizeof g->refbuf);
        else if (!rc)
            snprintf(g->refbuf, sizeof g->refbuf, "%s", HY_NOT_SAMPLED);
        g->ref = g->refbuf;
        return rc;
    } else {
        hy_ode_opts o;
        solve_opts(r, &o);
        o.cancel = hy_scene_run_cancel_hook(r);
        rc = hy_ode_solve(&r->model, &r->input, g->gamma, &o, p->t, p->npts, g->y, NULL, err);
        if (!rc && exact_ok && p->verbose && !r->no_verify) { /* the error, measured only when asked */
            double *ye = malloc(p->npts * sizeof *ye);
            if (ye && !hy_gamma_exact(&r->model, &r->input, g->gamma, p->t, p->npts, ye, NULL, err)) {
                g->err = 0;
                for (size_t i = 0; i < p->npts; i++)
                    g->err = fmax(g->err, fabs(ye[i] - g->y[i]));
                g->ref = "exact piecewise-exponential solution";
            }
            free(ye);
        } else if (!rc && exact_ok && p->verbose)
            g->ref = HY_NOT_SAMPLED;
        if (rc)
            return hy_decl_error(&dc->h, offsetof(hy_decl_compute, solver), err, rc, "gamma = %g: %s", g->gamma, err->msg);
    }
    g->seconds = hy_now() - t0;
    return rc;
}

static gamma_solve *find_solve(plan *p, double gamma)
{
    for (size_t i = 0; i < p->nsolves; i++)
        if (p->solves[i].gamma == gamma)
            return &p->solves[i];
    return NULL;
}

/* Decides the grid and the shared computations; solves each distinct γ once. */
void hy_scene_friction_needs(const hy_scene_doc *doc, int *need_steady, int *need_loops)
{
    *need_steady = *need_loops = 0;
    for (size_t i = 0; i < doc->nseries; i++) {
        int d = doc->series[i].data;
        if (d == HY_DATA_YSTAR || d == HY_DATA_YSTEADY || d == HY_DATA_YK)
            *need_steady = 1;
        if (d == HY_DATA_MINOR || d == HY_DATA_MAJOR)
            *need_steady = *need_loops = 1;
    }
    for (size_t i = 0; i < doc->nannotation; i++)
        if (doc->annotation[i].text && hy_scene_text_has_placeholder(doc->annotation[i].text))
            *need_steady = *need_loops = 1;
}

static int make_plan(hy_scene_run *r, plan *p, hy_error *err)
{
    int grc = hy_scene_run_grid(r, &p->t0, &p->t1, &p->npts, &p->per_period, &p->cycles, err);
    if (grc)
        return grc;
    size_t ns = r->doc.nseries;
    p->solves = calloc(ns ? ns : 1, sizeof *p->solves);
    if (!p->solves)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    /* the time grid: for y_γ solves and for u and y* over the time span (the
       table-only path outside the error sample samples no curve) */
    int need_steady, need_loops, need_grid = 0;
    hy_scene_friction_needs(&r->doc, &need_steady, &need_loops);
    for (size_t i = 0; i < ns; i++) { /* data, gamma and k checked by load (check_friction_series) */
        const hy_decl_series *ds = &r->doc.series[i];
        int d = ds->data;
        if ((d == HY_DATA_INPUT || d == HY_DATA_YSTAR) && !(r->numbers_only && r->no_verify))
            need_grid = 1;
        if (d == HY_DATA_YGAMMA || d == HY_DATA_TRANSIENT) {
            if (!find_solve(p, ds->gamma))
                p->solves[p->nsolves++].gamma = ds->gamma;
            need_grid = 1;
        }
    }
    int crc = check_solves(r, p, err);
    if (crc)
        return crc;
    if (need_grid) {
        if (!(p->t = malloc(p->npts * sizeof *p->t)))
            return hy_error_set(err, HY_ENOMEM, "out of memory for %zu points", p->npts);
        for (size_t i = 0; i < p->npts; i++)
            p->t[i] = p->t0 + (p->t1 - p->t0) * (double)i / (double)(p->npts - 1);
    }
    if (need_steady) {
        double t0 = p->verbose ? hy_now() : 0; /* timed for the plan only (the sweep's every point: no clock) */
        static const char *const mkeys[] = {"sigma0", "sigma1", "sigma2", "fc", "fs", "vs", "beta", "rho", "tau", "x0", NULL};
        int rc = hy_steady_init(&r->steady, &r->model, &r->input, err);
        if (rc)
            return hy_scene_located(&r->doc.model.h, mkeys, err); /* at the key the message names, else at [model] */
        r->have_steady = 1;
        if (p->verbose)
            plan_line(p, r, "steady state y° (Theorem 2, fixed point of the period map): %.3f ms\n", 1e3 * (hy_now() - t0));
    }
    if (need_loops) {
        double t0 = p->verbose ? hy_now() : 0;
        int rc = hy_loops_find(&r->steady, &r->loops, err);
        if (rc)
            return rc;
        r->have_loops = 1;
        if (p->verbose)
            plan_line(p, r, "major and minor loops (rainflow pairing of ψ_u's extrema): %.3f ms\n", 1e3 * (hy_now() - t0));
    }
    for (size_t i = 0; i < p->nsolves; i++) {
        int rc = hy_scene_run_check_cancel(r, err);
        if (!rc)
            rc = solve_gamma(r, p, &p->solves[i], err);
        if (rc)
            return rc;
        char what[160];
        snprintf(what, sizeof what, " for gamma = %g over %zu points%s", p->solves[i].gamma, p->npts,
                 p->solves[i].exact ? " (exact)" : "");
        plan_line(p, r, "y_gamma solve: %.3f ms%s\n", 1e3 * p->solves[i].seconds, what);
    }
    if (!need_steady && !p->nsolves)
        plan_line(p, r, "analytic only: no steady state, no ODE solve\n");
    return HY_OK;
}

/* ---- series ---------------------------------------------------------- */

static double interp(const plan *p, const double *y, double t)
{
    double f = (t - p->t0) / (p->t1 - p->t0) * (double)(p->npts - 1);
    if (!(f > 0))
        return y[0];
    if (!(f < (double)(p->npts - 1))) /* before the cast: f may be any size */
        return y[p->npts - 1];
    size_t i = (size_t)f;
    double w = f - (double)i;
    return y[i] * (1 - w) + y[i + 1] * w;
}

/* y of the series at time t (ϱ for psi, minor, major; v for g) */
static double series_y(const hy_scene_run *r, const plan *p, const hy_run_series *se, double t)
{
    switch (se->data) {
    case HY_DATA_INPUT: return hy_input_u(&r->input, t);
    case HY_DATA_PSI: return hy_input_psi(&r->input, t);
    case HY_DATA_G: return hy_model_g(&r->model, t);
    case HY_DATA_YSTAR: return hy_ystar_at(&r->steady, r->model.x0, t);
    case HY_DATA_YSTEADY: return hy_steady_at(&r->steady, t);
    case HY_DATA_YK: return hy_ystar_k(&r->steady, r->model.x0, (double)se->k, fmod(t, r->input.period));
    case HY_DATA_MINOR:
    case HY_DATA_MAJOR: return hy_steady_at_rho(&r->steady, t);
    default: {
        gamma_solve *g = find_solve((plan *)p, se->gamma);
        return g ? interp(p, g->y, t) : NAN;
    }
    }
}

/* x of the series at parameter t: u in loop figures, else t itself */
static double series_x(const hy_scene_run *r, const hy_run_series *se, double t)
{
    if (r->figure_kind != FIG_LOOP)
        return t;
    if (se->data == HY_DATA_MINOR || se->data == HY_DATA_MAJOR || se->data == HY_DATA_PSI)
        return hy_input_psi(&r->input, t);
    return hy_input_u(&r->input, t);
}

/* Samples the series over [a, b] of its parameter with n points (numbers
 * only: y alone, which the error is measured on; x is NaN, no table holds it). */
static void sample(const hy_scene_run *r, const plan *p, hy_run_series *se, size_t off, size_t n, double a, double b)
{
    for (size_t i = 0; i < n; i++) {
        double t = n > 1 ? a + (b - a) * (double)i / (double)(n - 1) : a;
        se->x[off + i] = r->numbers_only ? NAN : series_x(r, se, t);
        se->y[off + i] = series_y(r, p, se, t);
    }
}

/* ---- drawn-only series (figure_only) -----------------------------------
 * A series that is drawn and never written as data need not hold every point
 * of its grid when that has more than HY_THIN_MIN: one drawn only as its
 * mark is evaluated at the mark; a loop (y° against ψ_u, data = minor or
 * major) is kept at the grid points that a polyline through them needs to
 * stay within tol of the full grid's.  Within a run of ψ_u, ψ is linear in ϱ
 * and y° = s g0 + (y_i - s g0) e^{-a (ϱ - ϱ_i)} is monotone and convex or
 * concave, so the chord over [ϱ, ϱ + Δ] is within
 * Δ² a² |y_i - s g0| e^{-a (ϱ - ϱ_i)} / 8 of the curve vertically (so also
 * perpendicularly, in any scaling of the axes).  The grid points on both
 * sides of every run's end are kept: the extremes of x and y are the full
 * grid's and no turn is cut.  Values are computed as sample() computes them
 * (same ϱ, same functions), so every point drawn is one the full grid has. */

static int thin_wanted(const hy_scene_run *r, double points)
{
    return r->figure_only && points > HY_THIN_MIN && !r->doc.figure.full_resolution;
}

/* Whether series se draws only its mark (style none, a marker, at). */
static int mark_only(const hy_run_series *se, double *at)
{
    const hy_decl_series *d = se->decl;
    *at = d->at;
    return d->style == HY_LINE_NONE && d->marker && hy_decl_got(&d->h, offsetof(hy_decl_series, at)) == HY_SCENE_SET;
}

/* The end of the run of ψ_u that ϱ = rho lies in, in rho's own units (past
 * rho: an end closer than rho's resolution counts as the next double). */
static double run_end(const hy_input *in, double rho, size_t *run, double *rmod)
{
    *run = hy_input_run_at(in, rho, rmod);
    double end = rho + (in->runs[*run].rho1 - *rmod);
    return end > rho ? end : nextafter(rho, INFINITY);
}

/* The extent of y° over [a, b] of ϱ: its extremes lie at the ends and at the
 * ends of runs (monotone within each). */
static double loop_y_extent(const hy_scene_run *r, double a, double b)
{
    double lo = hy_steady_at_rho(&r->steady, a), hi = lo, x = a, rm;
    size_t run;
    for (size_t n = 0; x < b && n < 4 * r->input.nruns + 4; n++) {
        double e = run_end(&r->input, x, &run, &rm);
        x = e < b ? e : b;
        double y = hy_steady_at_rho(&r->steady, x);
        lo = fmin(lo, y), hi = fmax(hi, y);
    }
    return hi - lo;
}

/* The chord tolerance of series se's thinned loop: HY_THIN_TOL of the
 * narrowest y window the scene can show (y°'s range over the period, ylim,
 * zoom_y, each minor loop's range when the inset follows it), in the units
 * of y° before series.yscale.  0: not thinned. */
static double thin_tol(const hy_scene_run *r, const hy_run_series *se)
{
    const hy_decl_figure *df = &r->doc.figure;
    double lo = r->steady.y_run[0], hi = lo, f = se->decl->yscale;
    for (size_t i = 1; i <= r->input.nruns; i++)
        lo = fmin(lo, r->steady.y_run[i]), hi = fmax(hi, r->steady.y_run[i]);
    double w = hi - lo;
    if (df->ylog) /* the bound is for a linear y axis */
        return 0;
    if (hy_decl_got(&df->h, offsetof(hy_decl_figure, ylim)) == HY_SCENE_SET && !df->ylim.is_auto)
        w = fmin(w, fabs(df->ylim.v[1] - df->ylim.v[0]) / fabs(f));
    if (hy_decl_got(&df->h, offsetof(hy_decl_figure, zoom_y)) == HY_SCENE_SET)
        w = fmin(w, fabs(df->zoom_y.v[1] - df->zoom_y.v[0]) / fabs(f));
    int follow = df->zoom_follow; /* nonzero: minor (the schema's none, minor) */
    for (size_t i = 0; follow && i < r->loops.nminor; i++)
        w = fmin(w, loop_y_extent(r, r->loops.minor[i].rho_start, r->loops.minor[i].rho_close));
    return w > 0 && isfinite(w) ? HY_THIN_TOL * w : 0;
}

/* The grid index after j (of per on [a, b]) that a chord from j reaches
 * within tol: at most the last grid point of j's run, one step past it. */
static size_t thin_next(const hy_scene_run *r, double a, double b, size_t per, size_t j, double tol)
{
    double h = (b - a) / (double)(per - 1), rho = a + (b - a) * (double)j / (double)(per - 1), rm;
    size_t i;
    double f = floor((run_end(&r->input, rho, &i, &rm) - a) / h);
    size_t jb = f < (double)(per - 1) ? (size_t)f : per - 1;
    if (jb <= j)
        return j + 1;
    const hy_run *run = &r->input.runs[i];
    double as = r->steady.a, D = fabs(r->steady.y_run[i] - run->sign * r->steady.g0);
    double c = as * as * D * exp(-as * (rm - run->rho0)); /* |y''| at ϱ, its largest ahead in the run */
    double k = c > 0 ? floor(sqrt(8 * tol / c) / h) : INFINITY;
    k = fmin(k, floor((double)(per - 1) / HY_THIN_SPAN)); /* candidates as dense as HY_THIN_SPAN's grid */
    if (!(k >= 1))
        return j + 1;
    return k >= (double)(jb - j) ? jb : j + (size_t)k;
}

/* The points thin_sample keeps on [a, b]. */
static size_t thin_count(const hy_scene_run *r, double a, double b, size_t per, double tol)
{
    size_t m = 1;
    for (size_t j = 0; j < per - 1; j = thin_next(r, a, b, per, j, tol))
        m++;
    return m;
}

/* Samples the loop series over [a, b] at the grid points (of per) that
 * thin_next keeps; their number. */
static size_t thin_sample(const hy_scene_run *r, const plan *p, hy_run_series *se, size_t off, size_t per, double a,
                          double b, double tol)
{
    size_t m = 0;
    for (size_t j = 0;; j = thin_next(r, a, b, per, j, tol)) {
        double t = a + (b - a) * (double)j / (double)(per - 1); /* as sample() */
        se->x[off + m] = series_x(r, se, t);
        se->y[off + m] = series_y(r, p, se, t);
        m++;
        if (j >= per - 1)
            return m;
    }
}

/* max |y_γ(t) - y*_u(t)| over the plan's points i0 .. i1-1 (the {NAME.dist}
 * placeholder), or NaN when the limit was not computed */
static double distance_to_limit(const hy_scene_run *r, const plan *p, const gamma_solve *g, size_t i0, size_t i1)
{
    if (!r->have_steady)
        return NAN;
    double d = 0;
    for (size_t i = i0; i < i1; i++)
        d = fmax(d, fabs(g->y[i] - hy_ystar_at(&r->steady, r->model.x0, p->t[i])));
    return d;
}

/* The solve's error and what it was measured against (copied: the solve's
 * buffer goes with the plan). */
static void copy_err(hy_run_series *se, const gamma_solve *g)
{
    se->err = g->err;
    se->err_ref = NULL;
    if (g->ref) {
        snprintf(se->err_note, sizeof se->err_note, "%s", g->ref);
        se->err_ref = se->err_note;
    }
}

/* The error of a series computed with no_verify: not measured, and said so. */
static void not_sampled(hy_run_series *se)
{
    se->err = NAN;
    se->err_ref = HY_NOT_SAMPLED; /* a literal: no formatting at the sweep's every point */
}

/* minor, major: y° against ψ_u over each loop's interval of ϱ (thinned where
 * drawn only), a gap between loops. */
static int series_loops(hy_scene_run *r, const plan *p, hy_run_series *se, hy_error *err)
{
    size_t per = p->per_period;
    double a[64], b[64];
    int k = hy_scene_loop_intervals(r, se->data == HY_DATA_MAJOR, a, b, 64), rc;
    if (k < 0)
        return hy_scene_too_narrow(r, err);
    size_t total = 0, full = (size_t)k * (per + 1);
    double tol = per > 1 && thin_wanted(r, (double)full) ? thin_tol(r, se) : 0;
    for (int i = 0; i < k; i++)
        total += tol > 0 ? thin_count(r, a[i], b[i], per, tol) + 1 : per + 1;
    if ((rc = hy_run_series_alloc(se, total ? total : 1, err)))
        return rc;
    size_t off = 0;
    for (int i = 0; i < k; i++) {
        size_t m = per;
        if (tol > 0)
            m = thin_sample(r, p, se, off, per, a[i], b[i], tol);
        else
            sample(r, p, se, off, per, a[i], b[i]);
        se->x[off + m] = se->y[off + m] = NAN; /* gap */
        off += m + 1;
    }
    se->n = total;
    se->grid_n = total < full ? full : 0;
    if (r->no_verify)
        not_sampled(se);
    else
        hy_verify_loops(r, se, a, b, k, per, total < full);
    return HY_OK;
}

/* g: the friction function over the figure's x range (±4 vs where auto). */
static int series_g(hy_scene_run *r, const plan *p, hy_run_series *se, hy_error *err)
{
    size_t per = p->per_period;
    double lim[2] = {r->doc.figure.xlim.v[0], r->doc.figure.xlim.v[1]};
    if (r->doc.figure.xlim.is_auto) {
        lim[0] = -4 * r->model.vs;
        lim[1] = 4 * r->model.vs;
    }
    int rc = hy_run_series_alloc(se, per + 1, err);
    if (!rc)
        sample(r, p, se, 0, per + 1, lim[0], lim[1]);
    return rc;
}

/* psi: ψ_u over one period of ϱ. */
static int series_psi(hy_scene_run *r, const plan *p, hy_run_series *se, hy_error *err)
{
    size_t per = p->per_period;
    int rc = hy_run_series_alloc(se, per + 1, err);
    if (!rc)
        sample(r, p, se, 0, per + 1, 0, r->input.rho_T);
    return rc;
}

/* An earlier series of r that series_period sampled as it samples se (the
 * same data, the same k for yk, all n points), or NULL. */
static const hy_run_series *same_period(const hy_scene_run *r, const hy_run_series *se, size_t n)
{
    for (const hy_run_series *o = r->series; o < se; o++)
        if (o->data == se->data && (se->data != HY_DATA_YK || o->k == se->k) && o->n == n && !o->grid_n && o->y)
            return o;
    return NULL;
}

/* se as a copy of o: its points and its error (the same expressions on the
 * same operands, so the same bits: Fig. 15's two markers share y° over the
 * period). */
static void copy_period(hy_run_series *se, const hy_run_series *o)
{
    memcpy(se->x, o->x, o->n * sizeof *se->x);
    memcpy(se->y, o->y, o->n * sizeof *se->y);
    se->err = o->err;
    memcpy(se->err_note, o->err_note, sizeof se->err_note);
    se->err_ref = o->err_ref == o->err_note ? se->err_note : o->err_ref;
}

/* ysteady, yk: one period (a series drawn as its mark only: evaluated there,
 * by series_mark; one sampled as an earlier one was: copied from it). */
static int series_period(hy_scene_run *r, const plan *p, hy_run_series *se, hy_error *err)
{
    size_t per = p->per_period;
    double T = r->input.period, mark_at = 0;
    if (thin_wanted(r, (double)per + 1) && mark_only(se, &mark_at) && mark_at >= 0 && mark_at < T) {
        se->grid_n = per + 1; /* drawn as its mark: evaluated there only */
        return HY_OK;
    }
    int rc = hy_run_series_alloc(se, per + 1, err);
    if (rc)
        return rc;
    const hy_run_series *o = same_period(r, se, per + 1);
    if (o) {
        copy_period(se, o);
        return HY_OK;
    }
    sample(r, p, se, 0, per + 1, 0, T);
    se->y[per] = se->data == HY_DATA_YSTEADY ? r->steady.y_run[r->input.nruns]
                                             : hy_ystar_k(&r->steady, r->model.x0, (double)se->k, T);
    if (r->no_verify)
        not_sampled(se);
    else
        hy_verify_time(r, se, NULL, se->y, per + 1);
    return HY_OK;
}

/* ygamma, transient in a loop figure: the last period is the steady state at
 * this γ, the rest the transient. */
static int series_gamma_loop(hy_scene_run *r, const plan *p, hy_run_series *se, hy_error *err)
{
    double T = r->input.period;
    gamma_solve *g = find_solve((plan *)p, se->gamma);
    double split = p->t1 - T;
    size_t i0 = 0, i1 = p->npts;
    for (size_t i = 0; i < p->npts; i++)
        if (p->t[i] < split - 1e-12 * T)
            i0 = i + 1;
    if (p->cycles > 1) {
        if (se->data == HY_DATA_YGAMMA)
            i0 = i0 ? i0 - 1 : 0;
        else {
            i1 = i0;
            i0 = 0;
        }
    } else
        i0 = 0;
    int rc = hy_run_series_alloc(se, i1 - i0, err);
    if (rc)
        return rc;
    for (size_t i = i0; i < i1; i++) {
        se->x[i - i0] = hy_input_u(&r->input, p->t[i]);
        se->y[i - i0] = g->y[i];
    }
    copy_err(se, g);
    se->dist = distance_to_limit(r, p, g, i0, i1);
    return HY_OK;
}

/* ygamma, transient over time: the solve on the grid. */
static int series_gamma_time(hy_scene_run *r, const plan *p, hy_run_series *se, hy_error *err)
{
    gamma_solve *g = find_solve((plan *)p, se->gamma);
    int rc = hy_run_series_alloc(se, p->npts, err);
    if (rc)
        return rc;
    memcpy(se->x, p->t, p->npts * sizeof *se->x);
    memcpy(se->y, g->y, p->npts * sizeof *se->y);
    copy_err(se, g);
    se->dist = distance_to_limit(r, p, g, 0, p->npts);
    return HY_OK;
}

/* input, ystar: over the time span's grid. */
static int series_grid(hy_scene_run *r, const plan *p, hy_run_series *se, hy_error *err)
{
    int rc = hy_run_series_alloc(se, p->npts, err);
    if (rc)
        return rc;
    for (size_t i = 0; i < p->npts; i++) {
        se->x[i] = series_x(r, se, p->t[i]);
        se->y[i] = series_y(r, p, se, p->t[i]);
    }
    if (se->data == HY_DATA_YSTAR && r->no_verify)
        not_sampled(se);
    else if (se->data == HY_DATA_YSTAR)
        hy_verify_time(r, se, p->t, se->y, p->npts);
    return HY_OK;
}

/* The series' mark at its 'at', where written (a series drawn as its mark
 * only: its one point measured). */
static void series_mark(hy_scene_run *r, const plan *p, hy_run_series *se)
{
    double at = se->decl->at;
    if (hy_decl_got(&se->decl->h, offsetof(hy_decl_series, at)) != HY_SCENE_SET)
        return;
    se->has_mark = 1;
    se->mark_x = series_x(r, se, at);
    se->mark_y = series_y(r, p, se, at);
    if (se->grid_n && !se->n && r->no_verify)
        not_sampled(se);
    else if (se->grid_n && !se->n) /* its one point measured */
        hy_verify_time(r, se, &at, &se->mark_y, 1);
}

/* One series of the plan, by its data kind. */
static int compute_series(hy_scene_run *r, plan *p, hy_run_series *se, hy_error *err)
{
    double t0 = p->verbose ? hy_now() : 0; /* se->seconds is for the plan's log only */
    int rc = HY_OK;
    se->err = NAN;
    se->err_ref = NULL;
    se->dist = NAN;
    se->grid_n = 0;
    if (se->data == HY_DATA_MEASURED || se->data == HY_DATA_MODELLED)
        return HY_OK; /* from the data, after the model's compute (scene_data.c) */
    /* numbers only: u, ψ and g are not sampled; the closed forms are, so that
       their error is measured (issue 11) and the same as with figures */
    if (r->numbers_only && (se->data == HY_DATA_INPUT || se->data == HY_DATA_PSI || se->data == HY_DATA_G))
        return HY_OK;
    /* numbers only, errors not measured: the closed forms are not sampled
       either (the table holds none of their points), markers are evaluated at
       their point only */
    int loop = se->data == HY_DATA_MINOR || se->data == HY_DATA_MAJOR;
    int closed = loop || se->data == HY_DATA_YSTEADY || se->data == HY_DATA_YK || se->data == HY_DATA_YSTAR;
    if (closed && r->numbers_only && r->no_verify) {
        double a[64], b[64];
        if (loop && hy_scene_loop_intervals(r, se->data == HY_DATA_MAJOR, a, b, 64) < 0)
            return hy_scene_too_narrow(r, err); /* refused as when sampled */
        not_sampled(se);
    } else
        switch (se->data) {
        case HY_DATA_MINOR:
        case HY_DATA_MAJOR: rc = series_loops(r, p, se, err); break;
        case HY_DATA_G: rc = series_g(r, p, se, err); break;
        case HY_DATA_PSI: rc = series_psi(r, p, se, err); break;
        case HY_DATA_YSTEADY:
        case HY_DATA_YK: rc = series_period(r, p, se, err); break;
        case HY_DATA_YGAMMA:
        case HY_DATA_TRANSIENT:
            rc = r->figure_kind == FIG_LOOP ? series_gamma_loop(r, p, se, err) : series_gamma_time(r, p, se, err);
            break;
        default: rc = series_grid(r, p, se, err); /* input, ystar over the time span */
        }
    if (rc)
        return rc;
    series_mark(r, p, se);
    se->seconds = p->verbose ? hy_now() - t0 : 0;
    return HY_OK;
}

/* Points of one series before computing: the grid, one period, or one period per loop. */
static double series_points(const hy_scene_run *r, int d, double npts, double per)
{
    switch (d) {
    case HY_DATA_MINOR:
    case HY_DATA_MAJOR: return (per + 1) * fmin(64.0, fmax(1.0, (double)r->input.nruns));
    case HY_DATA_G:
    case HY_DATA_PSI:
    case HY_DATA_YSTEADY:
    case HY_DATA_YK: return per + 1;
    default: return npts;
    }
}

/* The friction models' estimate: the grid points of every distinct gamma
 * solve plus the points of every series (docs/SCENES.md, "Work budget"). */
int hy_scene_friction_estimate(const hy_scene_run *r, double *work, char *what, size_t size, hy_error *err)
{
    const hy_decl_compute *dc = &r->doc.compute;
    size_t na = r->doc.nannotation;
    long pts = dc->points, cycles = dc->cycles;
    double T = r->input.period, periods = (double)cycles;
    if (hy_decl_got(&dc->h, offsetof(hy_decl_compute, tspan)) == HY_SCENE_SET)
        periods = (dc->tspan.v[1] - dc->tspan.v[0]) / T;
    double npts = (double)pts * fmax(1.0, periods) + 1, pointsum = 0, *gam = NULL;
    size_t ns = r->doc.nseries, ng = 0;
    if (ns && !(gam = malloc(ns * sizeof *gam)))
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    for (size_t i = 0; i < ns; i++) {
        const hy_decl_series *ds = &r->doc.series[i];
        int d = HY_DATA_INPUT;
        double g = ds->gamma;
        hy_scene_series_data(ds, &d);
        pointsum += series_points(r, d, npts, (double)pts);
        if ((d == HY_DATA_YGAMMA || d == HY_DATA_TRANSIENT) && hy_decl_got(&ds->h, offsetof(hy_decl_series, gamma)) >= 0) {
            size_t j = 0;
            while (j < ng && gam[j] != g)
                j++;
            if (j == ng)
                gam[ng++] = g;
        }
    }
    free(gam);
    *work = hy_cost(r->cost_counts, HY_COST_POINT, (double)ng * npts + pointsum) +
            hy_cost(r->cost_counts, HY_COST_ANNOTATION, (double)na);
    if (what && size)
        snprintf(what, size, "%zu series, %zu distinct gamma solves over %.0f points (%ld per period, %g periods), "
                 "%zu annotations", ns, ng, npts, pts, fmax(1.0, periods), na);
    return HY_OK;
}

int hy_scene_friction_compute(hy_scene_run *r, FILE *log, hy_error *err)
{
    double t_start = hy_now();
    plan p;
    memset(&p, 0, sizeof p);
    p.verbose = log != NULL;
    int rc = hy_scene_run_series_new(r, err);
    size_t ns = r->nseries;
    for (size_t i = 0; i < ns && !rc; i++)
        rc = hy_scene_check_series_kind(r, &r->series[i], err);
    if (!rc)
        rc = make_plan(r, &p, err);
    for (size_t i = 0; i < ns && !rc; i++)
        if (!(rc = hy_scene_run_check_cancel(r, err)))
            rc = compute_series(r, &p, &r->series[i], err);
    r->seconds_compute = hy_now() - t_start;
    if (!rc && log) {
        fprintf(log, "%s: plan\n%s", r->path, r->plan);
        for (size_t i = 0; i < ns; i++) {
            const hy_run_series *se = &r->series[i];
            if (!hy_scene_series_log(se, log))
                continue;
            if (se->grid_n)
                fprintf(log, " (drawn: %s of the grid's %zu)", se->n ? "the points its curvature needs" : "its mark only",
                        se->grid_n);
            if (se->err_ref && isnan(se->err))
                fprintf(log, "  error %s", se->err_ref);
            else if (se->err_ref)
                fprintf(log, "  error %.3g vs %s", se->err, se->err_ref);
            else if (se->data == HY_DATA_YGAMMA || se->data == HY_DATA_TRANSIENT)
                fprintf(log, "  error not measured (no exact solution for this model and input)");
            fputc('\n', log);
        }
        fprintf(log, "  compute total %.3f ms (work estimate %.3g of the budget %.3g)\n", 1e3 * r->seconds_compute, r->work,
                r->budget > 0 ? r->budget : HY_SCENE_WORK_DEFAULT);
    }
    for (size_t i = 0; i < p.nsolves; i++)
        free(p.solves[i].y);
    free(p.solves);
    free(p.t);
    return rc;
}

/* What a Dahl or LuGre series draws: a data it has, and a y_gamma (ygamma,
 * transient) names its gamma (found by compute's plan before issue 22). */
static int check_friction_series(const hy_scene_run *r, hy_error *err)
{
    for (size_t i = 0; i < r->doc.nseries; i++) {
        const hy_decl_series *se = &r->doc.series[i];
        if (hy_decl_got(&se->h, offsetof(hy_decl_series, data)) < 0)
            return hy_decl_error(&se->h, HY_DECL_HEAD, err, HY_EINVAL, "series '%s' needs 'data = ...' (%s)", se->h.name,
                                 "input, psi, g, ystar, ysteady, ygamma, yk, transient, minor, major");
        if ((se->data == HY_DATA_YGAMMA || se->data == HY_DATA_TRANSIENT) &&
            hy_decl_got(&se->h, offsetof(hy_decl_series, gamma)) < 0)
            return hy_decl_error(&se->h, offsetof(hy_decl_series, data), err, HY_EINVAL,
                                 "series '%s' (data = %s) needs 'gamma'", se->h.name, hy_scene_data_name(se->data));
    }
    return HY_OK;
}

int hy_scene_friction_load(hy_scene_run *r, hy_error *err)
{
    int rc = check_friction_series(r, err); /* what the model does not accept: refused before */
    if (!rc)
        rc = hy_scene_run_build_model(r, err);
    if (!rc)
        rc = hy_scene_run_build_input(r, err);
    return rc;
}


#define FRICTION_CAPS (HY_CAP_STEADY | HY_CAP_YSTAR | HY_CAP_ENERGY | HY_CAP_EXACT_STEP | HY_CAP_GSL)

static const char *const output_only[] = {"output", NULL};
static const char *const dahl_keys[] = {"rho", "fc", "x0", NULL};
static const char *const lugre_keys[] = {"sigma0", "sigma1", "sigma2", "fc", "fs", "vs", "beta", "x0", NULL};
static const char *const filter_keys[] = {"rho", "fc", "tau", "x0", NULL};

const hy_scene_model hy_scene_model_dahl = {
    "dahl", dahl_keys, output_only, NULL, NULL, FRICTION_CAPS | HY_CAP_CLOSED_MINOR | HY_CAP_RATE_INDEPENDENT,
    "the bristle state z (y = Fc w)", hy_scene_friction_load, hy_scene_friction_estimate, hy_scene_friction_compute,
    NULL, 0, NULL, NULL, NULL, HY_INPUT_OTHERS, HY_DATA_PATH | 1u << HY_DATA_G, HY_COST_POINT};

const hy_scene_model hy_scene_model_lugre = {
    "lugre", lugre_keys, output_only, NULL, NULL, FRICTION_CAPS | HY_CAP_CLOSED_MINOR,
    "the bristle deflection z", hy_scene_friction_load, hy_scene_friction_estimate, hy_scene_friction_compute,
    NULL, 0, NULL, NULL, NULL, HY_INPUT_OTHERS, HY_DATA_PATH | 1u << HY_DATA_G, HY_COST_POINT};

const hy_scene_model hy_scene_model_dahl_filter = {
    "dahl-filter", filter_keys, output_only, NULL, NULL, FRICTION_CAPS,
    "the Dahl state and the filter output", hy_scene_friction_load, hy_scene_friction_estimate,
    hy_scene_friction_compute, NULL, 0, NULL, NULL, NULL, HY_INPUT_OTHERS, HY_DATA_PATH | 1u << HY_DATA_G, HY_COST_POINT};
