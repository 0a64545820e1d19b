/* SPDX-License-Identifier: MIT */
/* hy_loops.c: major and minor loops of the steady state by rainflow pairing of
 * the turning points of ψ_u (seed 000, Theorem A(b) and its multimodal
 * generalisation), with exact areas ∫ y° dψ. */
#include "hy_loops.h"

#include "hy_args.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct tp {
    double rho, u;   /* absolute ϱ of the turning point and its value */
    int is_max;
} tp;

/* Iterates over the monotone stretches of [rho0, rho1], calling fn on each. */
static size_t for_each_arc(const hy_steady *st, double rho0, double rho1,
                           void (*fn)(void *, const hy_arc *), void *ctx)
{
    const hy_input *in = st->in;
    size_t count = 0;
    double rho = rho0;
    while (rho < rho1) {
        double r;
        size_t i = hy_input_run_at(in, rho, &r);
        const hy_run *run = &in->runs[i];
        double base = rho - r; /* absolute ϱ of this period's start */
        double end = base + run->rho1;
        if (end <= rho) { /* rounding at a run end: step to the next run */
            i = (i + 1) % in->nruns;
            run = &in->runs[i];
            if (i == 0)
                base += in->rho_T;
            r = rho - base;
            end = base + run->rho1;
        }
        if (end > rho1)
            end = rho1;
        if (!(end > rho)) /* runs narrower than an ulp of ϱ (hy_input refuses such extrema) */
            break;
        hy_arc arc;
        arc.rho0 = rho;
        arc.rho1 = end;
        arc.sign = run->sign;
        double d = r - run->rho0;
        if (d < 0)
            d = 0;
        arc.u0 = run->u0 + run->sign * d;
        arc.y0 = hy_limit_step(st->a, st->g0, st->y_run[i], run->sign, d);
        if (fn)
            fn(ctx, &arc);
        count++;
        rho = end;
    }
    return count;
}

struct arc_buf { hy_arc *arcs; size_t max, n; };
static void collect_arc(void *ctx, const hy_arc *a)
{
    struct arc_buf *b = ctx;
    if (b->n < b->max)
        b->arcs[b->n] = *a;
    b->n++;
}

size_t hy_steady_arcs(const hy_steady *st, double rho0, double rho1, hy_arc *arcs, size_t max)
{
    struct arc_buf b = {arcs, max, 0};
    if (!hy__steady_ready(st) || !isfinite(rho0) || !isfinite(rho1) || (!arcs && max))
        return 0;
    return for_each_arc(st, rho0, rho1, collect_arc, &b);
}

struct area_acc { const hy_steady *st; double sum; };
static void add_area(void *ctx, const hy_arc *a)
{
    struct area_acc *acc = ctx;
    acc->sum += hy_limit_step_area(acc->st->a, acc->st->g0, a->y0, a->sign, a->rho1 - a->rho0);
}

double hy_steady_area(const hy_steady *st, double rho0, double rho1)
{
    struct area_acc acc = {st, 0};
    if (!hy__steady_ready(st) || !isfinite(rho0) || !isfinite(rho1))
        return NAN;
    for_each_arc(st, rho0, rho1, add_area, &acc);
    return acc.sum;
}

/* Turning points of one period starting at the global maximum, closed by it:
 * into seq (room for nruns + 1), raw (nruns) the scratch; their count. */
static size_t turning_points(const hy_input *in, tp *raw, tp *seq)
{
    size_t n = in->nruns;
    size_t m = 0;
    for (size_t i = 0; i < n; i++) { /* extremum at the start of run i */
        const hy_run *prev = &in->runs[(i + n - 1) % n], *cur = &in->runs[i];
        if (prev->sign == cur->sign)
            continue; /* runs split by the period boundary */
        raw[m].rho = cur->rho0;
        raw[m].u = cur->u0;
        raw[m].is_max = cur->sign < 0;
        m++;
    }
    size_t imax = 0;
    for (size_t i = 1; i < m; i++)
        if (raw[i].u > raw[imax].u)
            imax = i;
    for (size_t i = 0; i <= m; i++) {
        size_t j = (imax + i) % m;
        seq[i] = raw[j];
        seq[i].rho += (double)((imax + i) / m) * in->rho_T;
    }
    return m + 1;
}

/* The scratch of find for an input of nruns runs: turning points (raw and
 * the sequence), the rainflow stack, the loops found, then (with a caller's
 * buffer) the minor loops; each part aligned for a double. */
typedef struct find_parts { size_t raw, seq, stack, loops, minor, total; } find_parts;

static find_parts find_layout(size_t nruns)
{
    find_parts p;
    size_t n = nruns + 1, at = 0;
#define HY_PART(field, bytes) (p.field = at, at += ((bytes) + 15) / 16 * 16)
    HY_PART(raw, (nruns ? nruns : 1) * sizeof(tp));
    HY_PART(seq, n * sizeof(tp));
    HY_PART(stack, n * sizeof(size_t));
    HY_PART(loops, n * sizeof(hy_loop));
    HY_PART(minor, n * sizeof(hy_loop));
#undef HY_PART
    p.total = at;
    return p;
}

size_t hy_loops_work_size(size_t nruns)
{
    if (nruns >= SIZE_MAX / 8 / sizeof(hy_loop))
        return 0;
    return find_layout(nruns).total;
}

/* First ϱ after q where the path seq[q..] returns to value u (inclusive). */
static double close_point(const tp *seq, size_t q, size_t last, double u)
{
    for (size_t i = q; i < last; i++) {
        double lo = fmin(seq[i].u, seq[i + 1].u), hi = fmax(seq[i].u, seq[i + 1].u);
        if (i > q && seq[i].u == u)
            return seq[i].rho;
        if (u > lo && u <= hi && i + 1 <= last) {
            if (seq[i + 1].u == u)
                return seq[i + 1].rho;
            return seq[i].rho + fabs(u - seq[i].u);
        }
    }
    return seq[last].rho;
}

/* ∮ y° dψ along the path seq[ip] → ... → seq[iq] → ... until it returns to
 * u(seq[ip]) after seq[iq] (the close of close_point), seq[last] at most.
 * Arc lengths are differences of turning-point values of u (exact), not of ϱ
 * values near ϱ_T, and the integrand is δ = y - y_start (∮ du = 0 removes
 * y_start): on a run of direction s, δ relaxes towards c = s g0 - y_start,
 *     ∫_0^d δ dr = δ0 d φ1(ad) + c a d² φ2(ad),
 * so a loop w wide has an area of relative accuracy ~ε, not ε/w. */
static double loop_area(const hy_steady *st, const tp *seq, size_t ip, size_t iq, size_t last, double y_start)
{
    double u = seq[ip].u, delta = 0, area = 0, a = st->a;
    for (size_t i = ip; i < last; i++) {
        double lo = fmin(seq[i].u, seq[i + 1].u), hi = fmax(seq[i].u, seq[i + 1].u);
        if (i > iq && seq[i].u == u)
            break;
        int s = seq[i + 1].u > seq[i].u ? 1 : -1, closes = i >= iq && u > lo && u <= hi;
        double d = closes ? fabs(u - seq[i].u) : hi - lo, x = a * d, c = s * st->g0 - y_start, em = expm1(-x);
        area += hy_limit_step_area_em(a, s * c, delta, s, d, em); /* s (δ0 d φ1 + c a d² φ2), scaled where d² overflows */
        delta = exp(-x) * delta + c * -em;
        if (closes)
            break;
    }
    return area;
}

/* By start; among equal starts the longer loop first (it contains the others). */
static int cmp_loop(const void *a, const void *b)
{
    const hy_loop *p = a, *q = b;
    if (p->rho_start != q->rho_start)
        return (p->rho_start > q->rho_start) - (p->rho_start < q->rho_start);
    double lp = p->rho_close - p->rho_start, lq = q->rho_close - q->rho_start;
    return (lp < lq) - (lp > lq);
}

/* Nesting of the minor loops (sorted by cmp_loop), in O(n) with a stack of
 * open loops: rainflow loops are nested or disjoint, so the loops containing
 * one are exactly those still open when it starts.  depth = 1 + how many
 * minor loops strictly contain it; own_area = area minus direct children
 * (loops no minor loop contains are children of the major loop).
 * stack needs nminor entries. */
static void nest_loops(hy_loops *out, size_t *stack)
{
    size_t sp = 0;
    out->major.own_area = out->major.area;
    for (size_t i = 0; i < out->nminor; i++) {
        hy_loop *L = &out->minor[i];
        while (sp) {
            const hy_loop *M = &out->minor[stack[sp - 1]];
            if (M->rho_start <= L->rho_start && L->rho_close <= M->rho_close &&
                M->rho_close - M->rho_start > L->rho_close - L->rho_start)
                break;
            sp--;
        }
        L->depth = 1 + (int)sp;
        L->own_area = L->area;
        if (sp)
            out->minor[stack[sp - 1]].own_area -= L->area;
        else
            out->major.own_area -= L->area;
        stack[sp++] = i;
    }
}

/* The rainflow pairing of in's turning points; with st, the areas and the
 * y° values of the loops too (else areas 0, y NaN).  work: the caller's
 * hy_loops_work_size(in->nruns) bytes (out->minor then lies in it), or NULL
 * (allocated here, out->minor malloc'd). */
static int find(const hy_input *in, const hy_steady *st, hy_loops *out, void *work, hy_error *err)
{
    memset(out, 0, sizeof *out);
    find_parts fp = find_layout(in->nruns);
    char *w = work ? work : malloc(fp.total);
    if (!w)
        return hy_error_set(err, HY_ENOMEM, "out of memory for loop detection");
    tp *seq = (tp *)(void *)(w + fp.seq);
    size_t n = turning_points(in, (tp *)(void *)(w + fp.raw), seq);
    size_t *stack = (size_t *)(void *)(w + fp.stack);
    hy_loop *loops = (hy_loop *)(void *)(w + fp.loops);
    size_t sp = 0, nl = 0;
    for (size_t i = 0; i < n; i++) {
        stack[sp++] = i;
        while (sp >= 3) {
            const tp *p = &seq[stack[sp - 3]], *q = &seq[stack[sp - 2]], *r = &seq[stack[sp - 1]];
            double X = fabs(r->u - q->u), Y = fabs(q->u - p->u);
            if (X < Y || (X == Y && !p->is_max))
                break;
            hy_loop *L = &loops[nl++];
            memset(L, 0, sizeof *L);
            L->rho_start = p->rho;
            L->rho_turn = q->rho;
            L->rho_close = close_point(seq, stack[sp - 2], stack[sp - 1], p->u);
            L->y_start = st ? hy_steady_at_rho(st, p->rho) : NAN; /* once: loop_area starts from it */
            L->y_close = st ? hy_steady_at_rho(st, L->rho_close) : NAN;
            L->area = st ? loop_area(st, seq, stack[sp - 3], stack[sp - 2], stack[sp - 1], L->y_start) : 0.0;
            L->u_start = p->u;
            L->u_turn = q->u;
            L->starts_at_max = p->is_max;
            stack[sp - 3] = stack[sp - 1];
            sp -= 2;
        }
    }
    /* the major loop: the largest range, the last found among equals */
    size_t imaj = 0;
    for (size_t i = 1; i < nl; i++)
        if (fabs(loops[i].u_turn - loops[i].u_start) >= fabs(loops[imaj].u_turn - loops[imaj].u_start))
            imaj = i;
    out->major = loops[imaj];
    out->nminor = nl - 1;
    out->minor = work ? (hy_loop *)(void *)(w + fp.minor) : malloc((nl ? nl : 1) * sizeof *out->minor);
    if (!out->minor) {
        free(w);
        return hy_error_set(err, HY_ENOMEM, "out of memory for loops");
    }
    for (size_t i = 0, k = 0; i < nl; i++)
        if (i != imaj)
            out->minor[k++] = loops[i];
    /* express minor loops within [0, ρ_T) where possible, then sort */
    for (size_t i = 0; i < out->nminor; i++) {
        hy_loop *L = &out->minor[i];
        double shift = floor(L->rho_start / in->rho_T) * in->rho_T;
        L->rho_start -= shift;
        L->rho_turn -= shift;
        L->rho_close -= shift;
    }
    qsort(out->minor, out->nminor, sizeof *out->minor, cmp_loop);
    nest_loops(out, stack);
    out->area_period = st ? hy_steady_area(st, 0, in->rho_T) : NAN;
    if (!work)
        free(w);
    return HY_OK;
}

/* The refusal of find's arguments (hy_loops.h): out, and st (need_st) or in. */
static int check(const char *fn, const hy_input *in, const hy_steady *st, int need_st, hy_loops *out, hy_error *err)
{
    if (out)
        memset(out, 0, sizeof *out);
    const char *bad = !out                                     ? "out must not be NULL"
                      : need_st && !st                         ? "st must not be NULL"
                      : need_st && !hy__steady_ready(st)       ? "st is not an initialised steady state"
                      : !need_st && !in                        ? "in must not be NULL"
                      : !need_st && !hy__input_ready(in)       ? "in has no pieces (not made, or freed)"
                                                               : NULL;
    return bad ? hy_error_set(err, HY_EINVAL, "%s: %s", fn, bad) : HY_OK;
}

int hy_loops_find(const hy_steady *st, hy_loops *out, hy_error *err)
{
    int rc = check(__func__, NULL, st, 1, out, err);
    if (rc)
        return rc;
    return find(st->in, st, out, NULL, err);
}

int hy_loops_find_buf(const hy_steady *st, hy_loops *out, void *work, hy_error *err)
{
    int rc = check(__func__, NULL, st, 1, out, err);
    if (rc)
        return rc;
    return find(st->in, st, out, work, err);
}

int hy_loops_pair(const hy_input *in, hy_loops *out, hy_error *err)
{
    int rc = check(__func__, in, NULL, 0, out, err);
    if (rc)
        return rc;
    return find(in, NULL, out, NULL, err);
}

int hy_loops_nest(hy_loops *out, hy_error *err)
{
    HY_NONNULL(err, out);
    if (out->nminor && !out->minor)
        return hy_error_set(err, HY_EINVAL, "%s: out->minor must not be NULL (out->nminor is %zu)", __func__,
                            out->nminor);
    size_t *stack = malloc((out->nminor ? out->nminor : 1) * sizeof *stack);
    if (!stack)
        return hy_error_set(err, HY_ENOMEM, "out of memory for loop nesting");
    nest_loops(out, stack);
    free(stack);
    return HY_OK;
}

void hy_loops_free(hy_loops *l)
{
    if (l) {
        free(l->minor);
        l->minor = NULL;
        l->nminor = 0;
    }
}
