/* SPDX-License-Identifier: MIT */
/* hy_limit.c: γ → ∞ limit y*_u, k cycles, steady state y°_u and Theorem A
 * (seed 000, Theorem 2, Eqs. (4)-(8), (10)-(14)), in overflow-free form. */
#include "hy_limit.h"

#include "hy_args.h"

#include <math.h>
#include <stdlib.h>

/* φ1(x) and φ2(x) from e = expm1(-x), which each reads only where it needs
 * it (φ1: x >= 1e-8, φ2: x >= 0.5): one expm1 serves both. */
static double phi1_e(double x, double e)
{
    if (x < 1e-8)
        return 1 - 0.5 * x;
    return -e / x;
}

static double phi2_e(double x, double e)
{
    if (x < 0.5) { /* Σ (-x)^n/(n+2)!, 18 terms: error < 0.5^18/20! */
        double term = 0.5, sum = 0.5;
        for (int n = 1; n < 18; n++) {
            term *= -x / (n + 2);
            sum += term;
        }
        return sum;
    }
    return (x + e) / (x * x);
}

/* Below it e^{-x} - 1 is not needed: φ1, φ2 use their series. */
#define PHI_E_MIN 1e-8

/* expm1(-x) where φ1 or φ2 of x reads it, else 0 (not read) */
static double phi_e(double x)
{
    return x < PHI_E_MIN ? 0 : expm1(-x);
}

double hy_phi1(double x)
{
    return phi1_e(x, phi_e(x));
}

double hy_phi2(double x)
{
    return phi2_e(x, x < 0.5 ? 0 : expm1(-x));
}

/* The runs whose e^{-aΔ}, expm1(-aΔ) hy_steady_init_buf computes once. */
#define STEP_MEMO 16

/* hy_limit_step from e = e^{-x} and em = expm1(-x) (the same expression:
 * a run's pair, computed once, gives the same bits) */
static double step_e(double g0, double y, int s, double e, double em)
{
    return e * y + s * g0 * -em;
}

double hy_limit_step(double a, double g0, double y, int s, double d)
{
    double x = a * d;
    return step_e(g0, y, s, exp(-x), expm1(-x));
}

double hy_limit_step_area(double a, double g0, double y, int s, double d)
{
    return hy_limit_step_area_em(a, g0, y, s, d, phi_e(a * d));
}

double hy_limit_step_area_em(double a, double g0, double y, int s, double d, double em)
{
    /* ∫_0^d (e^{-ar} y + s g0 (1 - e^{-ar})) s dr = s y d φ1(ad) + a g0 d² φ2(ad) */
    double x = a * d, q = (a * g0) * d * d, e = x < PHI_E_MIN ? 0 : em; /* phi_e(x): φ1 and φ2 share it */
    if (isfinite(q) && x < 1e150)
        return s * y * d * phi1_e(x, e) + q * phi2_e(x, e);
    /* scaled where a g0 d² or x² (inside φ2) overflows although the area
     * fits (runs of 1e200 and more): a d² φ2(x) = d · x φ2(x) = d (1 - φ1(x)) */
    double xphi2 = x < 0.5 ? x * phi2_e(x, e) : 1 - phi1_e(x, e);
    return s * y * d * phi1_e(x, e) + g0 * (d * xphi2);
}

/* y°(0) = B/(1 - A) for the affine period map y ↦ A y + B.
 * Large aρ_T: B by forward composition (terms of size g0, no cancellation;
 * each run's e^{-aΔ_i}, expm1(-aΔ_i) from e, em where given, else computed).
 * Small aρ_T: B = -σ0 Σ s_i Δ_i c_i with c_i = 1 - φ1(aΔ_i) e^{-aR_i}, R_i the
 * variation after run i; uses Σ s_i Δ_i = 0 (periodic input) to remove the
 * O(1) terms that would otherwise cancel. */
static double steady_y0(const hy_input *in, double sigma0, double g0, double a, const double *e, const double *em)
{
    double one_minus_A = -expm1(-a * in->rho_T);
    if (a * in->rho_T >= 1) {
        double B = 0;
        for (size_t i = 0; i < in->nruns; i++) {
            const hy_run *r = &in->runs[i];
            B = e ? step_e(g0, B, r->sign, e[i], em[i]) : hy_limit_step(a, g0, B, r->sign, r->rho1 - r->rho0);
        }
        return B / one_minus_A;
    }
    double sum = 0;
    for (size_t i = 0; i < in->nruns; i++) {
        const hy_run *r = &in->runs[i];
        double d = r->rho1 - r->rho0, x = a * d, X = a * (in->rho_T - r->rho1);
        double c = -expm1(-X) + exp(-X) * x * hy_phi2(x);
        sum += r->sign * d * c;
    }
    return -sigma0 * sum / one_minus_A;
}

int hy_steady_init_buf(hy_steady *st, const hy_model *m, const hy_input *in, double *y_run, hy_error *err)
{
    HY_NONNULL(err, st);
    st->y_run = NULL;
    HY_NONNULL(err, m);
    HY_INPUT_READY(err, in);
    HY_NONNULL(err, y_run);
    int rc = hy_model_validate(m, err);
    if (rc)
        return rc;
    st->in = in;
    st->sigma0 = m->sigma0;
    st->g0 = hy_model_g0(m);
    st->a = m->sigma0 / st->g0;
    st->y_run = NULL;
    if (!isfinite(st->a) || !(st->a > 0))
        return hy_error_set(err, HY_EINVAL, "sigma0/g(0) = %g/%g is not a finite positive number", m->sigma0, st->g0);
    st->contraction = exp(-st->a * in->rho_T);
    st->y_run = y_run;
    /* hy_limit_step's pair of each run, once for y°(0) and the runs (up to
     * STEP_MEMO runs, on the stack: a bimodal input has 4) */
    double e[STEP_MEMO], em[STEP_MEMO];
    int memo = in->nruns <= STEP_MEMO;
    for (size_t i = 0; memo && i < in->nruns; i++) {
        double x = st->a * (in->runs[i].rho1 - in->runs[i].rho0);
        e[i] = exp(-x);
        em[i] = expm1(-x);
    }
    double y = steady_y0(in, st->sigma0, st->g0, st->a, memo ? e : NULL, em);
    for (size_t i = 0; i < in->nruns; i++) {
        const hy_run *r = &in->runs[i];
        st->y_run[i] = y;
        y = memo ? step_e(st->g0, y, r->sign, e[i], em[i]) : hy_limit_step(st->a, st->g0, y, r->sign, r->rho1 - r->rho0);
    }
    st->y_run[in->nruns] = st->y_run[0]; /* y°(T) = y°(0) (Theorem 2(b)) */
    return HY_OK;
}

int hy_steady_init(hy_steady *st, const hy_model *m, const hy_input *in, hy_error *err)
{
    HY_NONNULL(err, st);
    st->y_run = NULL;
    HY_NONNULL(err, m);
    HY_INPUT_READY(err, in);
    double *y_run = malloc((in->nruns + 1) * sizeof *y_run);
    if (!y_run) {
        st->y_run = NULL;
        int rc = hy_model_validate(m, err); /* a bad model is named first, as ever */
        return rc ? rc : hy_error_set(err, HY_ENOMEM, "out of memory");
    }
    int rc = hy_steady_init_buf(st, m, in, y_run, err);
    if (rc) {
        free(y_run);
        st->y_run = NULL;
    }
    return rc;
}

void hy_steady_free(hy_steady *st)
{
    if (st) {
        free(st->y_run);
        st->y_run = NULL;
    }
}

int hy__steady_ready(const hy_steady *st)
{
    return st && st->y_run && hy__input_ready(st->in);
}

double hy_steady_at_rho(const hy_steady *st, double rho)
{
    if (!hy__steady_ready(st))
        return NAN;
    double r;
    size_t i = hy_input_run_at(st->in, rho, &r);
    const hy_run *run = &st->in->runs[i];
    double d = r - run->rho0;
    if (d > run->rho1 - run->rho0)
        d = run->rho1 - run->rho0;
    return hy_limit_step(st->a, st->g0, st->y_run[i], run->sign, d);
}

double hy_steady_at(const hy_steady *st, double t)
{
    if (!hy__steady_ready(st))
        return NAN;
    double tm;
    size_t i = hy_input_piece_at(st->in, t, &tm, NULL);
    const hy_piece *p = &st->in->pieces[i];
    return hy_steady_at_rho(st, p->rho0 + fabs(hy_piece_u(p, tm) - p->u0));
}

double hy_ystar_k(const hy_steady *st, double x0, double k, double t)
{
    if (!hy__steady_ready(st))
        return NAN;
    double tm;
    size_t i = hy_input_piece_at(st->in, t, &tm, NULL);
    if (t >= st->in->period) /* t = T exactly: the end of cycle k */
        tm = st->in->period, i = st->in->npieces - 1;
    const hy_piece *p = &st->in->pieces[i];
    double r = p->rho0 + fabs(hy_piece_u(p, tm) - p->u0);
    double yo = hy_steady_at_rho(st, r);
    if (tm >= st->in->period)
        yo = st->y_run[st->in->nruns];
    /* the difference of two solutions decays as e^{-aρ} (linear in y) */
    double decay = exp(-(st->a * st->in->rho_T) * k) * exp(-st->a * r);
    return yo + (st->sigma0 * x0 - st->y_run[0]) * decay;
}

double hy_ystar_at(const hy_steady *st, double x0, double t)
{
    if (!hy__steady_ready(st))
        return NAN;
    double k = floor(t / st->in->period);
    double tm = hy_input_reduce(st->in, t, k); /* k T carried exactly */
    if (tm < 0 && k > 0)
        tm = hy_input_reduce(st->in, t, --k);
    if (tm < 0)
        tm = 0;
    return hy_ystar_k(st, x0, k, tm);
}

void hy_steady_sample(const hy_steady *st, size_t n, double *u_out, double *y_out)
{
    if (!hy__steady_ready(st) || !y_out || n < 2)
        return;
    const hy_input *in = st->in;
    double h = in->rho_T / (double)(n - 1);
    double Eh = exp(-st->a * h);
    size_t j = 0;
    for (size_t i = 0; i < in->nruns && j < n; i++) {
        const hy_run *run = &in->runs[i];
        double target = run->sign * st->g0;
        size_t jend = (i + 1 == in->nruns) ? n : (size_t)ceil(run->rho1 / h);
        if (jend > n)
            jend = n;
        double d = 0;
        for (size_t q = 0; j < jend; j++, q++) {
            double rr = (double)j * h - run->rho0;
            if ((q & 63) == 0) /* exact anchor */
                d = hy_limit_step(st->a, st->g0, st->y_run[i], run->sign, rr) - target;
            else
                d *= Eh;
            y_out[j] = target + d;
            if (u_out)
                u_out[j] = run->u0 + run->sign * rr;
        }
    }
    if (n >= 2) /* exact periodic end point */
        y_out[n - 1] = st->y_run[in->nruns];
}

int hy_theorem_a_init(hy_theorem_a *th, double sigma0, double g0, double umin1, double umin2,
                      double umax1, double umax2, hy_error *err)
{
    HY_NONNULL(err, th);
    hy_input in;
    int rc = hy_input_bimodal(&in, umin1, umin2, umax1, umax2, NULL, HY_SHAPE_LINEAR, err);
    if (rc)
        return rc;
    if (!(sigma0 > 0) || !isfinite(sigma0) || !(g0 > 0) || !isfinite(g0)) {
        hy_input_free(&in);
        return hy_error_set(err, HY_EINVAL, "Theorem A needs finite sigma0 > 0 and g(0) > 0 (got %g, %g)", sigma0, g0);
    }
    th->a = sigma0 / g0;
    th->g0 = g0;
    th->umin1 = umin1;
    th->umin2 = umin2;
    th->umax1 = umax1;
    th->umax2 = umax2;
    th->rho[0] = 0;
    th->rho[1] = umax1 - umin1;
    th->rho[2] = th->rho[1] + umax1 - umin2;
    th->rho[3] = th->rho[2] + umax2 - umin2;
    th->rho[4] = th->rho[3] + umax2 - umin1;
    th->rho[5] = umax1 - umin2 + th->rho[2];
    /* y°(0) of the theorem, rewritten with e^{-a(ϱ4-ϱi)} factors only:
       y°(0) = g0 (2E_1 - 2E_2 + 2E_3 - E_4 - 1)/(1 - E_4), E_i = e^{-a(ϱ4 - ϱi)} */
    double a = th->a, r4 = th->rho[4];
    double num = 2 * exp(-a * (r4 - th->rho[1])) - 2 * exp(-a * (r4 - th->rho[2])) +
                 2 * exp(-a * (r4 - th->rho[3])) - exp(-a * r4) - 1;
    double y0;
    if (a * r4 >= 1)
        y0 = g0 * num / -expm1(-a * r4);
    else /* small aϱ4: the general cancellation-free fixed point */
        y0 = steady_y0(&in, sigma0, g0, a, NULL, NULL);
    th->y[0] = y0;
    for (int i = 1; i <= 4; i++)
        th->y[i] = hy_limit_step(a, g0, th->y[i - 1], (i % 2) ? +1 : -1, th->rho[i] - th->rho[i - 1]);
    hy_input_free(&in);
    return HY_OK;
}

static int theorem_piece(const hy_theorem_a *th, double *rho)
{
    double r = fmod(*rho, th->rho[4]);
    if (r < 0)
        r += th->rho[4];
    int i = 0;
    while (i < 3 && r >= th->rho[i + 1])
        i++;
    *rho = r;
    return i;
}

double hy_theorem_a_eval(const hy_theorem_a *th, double rho)
{
    if (!th || !isfinite(rho))
        return NAN;
    int i = theorem_piece(th, &rho);
    return hy_limit_step(th->a, th->g0, th->y[i], (i % 2) ? -1 : +1, rho - th->rho[i]);
}

double hy_theorem_a_psi(const hy_theorem_a *th, double rho)
{
    if (!th || !isfinite(rho))
        return NAN;
    int i = theorem_piece(th, &rho);
    const double base[4] = {th->umin1, th->umax1, th->umin2, th->umax2};
    return base[i] + ((i % 2) ? -1 : +1) * (rho - th->rho[i]);
}

double hy_theorem_a_printed(const hy_theorem_a *th, double rho, int statement_signs)
{
    if (!th || !isfinite(rho))
        return NAN;
    double a = th->a, g0 = th->g0;
    const double *q = th->rho;
    double y = g0 * exp(-a * q[4]) / (1 - exp(-a * q[4])) *
               (2 * exp(a * q[1]) - 2 * exp(a * q[2]) + 2 * exp(a * q[3]) - exp(a * q[4]) - 1);
    int i = theorem_piece(th, &rho);
    double yi = y;
    for (int j = 1; j <= i; j++) { /* y°(ϱ_j) as printed: "+" in every recursion */
        double s = statement_signs ? 1.0 : ((j % 2) ? 1.0 : -1.0);
        yi = exp(-a * (q[j] - q[j - 1])) * (yi + s * g0 * (exp(a * (q[j] - q[j - 1])) - 1));
    }
    double s = statement_signs ? -1.0 : ((i % 2) ? -1.0 : 1.0);
    return exp(-a * (rho - q[i])) * (yi + s * g0 * (exp(a * (rho - q[i])) - 1));
}
