/* SPDX-License-Identifier: MIT */
/* test_edges.c: the numerical edges of issue 11, part 3.
 * A minor loop w wide (bimodal s·(0, 1, 2) with u_min,2 = s - w) has area
 *     A = a w² [2 g0 φ2(aw) - (g0 + y1) φ1(aw)²]
 * (one run down from y1 = y° at its start, one back up; the closed form of
 * the two exponential arcs, derived by hand and evaluated here in long
 * double).  hy_loops must give it to relative 1e-12: with the widths taken
 * as differences of ϱ values near s it was off by 2e-7 for w = 1e-9 s (and
 * by 9e-5 for w = 1e-12 at s = 1, which hy_input now refuses: below 1e-10
 * of the input's scale).  Cases: w = 1e-12 absolute at s = 1e-3 (a = 50
 * and 1000), and w/s = 1e-9, 1e-6, 1e-3, 0.3 at s = 1 (a = 1 and 50).  When
 * a s << 1 the loop's y° stays far below g0 (y1 ~ 1e-6 g0 at s = 1e-3,
 * a = 1) and A ≈ -a w² y1 is the small remainder of terms of size a w² g0:
 * then its relative accuracy is ε g0/|y1|, as is that of y1 itself. */
#include <string.h>

#include "hy_loops.h"
#include "tutil.h"

static long double phi1l(long double x)
{
    return x < 1e-4L ? 1 - x / 2 + x * x / 6 - x * x * x / 24 : -expm1l(-x) / x;
}

static long double phi2l(long double x)
{
    return x < 1e-4L ? 0.5L - x / 6 + x * x / 24 - x * x * x / 120 : (x + expm1l(-x)) / (x * x);
}

static void degenerate_loop(double s, double w, double sigma0)
{
    hy_model m;
    hy_input in;
    hy_error err;
    hy_steady st;
    hy_loops L;
    hy_model_lugre_init(&m, sigma0, 0, 1, 2, 1, 1);
    double umin2 = s - w;
    w = s - umin2; /* exact (Sterbenz): the width the input really has */
    if (hy_input_bimodal(&in, 0, umin2, s, 2 * s, NULL, HY_SHAPE_LINEAR, &err) || hy_steady_init(&st, &m, &in, &err) ||
        hy_loops_find(&st, &L, &err)) {
        CHECK(0, "w = %g: %s", w, err.msg);
        return;
    }
    CHECK(L.nminor == 1, "w = %g: %zu minor loops", w, L.nminor);
    if (L.nminor == 1) {
        long double a = (long double)m.sigma0 / hy_model_g0(&m), g0 = hy_model_g0(&m), y1 = L.minor[0].y_start;
        long double x = a * w;
        long double A = a * w * w * (2 * g0 * phi2l(x) - (g0 + y1) * phi1l(x) * phi1l(x));
        double rel = fabs((double)((L.minor[0].area - A) / A));
        printf("minor loop %.0e wide at scale %g, a = %g: area %.17g, exact %.17Lg, relative error %.2g\n", w, s, (double)a,
               L.minor[0].area, A, rel);
        CHECK(rel <= 1e-12, "w = %g, a = %g: area %.17g vs %.17Lg (relative %.3g > 1e-12)", w, (double)a,
              L.minor[0].area, A, rel);
    }
    hy_loops_free(&L);
    hy_steady_free(&st);
    hy_input_free(&in);
}

/* Issue 37's memos give the same bits as the expressions they stand for
 * (a table-only sweep must print the same digits): hy_limit_step_area_em
 * with expm1(-a d) is hy_limit_step_area, and the steady state's y° at each
 * run's end is hy_limit_step from the run before, as computed without the
 * per-run exponentials kept (inputs of 4 and 16 runs, kept; 18, not). */
static int same_bits(double x, double y)
{
    return !memcmp(&x, &y, sizeof x);
}

static void memo_bits(void)
{
    const double as[] = {1e-3, 0.5, 6, 1e3}, ds[] = {0, 1e-12, 1e-9, 1e-8, 0.3, 1, 1.7, 10, 1e200};
    const double ys[] = {0, -0.7, 1.3}, g0s[] = {1, 2};
    int bad = 0, n = 0;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 9; j++)
            for (int k = 0; k < 3; k++)
                for (int g = 0; g < 2; g++)
                    for (int s = -1; s <= 1; s += 2, n++) {
                        double a = as[i], d = ds[j];
                        bad += !same_bits(hy_limit_step_area_em(a, g0s[g], ys[k], s, d, expm1(-(a * d))),
                                          hy_limit_step_area(a, g0s[g], ys[k], s, d));
                    }
    CHECK(!bad, "hy_limit_step_area_em differs from hy_limit_step_area in %d of %d cases", bad, n);
    const size_t counts[] = {4, 16, 18};
    for (int c = 0; c < 3; c++) {
        double e[18];
        for (size_t i = 0; i < counts[c]; i++) /* alternating extrema of varied swings */
            e[i] = (i % 2 ? 1.0 : -1.0) * (0.3 + 0.11 * (double)((i * 7) % 5));
        for (int q = 0; q < 2; q++) {
            hy_model m;
            hy_input in;
            hy_steady st;
            hy_error err;
            hy_model_lugre_init(&m, q ? 40 : 0.05, 0, 1, 2, 1, 1); /* a rho_T above and below 1 */
            if (hy_input_multimodal(&in, e, counts[c], NULL, HY_SHAPE_LINEAR, &err) || hy_steady_init(&st, &m, &in, &err)) {
                CHECK(0, "%zu runs: %s", counts[c], err.msg);
                continue;
            }
            int differ = 0;
            for (size_t i = 0; i + 1 < in.nruns; i++) {
                const hy_run *r = &in.runs[i];
                differ += !same_bits(st.y_run[i + 1], hy_limit_step(st.a, st.g0, st.y_run[i], r->sign, r->rho1 - r->rho0));
            }
            CHECK(in.nruns == counts[c] && !differ, "%zu runs, sigma0 %g: %d of y°'s run ends differ from hy_limit_step's",
                  in.nruns, m.sigma0, differ);
            hy_steady_free(&st);
            hy_input_free(&in);
        }
    }
}

int main(void)
{
    memo_bits();
    degenerate_loop(1e-3, 1e-12, 100);
    degenerate_loop(1e-3, 1e-12, 2000);
    const double ws[] = {1e-9, 1e-6, 1e-3, 0.3};
    for (int i = 0; i < 4; i++) {
        degenerate_loop(1, ws[i], 2);
        degenerate_loop(1, ws[i], 100);
    }
    return tu_finish("edges");
}
