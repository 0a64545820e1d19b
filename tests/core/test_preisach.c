/* SPDX-License-Identifier: MIT */
/* test_preisach.c: the Preisach model (src/core/hy_preisach.c) against a
 * brute-force sum over N² relays (converging as h² = (6/N)²), against Everett
 * functions computed apart here (the closed form (F(a) - F(b))²/2 when both
 * factors are equal, and the other order of integration, ∫ g(β) [F(a) - F(β)] dβ,
 * in long double), return-point memory, wiping-out, congruency, every input kind,
 * the minor-loop area against Simpson's rule on the sampled loop, and extreme
 * densities. */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <math.h>
#include <stdlib.h>

#include "hy_preisach.h"
#include "tutil.h"

/* ---- reference Everett functions, long double ----------------------------- */

static long double ref_cdf(int dist, long double z)
{
    if (dist == HY_PREISACH_GAUSSIAN)
        return 0.5L * erfcl(-z / sqrtl(2.0L));
    return 0.5L + atanl(z) / 3.14159265358979323846264L;
}

/* P(lo <= Z <= hi) on the side of the median where it does not cancel */
static long double ref_diff(int dist, long double lo, long double hi)
{
    if (lo >= 0)
        return ref_cdf(dist, -lo) - ref_cdf(dist, -hi);
    return ref_cdf(dist, hi) - ref_cdf(dist, lo);
}

typedef struct ref_ctx {
    const hy_preisach *p;
    double a;
} ref_ctx;

/* g(β) P(β <= α <= a): the integrand with α integrated first */
static double ref_f(double be, void *v)
{
    const ref_ctx *c = v;
    const hy_preisach *p = c->p;
    long double zb = ((long double)be - p->mb) / p->sb;
    long double g = p->dist == HY_PREISACH_GAUSSIAN ? expl(-0.5L * zb * zb) / sqrtl(2 * 3.14159265358979323846264L)
                                                    : 1.0L / (3.14159265358979323846264L * (1 + zb * zb));
    return (double)(g / p->sb *
                    ref_diff(p->dist, ((long double)be - p->ma) / p->sa, ((long double)c->a - p->ma) / p->sa));
}

/* E(a, b) by GSL cquad (not the library's qag) over [b, a] cut into 64 pieces */
static double ref_everett(const hy_preisach *p, double a, double b)
{
    gsl_integration_cquad_workspace *ws = gsl_integration_cquad_workspace_alloc(200);
    ref_ctx c = {p, a};
    gsl_function f = {ref_f, &c};
    double sum = 0;
    for (int i = 0; i < 64; i++) {
        double x0 = b + (a - b) * i / 64.0, x1 = i == 63 ? a : b + (a - b) * (i + 1) / 64.0, r, e;
        gsl_integration_cquad(&f, x0, x1, 0, 1e-14, ws, &r, &e, NULL);
        sum += r;
    }
    gsl_integration_cquad_workspace_free(ws);
    return p->scale * sum;
}

static void test_everett(void)
{
    hy_error err;
    for (int dist = 0; dist < 2; dist++) {
        hy_preisach p;
        /* equal factors: E = K (F(a) - F(b))² / 2 exactly, K = ys / mass, mass = 1/2 */
        CHECK(!hy_preisach_init(&p, dist, 0.0, 0.3, 0.0, 0.3, 2.0, &err), "init: %s", err.msg);
        double worst = 0;
        for (int i = 0; i < 60; i++) {
            double a = tu_unif(-2, 2), b = tu_unif(-2, 2);
            if (i % 3 == 0)
                b = a - tu_logunif(1e-6, 1e-1);
            if (a < b) {
                double t = a;
                a = b;
                b = t;
            }
            long double d = ref_diff(dist, (long double)b / 0.3L, (long double)a / 0.3L);
            double ex = (double)(2.0L * d * d / 2.0L / 0.5L), E = 0;
            CHECK(!hy_preisach_everett(&p, a, b, &E, &err), "everett: %s", err.msg);
            double rel = fabs(E - ex) / ex;
            if (rel > worst)
                worst = rel;
        }
        printf("%s, equal factors: E against (F(a)-F(b))^2/2: worst relative error %.3g\n",
               hy_preisach_dist_name(dist), worst);
        CHECK(worst <= 1e-12, "%s: Everett closed form off by %.3g relative", hy_preisach_dist_name(dist), worst);

        /* coercive density: the other order of integration */
        CHECK(!hy_preisach_symmetric(&p, dist, 0.5, 0.2, 1.0, &err), "init: %s", err.msg);
        worst = 0;
        for (int i = 0; i < 12; i++) {
            double a = tu_unif(-1.5, 2), b = tu_unif(-2, 1.5);
            if (a < b) {
                double t = a;
                a = b;
                b = t;
            }
            double ex = ref_everett(&p, a, b), E = 0;
            CHECK(!hy_preisach_everett(&p, a, b, &E, &err), "everett: %s", err.msg);
            double rel = fabs(E - ex) / ex;
            if (rel > worst)
                worst = rel;
        }
        printf("%s, h_c = 0.5: E against the other order of integration: worst relative error %.3g\n",
               hy_preisach_dist_name(dist), worst);
        CHECK(worst <= 1e-12, "%s: Everett off by %.3g relative", hy_preisach_dist_name(dist), worst);

        /* E(+∞, b) + symmetry: E(a, -∞) of the mirrored density equals E(+∞, -a) */
        double e1 = 0, e2 = 0;
        hy_preisach_everett(&p, 0.7, -INFINITY, &e1, &err);
        hy_preisach_everett(&p, INFINITY, -0.7, &e2, &err);
        CHECK(fabs(e1 - e2) <= 1e-13, "%s: E(0.7, -inf) %.17g != E(inf, -0.7) %.17g (symmetric density)",
              hy_preisach_dist_name(dist), e1, e2);
        hy_preisach_everett(&p, 1e300, -1e300, &e1, &err);
        CHECK(fabs(e1 - 1.0) <= 1e-13, "%s: E(1e300, -1e300) = %.17g, not ys", hy_preisach_dist_name(dist), e1);
        CHECK_MSG(hy_preisach_everett(&p, -1, 1, &e1, &err), err, HY_EINVAL, "a >= b");
    }
}

/* ---- brute force over N² relays -------------------------------------------- */

static double dens(const hy_preisach *p, double al, double be)
{
    double za = (al - p->ma) / p->sa, zb = (be - p->mb) / p->sb;
    return p->scale * exp(-0.5 * (za * za + zb * zb)) / (2 * M_PI * p->sa * p->sb);
}

/* Relays at the cell centres of [-3, 3]², half weight on the diagonal; all
 * down first, then u[] in order (brute_demag, below, on the half-plane). */
static void brute_demag(const hy_preisach *p, int N, double hs, int demag, const double *u, size_t n, double *y);
static void brute(const hy_preisach *p, int N, const double *u, size_t n, double *y)
{
    brute_demag(p, N, INFINITY, 0, u, n, y);
}

static void test_brute_force(void)
{
    hy_error err;
    hy_preisach p;
    hy_preisach_symmetric(&p, HY_PREISACH_GAUSSIAN, 0.5, 0.2, 1.0, &err);
    /* reversals on multiples of 0.375: cell edges for every N below */
    const double u[] = {0, 1.5, -0.375, 0.75, -0.375, 1.125, -1.5, 0.375, -0.75};
    const size_t n = sizeof u / sizeof u[0];
    double y[9], yb[9];
    CHECK(!hy_preisach_apply(&p, u, n, y, &err), "apply: %s", err.msg);
    double prev = 0;
    for (int N = 32; N <= 512; N *= 2) {
        brute(&p, N, u, n, yb);
        double e = 0;
        for (size_t k = 0; k < n; k++)
            e = fmax(e, fabs(yb[k] - y[k]));
        double rate = prev > 0 ? log2(prev / e) : 0;
        printf("brute force, N = %3d: max |y_N - y| = %.3e, rate %.3f\n", N, e, rate);
        if (N >= 128)
            CHECK(rate > 1.9 && rate < 2.1, "N = %d: brute-force error rate %.3f, expected 2 (h^2)", N, rate);
        prev = e;
    }
    CHECK(prev < 1e-4, "N = 512: brute force still %.3g away", prev);
}

/* ---- Everett at the reversal points, memory properties ------------------------- */

static void test_reversals(void)
{
    hy_error err;
    for (int dist = 0; dist < 2; dist++) {
        hy_preisach p;
        hy_preisach_symmetric(&p, dist, 0.5, 0.2, 1.0, &err);
        const double u[] = {1.1, -0.6, 0.7, -0.1, 0.4, 0.1};
        double y[6];
        CHECK(!hy_preisach_apply(&p, u, 6, y, &err), "apply: %s", err.msg);
        if (dist == HY_PREISACH_GAUSSIAN) { /* from saturation: y = -ys + 2 E(u, -∞); no β below -8 */
            double ex = -1 + 2 * ref_everett(&p, 1.1, -8);
            CHECK(fabs(y[0] - ex) <= 1e-12 * fabs(ex), "y(1.1) from saturation %.17g, -ys + 2E = %.17g", y[0], ex);
        }
        /* along a first-order reversal curve y changes by exactly 2 E(max, min) */
        for (int k = 1; k < 6; k++) {
            double hi = fmax(u[k - 1], u[k]), lo = fmin(u[k - 1], u[k]);
            double ex = 2 * ref_everett(&p, hi, lo), got = fabs(y[k] - y[k - 1]);
            CHECK(fabs(got - ex) <= 1e-12 * ex, "%s: |y(%g) - y(%g)| = %.17g, 2E = %.17g (rel %.3g)",
                  hy_preisach_dist_name(dist), u[k - 1], u[k], got, ex, fabs(got - ex) / ex);
        }
    }

    hy_preisach p;
    hy_preisach_symmetric(&p, HY_PREISACH_GAUSSIAN, 0.5, 0.2, 1.0, &err);
    /* return-point memory: back at 0.8 after a minor loop, and nested ones */
    const double a[] = {-1, 0.8, -0.2, 0.5, 0.1, 0.5, -0.2, 0.8, 1.2};
    const double b[] = {-1, 0.8, 1.2};
    double ya[9], yb[3];
    hy_preisach_apply(&p, a, 9, ya, &err);
    hy_preisach_apply(&p, b, 3, yb, &err);
    CHECK(ya[5] == ya[3], "inner minor loop does not close: %.17g vs %.17g", ya[5], ya[3]);
    CHECK(ya[6] == ya[2], "outer minor loop does not close at -0.2: %.17g vs %.17g", ya[6], ya[2]);
    CHECK(ya[7] == ya[1], "minor loop does not close at 0.8: %.17g vs %.17g", ya[7], ya[1]);
    CHECK(ya[8] == yb[2], "wiping-out: after 1.2 the minor loops are not forgotten: %.17g vs %.17g", ya[8], yb[2]);
    /* congruency: the loop between -0.2 and 0.5 has the same height from two histories */
    const double c[] = {-1, 1.0, -0.2, 0.5, -0.2};
    const double d[] = {1, -1.0, 0.5, -0.2, 0.5};
    double yc[5], yd[5];
    hy_preisach_apply(&p, c, 5, yc, &err);
    hy_preisach_apply(&p, d, 5, yd, &err);
    CHECK(fabs((yc[3] - yc[2]) - (yd[4] - yd[3])) <= 1e-14, "loops between -0.2 and 0.5 not congruent: %.17g vs %.17g",
          yc[3] - yc[2], yd[4] - yd[3]);
    CHECK(fabs(yc[3] - yd[4]) > 0.1, "the two histories should sit at different heights (%.17g, %.17g)", yc[3], yd[4]);
    /* from positive saturation a symmetric density mirrors: y+(u) = -y-(-u) */
    const double e[] = {0.3, -0.9, 0.4, -0.1, 1.3};
    double ym[5], yp[5], neg[5];
    for (int k = 0; k < 5; k++)
        neg[k] = -e[k];
    hy_preisach_apply(&p, neg, 5, ym, &err);
    p.start = 1;
    hy_preisach_apply(&p, e, 5, yp, &err);
    p.start = -1;
    for (int k = 0; k < 5; k++)
        CHECK(fabs(yp[k] + ym[k]) <= 1e-14, "start +1 at %g: %.17g, mirrored %.17g", e[k], yp[k], -ym[k]);
    /* the memory keeps only dominant extrema */
    hy_preisach_mem m;
    hy_preisach_mem_init(&m, &p, 0, &err);
    for (int k = 0; k < 1000; k++)
        hy_preisach_mem_apply(&m, (k % 2 ? -1 : 1) * (1.0 + k * 1e-3), NULL, &err);
    CHECK(m.n <= 2, "growing alternation keeps %zu corners (wiping-out should keep 2)", m.n);
    hy_preisach_mem_free(&m);
}

/* ---- every input kind -------------------------------------------------------- */

static void test_inputs(void)
{
    hy_error err;
    hy_preisach p;
    hy_preisach_symmetric(&p, HY_PREISACH_LORENTZIAN, 0.4, 0.1, 1.0, &err);
    const char *specs[] = {"bimodal:0,0.2,1,1.5,1,2.2,3.2,5:cosine", "multimodal:-1,1,-0.5,0.6,0,1.2",
                           "sine:1.2,2", "triangle:-1,1,2", "pwl:0,0,1,1,1.5,-0.2,2,0.7,3,0", NULL};
    for (int s = 0; specs[s] || s == 5; s++) {
        hy_input in;
        int rc;
        if (s == 5) { /* a file's text through the file parser */
            const char *txt = "# t u\n0 0\n0.5 1.0\n1.0,-1.0\n1.5 0.3\n2.0 0\n";
            rc = hy_input_text(&in, txt, strlen(txt), "inline.dat", 1, &err);
        } else
            rc = hy_input_parse(&in, specs[s], &err);
        CHECK(!rc, "input %d: %s", s, err.msg);
        if (rc)
            continue;
        enum { NT = 90 };
        double t[3 * NT], y[3 * NT];
        for (int i = 0; i < 3 * NT; i++)
            t[i] = in.period * i / NT;
        rc = hy_preisach_drive(&p, &in, t, 3 * NT, y, &err);
        CHECK(!rc, "drive %s: %s", in.desc, err.msg);
        double worst = 0;
        int finite = 1;
        for (int i = 0; i < NT; i++) {
            worst = fmax(worst, fabs(y[NT + i] - y[2 * NT + i]));
            finite &= isfinite(y[i]) && fabs(y[i]) <= 1.0;
        }
        CHECK(finite, "%s: output not finite or beyond saturation", in.desc);
        CHECK(worst <= 1e-13, "%s: periods 2 and 3 differ by %.3g (periodic after one period)", in.desc, worst);
        hy_input_free(&in);
        if (!specs[s])
            break;
    }
    /* drive feeds the extrema between samples: a coarse sampling sees the same values */
    hy_input in;
    hy_input_parse(&in, "bimodal:0,0.2,1,1.5,1,2.2,3.2,5:cosine", &err);
    double t[2] = {2.2, 7.2}, y[2], seq[] = {0, 1, 0.2, 1.5, 0, 1, 0.2}, ys[7];
    hy_preisach_drive(&p, &in, t, 2, y, &err);
    hy_preisach_apply(&p, seq, 3, ys, &err);
    CHECK(fabs(y[0] - ys[2]) <= 1e-15, "drive at t2 (u_min,2): %.17g, sequence gives %.17g", y[0], ys[2]);
    hy_preisach_apply(&p, seq, 7, ys, &err);
    CHECK(fabs(y[1] - ys[6]) <= 1e-15, "drive at t2 + T with no samples between: %.17g vs %.17g", y[1], ys[6]);
    hy_input_free(&in);
}

/* ---- minor loop area ---------------------------------------------------------- */

/* ∮ u dy of the loop hi -> lo -> hi (hi reached from below): Simpson's rule */
static double simpson_area(const hy_preisach *p, double lo, double hi, int n)
{
    hy_preisach_mem m;
    hy_error err;
    hy_preisach_mem_init(&m, p, -3, &err); /* up to hi: a reversal there */
    hy_preisach_mem_apply(&m, hi, NULL, &err);
    double down = 0, up = 0, h = (hi - lo) / n, y;
    for (int i = 0; i <= n; i++) { /* descending branch, u = hi - i h */
        hy_preisach_mem_apply(&m, hi - i * h, &y, &err);
        down += (i == 0 || i == n ? 1 : (i % 2 ? 4 : 2)) * y;
    }
    for (int i = 0; i <= n; i++) { /* ascending branch, u = lo + i h */
        hy_preisach_mem_apply(&m, lo + i * h, &y, &err);
        up += (i == 0 || i == n ? 1 : (i % 2 ? 4 : 2)) * y;
    }
    hy_preisach_mem_free(&m);
    return (down - up) * h / 3; /* ∮ u dy = -∮ y du = ∫ (y_down - y_up) du */
}

static void test_area(void)
{
    hy_error err;
    hy_input in; /* Fig. 2's bimodal input */
    hy_input_parse(&in, "bimodal:0,0.2,1,1.5,1,2.2,3.2,5:cosine", &err);
    for (int dist = 0; dist < 2; dist++) {
        hy_preisach p;
        /* relays around ±0.3 of the middle of the input's range [0, 1.5] */
        hy_preisach_init(&p, dist, 1.0, 0.15, 0.4, 0.15, 1.0, &err);
        hy_minor_loop L;
        int rc = hy_preisach_minor_loop(&p, &in, &L, &err);
        CHECK(!rc, "minor loop: %s", err.msg);
        double s1 = simpson_area(&p, L.u_turn, L.u_start, 200), s2 = simpson_area(&p, L.u_turn, L.u_start, 400);
        double rich = s2 + (s2 - s1) / 15;
        printf("%s on Fig. 2's input: minor loop [%g, %g] area %.15g (Simpson 400: %.15g), period %.15g\n",
               hy_preisach_dist_name(dist), L.u_turn, L.u_start, L.area, rich, L.area_period);
        CHECK(L.area > 0 && L.area_period > L.area, "areas %g, %g not dissipative", L.area, L.area_period);
        CHECK(fabs(L.area - rich) <= 1e-9 * L.area, "area %.15g vs Simpson %.15g", L.area, rich);
        CHECK(L.y_close == L.y_start, "no return-point memory: %.17g vs %.17g", L.y_close, L.y_start);
        double major = simpson_area(&p, 0, 1.5, 400);
        CHECK(fabs(L.area_period - L.area - major) <= 1e-8 * major, "period area %.15g != minor + major %.15g",
              L.area_period, L.area + major);
    }
    hy_input_free(&in);
    hy_preisach p;
    hy_preisach_symmetric(&p, 0, 0.5, 0.2, 1, &err);
    hy_input_parse(&in, "sine:1,1", &err);
    hy_minor_loop L;
    CHECK_MSG(hy_preisach_minor_loop(&p, &in, &L, &err), err, HY_EINVAL, "not a bimodal input");
    hy_input_free(&in);
}

/* ---- extreme densities and refusals -------------------------------------------- */

static void test_extreme(void)
{
    hy_error err;
    for (int dist = 0; dist < 2; dist++) {
        hy_preisach p; /* width 1e-9 of the input range [-1, 1] */
        int rc = hy_preisach_symmetric(&p, dist, 0.5, 2e-9, 1.0, &err);
        CHECK(!rc, "width 2e-9: %s", err.msg);
        const double u[] = {-1, 1, 0.5 + 1e-9, 0.5 - 1e-9, -0.5, -0.5 - 1e-8, 0.7, -1};
        double y[8];
        rc = hy_preisach_apply(&p, u, 8, y, &err);
        CHECK(!rc, "narrow %s: %s", hy_preisach_dist_name(dist), err.msg);
        int ok = 1;
        for (int k = 0; k < 8; k++)
            ok &= isfinite(y[k]) && fabs(y[k]) <= 1 + 1e-12;
        CHECK(ok, "narrow %s: output not finite or past saturation", hy_preisach_dist_name(dist));
        /* nearly relays at ±0.5: saturated outside, the memory kept inside */
        double tol = dist == HY_PREISACH_GAUSSIAN ? 1e-12 : 1e-7;
        CHECK(fabs(y[1] - 1) <= tol && fabs(y[7] + 1) <= tol, "narrow %s: y(1) = %.17g, y(-1) = %.17g",
              hy_preisach_dist_name(dist), y[1], y[7]);
        CHECK(fabs(y[3] - 1) <= tol && fabs(y[4]) <= 1e-7 && y[5] < y[4] - 0.5,
              "narrow %s: y(0.5-) = %.17g, y(-0.5) = %.17g (half the relays), y(-0.5-5sigma) = %.17g",
              hy_preisach_dist_name(dist), y[3], y[4], y[5]);
        double area = 0;
        CHECK(!hy_preisach_loop_area(&p, -1, 1, &area, &err), "narrow area: %s", err.msg);
        CHECK(isfinite(area) && fabs(area - 2.0) < (dist ? 1e-6 : 1e-7), /* rectangle 2 x 1 */
              "narrow %s: major loop area %.17g, rectangular relay gives 2", hy_preisach_dist_name(dist), area);
    }
    hy_preisach p;
    CHECK_MSG(hy_preisach_symmetric(&p, 0, 0.5, 1e-14, 1, &err), err, HY_EINVAL, "sigma");
    CHECK_MSG(hy_preisach_symmetric(&p, 0, 0.5, 0, 1, &err), err, HY_EINVAL, "sigma");
    CHECK_MSG(hy_preisach_symmetric(&p, 0, 0.5, NAN, 1, &err), err, HY_EINVAL, "sigma");
    CHECK_MSG(hy_preisach_symmetric(&p, 0, 0.5, 0.1, -1, &err), err, HY_EINVAL, "ys");
    CHECK_MSG(hy_preisach_symmetric(&p, 7, 0.5, 0.1, 1, &err), err, HY_EINVAL, "distribution");
    CHECK_MSG(hy_preisach_init(&p, 0, -50, 0.1, 50, 0.1, 1, &err), err, HY_EINVAL, "no mass");
    CHECK(hy_preisach_dist_find("lorentzian") == HY_PREISACH_LORENTZIAN && hy_preisach_dist_find("cauchy") == -1,
          "distribution names");
    hy_preisach_symmetric(&p, 0, 0.5, 0.1, 1, &err);
    double y;
    hy_preisach_mem m;
    CHECK_MSG(hy_preisach_mem_init(&m, &p, INFINITY, &err), err, HY_EINVAL, "finite");
    hy_preisach_mem_init(&m, &p, 0, &err);
    CHECK_MSG(hy_preisach_mem_apply(&m, NAN, &y, &err), err, HY_EINVAL, "finite");
    hy_preisach_mem_free(&m);
}

/* ---- start states and the triangle ------------------------------------------ */

/* f_α = f_β = f (hc = 0) makes every case closed-form: E(a, b) = K (F(a) - F(b))²/2,
 * the triangle's mass (F(hs) - F(-hs))²/2, and from the demagnetised state
 * (relays up where α + β < 0) the initial curve y(u) = ±2K (F(u) - 1/2)²
 * (∫_0^u f (F(α) - F(-α)) dα = (F(u) - 1/2)²).  A Gaussian width much larger
 * than hs is the uniform density on the triangle: y = (u/hs)² on the initial
 * curve, -1 + (u + hs)²/(2 hs²) on the ascending major branch, loop area
 * 4 ys hs/3. */
static void test_triangle_closed_form(void)
{
    hy_error err;
    hy_preisach p;
    const double hs = 1.5, w = 0.7;
    CHECK(!hy_preisach_symmetric(&p, HY_PREISACH_GAUSSIAN, 0, w, 1.0, &err), "init: %s", err.msg);
    CHECK(!hy_preisach_support(&p, hs, &err), "support: %s", err.msg);
#define F(u) ref_cdf(HY_PREISACH_GAUSSIAN, (long double)(u) / w)
    long double mass = (F(hs) - F(-hs)) * (F(hs) - F(-hs)) / 2, K = 1 / mass;
    /* tolerance 1e-13: the quadrature's 1e-13 relative target (QUAD_RTOL) */
    CHECK(fabsl(p.mass - mass) <= 1e-13L * mass, "triangle mass %.17g, closed form %.17Lg", p.mass, mass);
    const double us[] = {-2, -1.5, -0.9, -0.2, 0, 0.3, 1.1, 1.5, 3};
    double worst = 0;
    for (int start = -1; start <= 1; start++) {
        p.start = start;
        for (size_t i = 0; i < sizeof us / sizeof us[0]; i++) {
            double u = us[i], y, uc = fmax(-hs, fmin(hs, u));
            long double want;
            if (start == HY_PREISACH_NEGATIVE) /* ascending major branch */
                want = -1 + K * (F(uc) - F(-hs)) * (F(uc) - F(-hs));
            else if (start == HY_PREISACH_POSITIVE) /* descending */
                want = 1 - K * (F(hs) - F(uc)) * (F(hs) - F(uc));
            else /* the initial magnetisation curve */
                want = (u >= 0 ? 2 : -2) * K * (F(uc) - 0.5L) * (F(uc) - 0.5L);
            CHECK(!hy_preisach_apply(&p, &u, 1, &y, &err), "apply: %s", err.msg);
            worst = fmax(worst, (double)fabsl(y - want));
            CHECK(fabsl(y - want) <= 1e-13L, "start %d, u = %g: y = %.17g, closed form %.17Lg", start, u, y, want);
        }
    }
    printf("triangle, f_alpha = f_beta: worst |y - closed form| %.3g over the three start states\n", worst);
    /* demagnetised: up to 0.6, down to -0.2 and back (return-point memory), then down to
       -0.9 wipes the corner at 0.6: the same as going to -0.9 at once */
    p.start = HY_PREISACH_DEMAGNETISED;
    const double seq[] = {0, 0.6, -0.2, 0.6, -0.9}, direct[] = {0, -0.9};
    double y[5], yd[2];
    CHECK(!hy_preisach_apply(&p, seq, 5, y, &err) && !hy_preisach_apply(&p, direct, 2, yd, &err), "%s", err.msg);
    CHECK(y[0] == 0, "demagnetised, symmetric density: y(0) = %.17g", y[0]);
    CHECK(y[3] == y[1], "return to 0.6: %.17g vs %.17g", y[3], y[1]);
    CHECK(y[4] == yd[1], "-0.9 after 0.6, -0.2: %.17g, directly: %.17g (the corner at 0.6 is wiped)", y[4], yd[1]);
    /* the uniform limit: the density varies by (hs/w)²/2 = 1.1e-8 over the triangle */
    CHECK(!hy_preisach_symmetric(&p, HY_PREISACH_GAUSSIAN, 0, 1e4 * hs, 1.0, &err), "init: %s", err.msg);
    CHECK(!hy_preisach_support(&p, hs, &err), "support: %s", err.msg);
    double e = 0, area;
    for (size_t i = 0; i < sizeof us / sizeof us[0]; i++) {
        double u = us[i], uc = fmax(-hs, fmin(hs, u)), yi, ya;
        p.start = HY_PREISACH_DEMAGNETISED;
        hy_preisach_apply(&p, &u, 1, &yi, &err);
        p.start = HY_PREISACH_NEGATIVE;
        hy_preisach_apply(&p, &u, 1, &ya, &err);
        e = fmax(e, fabs(yi - (uc >= 0 ? 1 : -1) * (uc / hs) * (uc / hs)));
        e = fmax(e, fabs(ya - (-1 + (uc + hs) * (uc + hs) / (2 * hs * hs))));
    }
    CHECK(!hy_preisach_loop_area(&p, -3, 3, &area, &err), "area: %s", err.msg);
    printf("uniform density on the triangle (Gaussian of width 1e4 hs): max |y - closed form| %.3g, major loop area "
           "%.15g (4 hs/3 = %.15g)\n", e, area, 4 * hs / 3);
    CHECK(e <= 1e-7, "uniform limit: y off the closed form by %.3g (density flat to 1.1e-8)", e);
    CHECK(fabs(area - 4 * hs / 3) <= 1e-7, "uniform major loop area %.15g, 4 hs/3 = %.15g", area, 4 * hs / 3);
    CHECK_MSG(hy_preisach_support(&p, 0, &err), err, HY_EINVAL, "hs must be > 0");
    CHECK(!hy_preisach_support(&p, INFINITY, &err) && p.hs == INFINITY && fabs(p.mass - 0.5) < 1e-15,
          "back to the half-plane: hs %g, mass %.17g", p.hs, p.mass);
#undef F
}

/* Relays on a grid, demagnetised (up where α + β < 0; the cells on α = -β
 * count 0) or from negative saturation, optionally only on the triangle
 * -hs <= β <= α <= hs, against the staircase for a density with different α
 * and β distributions: the error must fall as h² (rate 2 +- 0.1). */
static void brute_demag(const hy_preisach *p, int N, double hs, int demag, const double *u, size_t n, double *y)
{
    double h = 6.0 / N;
    double *w = malloc((size_t)N * N * sizeof *w);
    signed char *g = malloc((size_t)N * N);
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++) {
            double al = -3 + (i + 0.5) * h, be = -3 + (j + 0.5) * h;
            int out = j > i || al > hs || be < -hs;
            w[i * N + j] = out ? 0 : dens(p, al, be) * h * h * (i == j ? 0.5 : 1.0);
            g[i * N + j] = !demag ? -1 : i + j + 1 == N ? 0 : i + j + 1 < N ? 1 : -1;
        }
    for (size_t k = 0; k < n; k++) {
        double sum = 0;
        for (int i = 0; i < N; i++)
            for (int j = 0; j <= i; j++) {
                double al = -3 + (i + 0.5) * h, be = -3 + (j + 0.5) * h;
                if (u[k] >= al)
                    g[i * N + j] = 1;
                else if (u[k] <= be)
                    g[i * N + j] = -1;
                sum += w[i * N + j] * g[i * N + j];
            }
        y[k] = sum;
    }
    free(w);
    free(g);
}

static void test_demag_brute_force(void)
{
    hy_error err;
    hy_preisach p;
    CHECK(!hy_preisach_init(&p, HY_PREISACH_GAUSSIAN, 0.4, 0.3, -0.6, 0.45, 1.0, &err), "init: %s", err.msg);
    /* reversals on multiples of 0.375 (cell edges for every N below); the corners at 0.75 and
       -0.375 are wiped by -1.125, the demagnetised line's corner at 1.125 by -1.5 */
    const double u[] = {0, 0.75, -0.375, 0.375, -1.125, 1.125, -1.5, 0.375};
    const size_t n = sizeof u / sizeof u[0];
    for (int tri = 0; tri < 2; tri++) {
        double hs = tri ? 1.5 : INFINITY, y[8], yb[8], prev = 0;
        if (tri)
            CHECK(!hy_preisach_support(&p, hs, &err), "support: %s", err.msg);
        p.start = HY_PREISACH_DEMAGNETISED;
        CHECK(!hy_preisach_apply(&p, u, n, y, &err), "apply: %s", err.msg);
        if (!tri) { /* not symmetric: the demagnetised state is not 0 */
            double y0;
            CHECK(!hy_preisach_demag_output(&p, &y0, &err) && y0 == y[0] && fabs(y0) > 0.01, "y_D = %g", y0);
        }
        for (int N = 128; N <= 512; N *= 2) {
            /* the brute force's mass on [-3, 3]² falls short of the normalised one by < 1e-9 */
            brute_demag(&p, N, hs, 1, u, n, yb);
            double e = 0;
            for (size_t k = 0; k < n; k++)
                e = fmax(e, fabs(yb[k] - y[k]));
            double rate = prev > 0 ? log2(prev / e) : 0;
            printf("demagnetised, %s, N = %3d: max |y_N - y| = %.3e, rate %.3f\n", tri ? "triangle hs = 1.5" : "half-plane",
                   N, e, rate);
            if (N >= 256)
                CHECK(rate > 1.9 && rate < 2.1, "N = %d: brute-force error rate %.3f, expected 2 (h^2)", N, rate);
            prev = e;
        }
        CHECK(prev < 1e-3, "N = 512: brute force still %.3g away", prev);
    }
}

int main(void)
{
    gsl_set_error_handler_off();
    test_everett();
    test_brute_force();
    test_reversals();
    test_inputs();
    test_area();
    test_extreme();
    test_triangle_closed_form();
    test_demag_brute_force();
    return tu_finish("preisach");
}
