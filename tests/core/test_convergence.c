/* SPDX-License-Identifier: MIT */
/* test_convergence.c: ‖y_γ - y*_u‖∞ falls as γ grows (Examples 2 and 3,
 * γ = 1 … 1e6), the exact y_γ agrees with GSL, and y*_{u,k} → y°_u at the
 * predicted geometric rate e^{-aρ_T} per cycle (Theorem 2). */
#include <gsl/gsl_errno.h>

#include "hy_gamma.h"
#include "hy_limit.h"
#include "hy_ode.h"
#include "tutil.h"

enum { N = 3001 };
static double T[N], Y[N];

/* sup over 3 periods of |y_γ - y*| from x0 = 0 */
static double sup_gamma(const hy_model *m, const hy_input *in, const hy_steady *st, double gamma)
{
    hy_error err;
    for (int j = 0; j < N; j++)
        T[j] = 3 * in->period * j / (N - 1.0);
    int rc = hy_gamma_exact(m, in, gamma, T, N, Y, NULL, &err);
    CHECK(rc == HY_OK, "exact: %s", err.msg);
    double sup = 0;
    for (int j = 1; j < N; j++) /* j = 0: y_γ(0) carries (σ1/γ)ż(0), y*(0) does not */
        sup = fmax(sup, fabs(Y[j] - hy_ystar_at(st, m->x0, T[j])));
    return sup;
}

static void gamma_sweep(const char *name, const hy_model *m, const hy_input *in)
{
    hy_steady st;
    hy_error err;
    hy_steady_init(&st, m, in, &err);
    double prev = INFINITY, first = 0, last = 0;
    for (double g = 1; g <= 1e6; g *= 10) {
        double s = sup_gamma(m, in, &st, g);
        /* monotone decrease, and O(1/γ) for large γ: the error times γ stays bounded */
        CHECK(s < prev, "%s: sup error at γ=%g (%.3g) not below γ/10 (%.3g)", name, g, s, prev);
        if (g >= 100)
            CHECK(s * g < 10, "%s: γ·error = %.3g at γ=%g, expected O(1)", name, s * g, g);
        if (g == 1)
            first = s;
        last = s;
        prev = s;
    }
    printf("%s: sup|y_γ - y*| = %.3g at γ=1, %.3g at γ=1e6\n", name, first, last);
    /* exact solver against GSL at γ = 10 (rk8pd, tight tolerance): the exact
       form is exact, so only the solver's error (~1e-10) separates them */
    double yex[N];
    for (int j = 0; j < N; j++)
        T[j] = 3 * in->period * j / (N - 1.0);
    hy_gamma_exact(m, in, 10, T, N, yex, NULL, &err);
    hy_ode_opts o = hy_ode_defaults();
    o.stepper = "rk8pd";
    o.rtol = 1e-12;
    o.atol = 1e-13;
    int rc = hy_ode_solve(m, in, 10, &o, T, N, Y, NULL, &err);
    CHECK(rc == HY_OK, "%s: GSL: %s", name, err.msg);
    double d = 0;
    for (int j = 0; j < N; j++)
        d = fmax(d, fabs(yex[j] - Y[j]));
    CHECK(d < 1e-9, "%s: exact vs rk8pd at γ=10 differ by %.3g", name, d);
    hy_steady_free(&st);
}

static void k_cycles(const char *name, const hy_model *m, const hy_input *in)
{
    hy_steady st;
    hy_error err;
    hy_steady_init(&st, m, in, &err);
    /* independent y*_{u,k}: propagate run by run from y*(0) = σ0 x0 */
    double y = m->sigma0 * m->x0, prev_sup = 0;
    for (int k = 0; k <= 12; k++) {
        double sup = 0, ybar = y;
        for (size_t i = 0; i < in->nruns; i++) {
            const hy_run *r = &in->runs[i];
            for (int q = 0; q <= 8; q++) { /* points inside the run */
                double d = (r->rho1 - r->rho0) * q / 8.0;
                double yk = hy_limit_step(st.a, st.g0, ybar, r->sign, d);
                /* the time where ρ_u = r->rho0 + d: search by bisection on the piece grid */
                double lo = 0, hi = in->period;
                for (int it = 0; it < 80; it++) {
                    double mid = 0.5 * (lo + hi);
                    if (hy_input_rho(in, mid) < r->rho0 + d)
                        lo = mid;
                    else
                        hi = mid;
                }
                double t = 0.5 * (lo + hi);
                double got = hy_ystar_k(&st, m->x0, k, t);
                CHECK(fabs(got - yk) <= 1e-9 * st.g0, "%s: y*_{u,%d} closed form %.17g vs propagation %.17g", name, k, got, yk);
                sup = fmax(sup, fabs(yk - hy_steady_at_rho(&st, r->rho0 + d)));
            }
            ybar = hy_limit_step(st.a, st.g0, ybar, r->sign, r->rho1 - r->rho0);
        }
        /* each value carries ~1e-16 g0 of rounding, so the ratio is only
           measurable to 1e-6 while sup >= 1e-8 g0 */
        if (k > 0 && sup > 1e-8 * st.g0)
            CHECK(fabs(sup / prev_sup - st.contraction) <= 1e-6,
                  "%s: convergence rate %.12g at k=%d, predicted e^{-aρ_T} = %.12g", name, sup / prev_sup, k, st.contraction);
        prev_sup = sup;
        y = ybar;
    }
    printf("%s: contraction per cycle %.6g\n", name, st.contraction);
    hy_steady_free(&st);
}

int main(void)
{
    gsl_set_error_handler_off();
    hy_model m;
    hy_input in;
    hy_error err;
    hy_model_lugre_init(&m, 1, 1, 1, 2, 1, 1);
    hy_input_triangle(&in, 0, 1, 2, &err);
    gamma_sweep("example 2", &m, &in);
    k_cycles("example 2", &m, &in);
    hy_input_free(&in);
    hy_input_bimodal(&in, 0, 0.2, 1, 1.5, NULL, HY_SHAPE_LINEAR, &err);
    gamma_sweep("example 3", &m, &in);
    k_cycles("example 3", &m, &in);
    m.x0 = 0.7; /* another initial state */
    k_cycles("example 3, x0 = 0.7", &m, &in);
    hy_input_free(&in);
    return tu_finish("convergence");
}
