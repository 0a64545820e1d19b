/* SPDX-License-Identifier: MIT */
/* test_theorem_a.c: Theorem A's closed form = exact piece-by-piece propagation
 * = quadrature of Eqs. (6)+(8) = GSL integration at large γ, for Examples 2-4
 * and 1000 random bimodal and 1000 random multimodal inputs (fixed seed). */
#include <gsl/gsl_errno.h>
#include <stdlib.h>

#include "hy_gamma.h"
#include "hy_limit.h"
#include "hy_loops.h"
#include "hy_ode.h"
#include "refs.h"
#include "tutil.h"

/* Tolerances (all relative to g(0), the scale of |y°| <= g(0)):
 *  - closed form vs propagation: 1e-12.  Both are exact formulas evaluated in
 *    O(10) double operations (rounding ~1e-15 each, amplified at most by
 *    1/(1 - e^{-aϱ4}) <= ~50 for the drawn parameters).
 *  - quadrature: 1e-9.  QAG is asked for 1e-13 relative per piece; the
 *    integrand e^{a(ρ-ρref)} u̇ is smooth on each piece, so 1e-9 leaves margin
 *    for the summation and the division by 1 - e^{-aρ_T}.
 *  - GSL at γ = 1e6: the difference y_γ - y° is O(v_max/γ) (g(u̇/γ) - g(0) and
 *    the σ1 ż/γ term), so the bound is 50 v_max (1 + σ1)/γ plus the solver's 1e-9. */
#define TOL_EXACT 1e-12
#define TOL_QUAD 1e-9

static gsl_integration_workspace *W;
static double worst_quad, worst_exact, worst_gsl; /* largest error/tolerance seen */

typedef struct case_t {
    hy_model m;
    hy_input in;
    double vmax;
} case_t;

static double vmax_of(const hy_input *in)
{
    double v = 0;
    for (size_t i = 0; i < in->npieces; i++) {
        const hy_piece *p = &in->pieces[i];
        double s = fabs(p->u1 - p->u0) / (p->t1 - p->t0);
        v = fmax(v, p->shape == HY_PIECE_LINEAR ? s : s * 1.5707963267948966);
    }
    return v;
}

/* propagation vs quadrature vs quad-precision composition vs GSL */
static void check_steady(const char *name, case_t *c, int with_gsl)
{
    hy_steady st;
    hy_error err;
    int rc = hy_steady_init(&st, &c->m, &c->in, &err);
    CHECK(rc == HY_OK, "%s: steady init: %s", name, err.msg);
    if (rc)
        return;
    double g0 = st.g0;
    for (int j = 0; j <= 40; j++) {
        double t = c->in.period * j / 40.0;
        double y = hy_steady_at(&st, t);
        double yq = ref_quad_steady(&c->in, st.sigma0, g0, t, W);
        worst_quad = fmax(worst_quad, fabs(y - yq) / (TOL_QUAD * g0));
        CHECK(fabs(y - yq) <= TOL_QUAD * g0, "%s: t=%g propagation %.17g vs quadrature %.17g", name, t, y, yq);
        double r = hy_input_rho(&c->in, t);
        double y128 = (double)ref_q_steady_rho(&c->in, st.sigma0, g0, r);
        worst_exact = fmax(worst_exact, fabs(hy_steady_at_rho(&st, r) - y128) / (TOL_EXACT * g0));
        CHECK(fabs(hy_steady_at_rho(&st, r) - y128) <= TOL_EXACT * g0, "%s: ϱ=%g propagation %.17g vs quad-precision %.17g",
              name, r, hy_steady_at_rho(&st, r), y128);
    }
    if (with_gsl) {
        /* start on the steady state; integrate 2 periods at γ = 1e6 with rk8pd */
        const double gamma = 1e6;
        enum { N = 81 };
        double t[N], y[N];
        for (int j = 0; j < N; j++)
            t[j] = c->in.period * (1.0 + j / (double)(N - 1));
        hy_model m = c->m;
        m.x0 = st.y_run[0] / m.sigma0;
        hy_ode_opts o = hy_ode_defaults();
        o.stepper = "rk8pd";
        o.rtol = 1e-11;
        o.atol = 1e-12 * g0;
        rc = hy_ode_solve(&m, &c->in, gamma, &o, t, N, y, NULL, &err);
        CHECK(rc == HY_OK, "%s: GSL: %s", name, err.msg);
        double tol = 50 * c->vmax * (1 + m.sigma1) / gamma * fmax(1, m.fs) + 1e-9 * g0;
        double worst = 0;
        for (int j = 0; j < N && !rc; j++)
            worst = fmax(worst, fabs(y[j] - hy_steady_at(&st, t[j])));
        worst_gsl = fmax(worst_gsl, worst / tol);
        CHECK(worst <= tol, "%s: GSL at γ=1e6 differs from y° by %.3g > %.3g", name, worst, tol);
    }
    hy_steady_free(&st);
}

/* Theorem A's closed form against the propagation, on ϱ and on ψ. */
static void check_theorem(const char *name, const hy_model *m, double u1, double u2, double u3, double u4)
{
    hy_theorem_a th;
    hy_error err;
    int rc = hy_theorem_a_init(&th, m->sigma0, hy_model_g0(m), u1, u2, u3, u4, &err);
    CHECK(rc == HY_OK, "%s: theorem: %s", name, err.msg);
    hy_input in;
    rc = rc || hy_input_bimodal(&in, u1, u2, u3, u4, NULL, HY_SHAPE_LINEAR, &err);
    if (rc)
        return;
    hy_steady st;
    hy_steady_init(&st, m, &in, &err);
    for (int j = 0; j <= 100; j++) {
        double r = th.rho[4] * j / 100.0;
        CHECK_CLOSE(hy_theorem_a_eval(&th, r), hy_steady_at_rho(&st, r), TOL_EXACT * th.g0, name);
        CHECK_CLOSE(hy_theorem_a_psi(&th, r), hy_input_psi(&in, r), 1e-15 * (1 + fabs(u4)), "psi");
    }
    /* Theorem A(b): the minor loop is exactly [ϱ1, ϱ5] */
    hy_loops L;
    rc = hy_loops_find(&st, &L, &err);
    CHECK(rc == HY_OK && L.nminor == 1, "%s: one minor loop expected, got %zu", name, L.nminor);
    if (!rc && L.nminor == 1) {
        CHECK_CLOSE(L.minor[0].rho_start, th.rho[1], 1e-14 * th.rho[4], "ϱ1");
        CHECK_CLOSE(L.minor[0].rho_close, th.rho[5], 1e-14 * th.rho[4], "ϱ5");
    }
    hy_loops_free(&L);
    hy_steady_free(&st);
    hy_input_free(&in);
}

static void examples(void)
{
    case_t c;
    hy_error err;
    /* Example 2: σ0 = σ1 = 1, Fc = 1, Fs = 2, vs = 1, β = 1; triangle 0..1, T = 2 */
    hy_model_lugre_init(&c.m, 1, 1, 1, 2, 1, 1);
    hy_input_triangle(&c.in, 0, 1, 2, &err);
    c.vmax = vmax_of(&c.in);
    check_steady("example 2", &c, 1);
    hy_input_free(&c.in);
    /* Example 3: same model, bimodal 0, 0.2, 1, 1.5 */
    hy_input_bimodal(&c.in, 0, 0.2, 1, 1.5, NULL, HY_SHAPE_LINEAR, &err);
    c.vmax = 1;
    check_steady("example 3", &c, 1);
    check_theorem("example 3", &c.m, 0, 0.2, 1, 1.5);
    hy_input_free(&c.in);
    /* Example 4: σ0 = 6; 0, 0.5, 1, 1.5 (Fig. 15), σ0 = 1 (Fig. 16), u_min,2 = 0.2 (Fig. 17) */
    const double s0[3] = {6, 1, 1}, um2[3] = {0.5, 0.5, 0.2};
    for (int k = 0; k < 3; k++) {
        hy_model_lugre_init(&c.m, s0[k], 1, 1, 2, 1, 1);
        hy_input_bimodal(&c.in, 0, um2[k], 1, 1.5, NULL, HY_SHAPE_LINEAR, &err);
        c.vmax = 1;
        check_steady("example 4", &c, 1);
        check_theorem("example 4", &c.m, 0, um2[k], 1, 1.5);
        hy_input_free(&c.in);
    }
}

static void random_model(hy_model *m)
{
    double fc = tu_unif(0.5, 2);
    hy_model_lugre_init(m, tu_logunif(0.05, 20), tu_unif(0, 1), fc, fc * tu_unif(1, 3), tu_unif(0.5, 2), 1);
}

static void random_bimodal(int n_cases)
{
    char name[64];
    for (int k = 0; k < n_cases; k++) {
        case_t c;
        hy_error err;
        random_model(&c.m);
        double u[4];
        u[0] = tu_unif(-1, 1);                         /* umin1 */
        u[1] = (k % 10 == 0) ? u[0] : u[0] + tu_unif(0, 1);   /* umin2 (ties sometimes) */
        u[2] = u[1] + tu_unif(0.05, 1.5);              /* umax1 */
        u[3] = (k % 10 == 5) ? u[2] : u[2] + tu_unif(0, 1);   /* umax2 */
        if (u[0] == u[1] && u[2] == u[3])
            u[3] += 0.3;
        double t[4], tc = 0;
        for (int i = 0; i < 4; i++)
            t[i] = (tc += tu_unif(0.2, 2));
        int shape = (k % 2) ? HY_SHAPE_COSINE : HY_SHAPE_LINEAR;
        int rc = hy_input_bimodal(&c.in, u[0], u[1], u[2], u[3], t, shape, &err);
        CHECK(rc == HY_OK, "random bimodal %d: %s", k, err.msg);
        if (rc)
            continue;
        c.vmax = vmax_of(&c.in);
        snprintf(name, sizeof name, "random bimodal %d", k);
        check_steady(name, &c, 1);
        check_theorem(name, &c.m, u[0], u[1], u[2], u[3]);
        hy_input_free(&c.in);
    }
}

static void random_multimodal(int n_cases)
{
    char name[64];
    for (int k = 0; k < n_cases; k++) {
        case_t c;
        hy_error err;
        random_model(&c.m);
        size_t n = 2 * (1 + tu_next() % 6);
        double e[12], tm[13];
        e[0] = tu_unif(-1, 0);
        tm[0] = 0;
        for (size_t i = 1; i < n; i++)
            e[i] = (i % 2) ? e[i - 1] + tu_unif(0.05, 2) : e[i - 1] - tu_unif(0.05, 2);
        for (size_t i = 1; i <= n; i++)
            tm[i] = tm[i - 1] + tu_unif(0.2, 2);
        /* the last step must fall back to e[0]: make e[n-1] a maximum above e[0] */
        if (e[n - 1] <= e[0])
            e[n - 1] = e[0] + tu_unif(0.05, 1);
        int shape = (k % 2) ? HY_SHAPE_COSINE : HY_SHAPE_LINEAR;
        int rc = hy_input_multimodal(&c.in, e, n, tm, shape, &err);
        if (rc) /* alternation can fail after the fix-up above: draw again */
            continue;
        c.vmax = vmax_of(&c.in);
        snprintf(name, sizeof name, "random multimodal %d", k);
        check_steady(name, &c, 1);
        hy_input_free(&c.in);
    }
}

int main(void)
{
    gsl_set_error_handler_off();
    W = gsl_integration_workspace_alloc(1000);
    examples();
    random_bimodal(1000);
    random_multimodal(1000);
    gsl_integration_workspace_free(W);
    printf("largest error / tolerance: exact %.3g, quadrature %.3g, GSL at gamma=1e6 %.3g\n",
           worst_exact, worst_quad, worst_gsl);
    return tu_finish("theorem_a");
}
