/* hy_preisach.c: the classical Preisach model by its Everett function
 * E(a,b) = K ∫_b^a f_α(α) [G_β(α) - G_β(b)] dα (GSL qag, inner integral in closed
 * form) and the staircase of dominant extrema, y = ∓y_s + 2 Σ_j d_j E(edge j). */
#include "hy_preisach.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SQRT1_2 0.70710678118654752440
#define INV_SQRT_2PI 0.39894228040143267794
#define PI 3.14159265358979323846

#define QUAD_RTOL 1e-13    /* asked of every sub-interval                   */
#define QUAD_ACCEPT 1e-12  /* the most relative error a result may carry     */
#define QUAD_LIMIT 64      /* bisections per sub-interval                    */
#define GAUSS_CUT 40.0     /* φ(40) underflows: a Gaussian density ends here */
#define MAX_BREAKS 160

static const char *const dist_names[] = {"gaussian", "lorentzian"};
#define NDIST (sizeof dist_names / sizeof dist_names[0])

const char *hy_preisach_dist_name(int d) { return d >= 0 && (size_t)d < NDIST ? dist_names[d] : NULL; }

int hy_preisach_dist_find(const char *name)
{
    for (size_t i = 0; name && i < NDIST; i++)
        if (strcmp(name, dist_names[i]) == 0)
            return (int)i;
    return -1;
}

/* ---- one distribution in standard units ---------------------------------- */

static double pdf(int dist, double z)
{
    if (dist == HY_PREISACH_GAUSSIAN)
        return INV_SQRT_2PI * exp(-0.5 * z * z);
    return 1.0 / (PI * (1.0 + z * z));
}

/* P(Z <= z), accurate in both tails. */
static double cdf(int dist, double z)
{
    if (dist == HY_PREISACH_GAUSSIAN)
        return 0.5 * erfc(-z * SQRT1_2);
    return atan2(1.0, -z) / PI;
}

/* P(z <= Z <= x), x = z + w >= z, without cancellation (x and w are both
 * given, each computed from the data directly, so neither loses digits when
 * |z| is large or w small): the Gaussian by erf or
 * erfc on the side where the two terms do not cancel, or by Gauss-Legendre on
 * [z, z + w] when they would (then w is short against φ's scale); the
 * Lorentzian by atan x - atan z = atan2(w, 1 + x z). */
static double cdf_diff(const hy_preisach *p, int dist, double z, double x, double w)
{
    if (dist == HY_PREISACH_LORENTZIAN)
        return atan2(w, 1.0 + x * z) / PI;
    if (z < 0 && x > 0)
        return 0.5 * (erf(x * SQRT1_2) - erf(z * SQRT1_2));
    double hi = z >= 0 ? 0.5 * erfc(z * SQRT1_2) : 0.5 * erfc(-x * SQRT1_2);
    double lo = z >= 0 ? 0.5 * erfc(x * SQRT1_2) : 0.5 * erfc(-z * SQRT1_2);
    if (lo <= 0.5 * hi)
        return hi - lo;
    double s = 0, h = 0.5 * w;
    for (int i = 0; i < HY_PREISACH_GL; i++) {
        double v = z + h * (1.0 + p->glx[i]);
        s += p->glw[i] * exp(-0.5 * v * v);
    }
    return INV_SQRT_2PI * h * s;
}

/* Gauss-Legendre nodes and weights on [-1, 1] by Newton on P_n. */
static void gauss_legendre(int n, double *x, double *w)
{
    for (int i = 0; i < n; i++) {
        double r = cos(PI * (i + 0.75) / (n + 0.5)), dp = 1;
        for (int it = 0; it < 100; it++) {
            double p0 = 1, p1 = r;
            for (int j = 2; j <= n; j++) {
                double p2 = ((2.0 * j - 1) * r * p1 - (j - 1.0) * p0) / j;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (r * p1 - p0) / (r * r - 1);
            double dr = p1 / dp;
            r -= dr;
            if (fabs(dr) < 1e-17)
                break;
        }
        x[i] = r;
        w[i] = 2.0 / ((1 - r * r) * dp * dp);
    }
}

/* ---- parameters ---------------------------------------------------------- */

static int check_axis(const char *name, double m, double s, hy_error *err)
{
    if (!isfinite(m))
        return hy_error_set(err, HY_EINVAL, "Preisach %s centre must be finite (got %g)", name, m);
    if (!isfinite(s) || !(s > 0))
        return hy_error_set(err, HY_EINVAL, "Preisach %s width sigma must be finite and > 0 (got %g)", name, s);
    if (s < 1e-12 * fabs(m))
        return hy_error_set(err, HY_EINVAL,
                            "Preisach %s width sigma = %g is below 1e-12 of its centre %g: relays that close "
                            "cannot be told apart in double precision",
                            name, s, m);
    return HY_OK;
}

int hy_preisach_init(hy_preisach *p, int dist, double ma, double sa, double mb, double sb, double ys,
                     hy_error *err)
{
    int rc;
    if (!hy_preisach_dist_name(dist))
        return hy_error_set(err, HY_EINVAL, "unknown Preisach distribution %d (gaussian or lorentzian)", dist);
    if ((rc = check_axis("alpha (up-switching field)", ma, sa, err)) ||
        (rc = check_axis("beta (down-switching field)", mb, sb, err)))
        return rc;
    if (!isfinite(ys) || !(ys > 0))
        return hy_error_set(err, HY_EINVAL, "Preisach saturation output ys must be finite and > 0 (got %g)", ys);
    /* P(A >= B): A - B is normal N(ma - mb, sa² + sb²) or Cauchy(ma - mb, sa + sb) */
    double mass = dist == HY_PREISACH_GAUSSIAN ? cdf(dist, (ma - mb) / hypot(sa, sb))
                                               : cdf(dist, (ma - mb) / (sa + sb));
    if (!(mass >= 1e-300))
        return hy_error_set(err, HY_EINVAL,
                            "Preisach density has no mass on alpha >= beta (alpha centre %g far below beta centre %g)",
                            ma, mb);
    memset(p, 0, sizeof *p);
    p->dist = dist;
    p->ma = ma;
    p->sa = sa;
    p->mb = mb;
    p->sb = sb;
    p->ys = ys;
    p->start = -1;
    p->mass = mass;
    p->scale = ys / mass;
    gauss_legendre(HY_PREISACH_GL, p->glx, p->glw);
    return HY_OK;
}

int hy_preisach_symmetric(hy_preisach *p, int dist, double hc, double sigma, double ys, hy_error *err)
{
    return hy_preisach_init(p, dist, hc, sigma, -hc, sigma, ys, err);
}

/* ---- quadrature over [lo, hi] split at the densities' features --------- */

static size_t add_breaks(const hy_preisach *p, double m, double s, double *b, size_t n)
{
    b[n++] = m;
    double k = 0.5, kmax = p->dist == HY_PREISACH_GAUSSIAN ? 32.0 : 0x1p33;
    for (; k <= kmax; k *= 2) {
        b[n++] = m - k * s;
        b[n++] = m + k * s;
    }
    if (p->dist == HY_PREISACH_GAUSSIAN) {
        b[n++] = m - GAUSS_CUT * s;
        b[n++] = m + GAUSS_CUT * s;
    }
    return n;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* A tail beyond the outermost split, α = c ± L/t: for densities falling as
 * 1/α² (the Lorentzian) the integrand becomes nearly constant in t. */
typedef struct tail_ctx {
    gsl_function *f;
    double c, L;    /* α = c + L/t, L signed */
} tail_ctx;

static double tail_f(double t, void *v)
{
    const tail_ctx *c = v;
    return GSL_FN_EVAL(c->f, c->c + c->L / t) * fabs(c->L) / (t * t);
}

/* ∫_lo^hi f (lo may be -∞, hi +∞), split at m ± k s of both axes; every piece
 * to QUAD_RTOL, the sum accepted when its error bound is within QUAD_ACCEPT
 * (or, for relays far narrower than their fields, within what those fields'
 * ulps allow).  The variable is α - shift, so that α - b is exact near b.
 * Beyond the outermost split (only the Lorentzian's 2^33 widths reach there)
 * the piece is mapped onto t in (0, 1] by α = c ± L/t. */
static int integrate(const hy_preisach *p, gsl_function *f, double shift, double lo, double hi, double *out,
                     const char *what, hy_error *err)
{
    double b[MAX_BREAKS];
    size_t nb = add_breaks(p, p->ma - shift, p->sa, b, 0);
    nb = add_breaks(p, p->mb - shift, p->sb, b, nb);
    qsort(b, nb, sizeof *b, cmp_double);
    double pts[MAX_BREAKS + 2];
    size_t np = 0;
    pts[np++] = lo;
    for (size_t i = 0; i < nb; i++)
        if (b[i] > pts[np - 1] && b[i] < hi)
            pts[np++] = b[i];
    pts[np++] = hi;
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(QUAD_LIMIT);
    if (!ws)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    double sum = 0, abserr_sum = 0, worst_at = 0, worst = 0;
    double cmax = fmax(p->ma, p->mb) - shift, cmin = fmin(p->ma, p->mb) - shift;
    for (size_t i = 0; i + 1 < np; i++) {
        double r = 0, e = 0, a0 = pts[i], a1 = pts[i + 1];
        if (a0 >= b[nb - 1] || a1 <= b[0]) {
            int right = a0 >= b[nb - 1];
            tail_ctx tc = {f, right ? cmax : cmin, right ? a0 - cmax : a1 - cmin};
            double far = right ? a1 : a0, t1 = isinf(far) ? 0 : tc.L / (far - tc.c);
            gsl_function g = {tail_f, &tc};
            gsl_integration_qag(&g, t1, 1.0, 0, QUAD_RTOL, QUAD_LIMIT, GSL_INTEG_GAUSS21, ws, &r, &e);
        } else
            gsl_integration_qag(f, a0, a1, 0, QUAD_RTOL, QUAD_LIMIT, GSL_INTEG_GAUSS21, ws, &r, &e);
        sum += r;
        abserr_sum += e;
        if (e > worst) {
            worst = e;
            worst_at = isinf(a0) ? a1 : a0;
        }
    }
    gsl_integration_workspace_free(ws);
    /* a relay width far below the fields' magnitude limits what double can resolve */
    double cond = fmax(fabs(p->ma) / p->sa, fabs(p->mb) / p->sb);
    if (isfinite(shift))
        cond = fmax(cond, fabs(shift) / fmin(p->sa, p->sb));
    double accept = fmax(QUAD_ACCEPT, 64 * DBL_EPSILON * cond);
    if (!isfinite(sum) || abserr_sum > accept * fabs(sum) + 1e-300)
        return hy_error_set(err, HY_ENUM,
                            "Preisach %s: quadrature over [%g, %g] reached only %.3g relative (worst near %g)", what,
                            lo, hi, sum != 0 ? abserr_sum / fabs(sum) : abserr_sum, worst_at);
    *out = sum;
    return HY_OK;
}

/* ---- Everett function ---------------------------------------------------- */

typedef struct ev_ctx {
    const hy_preisach *p;
    double b, zb;
    int binf;
} ev_ctx;

/* The integrand at α = b + τ (b finite) or α = τ (b = -∞). */
static double everett_f(double tau, void *v)
{
    const ev_ctx *c = v;
    const hy_preisach *p = c->p;
    double al = c->binf ? tau : c->b + tau;
    double fa = pdf(p->dist, (al - p->ma) / p->sa) / p->sa;
    if (fa == 0)
        return 0;
    if (c->binf)
        return fa * cdf(p->dist, (al - p->mb) / p->sb);
    return fa * cdf_diff(p, p->dist, c->zb, (al - p->mb) / p->sb, tau / p->sb);
}

int hy_preisach_everett(const hy_preisach *p, double a, double b, double *E, hy_error *err)
{
    if (isnan(a) || isnan(b) || a < b || a == -INFINITY || b == INFINITY)
        return hy_error_set(err, HY_EINVAL, "Everett function E(a, b) needs a >= b (got a = %g, b = %g)", a, b);
    if (isinf(a) && isinf(b)) {
        *E = p->ys;
        return HY_OK;
    }
    double lo = b, hi = a;
    if (p->dist == HY_PREISACH_GAUSSIAN) { /* f_α vanishes beyond GAUSS_CUT widths */
        lo = fmax(lo, p->ma - GAUSS_CUT * p->sa);
        hi = fmin(hi, p->ma + GAUSS_CUT * p->sa);
    }
    if (!(hi > lo)) {
        *E = 0;
        return HY_OK;
    }
    ev_ctx c = {p, b, isinf(b) ? 0 : (b - p->mb) / p->sb, isinf(b)};
    gsl_function f = {everett_f, &c};
    double r;
    double shift = isinf(b) ? 0 : b;
    int rc = integrate(p, &f, shift, lo - shift, hi - shift, &r, "Everett function", err);
    if (rc)
        return rc;
    *E = p->scale * r;
    return HY_OK;
}

/* ---- staircase memory ------------------------------------------------------ */

static int sgn(double x) { return (x > 0) - (x < 0); }

/* E of the edge between v and w, in either order. */
static int edge_e(const hy_preisach *p, double v, double w, double *E, hy_error *err)
{
    return hy_preisach_everett(p, fmax(v, w), fmin(v, w), E, err);
}

int hy_preisach_mem_init(hy_preisach_mem *m, const hy_preisach *p, double u0, hy_error *err)
{
    memset(m, 0, sizeof *m);
    if (!isfinite(u0))
        return hy_error_set(err, HY_EINVAL, "Preisach input must be finite (got %g)", u0);
    m->cap = 16;
    m->s = malloc(m->cap * sizeof *m->s);
    m->c = malloc(m->cap * sizeof *m->c);
    if (!m->s || !m->c) {
        hy_preisach_mem_free(m);
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    }
    m->p = p;
    int up = p->start >= 0 ? 1 : -1;
    m->s[0] = up > 0 ? INFINITY : -INFINITY;
    m->c[0] = up > 0 ? p->ys : -p->ys;
    m->s[1] = u0;
    m->n = 1;
    int rc = edge_e(p, m->s[0], u0, &m->e_cur, err);
    if (rc) {
        hy_preisach_mem_free(m);
        return rc;
    }
    m->y = m->c[0] - 2.0 * up * m->e_cur;
    return HY_OK;
}

int hy_preisach_mem_apply(hy_preisach_mem *m, double u, double *y, hy_error *err)
{
    if (!isfinite(u))
        return hy_error_set(err, HY_EINVAL, "Preisach input must be finite (got %g)", u);
    if (u != m->s[m->n]) {
        if (m->n + 2 > m->cap) {
            size_t cap = 2 * m->cap;
            double *s = realloc(m->s, cap * sizeof *s);
            if (s)
                m->s = s;
            double *c = s ? realloc(m->c, cap * sizeof *c) : NULL;
            if (!c)
                return hy_error_set(err, HY_ENOMEM, "out of memory");
            m->c = c;
            m->cap = cap;
        }
        size_t n = m->n;
        int d = sgn(m->s[n] - m->s[n - 1]);
        double cn = 0;
        if ((u - m->s[n]) * d < 0) { /* reversal: the present edge is complete */
            cn = m->c[n - 1] + 2.0 * d * m->e_cur;
            n++;
            d = -d;
        }
        /* wiping-out: passing s[n-2] erases the last two corners */
        while (n >= 3 && (u - m->s[n - 2]) * d >= 0)
            n -= 2;
        double e;
        int rc = edge_e(m->p, m->s[n - 1], u, &e, err);
        if (rc)
            return rc;
        if (n > m->n)
            m->c[n - 1] = cn;
        m->s[n] = u;
        m->n = n;
        m->e_cur = e;
        m->y = m->c[n - 1] + 2.0 * d * e;
    }
    if (y)
        *y = m->y;
    return HY_OK;
}

void hy_preisach_mem_free(hy_preisach_mem *m)
{
    free(m->s);
    free(m->c);
    m->s = m->c = NULL;
    m->n = m->cap = 0;
}

int hy_preisach_apply(const hy_preisach *p, const double *u, size_t n, double *y, hy_error *err)
{
    if (n == 0)
        return HY_OK;
    hy_preisach_mem m;
    int rc = hy_preisach_mem_init(&m, p, u[0], err);
    if (rc)
        return rc;
    y[0] = m.y;
    for (size_t i = 1; i < n && !rc; i++)
        rc = hy_preisach_mem_apply(&m, u[i], &y[i], err);
    hy_preisach_mem_free(&m);
    return rc;
}

static int feed(void *ctx, double u, double *y, hy_error *err)
{
    return hy_preisach_mem_apply(ctx, u, y, err);
}

int hy_preisach_drive(const hy_preisach *p, const hy_input *in, const double *t, size_t n, double *y,
                      hy_error *err)
{
    hy_preisach_mem m;
    int rc = hy_preisach_mem_init(&m, p, hy_input_u(in, 0), err);
    if (rc)
        return rc;
    rc = hy_rateind_drive(in, t, n, feed, &m, y, err);
    hy_preisach_mem_free(&m);
    return rc;
}

/* ---- loop areas ------------------------------------------------------------ */

typedef struct area_ctx {
    const hy_preisach *p;
    double lo, hi;
} area_ctx;

/* μ of the rectangle β in [lo, u], α in [u, hi] (α >= β holds there) / K */
static double area_f(double u, void *v)
{
    const area_ctx *c = v;
    const hy_preisach *p = c->p;
    double fa = cdf_diff(p, p->dist, (u - p->ma) / p->sa, (c->hi - p->ma) / p->sa, (c->hi - u) / p->sa);
    double gb = cdf_diff(p, p->dist, (c->lo - p->mb) / p->sb, (u - p->mb) / p->sb, (u - c->lo) / p->sb);
    return fa * gb;
}

int hy_preisach_loop_area(const hy_preisach *p, double lo, double hi, double *area, hy_error *err)
{
    if (!isfinite(lo) || !isfinite(hi) || !(lo < hi))
        return hy_error_set(err, HY_EINVAL, "Preisach loop area needs finite lo < hi (got %g, %g)", lo, hi);
    area_ctx c = {p, lo, hi};
    gsl_function f = {area_f, &c};
    double r;
    int rc = integrate(p, &f, 0, lo, hi, &r, "loop area", err);
    if (rc)
        return rc;
    *area = 2.0 * p->scale * r;
    return HY_OK;
}

int hy_preisach_minor_loop(const hy_preisach *p, const hy_input *in, hy_minor_loop *out, hy_error *err)
{
    double e[4];
    int rc = hy_rateind_bimodal(in, e, err);
    if (rc)
        return rc;
    /* one period reaches both global extrema; the second is the steady one */
    const double seq[] = {e[1], e[2], e[3], e[0], e[1], e[2], e[1]};
    double y[8];
    hy_preisach_mem m;
    if ((rc = hy_preisach_mem_init(&m, p, e[0], err)))
        return rc;
    for (size_t i = 0; i < 7 && !rc; i++)
        rc = hy_preisach_mem_apply(&m, seq[i], &y[i], err);
    hy_preisach_mem_free(&m);
    hy_minor_loop L = {e[1], e[2], y[4], y[6], 0, 0, 1};
    double major = 0;
    if (!rc)
        rc = hy_preisach_loop_area(p, e[2], e[1], &L.area, err);
    if (!rc)
        rc = hy_preisach_loop_area(p, e[0], e[3], &major, err);
    if (rc)
        return rc;
    L.area_period = L.area + major;
    *out = L;
    return HY_OK;
}
