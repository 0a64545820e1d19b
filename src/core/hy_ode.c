/* SPDX-License-Identifier: MIT */
/* hy_ode.c: GSL odeiv2 integration of Eq. (3) of seed 000 and system (16),
 * restarted at every breakpoint of u̇.
 * Kernels read whole: hy_ode_solve (the driver's loop over the pieces of u̇:
 * where it stops, restarts and counts periods reads best in one place). */
#include "hy_ode.h"

#include "hy_args.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <string.h>

#include "hy_gamma.h"
#include "hy_ode_steppers.h"

/* The steppers, by name, in the order every list shows them (HY_ODE_STEPPERS,
 * hy_ode.h: the table and the name list are generated from it). */
typedef struct stepper_entry {
    const char *name;
    const gsl_odeiv2_step_type *const *type;
    int kind, order; /* HY_ODE_EXPLICIT/IMPLICIT; a one-step implicit one's order */
} stepper_entry;

#define STEPPER_ENTRY(n, kind, order, place) {#n, &gsl_odeiv2_step_##n, kind, order},
static const stepper_entry steppers[] = {HY_ODE_STEPPERS(STEPPER_ENTRY)};
#define NSTEPPERS (sizeof steppers / sizeof steppers[0])

#define STEPPER_NAME(n, kind, order, place) #n,
static const char *const stepper_names[NSTEPPERS + 1] = {HY_ODE_STEPPERS(STEPPER_NAME) NULL};

const char *const *hy_ode_stepper_names(void) { return stepper_names; }

/* The table entry of the stepper called name, or NULL. */
static const stepper_entry *stepper_find(const char *name)
{
    for (size_t i = 0; name && i < NSTEPPERS; i++)
        if (strcmp(steppers[i].name, name) == 0)
            return &steppers[i];
    return NULL;
}

const gsl_odeiv2_step_type *hy_ode_step_type(const char *name)
{
    const stepper_entry *e = stepper_find(name);
    return e ? *e->type : NULL;
}

int hy_ode_stepper_known(const char *name) { return hy_ode_step_type(name) != NULL; }

hy_ode_opts hy_ode_defaults(void)
{
    hy_ode_opts o = {"rkf45", 1e-8, 1e-10, 0, 1, 10000000UL, 0, NULL, NULL, 0, 1e7, NULL};
    return o;
}

typedef struct ctx {
    const hy_model *m;
    const hy_input *in;
    double gamma;
    const hy_piece *piece;  /* fixed piece (restart mode) or NULL: search  */
    double k;               /* index of the period the piece is in         */
    unsigned long nfev, njev;
} ctx;

static double ctx_du(const ctx *c, double t)
{
    if (c->piece)
        return hy_piece_du(c->piece, hy_input_reduce(c->in, t, c->k));
    return hy_input_du(c->in, t);
}

static int rhs(double t, const double y[], double f[], void *params)
{
    ctx *c = params;
    c->nfev++;
    double v = ctx_du(c, t);
    double lam = c->m->sigma0 * fabs(v) / hy_model_g(c->m, v / c->gamma);
    f[0] = -lam * y[0] + v;
    if (c->m->type->has_filter)
        f[1] = (c->gamma / c->m->tau) * (c->m->sigma0 * y[0] - y[1]);
    return GSL_SUCCESS;
}

static int jac(double t, const double y[], double *dfdy, double dfdt[], void *params)
{
    ctx *c = params;
    c->njev++;
    double v = ctx_du(c, t);
    double lam = c->m->sigma0 * fabs(v) / hy_model_g(c->m, v / c->gamma);
    /* dfdt by a central difference of the smooth coefficient inside a piece */
    double h = 1e-7 * (1 + fabs(t));
    double vp = ctx_du(c, t + h), vm = ctx_du(c, t - h);
    double lp = c->m->sigma0 * fabs(vp) / hy_model_g(c->m, vp / c->gamma);
    double lm = c->m->sigma0 * fabs(vm) / hy_model_g(c->m, vm / c->gamma);
    double dl = (lp - lm) / (2 * h), dv = (vp - vm) / (2 * h);
    if (c->m->type->has_filter) {
        double mu = c->gamma / c->m->tau;
        dfdy[0] = -lam;
        dfdy[1] = 0;
        dfdy[2] = mu * c->m->sigma0;
        dfdy[3] = -mu;
        dfdt[1] = 0;
    } else
        dfdy[0] = -lam;
    dfdt[0] = -dl * y[0] + dv;
    (void)y;
    return GSL_SUCCESS;
}

static double output(const ctx *c, double t, const double y[])
{
    if (c->m->type->has_filter)
        return y[1];
    double v = ctx_du(c, t);
    double lam = c->m->sigma0 * fabs(v) / hy_model_g(c->m, v / c->gamma);
    double zdot = -lam * y[0] + v;
    return c->m->sigma0 * y[0] + (c->m->sigma1 / c->gamma) * zdot + c->m->sigma2 * v / c->gamma;
}

static void take_stats(gsl_odeiv2_driver *d, hy_ode_stats *s)
{
    s->steps += d->e->count;
    s->fails += d->e->failed_steps;
}

/* An output time within snap_width of the current time or of a breakpoint is
 * served there instead of asking for a step of a few ulps (which implicit and
 * multistep steppers refuse). */
#define snap_width hy_input_snap

static int step_failed(int st, double tc, double target, hy_error *err)
{
    if (st == GSL_EMAXITER)
        return hy_error_set(err, HY_ENUM, "ODE step cap reached at t = %.17g before t = %.17g (raise max_steps or loosen the tolerance)",
                            tc, target);
    return hy_error_set(err, HY_ENUM, "ODE integration failed at t = %.17g: %s", tc, gsl_strerror(st));
}

/* After a step: GSL's status, then a non-finite state (which GSL reports as
 * success: say what went wrong instead). */
static int step_status(int st, size_t dim, const double y[], double tc, double target, hy_error *err)
{
    if (st != GSL_SUCCESS)
        return step_failed(st, tc, target, err);
    for (size_t i = 0; i < dim; i++)
        if (!isfinite(y[i]))
            return hy_error_set(err, HY_ENUM, "ODE solution became non-finite (y[%zu] = %g) by t = %.17g", i, y[i],
                                tc);
    return HY_OK;
}

/* Integrates from *tc to target (a target within snap_width of *tc is
 * served at *tc); on failure the message names the time. */
static int advance(gsl_odeiv2_driver *d, double *tc, double target, double y[], hy_error *err)
{
    if (target <= *tc + snap_width(*tc))
        return HY_OK;
    int st = gsl_odeiv2_driver_apply(d, tc, target, y);
    return step_status(st, d->sys->dimension, y, *tc, target, err);
}

/* Straight through (no fixed piece): t within snap width of a breakpoint,
 * where u̇ and so y are two-valued; such step ends are not traced. */
static int near_breakpoint(const ctx *c, double t)
{
    if (c->piece)
        return 0;
    double tm;
    const hy_piece *p = &c->in->pieces[hy_input_piece_at(c->in, t, &tm, NULL)];
    return tm - p->t0 <= snap_width(t) || p->t1 - tm <= snap_width(t);
}

/* Dense mode: free steps from *tc to tb; the outputs t[*j] <= tb below limit
 * come from the cubic Hermite interpolant of the accepted steps' ends (value
 * and slope; one extra evaluation of f per step, counted in nfev).  Step ends
 * below limit go to the trace when one is asked for. */
static int advance_dense(gsl_odeiv2_driver *d, gsl_odeiv2_system *sys, ctx *c, const hy_ode_opts *o,
                         hy_ode_stats *stats, double *tc, double tb, double limit, double y[], const double *t,
                         size_t n, size_t *j, double *y_out, hy_error *err)
{
    size_t dim = sys->dimension;
    double f[2], y0[2], f0[2];
    rhs(*tc, y, f, c);
    unsigned long steps = 0;
    while (*tc < tb) {
        double t0 = *tc;
        memcpy(y0, y, dim * sizeof *y);
        memcpy(f0, f, dim * sizeof *f);
        if (o->max_steps && ++steps > o->max_steps)
            return step_failed(GSL_EMAXITER, *tc, tb, err);
        int st = gsl_odeiv2_evolve_apply(d->e, d->c, d->s, sys, tc, tb, &d->h, y);
        if ((st = step_status(st, dim, y, *tc, tb, err)))
            return st;
        rhs(*tc, y, f, c);
        double h = *tc - t0;
        if (o->trace_t && stats->ntrace < o->trace_cap && *tc < limit && !near_breakpoint(c, *tc)) {
            o->trace_t[stats->ntrace] = *tc;
            o->trace_y[stats->ntrace++] = output(c, *tc, y);
        }
        for (; *j < n && t[*j] <= *tc && t[*j] < limit; (*j)++) {
            double s = h > 0 ? (t[*j] - t0) / h : 1, yi[2];
            double h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s);
            double h01 = s * s * (3 - 2 * s), h11 = s * s * (s - 1);
            for (size_t q = 0; q < dim; q++)
                yi[q] = h00 * y0[q] + h10 * h * f0[q] + h01 * y[q] + h11 * h * f[q];
            y_out[*j] = output(c, t[*j], yi);
        }
    }
    return HY_OK;
}

static int check_opts(const hy_ode_opts *o, hy_error *err)
{
    if (!o->stepper || !hy_ode_step_type(o->stepper))
        return hy_error_set(err, HY_EINVAL, "unknown ODE stepper '%s' (rk2, rk4, rkf45, rkck, rk8pd, rk1imp, rk2imp, rk4imp, bsimp, msadams, msbdf)",
                            o->stepper ? o->stepper : "(null)");
    if (!isfinite(o->rtol) || o->rtol < 0 || !isfinite(o->atol) || o->atol < 0 || (o->rtol == 0 && o->atol == 0))
        return hy_error_set(err, HY_EINVAL, "ODE tolerances must be finite, >= 0 and not both 0 (rtol = %g, atol = %g)", o->rtol, o->atol);
    if (!isfinite(o->h0) || o->h0 < 0)
        return hy_error_set(err, HY_EINVAL, "ODE first step h0 must be finite and >= 0 (got %g)", o->h0);
    if (!o->trace_t != !o->trace_y)
        return hy_error_set(err, HY_EINVAL, "ODE trace: trace_t and trace_y must be both NULL or both given");
    return HY_OK;
}

/* Serves the outputs t[*j] within snap width of the breakpoint tb, at tb,
 * on the piece that starts there. */
static void serve_at_breakpoint(const ctx *c, double tb, const double y[], const double *t, size_t n, size_t *j,
                                double *y_out)
{
    for (; *j < n && t[*j] <= tb + snap_width(tb); (*j)++)
        y_out[*j] = output(c, tb, y);
}

double hy_ode_work_estimate(const hy_model *m, const hy_input *in, double gamma, const hy_ode_opts *o,
                            double t_end, double *stiff)
{
    if (stiff)
        *stiff = NAN;
    if (!m || !m->type || !hy__input_ready(in) || !o || !isfinite(t_end))
        return NAN;
    const stepper_entry *e = stepper_find(o->stepper);
    int kind = 0, order = 0; /* 1: explicit; 2: one-step implicit of this order */
    if (e && e->kind == HY_ODE_EXPLICIT)
        kind = 1;
    else if (e && e->order > 0) {
        kind = 2;
        order = e->order;
    }
    double cycles = ceil(t_end / in->period), per_period = 0, ratio = 0;
    double gmax = fmax(hy_model_g0(m), m->fc); /* g ∈ [Fc, Fs]: a lower bound on λ on smooth pieces */
    for (size_t i = 0; i < in->npieces; i++) {
        const hy_piece *p = &in->pieces[i], *prev = &in->pieces[(i + in->npieces - 1) % in->npieces];
        double du = fabs(p->u1 - p->u0), dt = p->t1 - p->t0;
        if (du == 0)
            continue;
        double g = p->shape == HY_PIECE_LINEAR ? hy_model_g(m, (p->u1 - p->u0) / dt / gamma) : gmax;
        double r = m->sigma0 * du / g;
        if (m->type->has_filter)
            r = fmax(r, gamma / m->tau * dt);
        ratio = fmax(ratio, r);
        if (kind == 1)
            per_period += r; /* >= r/6 steps of >= 6 evaluations */
        else if (kind == 2 && (prev->u1 - prev->u0) * (p->u1 - p->u0) <= 0) /* a run starts: a transient */
            per_period += 9 * pow(fmax(o->rtol, 1e-300), -1.0 / (order + 1));
    }
    if (stiff)
        *stiff = ratio;
    return per_period * fmax(cycles, 1);
}

int hy_ode_check_work(const hy_model *m, const hy_input *in, double gamma, const hy_ode_opts *o, double t_end,
                      hy_error *err)
{
    HY_NONNULL(err, m);
    HY_INPUT_READY(err, in);
    HY_NONNULL(err, o);
    if (!isfinite(o->work_limit) || o->work_limit < 0)
        return hy_error_set(err, HY_EINVAL, "the ODE work_limit must be a finite number >= 0 (got %g)", o->work_limit);
    if (!isfinite(t_end))
        return hy_error_set(err, HY_EINVAL, "%s: t_end must be finite (got %g)", __func__, t_end);
    if (!m->type)
        return hy_model_validate(m, err); /* "model has no type" */
    double stiff, work = o->work_limit > 0 ? hy_ode_work_estimate(m, in, gamma, o, t_end, &stiff) : 0;
    if (work > o->work_limit)
        return hy_error_set(err, HY_EINVAL,
                            "refused: %s at rtol %g needs at least %.2g evaluations of f (limit %.2g): %s (the "
                            "stiffness ratio sigma0*du/g reaches %.3g on an input piece); use the exact solver "
                            "(piecewise-linear inputs), bsimp or msbdf",
                            o->stepper, o->rtol, work, o->work_limit,
                            o->stepper[2] == 'i' || o->stepper[3] == 'i' ? "a low-order implicit method at this tolerance"
                                                                         : "the problem is too stiff for an explicit stepper",
                            stiff);
    return HY_OK;
}

/* The first step on a piece of length len: h0 if given; in dense mode the
 * whole piece (the controller shrinks it as the tolerance asks, so a loose
 * tolerance costs few steps); else 1e-3 of it. */
static double first_step(const hy_ode_opts *o, double len)
{
    return o->h0 > 0 ? o->h0 : o->dense ? len : 1e-3 * len;
}

/* HY_OK when hy_ode_solve's other arguments are valid (the options, the
 * output times and the work they ask; the model, the input and gamma were
 * checked by hy__solve_args); else the error, in err. */
static int check_solve_args(const hy_model *m, const hy_input *in, double gamma, const hy_ode_opts *o,
                            const double *t, size_t n, hy_error *err)
{
    int rc;
    if ((rc = check_opts(o, err)))
        return rc;
    for (size_t i = 0; i < n; i++)
        if (!isfinite(t[i]) || t[i] < 0 || (i && t[i] < t[i - 1]))
            return hy_error_set(err, HY_EINVAL, "output times must be finite, >= 0 and ascending (t[%zu] = %g)", i, t[i]);
    return hy_ode_check_work(m, in, gamma, o, n ? t[n - 1] : 0, err);
}

int hy_ode_solve(const hy_model *m, const hy_input *in, double gamma, const hy_ode_opts *o,
                 const double *t, size_t n, double *y_out, hy_ode_stats *stats, hy_error *err)
{
    int rc;
    HY_NONNULL(err, o);
    if ((rc = hy__solve_args(__func__, m, in, gamma, t, n, y_out, "y_out", err)) ||
        (rc = check_solve_args(m, in, gamma, o, t, n, err)))
        return rc;
    hy_ode_stats local;
    if (!stats)
        stats = &local;
    memset(stats, 0, sizeof *stats);
    ctx c = {m, in, gamma, NULL, 0, 0, 0};
    size_t dim = m->type->has_filter ? 2 : 1;
    gsl_odeiv2_system sys = {rhs, jac, dim, &c};
    double h0 = first_step(o, in->pieces[0].t1 - in->pieces[0].t0);
    gsl_odeiv2_driver *d = gsl_odeiv2_driver_alloc_y_new(&sys, hy_ode_step_type(o->stepper), h0, o->atol, o->rtol);
    if (!d)
        return hy_error_set(err, HY_ENOMEM, "cannot allocate the GSL driver");
    if (o->max_steps)
        gsl_odeiv2_driver_set_nmax(d, o->max_steps);
    double y[2] = {m->x0, m->yf0};
    double tc = 0;
    size_t j = 0;
    if (!o->restart) {
        if (o->dense && n) {
            rc = advance_dense(d, &sys, &c, o, stats, &tc, t[n - 1], INFINITY, y, t, n, &j, y_out, err);
            if (!rc)
                serve_at_breakpoint(&c, tc, y, t, n, &j, y_out);
        }
        unsigned tick = 0;
        while (j < n && rc == HY_OK) {
            if (hy_cancel_poll(o->cancel, &tick, 256)) {
                rc = hy_cancel_error(err);
                break;
            }
            rc = advance(d, &tc, t[j], y, err);
            if (!rc)
                y_out[j++] = output(&c, tc, y);
        }
        take_stats(d, stats);
    }
    size_t ip = 0;
    double k = 0; /* time is (period k, piece ip): k T is formed, never summed */
    c.piece = &in->pieces[0];
    unsigned tick = 0;
    while (o->restart && j < n && rc == HY_OK) {
        const hy_piece *p = &in->pieces[ip];
        if (hy_cancel_poll(o->cancel, &tick, 8)) { /* a piece: up to a few hundred steps */
            rc = hy_cancel_error(err);
            take_stats(d, stats);
            break;
        }
        double tb = k * in->period + p->t1, limit = tb - snap_width(tb);
        if (o->dense) {
            double stop = fmin(tb, t[n - 1]);
            rc = advance_dense(d, &sys, &c, o, stats, &tc, stop, stop < limit ? INFINITY : limit, y, t, n, &j,
                               y_out, err);
        } else {
            while (j < n && t[j] < limit && rc == HY_OK) {
                rc = advance(d, &tc, t[j], y, err);
                if (!rc)
                    y_out[j++] = output(&c, tc, y);
            }
            if (!rc && j < n)
                rc = advance(d, &tc, tb, y, err);
        }
        if (rc || j >= n) {
            take_stats(d, stats);
            break;
        }
        tc = tb;
        take_stats(d, stats);
        gsl_odeiv2_driver_reset(d);
        stats->restarts++;
        if (++ip == in->npieces) {
            ip = 0;
            k += 1;
        }
        gsl_odeiv2_driver_reset_hstart(d, first_step(o, in->pieces[ip].t1 - in->pieces[ip].t0));
        c.piece = &in->pieces[ip];
        c.k = k;
        if (o->trace_t && stats->ntrace < o->trace_cap) {
            o->trace_t[stats->ntrace] = tb;
            o->trace_y[stats->ntrace++] = output(&c, tb, y);
        }
        serve_at_breakpoint(&c, tb, y, t, n, &j, y_out);
    }
    stats->nfev = c.nfev;
    stats->njev = c.njev;
    gsl_odeiv2_driver_free(d);
    return rc;
}
