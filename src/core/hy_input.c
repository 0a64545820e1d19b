/* SPDX-License-Identifier: MIT */
/* hy_input.c: periodic piecewise-monotone inputs, variation ρ_u (Eq. 5) and
 * normalised input ψ_u (Eqs. 9-10) of seed 000. */
#include "hy_input.h"

#include "hy_args.h"
#include "hy_file.h"
#include "hy_os.h"

#include <ctype.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>

#define HY_PI 3.14159265358979323846

static void piece_linear(hy_piece *p, double t0, double t1, double u0, double u1)
{
    memset(p, 0, sizeof *p);
    p->t0 = t0;
    p->t1 = t1;
    p->u0 = u0;
    p->u1 = u1;
    p->shape = HY_PIECE_LINEAR;
}

/* A half-cosine from (t0,u0) to (t1,u1): u = c + A sin(ωt + φ), u̇ = 0 at both ends. */
static void piece_halfcos(hy_piece *p, double t0, double t1, double u0, double u1)
{
    piece_linear(p, t0, t1, u0, u1);
    p->shape = HY_PIECE_SINE;
    p->c = 0.5 * (u0 + u1);
    p->amp = 0.5 * (u1 - u0);
    p->omega = HY_PI / (t1 - t0);
    p->phase = -p->omega * t0 - 0.5 * HY_PI;
}

double hy_piece_u(const hy_piece *p, double t)
{
    if (!p)
        return NAN;
    if (t <= p->t0)
        return p->u0;
    if (t >= p->t1)
        return p->u1;
    if (p->shape == HY_PIECE_LINEAR) {
        double s = (t - p->t0) / (p->t1 - p->t0);
        return p->u0 + (p->u1 - p->u0) * s;
    }
    double u = p->c + p->amp * sin(p->omega * t + p->phase);
    /* keep the piece monotone and inside its end values despite rounding */
    double lo = fmin(p->u0, p->u1), hi = fmax(p->u0, p->u1);
    return u < lo ? lo : (u > hi ? hi : u);
}

double hy_piece_du(const hy_piece *p, double t)
{
    if (!p)
        return NAN;
    if (p->shape == HY_PIECE_LINEAR)
        return (p->u1 - p->u0) / (p->t1 - p->t0);
    return p->amp * p->omega * cos(p->omega * t + p->phase);
}

static double piece_ddu(const hy_piece *p, double t)
{
    if (p->shape == HY_PIECE_LINEAR)
        return 0;
    return -p->amp * p->omega * p->omega * sin(p->omega * t + p->phase);
}

static int sgn(double x) { return (x > 0) - (x < 0); }

/* Smallest excursion an input given by its extrema may have, relative to its
 * scale S = max(largest |u|, total variation ρ_T): the loops are found and
 * sampled in ρ, whose values reach S, so an excursion w spans w / ulp(S) =
 * (w / S) 2^52 representable values: 1e-10 S leaves about 450,000, enough for
 * the points of a curve and for loop areas to ~1e-6 relative.  Narrower
 * excursions vanish in rounding (umin1 = -1e19 made a minor loop of width 0.8
 * narrower than one ulp of ρ). */
#define HY_EXCURSION_MIN_REL 1e-10

/* Checks the cyclic extrema e[0..n-1] against HY_EXCURSION_MIN_REL: returns 0,
 * or 1 with *big (the extremum of largest magnitude), *small (the start of
 * the narrowest excursion e[small] -> e[small+1]) and *scale set. */
static int excursion_too_small(const double *e, size_t n, size_t *big, size_t *small, double *scale)
{
    double var = 0, umax = 0, wmin = INFINITY;
    *big = *small = 0;
    for (size_t i = 0; i < n; i++) {
        double w = fabs(e[(i + 1) % n] - e[i]);
        var += w;
        if (fabs(e[i]) > umax) {
            umax = fabs(e[i]);
            *big = i;
        }
        if (w < wmin) {
            wmin = w;
            *small = i;
        }
    }
    *scale = fmax(umax, var);
    return wmin < HY_EXCURSION_MIN_REL * *scale;
}

/* ρ at every piece start, the runs (into runs, room for n), T and ρ_T of the
 * n > 0 pieces pcs, which in then points to; 0, or -1 when the input does not
 * rise and fall within its period (in's other fields unspecified). */
static int finish_runs(hy_input *in, hy_piece *pcs, hy_run *runs, size_t n)
{
    memset(in, 0, sizeof *in);
    in->runs = runs;
    in->pieces = pcs;
    in->npieces = n;
    in->all_linear = 1;
    double rho = 0;
    for (size_t i = 0; i < n; i++) {
        pcs[i].rho0 = rho;
        rho += fabs(pcs[i].u1 - pcs[i].u0);
        if (pcs[i].shape != HY_PIECE_LINEAR)
            in->all_linear = 0;
        int s = sgn(pcs[i].u1 - pcs[i].u0);
        if (s == 0)
            continue;
        hy_run *last = in->nruns ? &in->runs[in->nruns - 1] : NULL;
        if (last && last->sign == s) {
            last->p1 = i + 1;
            last->rho1 = rho;
            last->u1 = pcs[i].u1;
        } else {
            hy_run *r = &in->runs[in->nruns++];
            r->p0 = i;
            r->p1 = i + 1;
            r->rho0 = pcs[i].rho0;
            r->rho1 = rho;
            r->u0 = pcs[i].u0;
            r->u1 = pcs[i].u1;
            r->sign = s;
        }
    }
    in->period = pcs[n - 1].t1;
    in->rho_T = rho;
    return in->nruns < 2 || !(rho > 0) || !isfinite(rho) ? -1 : 0;
}

#define NO_RISE_FALL "input must rise and fall within its period (a periodic input needs at least two monotone runs with finite variation)"

/* Computes ρ at every piece start, the runs, T and ρ_T; takes ownership of pcs. */
static int finish(hy_input *in, hy_piece *pcs, size_t n, hy_error *err)
{
    memset(in, 0, sizeof *in);
    if (n == 0) {
        free(pcs);
        return hy_error_set(err, HY_EINVAL, "input has no pieces");
    }
    hy_run *runs = malloc(n * sizeof *runs);
    if (!runs) {
        free(pcs);
        return hy_error_set(err, HY_ENOMEM, "out of memory for input runs");
    }
    if (finish_runs(in, pcs, runs, n)) {
        hy_input_free(in);
        return hy_error_set(err, HY_EINVAL, NO_RISE_FALL);
    }
    return HY_OK;
}

void hy_input_free(hy_input *in)
{
    if (!in)
        return;
    free(in->pieces);
    free(in->runs);
    in->pieces = NULL;
    in->runs = NULL;
    in->npieces = in->nruns = 0;
}

static int check_finite_arr(const char *what, const double *v, size_t n, hy_error *err)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(v[i]))
            return hy_error_set(err, HY_EINVAL, "%s[%zu] must be a finite number (got %g)", what, i, v[i]);
    return HY_OK;
}

int hy_input_pwl(hy_input *in, const double *t, const double *u, size_t n, hy_error *err)
{
    int rc;
    HY_NONNULL(err, in);
    HY_NONNULL(err, t);
    HY_NONNULL(err, u);
    if (n < 3)
        return hy_error_set(err, HY_EINVAL, "a piecewise-linear input needs at least 3 points (got %zu)", n);
    if ((rc = check_finite_arr("t", t, n, err)) || (rc = check_finite_arr("u", u, n, err)))
        return rc;
    if (t[0] != 0)
        return hy_error_set(err, HY_EINVAL, "t[0] must be 0 (got %g)", t[0]);
    for (size_t i = 1; i < n; i++)
        if (!(t[i] > t[i - 1]))
            return hy_error_set(err, HY_EINVAL, "times must be strictly increasing: t[%zu] = %g is not > t[%zu] = %g",
                                i, t[i], i - 1, t[i - 1]);
    if (u[n - 1] != u[0])
        return hy_error_set(err, HY_EINVAL, "input is not periodic: u at the last point (%g) differs from u(0) = %g",
                            u[n - 1], u[0]);
    hy_piece *p = malloc((n - 1) * sizeof *p);
    if (!p)
        return hy_error_set(err, HY_ENOMEM, "out of memory for %zu pieces", n - 1);
    for (size_t i = 0; i + 1 < n; i++)
        piece_linear(&p[i], t[i], t[i + 1], u[i], u[i + 1]);
    rc = finish(in, p, n - 1, err);
    if (!rc)
        snprintf(in->desc, sizeof in->desc, "piecewise-linear input, %zu points", n);
    return rc;
}

int hy_input_multimodal(hy_input *in, const double *e, size_t n, const double *tm, int shape,
                        hy_error *err)
{
    int rc;
    HY_NONNULL(err, in);
    HY_NONNULL(err, e);
    if (n < 2 || n % 2)
        return hy_error_set(err, HY_EINVAL, "a multimodal input needs an even number (>= 2) of alternating extrema (got %zu)", n);
    if ((rc = check_finite_arr("extrema", e, n, err)))
        return rc;
    if (tm && (rc = check_finite_arr("times", tm, n + 1, err)))
        return rc;
    for (size_t i = 0; i < n; i++) {
        double d0 = e[(i + 1) % n] - e[i], d1 = e[(i + 2) % n] - e[(i + 1) % n];
        if (d0 == 0)
            return hy_error_set(err, HY_EINVAL, "consecutive extrema must differ: extrema[%zu] = extrema[%zu] = %g",
                                i, (i + 1) % n, e[i]);
        if (sgn(d0) == sgn(d1))
            return hy_error_set(err, HY_EINVAL, "extrema must alternate between maxima and minima: extrema[%zu] = %g is not an extremum",
                                (i + 1) % n, e[(i + 1) % n]);
    }
    size_t big, small;
    double scale;
    if (excursion_too_small(e, n, &big, &small, &scale))
        return hy_error_set(err, HY_EINVAL,
                            "extrema[%zu] = %g makes the input's scale %g (largest |u| or total variation), and "
                            "the excursion extrema[%zu] -> extrema[%zu] of %g is below %g of it: its loop cannot be "
                            "resolved in double precision",
                            big, e[big], scale, small, (small + 1) % n, fabs(e[(small + 1) % n] - e[small]),
                            HY_EXCURSION_MIN_REL);
    if (tm) {
        if (tm[0] != 0)
            return hy_error_set(err, HY_EINVAL, "times[0] must be 0 (got %g)", tm[0]);
        for (size_t i = 1; i <= n; i++)
            if (!(tm[i] > tm[i - 1]))
                return hy_error_set(err, HY_EINVAL, "times must be strictly increasing: t%zu = %g is not > t%zu = %g",
                                    i, tm[i], i - 1, tm[i - 1]);
    }
    hy_piece *p = malloc(n * sizeof *p);
    if (!p)
        return hy_error_set(err, HY_ENOMEM, "out of memory for %zu pieces", n);
    double t = 0;
    for (size_t i = 0; i < n; i++) {
        double a = e[i], b = e[(i + 1) % n];
        double t1 = tm ? tm[i + 1] : t + fabs(b - a);
        if (shape == HY_SHAPE_COSINE)
            piece_halfcos(&p[i], t, t1, a, b);
        else
            piece_linear(&p[i], t, t1, a, b);
        t = t1;
    }
    rc = finish(in, p, n, err);
    if (!rc)
        snprintf(in->desc, sizeof in->desc, "multimodal input, %zu extrema%s", n,
                 shape == HY_SHAPE_COSINE ? ", half-cosine pieces" : "");
    return rc;
}

/* The four pieces of a bimodal input (hy_input_bimodal's checks, in its
 * order) into p. */
static int bimodal_pieces(hy_piece p[4], double umin1, double umin2, double umax1, double umax2, const double t[4],
                          int shape, hy_error *err)
{
    const double v[4] = {umin1, umin2, umax1, umax2};
    const char *nm[4] = {"u_min,1", "u_min,2", "u_max,1", "u_max,2"};
    for (int i = 0; i < 4; i++)
        if (!isfinite(v[i]))
            return hy_error_set(err, HY_EINVAL, "%s must be a finite number (got %g)", nm[i], v[i]);
    if (!(umin1 <= umin2))
        return hy_error_set(err, HY_EINVAL, "Definition 1 needs u_min,1 <= u_min,2 (got %g > %g)", umin1, umin2);
    if (!(umin2 < umax1))
        return hy_error_set(err, HY_EINVAL, "Definition 1 needs u_min,2 < u_max,1 (got u_min,2 = %g >= u_max,1 = %g)",
                            umin2, umax1);
    if (!(umax1 <= umax2))
        return hy_error_set(err, HY_EINVAL, "Definition 1 needs u_max,1 <= u_max,2 (got %g > %g)", umax1, umax2);
    if (umin1 == umin2 && umax1 == umax2)
        return hy_error_set(err, HY_EINVAL, "Definition 1 needs u_min,1 != u_min,2 or u_max,1 != u_max,2 (both pairs are equal)");
    double tm[5] = {0, 0, 0, 0, 0};
    if (t) {
        for (int i = 0; i < 4; i++) {
            if (!isfinite(t[i]))
                return hy_error_set(err, HY_EINVAL, "t%d must be a finite number (got %g)", i + 1, t[i]);
            if (!(t[i] > (i ? t[i - 1] : 0)))
                return hy_error_set(err, HY_EINVAL, "Definition 1 needs 0 < t1 < t2 < t3 < t4 (t%d = %g)", i + 1, t[i]);
            tm[i + 1] = t[i];
        }
    }
    /* alternation may degenerate when u_min,1 == u_min,2: the extrema list is
       still min1, max1, min2, max2 with nonzero steps, so build it directly */
    const double e[4] = {umin1, umax1, umin2, umax2};
    const char *en[4] = {"u_min,1", "u_max,1", "u_min,2", "u_max,2"};
    size_t big, small;
    double scale;
    if (excursion_too_small(e, 4, &big, &small, &scale))
        return hy_error_set(err, HY_EINVAL,
                            "%s = %g makes the input's scale %g (largest |u| or total variation), and the "
                            "excursion from %s to %s of %g is below %g of it: its loop cannot be resolved in "
                            "double precision",
                            en[big], e[big], scale, en[small], en[(small + 1) % 4],
                            fabs(e[(small + 1) % 4] - e[small]), HY_EXCURSION_MIN_REL);
    double tc = 0;
    for (int i = 0; i < 4; i++) {
        double a = e[i], b = e[(i + 1) % 4];
        double t1 = t ? tm[i + 1] : tc + fabs(b - a);
        if (shape == HY_SHAPE_COSINE)
            piece_halfcos(&p[i], tc, t1, a, b);
        else
            piece_linear(&p[i], tc, t1, a, b);
        tc = t1;
    }
    return HY_OK;
}

int hy_input_bimodal(hy_input *in, double umin1, double umin2, double umax1, double umax2,
                     const double t[4], int shape, hy_error *err)
{
    HY_NONNULL(err, in);
    memset(in, 0, sizeof *in);
    hy_piece *p = malloc(4 * sizeof *p);
    if (!p)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    int rc = bimodal_pieces(p, umin1, umin2, umax1, umax2, t, shape, err);
    if (rc) {
        free(p);
        return rc;
    }
    rc = finish(in, p, 4, err);
    if (!rc)
        snprintf(in->desc, sizeof in->desc, "bimodal input (%g, %g, %g, %g)", umin1, umin2, umax1, umax2);
    return rc;
}

int hy_input_bimodal_buf(hy_input *in, hy_piece pieces[4], hy_run runs[4], double umin1, double umin2, double umax1,
                         double umax2, const double t[4], int shape, hy_error *err)
{
    HY_NONNULL(err, in);
    HY_NONNULL(err, pieces);
    HY_NONNULL(err, runs);
    int rc = bimodal_pieces(pieces, umin1, umin2, umax1, umax2, t, shape, err);
    if (!rc && finish_runs(in, pieces, runs, 4))
        rc = hy_error_set(err, HY_EINVAL, NO_RISE_FALL);
    return rc;
}

int hy_input_triangle(hy_input *in, double umin, double umax, double period, hy_error *err)
{
    HY_NONNULL(err, in);
    if (!isfinite(umin) || !isfinite(umax) || !(umin < umax))
        return hy_error_set(err, HY_EINVAL, "triangle needs finite min < max (got %g, %g)", umin, umax);
    if (!isfinite(period) || !(period > 0))
        return hy_error_set(err, HY_EINVAL, "triangle period must be > 0 (got %g)", period);
    double t[3] = {0, 0.5 * period, period}, u[3] = {umin, umax, umin};
    int rc = hy_input_pwl(in, t, u, 3, err);
    if (!rc)
        snprintf(in->desc, sizeof in->desc, "triangle %g..%g, period %g", umin, umax, period);
    return rc;
}

int hy_input_sine(hy_input *in, double amp, double period, double offset, hy_error *err)
{
    HY_NONNULL(err, in);
    if (!isfinite(amp) || amp == 0)
        return hy_error_set(err, HY_EINVAL, "sine amplitude must be finite and nonzero (got %g)", amp);
    if (!isfinite(period) || !(period > 0))
        return hy_error_set(err, HY_EINVAL, "sine period must be > 0 (got %g)", period);
    if (!isfinite(offset))
        return hy_error_set(err, HY_EINVAL, "sine offset must be finite (got %g)", offset);
    hy_piece *p = malloc(3 * sizeof *p);
    if (!p)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    double w = 2 * HY_PI / period;
    double tb[4] = {0, 0.25 * period, 0.75 * period, period};
    double ub[4] = {offset, offset + amp, offset - amp, offset};
    for (int i = 0; i < 3; i++) {
        piece_linear(&p[i], tb[i], tb[i + 1], ub[i], ub[i + 1]);
        p[i].shape = HY_PIECE_SINE;
        p[i].c = offset;
        p[i].amp = amp;
        p[i].omega = w;
        p[i].phase = 0;
    }
    int rc = finish(in, p, 3, err);
    if (!rc)
        snprintf(in->desc, sizeof in->desc, "sine, amplitude %g, period %g", amp, period);
    return rc;
}

/* The text of a message about content: a short excerpt if quote, else nothing. */
static const char *shown(const char *s, int quote, char *buf, size_t size)
{
    char ex[96];
    if (!quote)
        return "";
    snprintf(buf, size, ": '%s'", hy_file_excerpt(s, strlen(s), ex, sizeof ex));
    return buf;
}

/* Parses one "t u" / "t,u" line s into *a, *b; 1 for a blank or comment line,
 * 0 for a sample, or an error naming name:line. */
static int sample_line(const char *s, const char *name, size_t line, int quote, double *a, double *b,
                       hy_error *err)
{
    char q[128];
    while (isspace((unsigned char)*s))
        s++;
    if (*s == '#' || *s == '\0')
        return 1;
    char *end;
    *a = strtod(s, &end);
    if (end == s)
        return -hy_error_set(err, HY_EINVAL, "%s:%zu: expected two numbers 't u'%s", name, line,
                             shown(s, quote, q, sizeof q));
    s = end;
    while (isspace((unsigned char)*s) || *s == ',')
        s++;
    *b = strtod(s, &end);
    if (end == s)
        return -hy_error_set(err, HY_EINVAL, "%s:%zu: expected a second number (u) after t", name, line);
    for (s = end; isspace((unsigned char)*s); s++)
        ;
    if (*s && *s != '#')
        return -hy_error_set(err, HY_EINVAL, "%s:%zu: unexpected text after 't u'%s", name, line,
                             shown(s, quote, q, sizeof q));
    if (!isfinite(*a) || !isfinite(*b))
        return -hy_error_set(err, HY_EINVAL, "%s:%zu: values must be finite numbers", name, line);
    return 0;
}

/* Grows t and u (one spare slot each, for the closing sample) to hold n + 1. */
static int grow(double **t, double **u, size_t n, size_t *cap)
{
    if (n < *cap)
        return 0;
    size_t c = *cap ? 2 * *cap : 256;
    double *nt = realloc(*t, (c + 1) * sizeof **t);
    if (nt)
        *t = nt;
    double *nu = nt ? realloc(*u, (c + 1) * sizeof **u) : NULL;
    if (nu)
        *u = nu;
    if (!nt || !nu)
        return -1;
    *cap = c;
    return 0;
}

/* Reads "t u" / "t,u" lines of text[0..len) into growing arrays; errors name
 * name:line and, if quote, show at most a short excerpt of the line. */
static int read_samples(const char *text, size_t len, const char *name, int quote, double **pt,
                        double **pu, size_t *pn, hy_error *err)
{
    size_t n = 0, cap = 0, line = 0;
    double *t = NULL, *u = NULL;
    char buf[4096];
    int rc = HY_OK;
    for (const char *p = text, *end = text + len; p < end && !rc;) {
        const char *ls = p, *nl = memchr(p, '\n', (size_t)(end - p));
        size_t ll = (size_t)((nl ? nl : end) - p);
        line++;
        double a = 0, b = 0;
        const char *nul = memchr(p, '\0', ll);
        if (nul) /* strtod would stop there and drop the rest of the line */
            rc = hy_error_set(err, HY_EINVAL, "%s:%zu:%zu: NUL byte in the line (is this a text file?)", name, line,
                              (size_t)(nul - p) + 1);
        else if (ll >= sizeof buf)
            rc = hy_error_set(err, HY_EINVAL, "%s:%zu: line too long", name, line);
        p = nl ? nl + 1 : end;
        if (rc)
            break;
        memcpy(buf, ls, ll);
        buf[ll] = '\0';
        int r = sample_line(buf, name, line, quote, &a, &b, err);
        if (r < 0)
            rc = -r;
        if (r)
            continue;
        if (n && !(a > t[n - 1]))
            rc = quote ? hy_error_set(err, HY_EINVAL, "%s:%zu: time %g is not greater than the previous time %g", name, line, a, t[n - 1])
                       : hy_error_set(err, HY_EINVAL, "%s:%zu: the time is not greater than the previous time", name, line);
        else if (!n && a != 0)
            rc = quote ? hy_error_set(err, HY_EINVAL, "%s:%zu: the first sample must be at t = 0 (got %g)", name, line, a)
                       : hy_error_set(err, HY_EINVAL, "%s:%zu: the first sample must be at t = 0", name, line);
        else if (grow(&t, &u, n, &cap))
            rc = hy_error_set(err, HY_ENOMEM, "%s: out of memory at line %zu", name, line);
        else {
            t[n] = a;
            u[n] = b;
            n++;
        }
    }
    if (!rc && n < 2)
        rc = hy_error_set(err, HY_EINVAL, "%s: needs at least 2 samples 't u' (found %zu)", name, n);
    if (rc) {
        free(t);
        free(u);
        return rc;
    }
    if (u[n - 1] != u[0]) { /* close the period over one mean sampling step */
        t[n] = t[n - 1] + t[n - 1] / (double)(n - 1);
        u[n] = u[0];
        n++;
    }
    *pt = t;
    *pu = u;
    *pn = n;
    return HY_OK;
}

int hy_input_text(hy_input *in, const char *text, size_t len, const char *name, int quote,
                  hy_error *err)
{
    double *t = NULL, *u = NULL;
    size_t n = 0;
    HY_NONNULL(err, in);
    if (!text && len)
        return hy_error_set(err, HY_EINVAL, "hy_input_text: text must not be NULL (len is not 0)");
    if (!text)
        text = ""; /* len 0 */
    if (!name)
        name = "input";
    int rc = read_samples(text, len, name, quote, &t, &u, &n, err);
    if (rc)
        return rc;
    rc = hy_input_pwl(in, t, u, n, err);
    if (rc)
        hy_error_prefix(err, "%s", name);
    else
        snprintf(in->desc, sizeof in->desc, "sampled input from %s", name);
    free(t);
    free(u);
    return rc;
}

int hy_input_file(hy_input *in, const char *path, hy_error *err)
{
    HY_NONNULL(err, in);
    HY_NONNULL(err, path);
    char *buf;
    size_t len;
    int rc = hy_file_load(path, HY_INPUT_FILE_MAX, &buf, &len, "cannot open input file", err);
    if (rc)
        return rc;
    rc = hy_input_text(in, buf, len, path, 1, err);
    free(buf);
    return rc;
}

/* Parses a comma-separated list of numbers; returns the count or -1. */
static long parse_list(const char *s, double *out, size_t max, hy_error *err, const char *spec)
{
    size_t n = 0;
    while (*s) {
        char *end;
        double v = strtod(s, &end);
        if (end == s || (*end && *end != ',')) {
            hy_error_set(err, HY_EINVAL, "input '%s': '%.20s' is not a number", spec, s);
            return -1;
        }
        if (!isfinite(v)) {
            hy_error_set(err, HY_EINVAL, "input '%s': values must be finite", spec);
            return -1;
        }
        if (n == max) {
            hy_error_set(err, HY_EINVAL, "input '%s': more than %zu numbers", spec, max);
            return -1;
        }
        out[n++] = v;
        s = *end ? end + 1 : end;
    }
    return (long)n;
}

int hy_input_parse(hy_input *in, const char *spec, hy_error *err)
{
    HY_NONNULL(err, in);
    HY_NONNULL(err, spec);
    const char *colon = strchr(spec, ':');
    if (!colon)
        return hy_error_set(err, HY_EINVAL, "input '%s' needs the form KIND:VALUES (bimodal, multimodal, triangle, sine, pwl, file)", spec);
    size_t kl = (size_t)(colon - spec);
    const char *rest = colon + 1;
    if (kl == 4 && strncmp(spec, "file", 4) == 0)
        return hy_input_file(in, rest, err);
    char body[4096];
    snprintf(body, sizeof body, "%s", rest);
    int shape = HY_SHAPE_LINEAR;
    char *sh = strchr(body, ':');
    if (sh) {
        *sh++ = '\0';
        if (strcmp(sh, "cosine") == 0)
            shape = HY_SHAPE_COSINE;
        else if (strcmp(sh, "linear") != 0)
            return hy_error_set(err, HY_EINVAL, "input '%s': unknown shape '%s' (linear or cosine)", spec, sh);
    }
    enum { MAXV = 4096 };
    double *v = malloc(MAXV * sizeof *v);
    if (!v)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    long n = parse_list(body, v, MAXV, err, spec);
    int rc = HY_EINVAL;
    if (n < 0)
        rc = HY_EINVAL;
    else if (kl == 7 && strncmp(spec, "bimodal", 7) == 0) {
        if (n == 4 || n == 8)
            rc = hy_input_bimodal(in, v[0], v[1], v[2], v[3], n == 8 ? v + 4 : NULL, shape, err);
        else
            hy_error_set(err, HY_EINVAL, "input '%s': bimodal takes umin1,umin2,umax1,umax2[,t1,t2,t3,t4]", spec);
    } else if (kl == 10 && strncmp(spec, "multimodal", 10) == 0)
        rc = hy_input_multimodal(in, v, (size_t)n, NULL, shape, err);
    else if (kl == 8 && strncmp(spec, "triangle", 8) == 0) {
        if (n == 3)
            rc = hy_input_triangle(in, v[0], v[1], v[2], err);
        else
            hy_error_set(err, HY_EINVAL, "input '%s': triangle takes min,max,period", spec);
    } else if (kl == 4 && strncmp(spec, "sine", 4) == 0) {
        if (n == 2 || n == 3)
            rc = hy_input_sine(in, v[0], v[1], n == 3 ? v[2] : 0, err);
        else
            hy_error_set(err, HY_EINVAL, "input '%s': sine takes amp,period[,offset]", spec);
    } else if (kl == 3 && strncmp(spec, "pwl", 3) == 0) {
        if (n >= 6 && n % 2 == 0) {
            size_t m = (size_t)n / 2;
            double *t = malloc(2 * m * sizeof *t);
            if (!t)
                rc = hy_error_set(err, HY_ENOMEM, "out of memory");
            else {
                for (size_t i = 0; i < m; i++) {
                    t[i] = v[2 * i];
                    t[m + i] = v[2 * i + 1];
                }
                rc = hy_input_pwl(in, t, t + m, m, err);
                free(t);
            }
        } else
            hy_error_set(err, HY_EINVAL, "input '%s': pwl takes pairs t0,u0,t1,u1,... (at least 3)", spec);
    } else
        hy_error_set(err, HY_EINVAL, "input '%s': unknown kind '%.*s' (bimodal, multimodal, triangle, sine, pwl, file)",
                     spec, (int)kl, spec);
    free(v);
    return rc;
}

double hy_input_reduce(const hy_input *in, double t, double k)
{
    if (!in)
        return NAN;
    double hi = k * in->period;
    double lo = fma(k, in->period, -hi); /* k T = hi + lo exactly */
    return (t - hi) - lo;                /* t - hi is exact when t is in period k (Sterbenz) */
}

double hy_input_snap(double tb)
{
    return 8 * DBL_EPSILON * fmax(fabs(tb), DBL_MIN);
}

int hy__input_ready(const hy_input *in)
{
    return in && in->npieces && in->pieces && in->nruns && in->runs;
}

size_t hy_input_piece_at(const hy_input *in, double t, double *tmod, double *kcycles)
{
    if (!hy__input_ready(in)) {
        if (tmod)
            *tmod = NAN;
        if (kcycles)
            *kcycles = NAN;
        return 0;
    }
    double k = floor(t / in->period);
    double tm = hy_input_reduce(in, t, k);
    if (tm >= in->period) { /* rounding */
        k += 1;
        tm = hy_input_reduce(in, t, k);
    }
    if (tm < 0 && k > 0) {
        k -= 1;
        tm = hy_input_reduce(in, t, k);
    }
    if (tm < 0)
        tm = 0;
    size_t lo = 0, hi = in->npieces - 1;
    while (lo < hi) {
        size_t mid = (lo + hi + 1) / 2;
        if (in->pieces[mid].t0 <= tm)
            lo = mid;
        else
            hi = mid - 1;
    }
    if (tmod)
        *tmod = tm;
    if (kcycles)
        *kcycles = k;
    return lo;
}

double hy_input_u(const hy_input *in, double t)
{
    if (!hy__input_ready(in))
        return NAN;
    double tm;
    size_t i = hy_input_piece_at(in, t, &tm, NULL);
    return hy_piece_u(&in->pieces[i], tm);
}

double hy_input_du(const hy_input *in, double t)
{
    if (!hy__input_ready(in))
        return NAN;
    double tm;
    size_t i = hy_input_piece_at(in, t, &tm, NULL);
    return hy_piece_du(&in->pieces[i], tm);
}

double hy_input_ddu(const hy_input *in, double t)
{
    if (!hy__input_ready(in))
        return NAN;
    double tm;
    size_t i = hy_input_piece_at(in, t, &tm, NULL);
    return piece_ddu(&in->pieces[i], tm);
}

double hy_input_rho(const hy_input *in, double t)
{
    if (!hy__input_ready(in))
        return NAN;
    double tm, k;
    size_t i = hy_input_piece_at(in, t, &tm, &k);
    const hy_piece *p = &in->pieces[i];
    return k * in->rho_T + p->rho0 + fabs(hy_piece_u(p, tm) - p->u0);
}

size_t hy_input_run_at(const hy_input *in, double rho, double *rmod)
{
    if (!hy__input_ready(in)) {
        if (rmod)
            *rmod = NAN;
        return 0;
    }
    double k = floor(rho / in->rho_T);
    double r = rho - k * in->rho_T;
    if (r >= in->rho_T)
        r -= in->rho_T;
    if (r < 0)
        r = 0;
    size_t lo = 0, hi = in->nruns - 1;
    while (lo < hi) {
        size_t mid = (lo + hi + 1) / 2;
        if (in->runs[mid].rho0 <= r)
            lo = mid;
        else
            hi = mid - 1;
    }
    if (rmod)
        *rmod = r;
    return lo;
}

double hy_input_psi(const hy_input *in, double rho)
{
    if (!hy__input_ready(in))
        return NAN;
    double r;
    const hy_run *run = &in->runs[hy_input_run_at(in, rho, &r)];
    double d = r - run->rho0;
    double span = run->rho1 - run->rho0;
    if (d > span)
        d = span;
    return run->u0 + run->sign * d;
}
