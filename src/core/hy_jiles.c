/* SPDX-License-Identifier: MIT */
/* hy_jiles.c: Jiles-Atherton, dM/dH = χ_e/(1 - α χ_e), χ_e = (M_an - M)/(k δ) + c dM_an/dH_e
 * (1986), or dM/dH = [(M_an - M)/(δ k - α (M_an - M)) + c dM_an/dH_e]/(1 + c) (Jiles,
 * Thoelke and Devine 1992) (irreversible term 0 while (M_an - M) δ < 0), integrated
 * in H by GSL (rk8pd, or the stepper the caller names) with a restart at every
 * reversal and at every switch of that guard, within a step budget. */
#include "hy_jiles.h"

#include "hy_args.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hy_ode.h"
#include "hy_ode_steppers.h"

#define LAMBERT_N 18       /* continued-fraction depth: < 1e-20 relative for |x| < 2 */
#define DEN_MIN 1e-9       /* 1 - α χ_e below this: no physical solution             */
#define GUARD_TOL 1e-13    /* (M_an - M) δ / Ms beyond which the guard switches back  */

const char *const hy_jiles_variant_names[] = {"jiles1986", "jtd1992", NULL};

/* q = x / L(x) = 3 + x²/(5 + x²/(7 + ...)) for |x| < 2 (Lambert), and dq/dx. */
static double lambert_q(double x, double *dq)
{
    double x2 = x * x, q = 2.0 * LAMBERT_N + 1, d = 0;
    for (int j = LAMBERT_N - 1; j >= 1; j--) {
        d = 2 * x / q - x2 * d / (q * q);
        q = (2.0 * j + 1) + x2 / q;
    }
    if (dq)
        *dq = d;
    return q;
}

double hy_langevin(double x)
{
    if (fabs(x) < 2)
        return x / lambert_q(x, NULL);
    return 1.0 / tanh(x) - 1.0 / x;
}

double hy_langevin_d(double x)
{
    if (fabs(x) < 2) { /* (x/q)' = (q - x q')/q², no cancellation: q - x q' = 3 - x²/5 + ... */
        double dq, q = lambert_q(x, &dq);
        return (q - x * dq) / (q * q);
    }
    double s = sinh(x);
    return 1.0 / (x * x) - 1.0 / (s * s);
}

int hy_jiles_init(hy_jiles *j, double ms, double a, double k, double c, double alpha, hy_error *err)
{
    hy_jiles t = {ms, a, k, c, alpha, 0.0, HY_JILES_RTOL, NULL, HY_JILES_JA1986, 0, NULL};
    HY_NONNULL(err, j);
    int rc = hy_jiles_validate(&t, err);
    if (!rc)
        *j = t;
    return rc;
}

int hy_jiles_validate(const hy_jiles *j, hy_error *err)
{
    const char *names[] = {"Ms (saturation magnetisation)", "a (anhysteretic shape)", "k (pinning)"};
    HY_NONNULL(err, j);
    const double v[] = {j->ms, j->a, j->k};
    for (int i = 0; i < 3; i++)
        if (!isfinite(v[i]) || !(v[i] > 0))
            return hy_error_set(err, HY_EINVAL, "Jiles-Atherton %s must be finite and > 0 A/m (got %g)", names[i],
                                v[i]);
    if (!isfinite(j->c) || !(j->c >= 0) || (j->variant != HY_JILES_JTD1992 && !(j->c < 1)))
        return hy_error_set(err, HY_EINVAL,
                            "Jiles-Atherton c (reversibility) must be in [0, 1) for jiles1986, finite and >= 0 for "
                            "jtd1992 (got %g; c = 1 leaves jiles1986 no irreversible magnetisation)",
                            j->c);
    if (!isfinite(j->alpha) || !(j->alpha >= 0))
        return hy_error_set(err, HY_EINVAL, "Jiles-Atherton alpha (mean-field coupling) must be finite and >= 0 (got %g)",
                            j->alpha);
    double w = j->alpha * j->ms / (3 * j->a);
    if (!(w < 1))
        return hy_error_set(err, HY_EINVAL,
                            "Jiles-Atherton alpha = %g is too large: alpha Ms / (3 a) = %g >= 1, so the anhysteretic "
                            "curve M = Ms L((H + alpha M)/a) is not single-valued (spontaneous magnetisation)",
                            j->alpha, w);
    if (!isfinite(j->m0) || !(fabs(j->m0) < j->ms))
        return hy_error_set(err, HY_EINVAL, "Jiles-Atherton initial magnetisation m0 must satisfy |m0| < Ms (got %g)",
                            j->m0);
    if (!(j->rtol >= 1e-15 && j->rtol <= 1e-2))
        return hy_error_set(err, HY_EINVAL, "Jiles-Atherton rtol must be in [1e-15, 1e-2] (got %g)", j->rtol);
    if (j->stepper && !hy_ode_stepper_known(j->stepper))
        return hy_error_set(err, HY_EINVAL, "Jiles-Atherton: unknown GSL stepper '%.40s'", j->stepper);
    if (j->variant != HY_JILES_JA1986 && j->variant != HY_JILES_JTD1992)
        return hy_error_set(err, HY_EINVAL, "Jiles-Atherton variant %d is unknown (jiles1986 or jtd1992)", j->variant);
    return HY_OK;
}

int hy_jiles_input_check(const hy_jiles *j, double hmax, double travel, hy_error *err)
{
    HY_NONNULL(err, j);
    double scale = fmax(j->ms, fmax(j->a, j->k)), bound = HY_JILES_HMAX * scale;
    unsigned long budget = j->max_steps ? j->max_steps : HY_JILES_MAX_STEPS;
    if (!isfinite(hmax) || !isfinite(travel))
        return hy_error_set(err, HY_EINVAL, "Jiles-Atherton field H must be finite (got %g)", hmax);
    if (fabs(hmax) > bound)
        return hy_error_set(err, HY_EINVAL,
                            "the input's scale is beyond what Jiles-Atherton integrates: |H| reaches %g A/m, %.3g "
                            "times the model's largest field scale max(Ms, a, k) = %g A/m (at most %g, i.e. %g A/m, "
                            "far into saturation: scale the input down)",
                            fabs(hmax), fabs(hmax) / scale, scale, HY_JILES_HMAX, bound);
    double need = travel / (HY_JILES_STEP_K * j->k);
    if (need > (double)budget)
        return hy_error_set(err, HY_EINVAL,
                            "the input's scale is beyond what Jiles-Atherton integrates: the field travels %g A/m "
                            "(|H| up to %g A/m), %.3g times k = %g A/m, which needs at least %.3g steps (one every "
                            "few k) against a step budget of %lu: lower the input's amplitude or raise k",
                            travel, fabs(hmax), travel / j->k, j->k, need, budget);
    return HY_OK;
}

void hy_jiles_state_init(const hy_jiles *j, hy_jiles_state *s, double H0)
{
    if (!j || !s)
        return;
    s->H = H0;
    s->M = j->m0;
    s->hb = 0;
    s->steps = 0;
}

double hy_jiles_b(const hy_jiles_state *s) { return s ? HY_MU0 * (s->H + s->M) : NAN; }

/* ---- right-hand side in H: y[0] = M/Ms, y[1] = ∫ (H + M)/Ms dH ----------- */

typedef struct ja_ctx {
    const hy_jiles *j;
    double delta;       /* ±1                                            */
    int guard;          /* 1: irreversible term off                      */
    int bad;            /* the denominator vanished                      */
    double bad_h, bad_m;
    unsigned long nfev;
} ja_ctx;

/* (M_an - M) δ / Ms at field H and m = M/Ms */
static double guard_g(const ja_ctx *c, double H, double m)
{
    const hy_jiles *j = c->j;
    return (hy_langevin((H + j->alpha * j->ms * m) / j->a) - m) * c->delta;
}

static int ja_rhs(double H, const double y[], double f[], void *params)
{
    ja_ctx *c = params;
    const hy_jiles *j = c->j;
    c->nfev++;
    double x = (H + j->alpha * j->ms * y[0]) / j->a;
    double rev = j->c * hy_langevin_d(x) / j->a; /* c dM_an/dH_e per A/m, in units of Ms */
    double den;
    if (j->variant == HY_JILES_JTD1992) { /* [δ_M (M_an - M)/(δk - α(M_an - M)) + c dM_an/dH_e]/(1 + c) */
        double irr = 0;
        den = 1; /* (δk - α(M_an - M)) δ / k: 1 while the irreversible term is off */
        if (!c->guard) {
            double d = hy_langevin(x) - y[0];
            double dk = c->delta * j->k - j->alpha * j->ms * d;
            den = dk * c->delta / j->k;
            irr = d / dk;
        }
        f[0] = (irr + rev) / (1.0 + j->c);
    } else { /* χ_e/(1 - α χ_e) */
        double chi = rev;
        if (!c->guard)
            chi += (hy_langevin(x) - y[0]) / (j->k * c->delta);
        den = 1.0 - j->alpha * j->ms * chi;
        f[0] = chi / den;
    }
    if (!(den > DEN_MIN)) {
        c->bad = 1;
        c->bad_h = H;
        c->bad_m = y[0] * j->ms;
        return GSL_FAILURE; /* evolve retries with a smaller step: a trial stage may probe past the trajectory */
    }
    f[1] = H / j->ms + y[0];
    return GSL_SUCCESS;
}

double hy_jiles_dmdh(const hy_jiles *j, double H, double M, int delta)
{
    if (!j)
        return NAN;
    ja_ctx c = {j, delta > 0 ? 1.0 : -1.0, 0, 0, 0, 0, 0};
    double y[2] = {M / j->ms, 0}, f[2];
    c.guard = !(guard_g(&c, H, y[0]) > 0);
    return ja_rhs(H, y, f, &c) == GSL_SUCCESS ? f[0] * j->ms : NAN;
}

/* The Jacobian for the implicit steppers, by forward differences (the 2x2
 * system is cheap; its kink at the guard is never straddled). */
static int ja_jac(double H, const double y[], double *dfdy, double dfdt[], void *params)
{
    double f0[2], f1[2], yp[2] = {y[0], y[1]};
    int st = ja_rhs(H, y, f0, params);
    if (st)
        return st;
    for (int k = 0; k < 2; k++) {
        double h = 1.5e-8 * fmax(1.0, fabs(y[k]));
        yp[k] = y[k] + h;
        if ((st = ja_rhs(H, yp, f1, params)))
            return st;
        dfdy[0 * 2 + k] = (f1[0] - f0[0]) / h;
        dfdy[1 * 2 + k] = (f1[1] - f0[1]) / h;
        yp[k] = y[k];
    }
    double hH = 1.5e-8 * fmax(1.0, fabs(H));
    if ((st = ja_rhs(H + hH, y, f1, params)))
        return st;
    dfdt[0] = (f1[0] - f0[0]) / hH;
    dfdt[1] = (f1[1] - f0[1]) / hH;
    return GSL_SUCCESS;
}

static int ja_fail(const ja_ctx *c, int status, double H, hy_error *err)
{
    if (c->bad)
        return hy_error_set(err, HY_EINVAL,
                            "Jiles-Atherton alpha = %g is too large for k = %g: the denominator %s of the "
                            "irreversible law vanishes at H = %g A/m (M = %g A/m)",
                            c->j->alpha, c->j->k,
                            c->j->variant == HY_JILES_JTD1992 ? "delta k - alpha (Man - M)" : "1 - alpha dM/dHe",
                            c->bad_h, c->bad_m);
    return hy_error_set(err, HY_ENUM, "Jiles-Atherton: GSL %s failed at H = %g A/m: %s",
                        c->j->stepper ? c->j->stepper : "rk8pd", H, gsl_strerror(status));
}

/* A GSL driver owns the stepper, control and evolve objects: the implicit
 * and multistep steppers reach the control through it (GSL's
 * gsl_odeiv2_step_set_driver); the integration calls evolve directly. */
typedef struct ja_solver {
    gsl_odeiv2_driver *drv;
    gsl_odeiv2_step *step;
    gsl_odeiv2_control *ctl;
    gsl_odeiv2_evolve *ev;
} ja_solver;

static void solver_free(ja_solver *s)
{
    if (s->drv)
        gsl_odeiv2_driver_free(s->drv);
}

static int solver_alloc(ja_solver *s, const hy_jiles *j, gsl_odeiv2_system *sys, hy_error *err)
{
    static const double scale_abs[2] = {1.0, 1.0};
    const gsl_odeiv2_step_type *type = j->stepper ? hy_ode_step_type(j->stepper) : gsl_odeiv2_step_rk8pd;
    if (!type)
        return hy_error_set(err, HY_EINVAL, "Jiles-Atherton: unknown GSL stepper '%.40s'", j->stepper);
    s->drv = gsl_odeiv2_driver_alloc_scaled_new(sys, type, 1.0, j->rtol, j->rtol, 1.0, 0.0, scale_abs);
    if (!s->drv)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    s->step = s->drv->s;
    s->ctl = s->drv->c;
    s->ev = s->drv->e;
    return HY_OK;
}

/* The guard switches inside the last step [h0, h0 + h] from y0: finds the
 * switch by regula falsi (Illinois) on single steps from h0, leaves the state
 * just past it in *x, y. */
static int locate_switch(ja_solver *s, gsl_odeiv2_system *sys, ja_ctx *c, double x0, const double y0[2],
                         double h, double *x, double y[2], unsigned long *tries)
{
    double lo = 0, hi = h, glo = guard_g(c, x0, y0[0]), ghi = guard_g(c, x0 + h, y[0]);
    double yhi[2] = {y[0], y[1]}, yt[2], ye[2];
    int side = 0;
    for (int it = 0; it < 200 && fabs(hi - lo) > 4e-16 * (fabs(x0) + fabs(h)); it++) {
        double m = (glo != ghi) ? lo + (hi - lo) * glo / (glo - ghi) : 0.5 * (lo + hi);
        if (!(fabs(m - lo) > 0 && fabs(hi - m) > 0))
            m = 0.5 * (lo + hi);
        yt[0] = y0[0];
        yt[1] = y0[1];
        gsl_odeiv2_step_reset(s->step);
        ++*tries;
        int st = gsl_odeiv2_step_apply(s->step, x0, m, yt, ye, NULL, NULL, sys);
        if (st)
            return st;
        double gm = guard_g(c, x0 + m, yt[0]);
        if ((gm > 0) == (ghi > 0)) {
            hi = m;
            ghi = gm;
            yhi[0] = yt[0];
            yhi[1] = yt[1];
            if (side == 1)
                glo *= 0.5;
            side = 1;
        } else {
            lo = m;
            glo = gm;
            if (side == -1)
                ghi *= 0.5;
            side = -1;
        }
    }
    *x = x0 + hi;
    y[0] = yhi[0];
    y[1] = yhi[1];
    gsl_odeiv2_step_reset(s->step);
    return GSL_SUCCESS;
}

/* The step budget is spent in the stretch from h0 to H. */
static int over_budget(const hy_jiles *j, unsigned long budget, double h0, double H, const hy_jiles_state *s,
                       hy_error *err)
{
    return hy_error_set(err, HY_EINVAL,
                        "Jiles-Atherton step budget: more than %lu steps since the start, the last from H = %g to %g "
                        "A/m (stopped at H = %g A/m, M = %g A/m): a stretch of %.3g A/m is %.3g times k = %g A/m, "
                        "too stiff to integrate (lower the input's amplitude, or raise k)",
                        budget, h0, H, s->H, s->M, fabs(H - h0), fabs(H - h0) / j->k, j->k);
}

/* Integrates one monotone stretch from s->H to H, while s->steps stays
 * within j->max_steps (HY_JILES_MAX_STEPS when 0). */
static int stretch(const hy_jiles *j, ja_solver *sv, hy_jiles_state *s, double H, hy_jiles_stats *stats,
                   hy_error *err)
{
    ja_ctx c = {j, H > s->H ? 1.0 : -1.0, 0, 0, 0, 0, 0};
    gsl_odeiv2_system sys = {ja_rhs, ja_jac, 2, &c};
    double x = s->H, y[2] = {s->M / j->ms, 0};
    c.guard = guard_g(&c, x, y[0]) < 0;
    double h = c.delta * fmin(fabs(H - x), 0.01 * fmin(j->a, j->k));
    gsl_odeiv2_evolve_reset(sv->ev);
    gsl_odeiv2_step_reset(sv->step);
    int rc = HY_OK;
    unsigned long steps = 0, fails = 0, tries = 0, budget = j->max_steps ? j->max_steps : HY_JILES_MAX_STEPS;
    double h0 = s->H;
    unsigned tick = 0;
    while (x != H) {
        if (s->steps + steps + fails + tries + sv->ev->count + sv->ev->failed_steps > budget) {
            rc = over_budget(j, budget, h0, H, s, err);
            break;
        }
        double x0 = x, y0[2] = {y[0], y[1]};
        if (hy_cancel_poll(j->cancel, &tick, 64)) { /* s: the last good step */
            rc = hy_cancel_error(err);
            break;
        }
        c.bad = 0;
        int st = gsl_odeiv2_evolve_apply(sv->ev, sv->ctl, sv->step, &sys, &x, H, &h, y);
        if (st) {
            rc = ja_fail(&c, st, x, err);
            break;
        }
        /* GSL's step can land one ulp past H (t0 + h rounded): the stretch
         * is done there; went on, the next step would point back at H */
        if (c.delta * (H - x) < 0)
            x = H;
        double g = guard_g(&c, x, y[0]);
        if ((c.guard && g > 0) || (!c.guard && g < -GUARD_TOL)) {
            st = locate_switch(sv, &sys, &c, x0, y0, x - x0, &x, y, &tries);
            if (st) {
                rc = ja_fail(&c, st, x, err);
                break;
            }
            /* x0 + hi may round one ulp past H likewise */
            if (c.delta * (H - x) < 0)
                x = H;
            c.guard = !c.guard;
            steps += sv->ev->count;
            fails += sv->ev->failed_steps;
            gsl_odeiv2_evolve_reset(sv->ev);
            if (stats)
                stats->switches++;
        }
        s->H = x; /* the last good step */
        s->M = y[0] * j->ms;
    }
    s->hb += y[1] * j->ms;
    s->steps += steps + fails + tries + sv->ev->count + sv->ev->failed_steps;
    if (stats) {
        stats->steps += steps + sv->ev->count;
        stats->fails += fails + sv->ev->failed_steps;
        stats->nfev += c.nfev;
        stats->stretches++;
    }
    return rc;
}

int hy_jiles_apply(const hy_jiles *j, hy_jiles_state *s, double H, hy_jiles_stats *stats, hy_error *err)
{
    HY_NONNULL(err, j);
    HY_NONNULL(err, s);
    int rc = hy_jiles_input_check(j, H, 0, err);
    if (rc)
        return rc;
    if (H == s->H)
        return HY_OK;
    ja_solver sv = {0};
    gsl_odeiv2_system any = {ja_rhs, ja_jac, 2, NULL}; /* the driver's own; each stretch passes its own */
    rc = solver_alloc(&sv, j, &any, err);
    if (!rc)
        rc = stretch(j, &sv, s, H, stats, err);
    solver_free(&sv);
    return rc;
}

/* ---- driving ---------------------------------------------------------------- */

typedef struct drive_ctx {
    const hy_jiles *j;
    hy_jiles_state s;
    hy_jiles_stats *stats;
} drive_ctx;

static int feed(void *ctx, double u, double *y, hy_error *err)
{
    drive_ctx *d = ctx;
    int rc = hy_jiles_apply(d->j, &d->s, u, d->stats, err);
    *y = d->s.M;
    return rc;
}

int hy_jiles_drive(const hy_jiles *j, const hy_input *in, const double *t, size_t n, double *M, double *B,
                   hy_jiles_stats *stats, hy_error *err)
{
    HY_NONNULL(err, j);
    HY_INPUT_READY(err, in);
    HY_NONNULL_N(err, t, n);
    int rc = hy_jiles_validate(j, err);
    if (rc || n == 0)
        return rc;
    double *m = M ? M : malloc(n * sizeof *m);
    if (!m)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    drive_ctx d = {j, {0, 0, 0, 0}, stats};
    hy_jiles_state_init(j, &d.s, hy_input_u(in, 0));
    rc = hy_rateind_drive(in, t, n, feed, &d, m, err);
    if (!rc && B) /* the value fed last at t[i] is u(t[i]) */
        for (size_t i = 0; i < n; i++)
            B[i] = HY_MU0 * (hy_input_u(in, t[i]) + m[i]);
    if (!M)
        free(m);
    return rc;
}

/* ---- loop features ------------------------------------------------------------ */

/* B (which = 0) or M (which = 1) of a state */
static double feature(const hy_jiles_state *s, int which) { return which ? s->M : hy_jiles_b(s); }

/* Descending from *top (feature > 0) towards lo (feature < 0): the field where the
 * feature is 0, by regula falsi (Illinois), each trial integrated from the
 * highest state known to be above the root. */
static int descend_root(const hy_jiles *j, const hy_jiles_state *top, double lo, int which, double *root,
                        hy_error *err)
{
    hy_jiles_state hi = *top, t = *top;
    int rc = hy_jiles_apply(j, &t, lo, NULL, err);
    if (rc)
        return rc;
    double fhi = feature(&hi, which), flo = feature(&t, which);
    if (!(fhi > 0 && flo < 0))
        return hy_error_set(err, HY_ENUM, "Jiles-Atherton: %s does not change sign between H = %g and %g A/m",
                            which ? "M" : "B", lo, top->H);
    int side = 0;
    for (int it = 0; it < 200 && hi.H - lo > 1e-14 * fabs(top->H - lo); it++) {
        double h = hi.H - (hi.H - lo) * fhi / (fhi - flo);
        if (!(h < hi.H && h > lo))
            h = 0.5 * (hi.H + lo);
        t = hi;
        if ((rc = hy_jiles_apply(j, &t, h, NULL, err)))
            return rc;
        double f = feature(&t, which);
        if (f > 0) {
            hi = t;
            fhi = f;
            if (side == 1)
                flo *= 0.5;
            side = 1;
        } else {
            lo = h;
            flo = f;
            if (side == -1)
                fhi *= 0.5;
            side = -1;
        }
    }
    *root = hi.H - (hi.H - lo) * fhi / (fhi - flo);
    return HY_OK;
}

int hy_jiles_major_loop(const hy_jiles *j, double hmax, hy_jiles_loop *out, hy_error *err)
{
    HY_NONNULL(err, j);
    HY_NONNULL(err, out);
    int rc = hy_jiles_validate(j, err);
    if (rc)
        return rc;
    if (!isfinite(hmax) || !(hmax > 0))
        return hy_error_set(err, HY_EINVAL, "Jiles-Atherton major loop: hmax must be finite and > 0 A/m (got %g)", hmax);
    hy_jiles_state s;
    hy_jiles_state_init(j, &s, 0.0);
    if ((rc = hy_jiles_apply(j, &s, hmax, NULL, err)))
        return rc;
    hy_jiles_loop L = {0, 0, 0, 0, 0, 0};
    for (;;) {
        double prev = s.M;
        if ((rc = hy_jiles_apply(j, &s, -hmax, NULL, err)) || (rc = hy_jiles_apply(j, &s, hmax, NULL, err)))
            return rc;
        L.cycles++;
        if (fabs(s.M - prev) < 1e-12 * j->ms)
            break;
        if (L.cycles == 100)
            return hy_error_set(err, HY_ENUM, "Jiles-Atherton major loop: not periodic after 100 cycles of +-%g A/m",
                                hmax);
    }
    L.bmax = hy_jiles_b(&s);
    if ((rc = hy_jiles_apply(j, &s, 0.0, NULL, err)))
        return rc;
    L.br = hy_jiles_b(&s);
    L.mr = s.M;
    double hb, hm;
    if ((rc = descend_root(j, &s, -hmax, 0, &hb, err)) || (rc = descend_root(j, &s, -hmax, 1, &hm, err)))
        return rc;
    L.hc = -hb;
    L.hci = -hm;
    *out = L;
    return HY_OK;
}

int hy_jiles_minor_loop(const hy_jiles *j, const hy_input *in, hy_minor_loop *out, hy_error *err)
{
    double e[4];
    HY_NONNULL(err, j);
    HY_INPUT_READY(err, in);
    HY_NONNULL(err, out);
    int rc = hy_jiles_validate(j, err);
    if (rc || (rc = hy_rateind_bimodal(in, e, err)))
        return rc;
    hy_jiles_state s;
    hy_jiles_state_init(j, &s, e[0]);
    hy_minor_loop L = {e[1], e[2], 0, 0, 0, 0, 0};
    for (;;) {
        double prev = s.M;
        for (int i = 1; i <= 4 && !rc; i++)
            rc = hy_jiles_apply(j, &s, e[i % 4], NULL, err);
        if (rc)
            return rc;
        L.cycles++;
        if (fabs(s.M - prev) < 1e-11 * j->ms)
            break;
        if (L.cycles == 400)
            return hy_error_set(err, HY_ENUM, "Jiles-Atherton minor loop: %s not periodic after 400 periods", in->desc);
    }
    double hb0 = s.hb, hba, hbb;
    if ((rc = hy_jiles_apply(j, &s, e[1], NULL, err)))
        return rc;
    L.y_start = hy_jiles_b(&s);
    hba = s.hb;
    if ((rc = hy_jiles_apply(j, &s, e[2], NULL, err)) || (rc = hy_jiles_apply(j, &s, e[1], NULL, err)))
        return rc;
    L.y_close = hy_jiles_b(&s);
    hbb = s.hb;
    if ((rc = hy_jiles_apply(j, &s, e[3], NULL, err)) || (rc = hy_jiles_apply(j, &s, e[0], NULL, err)))
        return rc;
    L.area = -HY_MU0 * (hbb - hba);
    L.area_period = -HY_MU0 * (s.hb - hb0);
    *out = L;
    return HY_OK;
}
