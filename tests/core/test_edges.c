/* test_edges.c: the numerical edges of issue 11, part 3.
 * A minor loop w = 1e-12 wide (bimodal 0, 1 - w, 1, 2) has area
 *     A = a w² [2 g0 φ2(aw) - (g0 + y1) φ1(aw)²]
 * (one run down from y1 = y° at its start, one back up; the closed form of
 * the two exponential arcs, derived by hand and evaluated here in long
 * double).  hy_loops must give it to relative 1e-12: it was off by 9e-5
 * when the widths were differences of ϱ values near 1.  The same formula
 * checks loops 1e-6, 1e-3 and 0.3 wide, for a = 1 and a = 50. */
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

static void degenerate_loop(double w, double sigma0)
{
    hy_model m;
    hy_input in;
    hy_error err;
    hy_steady st;
    hy_loops L;
    hy_model_lugre_init(&m, sigma0, 0, 1, 2, 1, 1);
    double umin2 = 1 - w;
    w = 1 - umin2; /* exact (Sterbenz): the width the input really has */
    if (hy_input_bimodal(&in, 0, umin2, 1, 2, NULL, HY_SHAPE_LINEAR, &err) || hy_steady_init(&st, &m, &in, &err) ||
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
        printf("minor loop %.0e wide, a = %g: area %.17g, exact %.17Lg, relative error %.2g\n", w, (double)a,
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
    const double ws[] = {1e-12, 1e-6, 1e-3, 0.3};
    for (int i = 0; i < 4; i++) {
        degenerate_loop(ws[i], 2);
        degenerate_loop(ws[i], 100);
    }
    return tu_finish("edges");
}
