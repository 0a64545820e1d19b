/* hy_ode.c: GSL odeiv2 integration of Eq. (3) of seed 000 and system (16),
 * restarted at every breakpoint of u̇. */
#include "hy_ode.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <string.h>

#include "hy_gamma.h"

typedef struct stepper_entry {
    const char *name;
    const gsl_odeiv2_step_type *const *type;
} stepper_entry;

static const stepper_entry steppers[] = {
    {"rk2", &gsl_odeiv2_step_rk2},       {"rk4", &gsl_odeiv2_step_rk4},
    {"rkf45", &gsl_odeiv2_step_rkf45},   {"rkck", &gsl_odeiv2_step_rkck},
    {"rk8pd", &gsl_odeiv2_step_rk8pd},   {"rk1imp", &gsl_odeiv2_step_rk1imp},
    {"rk2imp", &gsl_odeiv2_step_rk2imp}, {"rk4imp", &gsl_odeiv2_step_rk4imp},
    {"bsimp", &gsl_odeiv2_step_bsimp},   {"msadams", &gsl_odeiv2_step_msadams},
    {"msbdf", &gsl_odeiv2_step_msbdf},
};
#define NSTEPPERS (sizeof steppers / sizeof steppers[0])

static const char *const stepper_names[NSTEPPERS + 1] = {
    "rk2", "rk4", "rkf45", "rkck", "rk8pd", "rk1imp", "rk2imp", "rk4imp", "bsimp", "msadams", "msbdf", NULL};

const char *const *hy_ode_stepper_names(void) { return stepper_names; }

static const gsl_odeiv2_step_type *find_stepper(const char *name)
{
    for (size_t i = 0; i < NSTEPPERS; i++)
        if (strcmp(steppers[i].name, name) == 0)
            return *steppers[i].type;
    return NULL;
}

int hy_ode_stepper_known(const char *name) { return name && find_stepper(name) != NULL; }

hy_ode_opts hy_ode_defaults(void)
{
    hy_ode_opts o = {"rkf45", 1e-8, 1e-10, 0, 1, 10000000UL};
    return o;
}

typedef struct ctx {
    const hy_model *m;
    const hy_input *in;
    double gamma;
    const hy_piece *piece;  /* fixed piece (restart mode) or NULL: search  */
    double base;            /* start time of the period the piece is in    */
    unsigned long nfev, njev;
} ctx;

static double ctx_du(const ctx *c, double t)
{
    if (c->piece)
        return hy_piece_du(c->piece, t - c->base);
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

/* Integrates from *tc to target; on failure the message names the time. */
static int advance(gsl_odeiv2_driver *d, double *tc, double target, double y[], hy_error *err)
{
    if (target <= *tc)
        return HY_OK;
    int st = gsl_odeiv2_driver_apply(d, tc, target, y);
    if (st == GSL_EMAXITER)
        return hy_error_set(err, HY_ENUM, "ODE step cap reached at t = %.17g before t = %.17g (raise max_steps or loosen the tolerance)",
                            *tc, target);
    if (st != GSL_SUCCESS)
        return hy_error_set(err, HY_ENUM, "ODE integration failed at t = %.17g: %s", *tc, gsl_strerror(st));
    for (size_t i = 0; i < d->sys->dimension; i++)
        if (!isfinite(y[i])) /* GSL reports success: say what went wrong instead */
            return hy_error_set(err, HY_ENUM, "ODE solution became non-finite (y[%zu] = %g) by t = %.17g",
                                i, y[i], *tc);
    return HY_OK;
}

static int check_opts(const hy_ode_opts *o, hy_error *err)
{
    if (!o->stepper || !find_stepper(o->stepper))
        return hy_error_set(err, HY_EINVAL, "unknown ODE stepper '%s' (rk2, rk4, rkf45, rkck, rk8pd, rk1imp, rk2imp, rk4imp, bsimp, msadams, msbdf)",
                            o->stepper ? o->stepper : "(null)");
    if (!isfinite(o->rtol) || o->rtol < 0 || !isfinite(o->atol) || o->atol < 0 || (o->rtol == 0 && o->atol == 0))
        return hy_error_set(err, HY_EINVAL, "ODE tolerances must be finite, >= 0 and not both 0 (rtol = %g, atol = %g)", o->rtol, o->atol);
    if (!isfinite(o->h0) || o->h0 < 0)
        return hy_error_set(err, HY_EINVAL, "ODE first step h0 must be finite and >= 0 (got %g)", o->h0);
    return HY_OK;
}

int hy_ode_solve(const hy_model *m, const hy_input *in, double gamma, const hy_ode_opts *o,
                 const double *t, size_t n, double *y_out, hy_ode_stats *stats, hy_error *err)
{
    int rc;
    if ((rc = hy_model_validate(m, err)) || (rc = hy_gamma_check(gamma, err)) || (rc = check_opts(o, err)))
        return rc;
    for (size_t i = 0; i < n; i++)
        if (!isfinite(t[i]) || t[i] < 0 || (i && t[i] < t[i - 1]))
            return hy_error_set(err, HY_EINVAL, "output times must be finite, >= 0 and ascending (t[%zu] = %g)", i, t[i]);
    hy_ode_stats local;
    if (!stats)
        stats = &local;
    memset(stats, 0, sizeof *stats);
    ctx c = {m, in, gamma, NULL, 0, 0, 0};
    size_t dim = m->type->has_filter ? 2 : 1;
    gsl_odeiv2_system sys = {rhs, jac, dim, &c};
    double h0 = o->h0 > 0 ? o->h0 : 1e-3 * in->pieces[0].t1 - 0;
    gsl_odeiv2_driver *d = gsl_odeiv2_driver_alloc_y_new(&sys, find_stepper(o->stepper), h0, o->atol, o->rtol);
    if (!d)
        return hy_error_set(err, HY_ENOMEM, "cannot allocate the GSL driver");
    if (o->max_steps)
        gsl_odeiv2_driver_set_nmax(d, o->max_steps);
    double y[2] = {m->x0, m->yf0};
    double tc = 0;
    size_t ip = 0, j = 0;
    double base = 0;
    if (o->restart)
        c.piece = &in->pieces[0];
    while (j < n && rc == HY_OK) {
        if (!o->restart) {
            while (j < n && rc == HY_OK) {
                rc = advance(d, &tc, t[j], y, err);
                if (!rc)
                    y_out[j++] = output(&c, tc, y);
            }
            break;
        }
        const hy_piece *p = &in->pieces[ip];
        double tend = base + p->t1;
        while (j < n && t[j] < tend && rc == HY_OK) {
            rc = advance(d, &tc, t[j], y, err);
            if (!rc)
                y_out[j++] = output(&c, tc, y);
        }
        if (rc || j >= n)
            break;
        rc = advance(d, &tc, tend, y, err);
        tc = tend;
        take_stats(d, stats);
        gsl_odeiv2_driver_reset(d);
        gsl_odeiv2_driver_reset_hstart(d, o->h0 > 0 ? o->h0 : 1e-3 * (p->t1 - p->t0));
        stats->restarts++;
        if (++ip == in->npieces) {
            ip = 0;
            base += in->period;
        }
        c.piece = &in->pieces[ip];
        c.base = base;
    }
    if (!o->restart || j >= n)
        take_stats(d, stats);
    stats->nfev = c.nfev;
    stats->njev = c.njev;
    gsl_odeiv2_driver_free(d);
    return rc;
}
