/* SPDX-License-Identifier: MIT */
/* hy_boucwen.c: Bouc-Wen oscillator, Eqs. (1)-(3), integrated by the Newmark
 * rules of Eqs. (4)-(5) with Newton-Raphson on the implicit step (seeds/001,
 * Section 3); Table 2 from Table 1; the benchmark's synthesis (Section 4). */
#include "hy_boucwen.h"

#include "hy_args.h"
#include "hy_signal.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

void hy_boucwen_params_default(hy_boucwen_params *p)
{
    if (!p)
        return;
    p->m = 2.0;
    p->c = 10.0;
    p->k = 5e4;
    p->alpha = 5e4;
    p->beta = 1e3;
    p->gamma = 0.8;
    p->delta = -1.1;
    p->nu = 1.0;
}

static const struct {
    const char *name;
    size_t off;
    int domain; /* 0: finite, 1: >= 0, 2: > 0 */
} param_table[] = {
    {"m", offsetof(hy_boucwen_params, m), 2},
    {"c", offsetof(hy_boucwen_params, c), 1},
    {"k", offsetof(hy_boucwen_params, k), 1},
    {"alpha", offsetof(hy_boucwen_params, alpha), 1},
    {"beta", offsetof(hy_boucwen_params, beta), 1},
    {"gamma", offsetof(hy_boucwen_params, gamma), 0},
    {"delta", offsetof(hy_boucwen_params, delta), 0},
    {"nu", offsetof(hy_boucwen_params, nu), 2},
};
#define NPARAM (sizeof param_table / sizeof param_table[0])

static double *param_ptr(hy_boucwen_params *p, size_t i)
{
    return (double *)((char *)p + param_table[i].off);
}

static double param_get(const hy_boucwen_params *p, size_t i)
{
    return *(const double *)((const char *)p + param_table[i].off);
}

int hy_boucwen_params_validate(const hy_boucwen_params *p, hy_error *err)
{
    static const char *what[] = {"finite", "finite and >= 0", "finite and > 0"};
    HY_NONNULL(err, p);
    for (size_t i = 0; i < NPARAM; i++) {
        double v = param_get(p, i);
        int d = param_table[i].domain;
        int ok = isfinite(v) && (d == 0 || (d == 1 && v >= 0) || (d == 2 && v > 0));
        if (!ok)
            return hy_error_set(err, HY_EINVAL,
                                "Bouc-Wen parameter %s = %g must be %s",
                                param_table[i].name, v, what[d]);
    }
    if (!(p->k + p->alpha > 0))
        return hy_error_set(err, HY_EINVAL,
                            "Bouc-Wen parameters k + alpha = %g must be > 0 "
                            "(the linearised stiffness)", p->k + p->alpha);
    return HY_OK;
}

int hy_boucwen_params_set(hy_boucwen_params *p, const char *name, double value,
                          hy_error *err)
{
    HY_NONNULL(err, p);
    HY_NONNULL(err, name);
    for (size_t i = 0; i < NPARAM; i++) {
        if (strcmp(name, param_table[i].name) == 0) {
            *param_ptr(p, i) = value;
            return HY_OK;
        }
    }
    return hy_error_set(err, HY_EINVAL,
                        "unknown Bouc-Wen parameter '%s' (known: m, c, k, "
                        "alpha, beta, gamma, delta, nu)", name);
}

int hy_boucwen_params_parse(hy_boucwen_params *p, const char *assignment,
                            hy_error *err)
{
    HY_NONNULL(err, p);
    HY_NONNULL(err, assignment);
    const char *eq = strchr(assignment, '=');
    char name[32];
    size_t len = eq ? (size_t)(eq - assignment) : 0;
    if (!eq || len == 0 || len >= sizeof name)
        return hy_error_set(err, HY_EINVAL,
                            "parameter assignment '%s' is not of the form "
                            "name=value", assignment);
    memcpy(name, assignment, len);
    name[len] = '\0';
    char *end;
    double v = strtod(eq + 1, &end);
    if (end == eq + 1 || *end != '\0')
        return hy_error_set(err, HY_EINVAL,
                            "parameter %s: value '%s' is not a number", name,
                            eq + 1);
    return hy_boucwen_params_set(p, name, v, err);
}

int hy_boucwen_table2(const hy_boucwen_params *p, hy_boucwen_modal *out,
                      hy_error *err)
{
    HY_NONNULL(err, p);
    HY_NONNULL(err, out);
    int rc = hy_boucwen_params_validate(p, err);
    if (rc)
        return rc;
    double kl = p->k + p->alpha;
    out->f0_hz = sqrt(kl / p->m) / (2.0 * M_PI);
    out->zeta = p->c / (2.0 * sqrt(kl * p->m));
    return HY_OK;
}

void hy_newmark_opts_default(hy_newmark_opts *o)
{
    if (!o)
        return;
    o->a = 0.5;
    o->b = 0.25;
    o->c = 0.5;
    o->tol = 1e-12;
    o->max_iter = 50;
    o->cancel = NULL;
}

int hy_newmark_opts_validate(const hy_newmark_opts *o, hy_error *err)
{
    HY_NONNULL(err, o);
    if (!(isfinite(o->a) && o->a > 0 && o->a <= 1))
        return hy_error_set(err, HY_EINVAL, "Newmark constant a = %g must be in (0, 1]", o->a);
    if (!(isfinite(o->b) && o->b > 0 && o->b <= 0.5))
        return hy_error_set(err, HY_EINVAL, "Newmark constant b = %g must be in (0, 0.5]", o->b);
    if (!(isfinite(o->c) && o->c > 0 && o->c <= 1))
        return hy_error_set(err, HY_EINVAL, "Newmark constant c = %g must be in (0, 1]", o->c);
    if (!(isfinite(o->tol) && o->tol > 0 && o->tol <= 1e-3))
        return hy_error_set(err, HY_EINVAL, "Newton tolerance tol = %g must be in (0, 1e-3]", o->tol);
    if (o->max_iter < 1)
        return hy_error_set(err, HY_EINVAL, "Newton max_iter = %d must be >= 1", o->max_iter);
    return HY_OK;
}

/* ż = f(v, z) of Eq. (3) and its partial derivatives (fv, fz).  The seed's
 * text lost the parentheses; the official validation pair decides for
 * α ẏ − β (γ |ẏ| |z|^(ν−1) z + δ ẏ |z|^ν): it reproduces yval_multisine to
 * 2e-16 m e_RMS, the reading without them is off by 7.6e-4 m.
 *
 * Inlined into the Newton loop, with nu1 (ν = 1, Table 1's value) a constant
 * of each copy: the powers drop out and the signs of ẏ and z select ±γ and
 * ±δ ẏ instead of multiplying by sign(·) converted from an integer.  Every
 * operation and its order are those of the plain formula (x · 1, x · (−1)
 * and x · 0 are what the selections return), so the results are the same
 * bits; the Newmark steps of a bw_fig1a render took 27 ms instead of 38 ms. */
static inline __attribute__((always_inline)) double zdot_nu(const hy_boucwen_params *p, int nu1, double v,
                                                            double z, double *fv, double *fz)
{
    double az = fabs(z), av = fabs(v);
    double g, zn, dzn; /* g = |z|^(ν-1) z, zn = |z|^ν, dzn = ν |z|^(ν-1) */
    if (nu1) {
        g = z;
        zn = az;
        dzn = 1.0;
    } else {
        zn = pow(az, p->nu);
        g = (double)((z > 0) - (z < 0)) * zn;
        /* ν < 1 makes the derivative infinite at z = 0: keep it finite. */
        dzn = p->nu * pow(az > DBL_MIN ? az : DBL_MIN, p->nu - 1.0);
    }
    double gsv = v > 0 ? p->gamma : v < 0 ? -p->gamma : p->gamma * 0.0; /* γ sign(ẏ) */
    double dv = p->delta * v, gav = p->gamma * av;
    double dvsz = z > 0 ? dv : z < 0 ? -dv : dv * 0.0; /* δ ẏ sign(z) */
    *fv = p->alpha - p->beta * (gsv * g + p->delta * zn);
    *fz = nu1 ? -p->beta * (gav + dvsz) : -p->beta * (gav * dzn + dvsz * dzn);
    return p->alpha * v - p->beta * (gav * g + dv * zn);
}

static double zdot(const hy_boucwen_params *p, double v, double z)
{
    double fv, fz;
    return p->nu == 1.0 ? zdot_nu(p, 1, v, z, &fv, &fz) : zdot_nu(p, 0, v, z, &fv, &fz);
}

void hy_boucwen_state_init(const hy_boucwen_params *p, double u0, double y0,
                           double v0, double z0, hy_boucwen_state *s)
{
    if (!p || !s)
        return;
    s->t = 0.0;
    s->y = y0;
    s->v = v0;
    s->z = z0;
    s->a = (u0 - p->c * v0 - p->k * y0 - z0) / p->m;
    s->zd = zdot(p, v0, z0);
}

/* One Newmark step (hy_boucwen_step), nu1 as in zdot_nu; on failure the
 * last residuals in r[0], r[1] and s unchanged.  These three are always
 * inlined: a copy left with nu1 a run-time argument (and pow's call in the
 * loop) was nearly as slow as before (32-35 ms, not 27). */
static inline __attribute__((always_inline)) int step_nu(const hy_boucwen_params *p, int nu1,
                                                         const hy_newmark_opts *o, double h, double u1,
                                                         hy_boucwen_state *s, double r[2])
{
    /* Predictors of Eqs. (4)-(5) with ÿ(t+h) = ż(t+h) = 0. */
    double vp = s->v + (1.0 - o->a) * h * s->a;
    double yp = s->y + h * s->v + (0.5 - o->b) * h * h * s->a;
    double zp = s->z + (1.0 - o->c) * h * s->zd;
    double ah = o->a * h, bh2 = o->b * h * h, ch = o->c * h;
    double j11 = p->m + p->c * ah + p->k * bh2; /* ∂R1/∂ÿ */
    double A = 0.0, Zd = 0.0, r1 = 0.0, r2 = 0.0;
    for (int it = 0; it < o->max_iter; it++) {
        double V = vp + ah * A, Y = yp + bh2 * A, Z = zp + ch * Zd;
        double fv, fz, f = zdot_nu(p, nu1, V, Z, &fv, &fz);
        r1 = p->m * A + p->c * V + p->k * Y + Z - u1; /* Eq. (1) */
        r2 = Zd - f;                                   /* Eq. (3) */
        /* Jacobian of (r1, r2) in (ÿ, ż): [j11, ch; -fv ah, 1 - fz ch]. */
        double j21 = -fv * ah, j22 = 1.0 - fz * ch;
        double det = j11 * j22 - ch * j21;
        double dA = -(r1 * j22 - ch * r2) / det;
        double dZ = -(j11 * r2 - j21 * r1) / det;
        A += dA;
        Zd += dZ;
        if (!isfinite(A) || !isfinite(Zd))
            break;
        double fscale = fabs(u1) + fabs(p->m * A) + fabs(p->c * V) +
                        fabs(p->k * Y) + fabs(Z) + DBL_MIN;
        double zscale = fabs(Zd) + fabs(p->alpha * V) + DBL_MIN;
        /* Absolute floor: the updates rounding alone produces.  R1 sums five
           terms of size <= fscale: a few ulps of fscale.  V = vp + ah A and
           Z = zp + ch Zd carry a few ulps of their terms, which cancel near a
           velocity reversal (|V| << |vp|), and f passes that on times fv and
           fz.  4 ulps each: the Newton update then flips A by one ulp forever
           (-7.1e-15 N at u = 40 N) unless it stops here.  ÿ itself is then
           known only to ffloor / j11, and ż depends on it through
           V = vp + ah ÿ: its floor carries fv ah ffloor / j11 as well (without
           it, ÿ's flip of 1.4e-14 N / j11 moved ż by 1.6e-14 N/s against a
           floor of 1.5e-16 at amp = 100 N in bw_fig1a, and the step failed). */
        double ffloor = 4 * DBL_EPSILON * fscale;
        double zfloor = 4 * DBL_EPSILON * (fabs(Zd) + fabs(fv) * (fabs(vp) + fabs(ah * A)) +
                                           fabs(fz) * (fabs(zp) + fabs(ch * Zd))) +
                        fabs(fv) * ah * ffloor / j11;
        if (fabs(dA) * j11 <= o->tol * fscale + ffloor && fabs(dZ) <= o->tol * zscale + zfloor) {
            s->t += h;
            s->a = A;
            s->zd = Zd;
            s->v = vp + ah * A;
            s->y = yp + bh2 * A;
            s->z = zp + ch * Zd;
            return HY_OK;
        }
    }
    r[0] = r1;
    r[1] = r2;
    return HY_ENUM;
}

static int step_failed(const hy_newmark_opts *o, double h, const hy_boucwen_state *s, const double r[2],
                       hy_error *err)
{
    return hy_error_set(err, HY_ENUM,
                        "Newmark step at t = %.9g s did not converge in %d "
                        "Newton iterations (residuals %.3g N and %.3g N/s)",
                        s->t + h, o->max_iter, r[0], r[1]);
}

int hy_boucwen_step(const hy_boucwen_params *p, const hy_newmark_opts *o,
                    double h, double u1, hy_boucwen_state *s, hy_error *err)
{
    HY_NONNULL(err, p);
    HY_NONNULL(err, o);
    HY_NONNULL(err, s);
    double r[2];
    int rc = p->nu == 1.0 ? step_nu(p, 1, o, h, u1, s, r) : step_nu(p, 0, o, h, u1, s, r);
    return rc ? step_failed(o, h, s, r, err) : HY_OK;
}

/* Steps 1 .. n-1 of simulate from s, the force u[i mod nper], nu1 as in
 * zdot_nu: one copy of the step per value, the test of ν out of the loop. */
static inline __attribute__((always_inline)) int steps_nu(const hy_boucwen_params *p, int nu1,
                                                          const hy_newmark_opts *o, double h, const double *u,
                                                          size_t nper, size_t n, hy_boucwen_state *s, double *y,
                                                          double *z, hy_error *err)
{
    double r[2];
    hy_boucwen_state st = *s; /* a local: in registers, not reloaded after each store to y */
    unsigned tick = 0;
    for (size_t i = 1, j = 1 % nper; i < n;) { /* blocks of steps, the cancel hook between them */
        size_t end = n - i > HY_NEWMARK_CANCEL_STEPS ? i + HY_NEWMARK_CANCEL_STEPS : n;
        for (; i < end; i++, j = j + 1 == nper ? 0 : j + 1) {
            if (step_nu(p, nu1, o, h, u[j], &st, r))
                return step_failed(o, h, &st, r, err);
            y[i] = st.y;
            if (z)
                z[i] = st.z;
        }
        if (i < n && hy_cancel_poll(o->cancel, &tick, 1)) {
            *s = st;
            return hy_cancel_error(err);
        }
    }
    *s = st;
    return HY_OK;
}

/* hy_boucwen_simulate of the force u[i mod nper] (u: nper samples). */
static int simulate(const hy_boucwen_params *p, const hy_newmark_opts *o, double h, const double *u, size_t nper,
                    size_t n, const double *ic, double *y, double *z, hy_error *err)
{
    int rc = hy_boucwen_params_validate(p, err);
    if (!rc)
        rc = hy_newmark_opts_validate(o, err);
    if (rc)
        return rc;
    if (!(isfinite(h) && h > 0))
        return hy_error_set(err, HY_EINVAL, "time step h = %g must be finite and > 0", h);
    if (n == 0 || nper == 0)
        return hy_error_set(err, HY_EINVAL, "input force u is empty");
    for (size_t i = 0; i < nper; i++)
        if (!isfinite(u[i]))
            return hy_error_set(err, HY_EINVAL,
                                "input force u[%zu] = %g is not finite", i, u[i]);
    hy_boucwen_state s;
    hy_boucwen_state_init(p, u[0], ic ? ic[0] : 0.0, ic ? ic[1] : 0.0,
                          ic ? ic[2] : 0.0, &s);
    y[0] = s.y;
    if (z)
        z[0] = s.z;
    return p->nu == 1.0 ? steps_nu(p, 1, o, h, u, nper, n, &s, y, z, err)
                        : steps_nu(p, 0, o, h, u, nper, n, &s, y, z, err);
}

int hy_boucwen_simulate(const hy_boucwen_params *p, const hy_newmark_opts *o,
                        double h, const double *u, size_t n, const double *ic,
                        double *y, double *z, hy_error *err)
{
    HY_NONNULL(err, p);
    HY_NONNULL(err, o);
    HY_NONNULL(err, u);
    HY_NONNULL(err, y);
    return simulate(p, o, h, u, n, n, ic, y, z, err);
}

int hy_boucwen_synth(const hy_boucwen_params *p, const hy_newmark_opts *o,
                     double fs, size_t r, int staged, const double *u_int,
                     size_t n_int, double *y_out, hy_error *err)
{
    HY_NONNULL(err, p);
    HY_NONNULL(err, o);
    HY_NONNULL(err, u_int);
    HY_NONNULL(err, y_out);
    if (n_int > SIZE_MAX / sizeof(double))
        return hy_error_set(err, HY_EINVAL, "%zu samples do not fit in memory", n_int);
    if (!(isfinite(fs) && fs > 0))
        return hy_error_set(err, HY_EINVAL, "sampling rate fs = %g must be finite and > 0", fs);
    if (r < 1)
        return hy_error_set(err, HY_EINVAL, "upsampling factor r must be >= 1");
    double *y = malloc((n_int ? n_int : 1) * sizeof *y);
    if (!y)
        return hy_error_set(err, HY_ENOMEM, "out of memory for %zu output samples", n_int);
    int rc = hy_boucwen_simulate(p, o, 1.0 / (fs * (double)r), u_int, n_int,
                                 NULL, y, NULL, err);
    if (!rc) {
        size_t ny;
        rc = hy_signal_decimate_stages(y, n_int, r, staged, y_out, &ny, err);
    }
    free(y);
    return rc;
}

int hy_boucwen_synth_periodic(const hy_boucwen_params *p,
                              const hy_newmark_opts *o, double fs, size_t r,
                              int staged, const double *u_period,
                              size_t n_period, size_t periods, double *y_out,
                              hy_error *err)
{
    return hy_boucwen_synth_periodic_kept(p, o, fs, r, staged, u_period, n_period, 0, periods, y_out, err);
}

int hy_boucwen_synth_periodic_kept(const hy_boucwen_params *p, const hy_newmark_opts *o, double fs, size_t r,
                                   int staged, const double *u_period, size_t n_period, size_t first,
                                   size_t periods, double *y_out, hy_error *err)
{
    HY_NONNULL(err, p);
    HY_NONNULL(err, o);
    HY_NONNULL(err, u_period);
    HY_NONNULL(err, y_out);
    if (periods < 1 || first >= periods)
        return hy_error_set(err, HY_EINVAL, "number of periods must be >= 1 (and more than the %zu dropped)", first);
    if (r < 1 || n_period == 0 || n_period % r)
        return hy_error_set(err, HY_EINVAL,
                            "period length %zu must be a positive multiple of "
                            "the upsampling factor %zu", n_period, r);
    if (periods >= SIZE_MAX / sizeof(double) / n_period / 2)
        return hy_error_set(err, HY_EINVAL, "%zu periods of %zu samples do not fit in memory", periods, n_period);
    if (!(isfinite(fs) && fs > 0))
        return hy_error_set(err, HY_EINVAL, "sampling rate fs = %g must be finite and > 0", fs);
    /* The record is periods + 1 periods long (the extra one keeps the
       filter's edge off the last kept period), but the kept outputs read
       the integrated y only within reach of their own samples: it is
       integrated to the last kept output's reach and decimated from a
       multiple of r before the first one's (hy_signal_decimate_reach), the
       same bits as the whole record decimated (bw_fig1a: 450,086 Newmark
       steps instead of 465,000, 1/3 of the FIR work). */
    size_t reach = hy_signal_decimate_reach(r, staged), nd = n_period / r;
    size_t tail = reach + 1 > r ? reach + 1 - r : 0, head = first * n_period, back = (reach + r - 1) / r * r;
    size_t end = periods * n_period + (tail < n_period ? tail : n_period), off = head >= back ? head - back : 0;
    double *y = malloc(end * sizeof *y), *yd = malloc(((end - off) / r + 1) * sizeof *yd);
    int rc = y && yd ? HY_OK : hy_error_set(err, HY_ENOMEM, "out of memory for %zu samples", end);
    if (!rc)
        rc = simulate(p, o, 1.0 / (fs * (double)r), u_period, n_period, end, NULL, y, NULL, err);
    size_t ny;
    if (!rc)
        rc = hy_signal_decimate_stages(y + off, end - off, r, staged, yd, &ny, err);
    if (!rc)
        memcpy(y_out, yd + (head - off) / r, (periods - first) * nd * sizeof *yd);
    free(y);
    free(yd);
    return rc;
}
