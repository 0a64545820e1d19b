/* SPDX-License-Identifier: MIT */
/* hy_preisach.h: the classical Preisach model, y(t) = ∫∫_{α≥β} μ(α,β) γ_αβ[u](t) dα dβ,
 * evaluated exactly through its Everett function E(a,b) = ∫∫_{b≤β≤α≤a} μ and the
 * staircase memory of the input's dominant extrema (wiping-out).
 *
 * Each relay γ_αβ switches to +1 when u rises to α and to -1 when u falls to β.
 * The density is factorised, μ(α,β) = K f((α-m_α)/s_α)/s_α · f((β-m_β)/s_β)/s_β
 * on α >= β, with f a named distribution (HY_PREISACH_GAUSSIAN, _LORENTZIAN)
 * and K chosen so that saturation gives ±y_s.  After a history with alternating
 * dominant extrema s_1, s_2, ..., s_n (s_0 = ∓∞ the initial saturation, s_n the
 * present input),
 *     y = ∓y_s + 2 Σ_j d_j E(max(s_{j-1},s_j), min(s_{j-1},s_j)),  d_j = sign(s_j - s_{j-1}),
 * so the output of a piecewise-monotone input is exact at every sample (no time
 * stepping), minor loops close where they started (return-point memory) and
 * loops between the same two reversal values are congruent.
 *
 * E has no elementary closed form here: the inner integral (over β) is a CDF
 * difference, but the outer one is ∫ φ(x) Φ(x + d) dx (a bivariate normal
 * probability, Owen's T) for the Gaussian and ∫ atan(y + c)/(1 + y²) dy (a
 * complex dilogarithm) for the Lorentzian, elementary only when both factors
 * are the same distribution (E = K (F(a) - F(b))² / 2).  So E is one adaptive
 * Gauss-Kronrod quadrature (GSL qag, split at the densities' centres and
 * widths) of the closed-form inner integral, to 1e-13 relative (measured
 * 4e-14 against the other order of integration).  Relays much narrower than
 * their fields' magnitude, s << |m|, are limited by what the fields' ulps
 * resolve: an error bound up to 64 ε |m|/s is accepted there.
 *
 *     hy_preisach p;
 *     hy_preisach_symmetric(&p, HY_PREISACH_GAUSSIAN, 0.5, 0.2, 1.0, &err); // h_c, σ, y_s
 *     double u[] = {0, 1, -0.3, 0.6, -0.3}, y[5];
 *     hy_preisach_apply(&p, u, 5, y, &err);    // from negative saturation
 *
 * The GSL error handler must be off (gsl_set_error_handler_off) in programs
 * that call this.  hy_preisach holds no allocation; a hy_preisach_mem does.
 */
#ifndef HY_PREISACH_H
#define HY_PREISACH_H

#include <stddef.h>
#include "hy_input.h"
#include "hy_rateind.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { HY_PREISACH_GAUSSIAN = 0, HY_PREISACH_LORENTZIAN = 1 };

/* The state before u(0) (hy_preisach.start). */
enum { HY_PREISACH_NEGATIVE = -1, HY_PREISACH_DEMAGNETISED = 0, HY_PREISACH_POSITIVE = 1 };

#define HY_PREISACH_GL 20 /* Gauss-Legendre nodes for short CDF differences */

/* A tabulated density (hy_preisach_table.h builds, reads and fits one): weighted
 * relays; the three sums the model evaluates over it live here, with the model. */
typedef struct hy_preisach_table {
    size_t n;              /* nodes with μ > 0                          */
    double *alpha, *beta;  /* their switching fields α = H_b, β = H_a   */
    double *w;             /* μ times the cell's area in (α, β)          */
    size_t nclipped;       /* finite nodes with ρ < 0 set to 0           */
} hy_preisach_table;

/* E(a, b): the weight of the nodes with b <= β and α <= a (0 when a <= b).
 * The three table sums: t NULL, or a table with nodes but a NULL array,
 * gives NaN. */
double hy_preisach_table_everett(const hy_preisach_table *t, double a, double b);

/* For hy_preisach's demagnetised state (relays up where α + β < 0): the
 * weight switched moving monotonically from 0 to u, up (u > 0: relays with
 * α + β >= 0 and α <= u) or down (u < 0: α + β < 0 and β >= u). */
double hy_preisach_table_demag(const hy_preisach_table *t, double u);

/* ∮ u dy of the loop between lo < hi: 2 Σ w (α − β) over lo <= β, α <= hi. */
double hy_preisach_table_area(const hy_preisach_table *t, double lo, double hi);

typedef struct hy_preisach {
    int dist;            /* HY_PREISACH_GAUSSIAN or HY_PREISACH_LORENTZIAN      */
    double ma, sa;       /* up-switching fields α: centre and width (> 0)       */
    double mb, sb;       /* down-switching fields β: centre and width (> 0)     */
    double ys;           /* output at positive saturation (> 0)                 */
    int start;           /* HY_PREISACH_NEGATIVE (default, saturated before u(0)),
                            _POSITIVE, or _DEMAGNETISED: the state an alternating
                            input of decaying amplitude leaves at u = 0, relays
                            up exactly where α + β < 0 (the line α = -β is the
                            staircase), then moved monotonically to u(0)      */
    double hs;           /* support: +∞ the half-plane α >= β (default), or the
                            triangle -hs <= β <= α <= hs (hy_preisach_support) */
    /* filled by hy_preisach_init (and hy_preisach_support) */
    double mass;         /* ∫∫ of the unscaled density over the support         */
    double scale;        /* K = ys / mass                                       */
    double glx[HY_PREISACH_GL], glw[HY_PREISACH_GL]; /* nodes/weights on [-1,1] */
    /* NULL: the analytic density above; else a tabulated density
       (hy_preisach_tabulated), borrowed: it must outlive p */
    const struct hy_preisach_table *table;
} hy_preisach;

/* The distributions' names in the order of their values, NULL-terminated
 * (the scene key model.pr_density lists them from here). */
extern const char *const hy_preisach_dist_names[];
/* Name of distribution d ("gaussian", "lorentzian"), NULL when unknown. */
const char *hy_preisach_dist_name(int d);
/* Distribution by name; -1 when unknown or name is NULL. */
int hy_preisach_dist_find(const char *name);

/* Fills p with density dist(α; ma, sa) · dist(β; mb, sb) scaled to saturation
 * ±ys, starting negatively saturated.  HY_EINVAL names the bad parameter: a
 * width must be > 0 and at least 1e-12 of its centre's magnitude (narrower
 * relays cannot be told apart in double precision), ys > 0, all finite, and
 * the density must put at least 1e-300 of its mass on α >= β.  p must not be
 * NULL (HY_EINVAL). */
int hy_preisach_init(hy_preisach *p, int dist, double ma, double sa, double mb, double sb, double ys,
                     hy_error *err);
/* The usual symmetric density: α around +hc, β around -hc, both of width
 * sigma (as hy_preisach_init: p must not be NULL). */
int hy_preisach_symmetric(hy_preisach *p, int dist, double hc, double sigma, double ys, hy_error *err);

/* Fills p with the tabulated density t (weighted relays, hy_preisach_table.h;
 * borrowed): ys = the relays' total weight, from negative saturation, on
 * the half-plane; the Everett function, the demagnetised state and loop
 * areas are the sums over the relays (exact for this discrete density).
 * HY_EINVAL for a table without a relay of weight > 0; p and t must not be
 * NULL, nor t's arrays when t->n > 0 (HY_EINVAL). */
int hy_preisach_tabulated(hy_preisach *p, const struct hy_preisach_table *t, hy_error *err);

/* Puts the density on the triangle -hs <= β <= α <= hs (the relays outside
 * it are removed; the input saturates the model at |u| >= hs) and scales it
 * to ±ys there; hs = +∞ restores the half-plane.  HY_EINVAL when hs is not
 * > 0 or the triangle holds less than 1e-300 of the density's mass, and for p
 * NULL. */
int hy_preisach_support(hy_preisach *p, double hs, hy_error *err);

/* Everett function E(a, b) = K ∫∫_{b≤β≤α≤a} of the density, a >= b; a may be
 * +∞ and b -∞ (E(+∞,-∞) = ys).  HY_EINVAL when a < b or either is NaN,
 * HY_ENUM when the quadrature cannot reach 1e-12 relative (message says where).
 * p and E must not be NULL (HY_EINVAL). */
int hy_preisach_everett(const hy_preisach *p, double a, double b, double *E, hy_error *err);

/* The staircase memory: s[0] = ∓∞ (initial saturation) or 0 (demagnetised:
 * the line α = -β, whose corner at level |s[1]| is wiped when the input
 * passes -s[1]), s[1..n] alternating dominant extrema ending with the
 * present input s[n]; c[j] is the output with edges 1..j complete.  Owns s
 * and c. */
typedef struct hy_preisach_mem {
    const hy_preisach *p;   /* borrowed: must outlive the memory          */
    double *s, *c;
    size_t n, cap;
    double e_cur;           /* E of the present edge (s[n-1], s[n])       */
    double y;               /* output at s[n]                             */
    int demag;              /* s[0] is the demagnetised line              */
} hy_preisach_mem;

/* The output of the demagnetised state at u = 0 (0 for a symmetric density,
 * ma = -mb and sa = sb) into *y (p and y must not be NULL: HY_EINVAL). */
int hy_preisach_demag_output(const hy_preisach *p, double *y, hy_error *err);

/* Saturates (p->start) and then moves the input monotonically to u0.  On error
 * (HY_EINVAL for a non-finite u0, HY_ENOMEM, HY_ENUM) m owns nothing.  m and p
 * must not be NULL (HY_EINVAL). */
int hy_preisach_mem_init(hy_preisach_mem *m, const hy_preisach *p, double u0, hy_error *err);
/* Moves the input monotonically from its present value to u; *y (may be NULL)
 * gets the output.  On error the memory is left as before the call.  m must
 * not be NULL nor empty (not initialised, or freed): HY_EINVAL. */
int hy_preisach_mem_apply(hy_preisach_mem *m, double u, double *y, hy_error *err);
/* Frees m's memory curve and empties it (m may be NULL: nothing done; a
 * second call is harmless). */
void hy_preisach_mem_free(hy_preisach_mem *m);

/* Output for the input sequence u[0..n-1] (u[0] reached from saturation,
 * monotone between consecutive values): y[i] after u[i].  p must not be NULL,
 * nor u and y when n > 0 (HY_EINVAL). */
int hy_preisach_apply(const hy_preisach *p, const double *u, size_t n, double *y, hy_error *err);

/* Output at ascending times t[0..n-1] for an input of hy_input.h (every
 * extremum between samples is fed; exact).  p, in (with pieces) and y must
 * not be NULL, nor t when n > 0 (HY_EINVAL). */
int hy_preisach_drive(const hy_preisach *p, const hy_input *in, const double *t, size_t n, double *y,
                      hy_error *err);

/* ∮ u dy of the closed loop between reversal values lo < hi (any history: the
 * loops are congruent): 2K ∫_lo^hi P(u ≤ α ≤ hi) P(lo ≤ β ≤ u) du (lo and hi
 * clipped to the triangle's ±hs), by
 * adaptive quadrature to 1e-12 relative.  Energy per cycle when u = H, y = B.
 * p and area must not be NULL (HY_EINVAL). */
int hy_preisach_loop_area(const hy_preisach *p, double lo, double hi, double *area, hy_error *err);

/* The steady minor loop of a bimodal input (hy_rateind.h): y_close == y_start
 * (return-point memory), areas from hy_preisach_loop_area, cycles = 1 (the
 * state is periodic once both global extrema were visited).  p, in and out
 * must not be NULL (HY_EINVAL). */
int hy_preisach_minor_loop(const hy_preisach *p, const hy_input *in, hy_minor_loop *out, hy_error *err);

#ifdef __cplusplus
}
#endif

#endif
