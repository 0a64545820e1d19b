/* SPDX-License-Identifier: MIT */
/* test_extreme.c: stiff and extreme parameters stay finite and equal an
 * independent 113-bit (__float128) reference: σ0 ∈ [1e-6, 1e12],
 * g(0) ∈ [1e-12, 1e6], input amplitudes 1e-9 … 1e6, γ ∈ [1e-6, 1e15],
 * k up to 1e9 cycles; loop areas at inputs of ±1e200 and ±1e300. */
#include <gsl/gsl_errno.h>

#include "hy_gamma.h"
#include "hy_limit.h"
#include "hy_loops.h"
#include "refs.h"
#include "tutil.h"

/* Tolerance for y°: 1e-11 of the loop's own scale S = max|y_ref|.  The
 * double-precision evaluation rounds O(10) times per value; the two regimes
 * of the fixed point (direct composition for aρ_T >= 1, the cancellation-free
 * sum for aρ_T < 1) amplify that by at most ~ρ_T/Δ_min (<= 20 here).  Points
 * are placed at run starts plus fractions, and the sensitivity |dy/dϱ|·ϱ·ε to
 * the rounding of ϱ itself is added (it dominates when a is huge). */
static void steady_grid(void)
{
    const double s0[] = {1e-6, 1e-3, 1, 1e3, 1e5, 1e9, 1e12};
    const double g0s[] = {1e-12, 1e-6, 1.5, 1e3, 1e6};
    const double amps[] = {1e-9, 1e-3, 1, 1e3, 1e6};
    double worst = 0;
    for (size_t i = 0; i < sizeof s0 / sizeof *s0; i++)
        for (size_t j = 0; j < sizeof g0s / sizeof *g0s; j++)
            for (size_t k = 0; k < sizeof amps / sizeof *amps; k++)
                for (int shape = 0; shape < 2; shape++) {
                    double A = amps[k];
                    hy_model m;
                    hy_input in;
                    hy_error err;
                    hy_model_dahl_init(&m, s0[i] / g0s[j], g0s[j]); /* σ0 = ρ Fc, g = Fc */
                    m.sigma0 = s0[i];
                    int rc = shape ? hy_input_bimodal(&in, 0, 0.2 * A, A, 1.5 * A, NULL, HY_SHAPE_LINEAR, &err)
                                   : hy_input_multimodal(&in, (const double[]){0, A, 0.3 * A, 0.9 * A, 0.5 * A, 1.7 * A}, 6, NULL,
                                                         HY_SHAPE_LINEAR, &err);
                    CHECK(rc == HY_OK, "input: %s", err.msg);
                    hy_steady st;
                    rc = hy_steady_init(&st, &m, &in, &err);
                    CHECK(rc == HY_OK, "σ0=%g g0=%g: %s", s0[i], g0s[j], err.msg);
                    if (rc) {
                        hy_input_free(&in);
                        continue;
                    }
                    double ys[64], yr[64], rh[64], S = 0;
                    for (int q = 0; q < 64; q++) {
                        const hy_run *r = &in.runs[q % in.nruns];
                        rh[q] = r->rho0 + (r->rho1 - r->rho0) * (q / (int)in.nruns) / 16.0;
                        ys[q] = hy_steady_at_rho(&st, rh[q]);
                        yr[q] = (double)ref_q_steady_rho(&in, m.sigma0, g0s[j], rh[q]);
                        S = fmax(S, fabs(yr[q]));
                    }
                    for (int q = 0; q < 64; q++) {
                        double sens = 2 * st.a * st.g0 * in.rho_T * 2.3e-16;
                        double tol = 1e-11 * S + sens;
                        CHECK(isfinite(ys[q]) && fabs(ys[q] - yr[q]) <= tol,
                              "σ0=%g g0=%g amp=%g ϱ=%g: %.17g vs quad %.17g (tol %.3g)", s0[i], g0s[j], A, rh[q], ys[q], yr[q], tol);
                        if (S > 0)
                            worst = fmax(worst, fabs(ys[q] - yr[q]) / tol);
                    }
                    CHECK(fabs(st.y_run[0]) <= st.g0 * (1 + 1e-15), "|y°(0)| <= g(0) at σ0=%g g0=%g", s0[i], g0s[j]);
                    hy_loops L;
                    rc = hy_loops_find(&st, &L, &err);
                    /* energy >= 0 up to rounding of the terms y·Δu (~1e-16 S·range) */
                    CHECK(rc == HY_OK && isfinite(L.area_period) && L.area_period >= -1e-13 * S * 1.7 * A,
                          "loops at σ0=%g g0=%g amp=%g: energy %g", s0[i], g0s[j], A, L.area_period);
                    for (size_t q = 0; q < L.nminor; q++)
                        CHECK(isfinite(L.minor[q].area), "minor loop area finite");
                    hy_loops_free(&L);
                    hy_steady_free(&st);
                    hy_input_free(&in);
                }
    printf("steady state over the extreme grid: largest error/tolerance %.3g\n", worst);
}

/* k up to 1e9: y*_{u,k} against the period map raised to the k-th power by
 * binary exponentiation in quad precision. */
static void many_cycles(void)
{
    const double s0[] = {1e-6, 1e-3, 1, 1e4};
    const double ks[] = {0, 1, 10, 1e3, 1e6, 1e9};
    for (size_t i = 0; i < 4; i++) {
        hy_model m;
        hy_input in;
        hy_error err;
        hy_model_dahl_init(&m, s0[i] / 1e6 * 1e6, 1);
        m.sigma0 = s0[i];
        m.fc = m.fs = 1e3; /* g0 = 1e3: a down to 1e-9, so 1e9 cycles matter */
        m.x0 = 5e2 / s0[i];
        hy_input_bimodal(&in, 0, 0.2, 1, 1.5, NULL, HY_SHAPE_LINEAR, &err);
        hy_steady st;
        hy_steady_init(&st, &m, &in, &err);
        __float128 a = (__float128)m.sigma0 / ((__float128)1e3), A, B;
        ref_q_map(&in, a, ((__float128)1e3), &A, &B);
        for (size_t j = 0; j < 6; j++) {
            /* (A, B)^k: y_k(0) = A^k y0 + B (1 + A + ... + A^{k-1}) */
            __float128 Ak = 1, Bk = 0, P = A, Q = B;
            unsigned long long k = (unsigned long long)ks[j];
            while (k) {
                if (k & 1) {
                    Bk = P * Bk + Q;
                    Ak = P * Ak;
                }
                Q = P * Q + Q;
                P = P * P;
                k >>= 1;
            }
            double ref = (double)(Ak * ((__float128)m.sigma0 * (__float128)m.x0) + Bk);
            double got = hy_ystar_k(&st, m.x0, ks[j], 0);
            CHECK(isfinite(got) && fabs(got - ref) <= 1e-9 * 1e3,
                  "σ0=%g k=%g: y*_{u,k}(0) = %.17g vs quad %.17g", s0[i], ks[j], got, ref);
        }
        hy_steady_free(&st);
        hy_input_free(&in);
    }
}

/* y_γ for γ ∈ [1e-6, 1e15] against a quad-precision piecewise exponential */
static void gamma_extremes(void)
{
    const double gs[] = {1e-6, 1e-3, 1, 1e3, 1e9, 1e15};
    const double s0[] = {1e-3, 1, 1e5, 1e12};
    enum { N = 97 };
    double t[N], y[N];
    for (size_t i = 0; i < 4; i++)
        for (size_t j = 0; j < 6; j++) {
            hy_model m;
            hy_input in;
            hy_error err;
            hy_model_lugre_init(&m, s0[i], sqrt(s0[i]), 1, 1.5, 1e-3, 2);
            hy_input_bimodal(&in, 0, 0.2e-4, 1e-4, 1.5e-4, (const double[]){1, 2, 3, 4}, HY_SHAPE_LINEAR, &err);
            for (int q = 0; q < N; q++)
                t[q] = 2 * in.period * q / (N - 1.0) + 1e-3;
            int rc = hy_gamma_exact(&m, &in, gs[j], t, N, y, NULL, &err);
            CHECK(rc == HY_OK, "γ=%g: %s", gs[j], err.msg);
            /* reference: z through pieces in quad precision */
            __float128 z = 0, S = 0, refy[N];
            size_t q = 0;
            for (int cyc = 0; cyc < 3 && q < N; cyc++)
                for (size_t p = 0; p < in.npieces && q < N; p++) {
                    const hy_piece *pc = &in.pieces[p];
                    __float128 t0 = cyc * (__float128)in.period + pc->t0, t1 = t0 + (pc->t1 - pc->t0);
                    __float128 v = ((__float128)pc->u1 - pc->u0) / ((__float128)pc->t1 - pc->t0);
                    __float128 av = v < 0 ? -v : v;
                    __float128 g = 1 + ((__float128)0.5) * expq(-powq(av / (gs[j] * ((__float128)1e-3)), 2));
                    __float128 lam = (__float128)m.sigma0 * av / g, zeq = (v > 0 ? g : -g) / m.sigma0;
                    while (q < N && t[q] < t1) {
                        __float128 zz = zeq + (z - zeq) * expq(-lam * (t[q] - t0));
                        __float128 zd = -lam * (zz - zeq);
                        refy[q] = m.sigma0 * zz + (__float128)m.sigma1 / gs[j] * zd;
                        S = fmaxq(S, fabsq(refy[q]));
                        q++;
                    }
                    z = zeq + (z - zeq) * expq(-lam * (t1 - t0));
                }
            for (q = 0; q < N && !rc; q++) {
                double tol = 1e-10 * (double)S + 1e-300;
                CHECK(isfinite(y[q]) && fabs(y[q] - (double)refy[q]) <= tol, "σ0=%g γ=%g t=%g: %.17g vs quad %.17g", s0[i],
                      gs[j], t[q], y[q], (double)refy[q]);
            }
            hy_input_free(&in);
        }
}

/* Loop areas at inputs of ±1e200 and ±1e300 (issue 36 item 6): the runs'
 * a d² φ2(ad) overflowed (d², and x² inside φ2) and the areas and energy
 * were NaN although they fit.  Dahl with σ0 = 6, g(0) = 2 on the bimodal
 * input (-A, -A/2, A/2, A): every run saturates at once (a d = 3e200), so
 * the loops are rectangles 2 g0 (hi - lo) up to terms g0/a (1e-200 of
 * them): major own 2 g0 2A, minor 2 g0 A, the major's path round both, the
 * energy both; each within 1e-12 relative. */
static void huge_amplitudes(void)
{
    const double amps[] = {1e200, 1e300};
    for (size_t k = 0; k < sizeof amps / sizeof *amps; k++) {
        double A = amps[k], g0 = 2;
        hy_model m;
        hy_input in;
        hy_error err;
        hy_model_dahl_init(&m, 6 / g0, g0);
        m.sigma0 = 6;
        int rc = hy_input_bimodal(&in, -A, -0.5 * A, 0.5 * A, A, NULL, HY_SHAPE_LINEAR, &err);
        CHECK(rc == HY_OK, "input: %s", err.msg);
        hy_steady st;
        if (rc || (rc = hy_steady_init(&st, &m, &in, &err))) {
            CHECK(0, "amp %g: %s", A, err.msg);
            hy_input_free(&in);
            continue;
        }
        hy_loops L;
        rc = hy_loops_find(&st, &L, &err);
        double major = 2 * g0 * (2 * A), minor = 2 * g0 * A;
        CHECK(rc == HY_OK && L.nminor == 1, "amp %g: one minor loop (%s)", A, rc ? err.msg : "");
        if (!rc) {
            CHECK_CLOSE(L.major.own_area / major, 1, 1e-12, "major loop's own area / 2 g0 (hi - lo)");
            CHECK_CLOSE(L.major.area / (major + minor), 1, 1e-12, "major loop's area (round the minor too)");
            if (L.nminor == 1)
                CHECK_CLOSE(L.minor[0].area / minor, 1, 1e-12, "minor loop's area / 2 g0 (hi - lo)");
            CHECK_CLOSE(L.area_period / (major + minor), 1, 1e-12, "energy per cycle");
            hy_loops_free(&L);
        }
        hy_steady_free(&st);
        hy_input_free(&in);
    }
}

int main(void)
{
    gsl_set_error_handler_off();
    steady_grid();
    many_cycles();
    gamma_extremes();
    huge_amplitudes();
    return tu_finish("extreme");
}
