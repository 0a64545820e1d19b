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

int main(void)
{
    degenerate_loop(1e-3, 1e-12, 100);
    degenerate_loop(1e-3, 1e-12, 2000);
    const double ws[] = {1e-9, 1e-6, 1e-3, 0.3};
    for (int i = 0; i < 4; i++) {
        degenerate_loop(1, ws[i], 2);
        degenerate_loop(1, ws[i], 100);
    }
    return tu_finish("edges");
}
