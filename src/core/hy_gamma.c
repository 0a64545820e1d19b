/* SPDX-License-Identifier: MIT */
/* hy_gamma.c: exact piecewise-exponential solution of Eq. (3) of seed 000 for
 * piecewise-linear inputs, and of system (16) with its first-order filter. */
#include "hy_gamma.h"

#include "hy_args.h"

#include <math.h>
#include "hy_limit.h"

int hy_gamma_check(double gamma, hy_error *err)
{
    if (!isfinite(gamma) || !(gamma > 0))
        return hy_error_set(err, HY_EINVAL, "gamma must be a finite number > 0 (got %g)", gamma);
    return HY_OK;
}

int hy__solve_args(const char *fn, const hy_model *m, const hy_input *in, double gamma, const double *t, size_t n,
                   const double *y, const char *yname, hy_error *err)
{
    const char *null = !m ? "m" : !in ? "in" : !y ? yname : !t && n ? "t" : NULL;
    if (null)
        return hy_error_set(err, HY_EINVAL, "%s: %s must not be NULL", fn, null);
    if (!hy__input_ready(in))
        return hy_error_set(err, HY_EINVAL, "%s: in " HY__NO_PIECES, fn);
    int rc = hy_model_validate(m, err);
    return rc ? rc : hy_gamma_check(gamma, err);
}

int hy_gamma_exact_applies(const hy_model *m, const hy_input *in)
{
    if (!m || !hy__input_ready(in))
        return 0;
    return in->all_linear || hy_model_rate_independent(m);
}

/* State of the solution at the start of a piece. */
typedef struct seg {
    double z, yf;
} seg;

/* Coefficients of z on one piece. */
typedef struct coef {
    double lambda, zeq, v;
    int linear;
} coef;

static coef piece_coef(const hy_model *m, const hy_piece *p, double gamma)
{
    coef c = {0, 0, 0, p->shape == HY_PIECE_LINEAR};
    if (c.linear) {
        c.v = (p->u1 - p->u0) / (p->t1 - p->t0);
        if (c.v != 0) {
            double g = hy_model_g(m, c.v / gamma);
            c.lambda = m->sigma0 * fabs(c.v) / g;
            c.zeq = (c.v > 0 ? g : -g) / m->sigma0;
        }
    } else { /* rate-independent model on a monotone smooth piece */
        double g = hy_model_g0(m);
        c.lambda = m->sigma0 / g; /* per unit of variation */
        c.zeq = (p->u1 > p->u0 ? g : -g) / m->sigma0;
    }
    return c;
}

/* e^{-λs} (X0-Xe) μ φ(s) + ... : the filter driven by an exponential (exact). */
static double filter_at(double X0, double Xe, double lambda, double mu, double yf0, double s)
{
    double dl = fabs(mu - lambda), lo = fmin(mu, lambda);
    double phi = exp(-lo * s) * s * hy_phi1(dl * s); /* (e^{-λs} - e^{-μs})/(μ - λ) */
    return Xe + (X0 - Xe) * mu * phi + (yf0 - Xe) * exp(-mu * s);
}

/* Evaluates state/output at time t inside piece p from the start state s0. */
static void eval_piece(const hy_model *m, const hy_piece *p, const coef *c, double gamma,
                       const seg *s0, double t, seg *s1, double *y)
{
    double dt = t - p->t0;
    /* z = z0 e^{-x} + z_eq (1 - e^{-x}), with z_eq (1 - e^{-x}) written as
       (drive) φ1(x) so that a large z_eq (small σ0) does not cancel */
    double x, drive;
    if (c->linear) {
        x = c->lambda * dt;
        drive = c->v * dt;
    } else {
        double du = hy_piece_u(p, t) - p->u0;
        x = c->lambda * fabs(du);
        drive = du;
    }
    double ex = exp(-x);
    double z = (c->lambda == 0) ? s0->z + drive : s0->z * ex + drive * hy_phi1(x);
    s1->z = z;
    s1->yf = s0->yf;
    if (m->type->has_filter) {
        double mu = gamma / m->tau, X = m->sigma0 * z;
        if (c->lambda == 0)
            s1->yf = X + (s0->yf - X) * exp(-mu * dt);
        else if (c->linear)
            s1->yf = filter_at(m->sigma0 * s0->z, m->sigma0 * c->zeq, c->lambda, mu, s0->yf, dt);
        *y = s1->yf;
        return;
    }
    double v = c->linear ? c->v : hy_piece_du(p, t);
    /* ż = v - λ z = (v - λ z0) e^{-x}: exact, and 0 once the state saturates */
    double zdot = (v - c->lambda * (c->linear ? 1.0 : fabs(v)) * s0->z) * ex;
    *y = m->sigma0 * z + (m->sigma1 / gamma) * zdot + m->sigma2 * v / gamma;
}

int hy_gamma_exact(const hy_model *m, const hy_input *in, double gamma, const double *t, size_t n,
                   double *y_out, double *z_out, hy_error *err)
{
    int rc = hy__solve_args(__func__, m, in, gamma, t, n, y_out, "y_out", err);
    if (rc)
        return rc;
    if (!hy_gamma_exact_applies(m, in))
        return hy_error_set(err, HY_EUNSUP,
                            "no exact solution for %s with %s at finite gamma (needs a piecewise-linear input or a rate-independent model); choose an ODE solver",
                            m->type->name, in->desc);
    for (size_t i = 0; i < n; i++)
        if (!isfinite(t[i]) || t[i] < 0 || (i && t[i] < t[i - 1]))
            return hy_error_set(err, HY_EINVAL, "output times must be finite, >= 0 and ascending (t[%zu] = %g)", i, t[i]);
    seg s = {m->x0, m->yf0};
    size_t ip = 0;           /* current piece index within the period        */
    double k = 0;            /* index of the current period: time is (k, tm) */
    coef c = piece_coef(m, &in->pieces[0], gamma);
    for (size_t j = 0; j < n; j++) {
        /* tm = t[j] - kT, formed from k each time (never a running sum) */
        double tm = hy_input_reduce(in, t[j], k);
        /* advance whole pieces until tm lies in [t0, t1) of piece ip; a time
           within hy_input_snap of t1 counts as the next piece's start */
        while (tm >= in->pieces[ip].t1 - hy_input_snap(k * in->period + in->pieces[ip].t1)) {
            const hy_piece *p = &in->pieces[ip];
            seg s1;
            double ydummy;
            eval_piece(m, p, &c, gamma, &s, p->t1, &s1, &ydummy);
            s = s1;
            if (++ip == in->npieces) {
                ip = 0;
                k += 1;
                if (!isfinite(k * in->period) || k > 0x1p52)
                    return hy_error_set(err, HY_EINVAL, "time %g is too large", t[j]);
                tm = hy_input_reduce(in, t[j], k);
            }
            c = piece_coef(m, &in->pieces[ip], gamma);
        }
        seg s1;
        double y;
        eval_piece(m, &in->pieces[ip], &c, gamma, &s, fmax(tm, in->pieces[ip].t0), &s1, &y);
        y_out[j] = y;
        if (z_out)
            z_out[j] = s1.z;
    }
    return HY_OK;
}
