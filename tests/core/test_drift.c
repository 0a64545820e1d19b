/* SPDX-License-Identifier: MIT */
/* test_drift.c: time that does not drift (issue 11, part 2).
 *
 * 1. The exact y_γ of the stiff LuGre (Åström & Canudas de Wit: σ0 = 1e5,
 *    σ1 = √σ0, Fc = 1, Fs = 1.5, vs = 1 mm/s, β = 2; 0.1 mm bimodal input,
 *    γ = 1) in period 1, 60 and 1e6 against a __float128 evaluation of the
 *    same formula at the same double times, with the time within the period
 *    formed exactly in 113 bits: the error in periods 60 and 1e6 must stay
 *    within 10x the period-1 error (it grew to 1.2e-9 by period 60 when the
 *    period start was a running sum).
 * 2. Output times a few ulps from a breakpoint: msbdf on Example 3 (the
 *    command of the issue) and rk1imp/rk2imp/rk4imp on the stiff problem used
 *    to fail on a step of one ulp; they must succeed, and agree with the exact
 *    solution to a bound set by their tolerance.
 */
#include <gsl/gsl_errno.h>
#include <quadmath.h>

#include "hy_gamma.h"
#include "hy_ode.h"
#include "tutil.h"

typedef __float128 q;

static q g_q(const hy_model *m, q v)
{
    q r = fabsq(v / m->vs);
    return (q)m->fc + ((q)m->fs - m->fc) * expq(-powq(r, m->beta));
}

/* z at the end of piece p from z0 (quad). */
static q piece_end_q(const hy_model *m, const hy_piece *p, double gamma, q z)
{
    q v = ((q)p->u1 - p->u0) / ((q)p->t1 - p->t0);
    if (v == 0)
        return z;
    q lam = m->sigma0 * fabsq(v) / g_q(m, v / gamma), zeq = v / lam;
    return zeq + (z - zeq) * expq(-lam * ((q)p->t1 - p->t0));
}

/* y at time tm within the period, from z at the period's start (quad). */
static q y_in_period_q(const hy_model *m, const hy_input *in, double gamma, q z, q tm)
{
    size_t i = 0;
    while (i + 1 < in->npieces && tm >= in->pieces[i].t1) {
        z = piece_end_q(m, &in->pieces[i], gamma, z);
        i++;
    }
    const hy_piece *p = &in->pieces[i];
    q v = ((q)p->u1 - p->u0) / ((q)p->t1 - p->t0), zz = z, zd = 0;
    if (v != 0) {
        q lam = m->sigma0 * fabsq(v) / g_q(m, v / gamma), zeq = v / lam;
        zz = zeq + (z - zeq) * expq(-lam * (tm - p->t0));
        zd = -lam * (zz - zeq);
    }
    return m->sigma0 * zz + (q)m->sigma1 / gamma * zd + (q)m->sigma2 * v / gamma;
}

static q period_map_q(const hy_model *m, const hy_input *in, double gamma, q z)
{
    for (size_t i = 0; i < in->npieces; i++)
        z = piece_end_q(m, &in->pieces[i], gamma, z);
    return z;
}

static void stiff(hy_model *m, hy_input *in)
{
    hy_error err;
    hy_model_lugre_init(m, 1e5, sqrt(1e5), 1, 1.5, 1e-3, 2);
    m->x0 = 0;
    const double tm[4] = {0.1, 0.18, 0.31, 0.46};
    if (hy_input_bimodal(in, 0, 0.2e-4, 1e-4, 1.5e-4, tm, HY_SHAPE_LINEAR, &err))
        fprintf(stderr, "input: %s\n", err.msg);
}

static void exact_periods(void)
{
    enum { PER = 50, NK = 3 };
    const double ks[NK] = {0, 59, 999999}; /* periods 1, 60 and 1e6 */
    hy_model m;
    hy_input in;
    hy_error err;
    stiff(&m, &in);
    double T = in.period, t[NK * PER], y[NK * PER];
    for (int a = 0; a < NK; a++)
        for (int i = 0; i < PER; i++)
            t[a * PER + i] = ks[a] * T + T * (i + 0.37) / PER;
    int rc = hy_gamma_exact(&m, &in, 1, t, NK * PER, y, NULL, &err);
    CHECK(rc == HY_OK, "exact over 1e6 periods: %s", err.msg);
    /* z at the start of period k: from x0 for k = 0; for k >= 1 the period map
     * contracts by e^{-Σ λΔt} ≈ e^{-40}, so its fixed point (4 iterations)
     * is z(kT) to far below double precision. */
    q z0 = m.x0, zstar = period_map_q(&m, &in, 1, z0);
    for (int it = 0; it < 4; it++)
        zstar = period_map_q(&m, &in, 1, zstar);
    double e[NK];
    for (int a = 0; a < NK; a++) {
        e[a] = 0;
        for (int i = 0; i < PER; i++) {
            double tt = t[a * PER + i];
            q tmq = (q)tt - (q)ks[a] * (q)T; /* exact: 53 + 20 bits < 113 */
            q yr = y_in_period_q(&m, &in, 1, a ? zstar : z0, tmq);
            e[a] = fmax(e[a], fabs((double)((q)y[a * PER + i] - yr)));
        }
    }
    double g0 = hy_model_g0(&m), floor1 = fmax(e[0], 1e-15 * g0);
    printf("stiff LuGre, exact solver: max error period 1 %.3g, period 60 %.3g, period 1e6 %.3g (g(0) = %g)\n", e[0],
           e[1], e[2], g0);
    CHECK(e[0] <= 1e-13 * g0, "period-1 error %.3g above 1e-13 g(0)", e[0]);
    CHECK(e[1] <= 10 * floor1, "period-60 error %.3g > 10x period-1 error %.3g", e[1], floor1);
    CHECK(e[2] <= 10 * floor1, "period-1e6 error %.3g > 10x period-1 error %.3g", e[2], floor1);
    hy_input_free(&in);
}

/* the GSL steppers at output times that land within ulps of a breakpoint */
static void near_breakpoints(void)
{
    hy_error err;
    hy_model m;
    hy_input in;
    /* the command: Example 3, γ = 1, 10 cycles, 81 points, msbdf
     * (t = 36.800000000000004 lies one ulp past a breakpoint) */
    hy_model_lugre_init(&m, 1, 1, 1, 2, 1, 1);
    m.x0 = 0;
    hy_input_bimodal(&in, 0, 0.2, 1, 1.5, NULL, HY_SHAPE_LINEAR, &err);
    enum { N = 81 };
    double t[N], y[N], ye[N];
    for (int i = 0; i < N; i++)
        t[i] = 10 * in.period * i / (N - 1);
    hy_ode_opts o = hy_ode_defaults();
    o.stepper = "msbdf";
    o.rtol = 1e-10;
    o.atol = 1e-12;
    int rc = hy_ode_solve(&m, &in, 1, &o, t, N, y, NULL, &err);
    CHECK(rc == HY_OK, "msbdf on Example 3, 10 cycles: %s", err.msg);
    hy_gamma_exact(&m, &in, 1, t, N, ye, NULL, &err);
    double e = 0;
    for (int i = 0; i < N && !rc; i++)
        e = fmax(e, fabs(y[i] - ye[i]));
    /* rtol 1e-10 over 40 pieces, |y| <= 2: 1e-7 leaves room for the
     * global growth of the local errors; a wrong piece at a breakpoint
     * would be off by O(1) (ż jumps) */
    CHECK(!rc && e < 1e-7, "msbdf error %.3g", e);
    hy_input_free(&in);

    /* stiff problem with the normalised bimodal input (T = 4.6e-4 s): 4 cycles
     * of 81 points put t = 0.00138 = 3T one ulp from the breakpoint */
    hy_model_lugre_init(&m, 1e5, sqrt(1e5), 1, 1.5, 1e-3, 2);
    m.x0 = 0;
    hy_input_bimodal(&in, 0, 0.2e-4, 1e-4, 1.5e-4, NULL, HY_SHAPE_LINEAR, &err);
    for (int i = 0; i < N; i++)
        t[i] = 4 * in.period * i / (N - 1);
    hy_gamma_exact(&m, &in, 1, t, N, ye, NULL, &err);
    const char *imp[] = {"rk1imp", "rk2imp", "rk4imp"};
    for (int s = 0; s < 3; s++) {
        o.stepper = imp[s];
        o.rtol = 1e-8;
        o.atol = 1e-2 * o.rtol * hy_model_g0(&m) / m.sigma0;
        rc = hy_ode_solve(&m, &in, 1, &o, t, N, y, NULL, &err);
        CHECK(rc == HY_OK, "%s on the stiff problem: %s", imp[s], err.msg);
        e = 0;
        double ymax = 0;
        for (int i = 0; i < N && !rc; i++) {
            e = fmax(e, fabs(y[i] - ye[i]));
            ymax = fmax(ymax, fabs(ye[i]));
        }
        /* y reaches σ1 |ż| ≈ 630 at the breakpoints (v = ±1 m/s); 1e-4 max|y|
         * is above what rtol 1e-8 gives a first-order method and far below the
         * jump of ż that a wrong piece at a breakpoint would show (~max|y|) */
        CHECK(!rc && e < 1e-4 * ymax, "%s error %.3g (max|y| %.3g)", imp[s], e, ymax);
        printf("%s on the stiff problem, 4 cycles, 81 points: error %.3g\n", imp[s], e);
    }
    hy_input_free(&in);
}

/* The run the work estimate refuses (rk4, σ0 = 1e300) still reports a
 * non-finite solution by name when no limit stops it up front. */
static void refusal_and_nonfinite(void)
{
    hy_model m;
    hy_input in;
    hy_error err;
    hy_model_lugre_init(&m, 1e300, 1, 1, 2, 1, 1);
    hy_input_bimodal(&in, 0, 0.2, 1, 1.5, NULL, HY_SHAPE_LINEAR, &err);
    double t[2] = {0.5, 3}, y[2];
    hy_ode_opts o = hy_ode_defaults();
    o.stepper = "rk4";
    CHECK_MSG(hy_ode_solve(&m, &in, 5, &o, t, 2, y, NULL, &err), err, HY_EINVAL, "refused: rk4 at rtol 1e-08");
    CHECK(strstr(err.msg, "bsimp or msbdf") != NULL, "no advice: %s", err.msg);
    o.work_limit = 0;
    CHECK_MSG(hy_ode_solve(&m, &in, 5, &o, t, 2, y, NULL, &err), err, HY_ENUM, "ODE solution became non-finite (y[0] = ");
    hy_input_free(&in);
}

int main(void)
{
    gsl_set_error_handler_off();
    exact_periods();
    near_breakpoints();
    refusal_and_nonfinite();
    return tu_finish("drift");
}
