/* SPDX-License-Identifier: MIT */
/* hy_preisach.c: the classical Preisach model by its Everett function
 * E(a,b) = K ∫_b^a f_α(α) [G_β(α) - G_β(b)] dα (GSL qag, inner integral in closed
 * form) and the staircase of dominant extrema, y = ∓y_s + 2 Σ_j d_j E(edge j), on
 * the half-plane or the triangle -hs <= β <= α <= hs, from saturation or from
 * the demagnetised state (the staircase α = -β). */
#include "hy_preisach.h"

#include "hy_args.h"

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

const char *const hy_preisach_dist_names[] = {"gaussian", "lorentzian", NULL};
#define NDIST (sizeof hy_preisach_dist_names / sizeof hy_preisach_dist_names[0] - 1)

const char *hy_preisach_dist_name(int d) { return d >= 0 && (size_t)d < NDIST ? hy_preisach_dist_names[d] : NULL; }

int hy_preisach_dist_find(const char *name)
{
    for (size_t i = 0; name && i < NDIST; i++)
        if (strcmp(name, hy_preisach_dist_names[i]) == 0)
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
    HY_NONNULL(err, p);
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
    p->start = HY_PREISACH_NEGATIVE;
    p->hs = INFINITY;
    p->mass = mass;
    p->scale = ys / mass;
    gauss_legendre(HY_PREISACH_GL, p->glx, p->glw);
    return HY_OK;
}

int hy_preisach_tabulated(hy_preisach *p, const hy_preisach_table *t, hy_error *err)
{
    double ys = 0;
    HY_NONNULL(err, p);
    HY_NONNULL(err, t);
    if (t->n && (!t->alpha || !t->beta || !t->w))
        return hy_error_set(err, HY_EINVAL, "%s: the table's arrays must not be NULL (t->n is %zu)", __func__, t->n);
    for (size_t k = 0; k < t->n; k++)
        ys += t->w[k];
    if (!(ys > 0) || !isfinite(ys))
        return hy_error_set(err, HY_EINVAL, "Preisach tabulated density: no relay of weight > 0 (an all-zero density)");
    memset(p, 0, sizeof *p);
    p->ys = ys;
    p->start = HY_PREISACH_NEGATIVE;
    p->hs = INFINITY;
    p->mass = ys;
    p->scale = 1;
    p->table = t;
    return HY_OK;
}

int hy_preisach_symmetric(hy_preisach *p, int dist, double hc, double sigma, double ys, hy_error *err)
{
    return hy_preisach_init(p, dist, hc, sigma, -hc, sigma, ys, err);
}

/* E(a, b) of the unscaled density (declared here, defined with the Everett function) */
static int everett_unscaled(const hy_preisach *p, double a, double b, double *E, hy_error *err);

int hy_preisach_support(hy_preisach *p, double hs, hy_error *err)
{
    HY_NONNULL(err, p);
    if (isnan(hs) || !(hs > 0))
        return hy_error_set(err, HY_EINVAL, "Preisach saturation field hs must be > 0 (got %g)", hs);
    if (hs == INFINITY) { /* the half-plane: P(A >= B) in closed form, as hy_preisach_init */
        int start = p->start, rc = hy_preisach_init(p, p->dist, p->ma, p->sa, p->mb, p->sb, p->ys, err);
        p->start = start;
        return rc;
    }
    hy_preisach t = *p;
    t.hs = hs;
    double mass;
    int rc = everett_unscaled(&t, hs, -hs, &mass, err);
    if (rc)
        return rc;
    if (!(mass >= 1e-300))
        return hy_error_set(err, HY_EINVAL,
                            "Preisach density has no mass on the triangle -hs <= beta <= alpha <= hs (hs = %g): "
                            "every relay switches beyond the saturation field",
                            hs);
    t.mass = mass;
    t.scale = p->ys / mass;
    *p = t;
    return HY_OK;
}

/* ---- quadrature over [lo, hi] split at the densities' features --------- */

/* Every split point is an anchor (a centre m_α, m_β, or an end of the range)
 * plus an offset, and each piece is integrated in v = α - o from the anchor o
 * nearest to it, with every difference to an anchor formed as (o - anchor) + v:
 * the quantity that matters on that piece (α - m_α inside a narrow density,
 * α - b in a thin triangle) is then exact in v, however far the fields are
 * from 0 or from each other. */
typedef double (*q_fn)(double v, double o, const void *ctx);

typedef struct qpt {
    double al;      /* the point itself                       */
    int anchor;     /* index into quad.anchor, -1: none (±∞)  */
    double off;     /* al = anchor + off                      */
} qpt;

typedef struct quad {
    q_fn f;
    const void *ctx;
    double anchor[4];
    int nanchor;
} quad;

typedef struct piece_ctx {
    const quad *q;
    double o, L;    /* regular: α = o + v; tail: α = o + L/t    */
} piece_ctx;

static double piece_f(double v, void *c)
{
    const piece_ctx *pc = c;
    return pc->q->f(v, pc->o, pc->q->ctx);
}

/* A tail beyond the outermost split, α = o + L/t: for densities falling as
 * 1/α² (the Lorentzian) the integrand becomes nearly constant in t. */
static double tail_f(double t, void *c)
{
    const piece_ctx *pc = c;
    return pc->q->f(pc->L / t, pc->o, pc->q->ctx) * fabs(pc->L) / (t * t);
}

static size_t add_breaks(const hy_preisach *p, int anchor, double m, double s, qpt *b, size_t n)
{
    double k = 0.5, kmax = p->dist == HY_PREISACH_GAUSSIAN ? 32.0 : 0x1p33;
    b[n++] = (qpt){m, anchor, 0};
    for (; k <= kmax; k *= 2) {
        b[n++] = (qpt){m - k * s, anchor, -k * s};
        b[n++] = (qpt){m + k * s, anchor, k * s};
    }
    if (p->dist == HY_PREISACH_GAUSSIAN) {
        b[n++] = (qpt){m - GAUSS_CUT * s, anchor, -GAUSS_CUT * s};
        b[n++] = (qpt){m + GAUSS_CUT * s, anchor, GAUSS_CUT * s};
    }
    return n;
}

static int cmp_qpt(const void *a, const void *b)
{
    double x = ((const qpt *)a)->al, y = ((const qpt *)b)->al;
    return (x > y) - (x < y);
}

/* v of point P from anchor index o */
static double offset_from(const quad *q, const qpt *P, int o)
{
    return P->anchor == o ? P->off : P->al - q->anchor[o];
}

/* The anchor nearest to [a0, a1]. */
static int nearest_anchor(const quad *q, double a0, double a1)
{
    int best = 0;
    double bd = INFINITY;
    for (int i = 0; i < q->nanchor; i++) {
        double x = q->anchor[i], d = x < a0 ? a0 - x : (x > a1 ? x - a1 : 0);
        if (d < bd) {
            bd = d;
            best = i;
        }
    }
    return best;
}

/* ∫ over [lo, hi] (lo.al may be -∞, hi.al +∞) of q->f; q->anchor[0], [1] are
 * m_α, m_β.  Every piece to QUAD_RTOL; the sum accepted when its error bound
 * is within QUAD_ACCEPT (or, for relays far narrower than their fields, within
 * what those fields' ulps allow). */
static int integrate(const hy_preisach *p, const quad *q, qpt lo, qpt hi, double *out, const char *what,
                     hy_error *err)
{
    qpt b[MAX_BREAKS], pts[MAX_BREAKS + 2];
    size_t nb = add_breaks(p, 0, p->ma, p->sa, b, 0);
    nb = add_breaks(p, 1, p->mb, p->sb, b, nb);
    qsort(b, nb, sizeof *b, cmp_qpt);
    size_t np = 0;
    pts[np++] = lo;
    for (size_t i = 0; i < nb; i++)
        if (b[i].al > pts[np - 1].al && b[i].al < hi.al)
            pts[np++] = b[i];
    pts[np++] = hi;
    gsl_integration_workspace *ws = gsl_integration_workspace_alloc(QUAD_LIMIT);
    if (!ws)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    double sum = 0, abserr_sum = 0, worst_at = 0, worst = 0;
    int right_c = p->ma >= p->mb ? 0 : 1;
    for (size_t i = 0; i + 1 < np; i++) {
        const qpt *P0 = &pts[i], *P1 = &pts[i + 1];
        double r = 0, e = 0;
        if (P0->al >= b[nb - 1].al || P1->al <= b[0].al) { /* a far tail */
            int right = P0->al >= b[nb - 1].al, c = right ? right_c : 1 - right_c;
            const qpt *near = right ? P0 : P1, *far = right ? P1 : P0;
            piece_ctx pc = {q, q->anchor[c], offset_from(q, near, c)};
            double t1 = isinf(far->al) ? 0 : pc.L / offset_from(q, far, c);
            gsl_function g = {tail_f, &pc};
            gsl_integration_qag(&g, t1, 1.0, 0, QUAD_RTOL, QUAD_LIMIT, GSL_INTEG_GAUSS21, ws, &r, &e);
        } else {
            int o = nearest_anchor(q, P0->al, P1->al);
            piece_ctx pc = {q, q->anchor[o], 0};
            gsl_function g = {piece_f, &pc};
            gsl_integration_qag(&g, offset_from(q, P0, o), offset_from(q, P1, o), 0, QUAD_RTOL, QUAD_LIMIT,
                                GSL_INTEG_GAUSS21, ws, &r, &e);
        }
        sum += r;
        abserr_sum += e;
        if (e > worst) {
            worst = e;
            worst_at = isinf(P0->al) ? P1->al : P0->al;
        }
    }
    gsl_integration_workspace_free(ws);
    double cond = fmax(fabs(p->ma) / p->sa, fabs(p->mb) / p->sb);
    double accept = fmax(QUAD_ACCEPT, 64 * DBL_EPSILON * cond);
    if (!isfinite(sum) || abserr_sum > accept * fabs(sum) + 1e-300)
        return hy_error_set(err, HY_ENUM,
                            "Preisach %s: quadrature over [%g, %g] reached only %.3g relative (worst near %g)", what,
                            lo.al, hi.al, sum != 0 ? abserr_sum / fabs(sum) : abserr_sum, worst_at);
    *out = sum;
    return HY_OK;
}

/* ---- Everett function ---------------------------------------------------- */

typedef struct ev_ctx {
    const hy_preisach *p;
    double b, zb;
    int binf;
} ev_ctx;

/* f_α(α) P(b <= β <= α) at α = o + v (P(β <= α) when b = -∞) */
static double everett_f(double v, double o, const void *ctx)
{
    const ev_ctx *c = ctx;
    const hy_preisach *p = c->p;
    double fa = pdf(p->dist, ((o - p->ma) + v) / p->sa) / p->sa;
    if (fa == 0)
        return 0;
    double x = ((o - p->mb) + v) / p->sb;
    if (c->binf)
        return fa * cdf(p->dist, x);
    return fa * cdf_diff(p, p->dist, c->zb, x, ((o - c->b) + v) / p->sb);
}

static int everett_unscaled(const hy_preisach *p, double a, double b, double *E, hy_error *err)
{
    hy_preisach t = *p;
    t.scale = 1;
    t.ys = INFINITY; /* E(+∞, -∞) is never asked here: a and b are finite */
    return hy_preisach_everett(&t, a, b, E, err);
}

int hy_preisach_everett(const hy_preisach *p, double a, double b, double *E, hy_error *err)
{
    HY_NONNULL(err, p);
    HY_NONNULL(err, E);
    if (isnan(a) || isnan(b) || a < b || a == -INFINITY || b == INFINITY)
        return hy_error_set(err, HY_EINVAL, "Everett function E(a, b) needs a >= b (got a = %g, b = %g)", a, b);
    if (isinf(a) && isinf(b)) {
        *E = p->ys;
        return HY_OK;
    }
    if (p->table) {
        *E = hy_preisach_table_everett(p->table, a, b);
        return HY_OK;
    }
    if (p->hs < INFINITY) { /* the triangle: no relay beyond ±hs */
        a = fmin(a, p->hs);
        b = fmax(b, -p->hs);
        if (!(a > b)) {
            *E = 0;
            return HY_OK;
        }
    }
    ev_ctx c = {p, b, isinf(b) ? 0 : (b - p->mb) / p->sb, isinf(b)};
    quad q = {everett_f, &c, {p->ma, p->mb, 0, 0}, 2};
    qpt lo = {b, -1, 0}, hi = {a, -1, 0};
    if (isfinite(b)) {
        q.anchor[q.nanchor] = b;
        lo = (qpt){b, q.nanchor++, 0};
    }
    if (isfinite(a)) {
        q.anchor[q.nanchor] = a;
        hi = (qpt){a, q.nanchor++, 0};
    }
    if (p->dist == HY_PREISACH_GAUSSIAN) { /* f_α vanishes beyond GAUSS_CUT widths */
        if (lo.al < p->ma - GAUSS_CUT * p->sa)
            lo = (qpt){p->ma - GAUSS_CUT * p->sa, 0, -GAUSS_CUT * p->sa};
        if (hi.al > p->ma + GAUSS_CUT * p->sa)
            hi = (qpt){p->ma + GAUSS_CUT * p->sa, 0, GAUSS_CUT * p->sa};
    }
    if (!(hi.al > lo.al)) {
        *E = 0;
        return HY_OK;
    }
    double r;
    int rc = integrate(p, &q, lo, hi, &r, "Everett function", err);
    if (rc)
        return rc;
    *E = p->scale * r;
    return HY_OK;
}

/* ---- the demagnetised state: the staircase α = -β ------------------------- */

typedef struct dm_ctx {
    const hy_preisach *p;
    int up;  /* 1: f_α(α) P(-α <= β <= α) over α; 0: f_β(β) P(β <= α <= -β) over β */
} dm_ctx;

static double demag_f(double v, double o, const void *ctx)
{
    const dm_ctx *c = ctx;
    const hy_preisach *p = c->p;
    double x = o + v;
    if (c->up) {
        double fa = pdf(p->dist, ((o - p->ma) + v) / p->sa) / p->sa;
        return fa == 0 ? 0 : fa * cdf_diff(p, p->dist, (-x - p->mb) / p->sb, (x - p->mb) / p->sb, 2 * x / p->sb);
    }
    double fb = pdf(p->dist, ((o - p->mb) + v) / p->sb) / p->sb;
    return fb == 0 ? 0 : fb * cdf_diff(p, p->dist, (x - p->ma) / p->sa, (-x - p->ma) / p->sa, -2 * x / p->sa);
}

/* The mass (scaled) of the relays the input switches moving monotonically
 * from 0 to u in the demagnetised state: u > 0, {-α < β <= α <= u} (down
 * relays switched up); u < 0, {u <= β <= α < -β} (up relays switched down);
 * both clipped to the triangle.  u = ±∞: all of them. */
static int demag_edge(const hy_preisach *p, double u, double *T, hy_error *err)
{
    int up = u > 0;
    if (p->table) {
        *T = hy_preisach_table_demag(p->table, u);
        return HY_OK;
    }
    double lim = up ? fmin(u, p->hs) : fmax(u, -p->hs);
    if (p->dist == HY_PREISACH_GAUSSIAN) /* the density of the integration variable ends at GAUSS_CUT widths */
        lim = up ? fmin(lim, p->ma + GAUSS_CUT * p->sa) : fmax(lim, p->mb - GAUSS_CUT * p->sb);
    if (u == 0 || !(up ? lim > 0 : lim < 0)) {
        *T = 0;
        return HY_OK;
    }
    dm_ctx c = {p, up};
    quad q = {demag_f, &c, {p->ma, p->mb, 0, 0}, 3};
    qpt zero = {0, 2, 0}, end = {lim, -1, 0};
    if (isfinite(lim)) {
        q.anchor[3] = lim;
        end = (qpt){lim, 3, 0};
        q.nanchor = 4;
    }
    double r;
    int rc = integrate(p, &q, up ? zero : end, up ? end : zero, &r, "demagnetised state", err);
    if (!rc)
        *T = p->scale * r;
    return rc;
}

int hy_preisach_demag_output(const hy_preisach *p, double *y, hy_error *err)
{
    double tu, td;
    HY_NONNULL(err, p);
    HY_NONNULL(err, y);
    int rc = demag_edge(p, INFINITY, &tu, err);
    if (!rc)
        rc = demag_edge(p, -INFINITY, &td, err);
    if (!rc) /* relays up where α + β < 0: those switched down going to -∞, less those switched up going to +∞ */
        *y = td - tu;
    return rc;
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
    HY_NONNULL(err, m);
    memset(m, 0, sizeof *m);
    HY_NONNULL(err, p);
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
    m->s[1] = u0;
    m->n = 1;
    int rc;
    if (p->start == HY_PREISACH_DEMAGNETISED) { /* the line α = -β, from u = 0 to u0 */
        m->demag = 1;
        m->s[0] = 0;
        rc = hy_preisach_demag_output(p, &m->c[0], err);
        if (!rc)
            rc = demag_edge(p, u0, &m->e_cur, err);
        m->y = m->c[0] + 2.0 * sgn(u0) * m->e_cur;
    } else {
        int up = p->start == HY_PREISACH_POSITIVE ? 1 : -1;
        m->s[0] = up > 0 ? INFINITY : -INFINITY;
        m->c[0] = up > 0 ? p->ys : -p->ys;
        rc = edge_e(p, m->s[0], u0, &m->e_cur, err);
        m->y = m->c[0] - 2.0 * up * m->e_cur;
    }
    if (rc)
        hy_preisach_mem_free(m);
    return rc;
}

int hy_preisach_mem_apply(hy_preisach_mem *m, double u, double *y, hy_error *err)
{
    HY_NONNULL(err, m);
    if (!m->s || !m->c || !m->p)
        return hy_error_set(err, HY_EINVAL, "%s: m is empty (not initialised, or freed)", __func__);
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
        /* the demagnetised line's corner at level |s[1]| goes when u passes -s[1] */
        if (m->demag && n == 2 && (u + m->s[1]) * d >= 0)
            n = 1;
        double e;
        int rc = m->demag && n == 1 ? demag_edge(m->p, u, &e, err) : edge_e(m->p, m->s[n - 1], u, &e, err);
        if (rc)
            return rc;
        if (m->demag && n == 1)
            d = sgn(u);
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
    if (!m)
        return;
    free(m->s);
    free(m->c);
    m->s = m->c = NULL;
    m->n = m->cap = 0;
}

int hy_preisach_apply(const hy_preisach *p, const double *u, size_t n, double *y, hy_error *err)
{
    HY_NONNULL(err, p);
    HY_NONNULL_N(err, u, n);
    HY_NONNULL_N(err, y, n);
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
    HY_NONNULL(err, p);
    HY_INPUT_READY(err, in);
    HY_NONNULL(err, y);
    HY_NONNULL_N(err, t, n);
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

/* μ/K of the rectangle β in [lo, u], α in [u, hi] (α >= β holds there), u = o + v */
static double area_f(double v, double o, const void *ctx)
{
    const area_ctx *c = ctx;
    const hy_preisach *p = c->p;
    double fa = cdf_diff(p, p->dist, ((o - p->ma) + v) / p->sa, (c->hi - p->ma) / p->sa, ((c->hi - o) - v) / p->sa);
    double gb = cdf_diff(p, p->dist, (c->lo - p->mb) / p->sb, ((o - p->mb) + v) / p->sb, ((o - c->lo) + v) / p->sb);
    return fa * gb;
}

int hy_preisach_loop_area(const hy_preisach *p, double lo, double hi, double *area, hy_error *err)
{
    HY_NONNULL(err, p);
    HY_NONNULL(err, area);
    if (!isfinite(lo) || !isfinite(hi) || !(lo < hi))
        return hy_error_set(err, HY_EINVAL, "Preisach loop area needs finite lo < hi (got %g, %g)", lo, hi);
    if (p->table) {
        *area = hy_preisach_table_area(p->table, lo, hi);
        return HY_OK;
    }
    lo = fmax(lo, -p->hs); /* the triangle: no relay beyond ±hs */
    hi = fmin(hi, p->hs);
    if (!(lo < hi)) {
        *area = 0;
        return HY_OK;
    }
    area_ctx c = {p, lo, hi};
    quad q = {area_f, &c, {p->ma, p->mb, lo, hi}, 4};
    double r;
    int rc = integrate(p, &q, (qpt){lo, 2, 0}, (qpt){hi, 3, 0}, &r, "loop area", err);
    if (rc)
        return rc;
    *area = 2.0 * p->scale * r;
    return HY_OK;
}

int hy_preisach_minor_loop(const hy_preisach *p, const hy_input *in, hy_minor_loop *out, hy_error *err)
{
    double e[4];
    HY_NONNULL(err, p);
    HY_INPUT_READY(err, in);
    HY_NONNULL(err, out);
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

/* t can be summed over: not NULL, its arrays there when it has nodes. */
static int table_ok(const hy_preisach_table *t)
{
    return t && (!t->n || (t->alpha && t->beta && t->w));
}

double hy_preisach_table_everett(const hy_preisach_table *t, double a, double b)
{
    double e = 0;
    if (!table_ok(t))
        return NAN;
    for (size_t k = 0; k < t->n; k++)
        if (t->beta[k] >= b && t->alpha[k] <= a)
            e += t->w[k];
    return e;
}

double hy_preisach_table_demag(const hy_preisach_table *t, double u)
{
    double s = 0;
    if (!table_ok(t))
        return NAN;
    for (size_t k = 0; k < t->n; k++) {
        int down = t->alpha[k] + t->beta[k] >= 0;
        if (u > 0 ? down && t->alpha[k] <= u : u < 0 && !down && t->beta[k] >= u)
            s += t->w[k];
    }
    return s;
}

double hy_preisach_table_area(const hy_preisach_table *t, double lo, double hi)
{
    double s = 0;
    if (!table_ok(t))
        return NAN;
    for (size_t k = 0; k < t->n; k++)
        if (t->beta[k] >= lo && t->alpha[k] <= hi)
            s += t->w[k] * (t->alpha[k] - t->beta[k]);
    return 2 * s;
}
