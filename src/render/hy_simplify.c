/* SPDX-License-Identifier: MIT */
/* hy_simplify.c: polylines at the output's resolution (see hy_simplify.h). */
#include "hy_simplify.h"

#include <math.h>
#include <stdlib.h>

void hy_simplify_begin(hy_simplify *s, double tol, hy_simplify_emit emit, void *ctx)
{
    *s = (hy_simplify){0};
    s->tol = tol;
    s->emit = emit;
    s->ctx = ctx;
}

static double cross(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

/* Starts a segment at (x, y), already emitted. */
static void anchor(hy_simplify *s, double x, double y)
{
    s->ax = x, s->ay = y;
    s->state = 1;
    s->cone = 0;
    s->rmax2 = 0.0;
}

/* Whether the segment may end at offset (dx, dy) from its start: every point
 * merged so far stays within tol of it. */
static int fits(const hy_simplify *s, double dx, double dy, double r2)
{
    if (r2 < s->rmax2)
        return 0;
    if (!s->cone)
        return 1;
    /* the cone is narrower than a half turn: these two tests bound it */
    return cross(s->rx, s->ry, dx, dy) >= 0.0 && cross(dx, dy, s->lx, s->ly) >= 0.0;
}

/* Merges the point at offset (dx, dy): the cone narrows to the directions
 * that pass within tol of it.  The point's own cone (half-angle asin(tol/r)
 * < a quarter turn) and the cone so far both hold its direction, so their
 * intersection is a cone about it: each edge is the one nearer to it. */
static void merge(hy_simplify *s, double x, double y, double dx, double dy, double r2)
{
    s->cx = x, s->cy = y;
    s->state = 2;
    if (r2 > s->rmax2)
        s->rmax2 = r2;
    if (r2 <= s->tol * s->tol)
        return;
    double r = sqrt(r2), sn = s->tol / r, cs = sqrt(1.0 - sn * sn), ux = dx / r, uy = dy / r;
    double lx = ux * cs - uy * sn, ly = ux * sn + uy * cs;   /* rotated one way by asin(tol / r) */
    double rx = ux * cs + uy * sn, ry = -ux * sn + uy * cs;  /* and the other */
    if (s->cone == 0) {
        s->lx = lx, s->ly = ly, s->rx = rx, s->ry = ry;
        s->cone = 1;
        return;
    }
    if (cross(s->lx, s->ly, lx, ly) < 0.0)
        s->lx = lx, s->ly = ly;
    if (cross(s->rx, s->ry, rx, ry) > 0.0)
        s->rx = rx, s->ry = ry;
}

void hy_simplify_point(hy_simplify *s, double x, double y, int keep)
{
    if (isnan(x) || isnan(y)) {
        if (s->state) {
            hy_simplify_end(s);
            s->emit(s->ctx, NAN, NAN);
        }
        return;
    }
    if (s->state == 0) {
        s->emit(s->ctx, x, y);
        anchor(s, x, y);
        return;
    }
    double dx = x - s->ax, dy = y - s->ay, r2 = dx * dx + dy * dy;
    if (s->state == 2 && !fits(s, dx, dy, r2)) {
        s->emit(s->ctx, s->cx, s->cy);
        anchor(s, s->cx, s->cy);
        dx = x - s->ax, dy = y - s->ay, r2 = dx * dx + dy * dy;
    }
    merge(s, x, y, dx, dy, r2);
    if (keep) {
        s->emit(s->ctx, x, y);
        anchor(s, x, y);
    }
}

void hy_simplify_end(hy_simplify *s)
{
    if (s->state == 2)
        s->emit(s->ctx, s->cx, s->cy);
    s->state = 0;
}

void hy_turns_begin(hy_turns *t, double tol)
{
    *t = (hy_turns){0};
    t->tol = tol;
    t->dir[0] = t->dir[1] = 2;
}

static void push(hy_turns *t, size_t i)
{
    if (t->n == t->cap) {
        size_t cap = t->cap ? 2 * t->cap : 64;
        size_t *p = realloc(t->idx, cap * sizeof *p);
        if (!p) {
            t->oom = 1;
            return;
        }
        t->idx = p, t->cap = cap;
    }
    t->idx[t->n++] = i;
}

/* One coordinate: dir 2 starts a piece, 0 waits for a move past tol, then
 * the running extreme is a turning point once the curve leaves it by tol. */
static void turn1(hy_turns *t, int k, double v, size_t i)
{
    int d = t->dir[k];
    if (d == 2) {
        t->start[k] = v;
        t->dir[k] = 0;
    } else if (d == 0) {
        if (v > t->start[k] + t->tol || v < t->start[k] - t->tol)
            t->dir[k] = v > t->start[k] ? 1 : -1, t->ext[k] = v, t->at[k] = i;
    } else if (d * (v - t->ext[k]) >= 0.0) {
        t->ext[k] = v, t->at[k] = i;
    } else if (d * (t->ext[k] - v) > t->tol) {
        push(t, t->at[k]);
        t->dir[k] = -d, t->ext[k] = v, t->at[k] = i;
    }
}

void hy_turns_point(hy_turns *t, double x, double y, size_t i)
{
    if (isnan(x) || isnan(y)) {
        t->dir[0] = t->dir[1] = 2;
        return;
    }
    double v[2] = {x, y};
    for (int k = 0; k < 2; k++) {
        turn1(t, k, v[k], i);
        if (!t->any || v[k] < t->lo[k])
            t->lo[k] = v[k], t->ilo[k] = i;
        if (!t->any || v[k] > t->hi[k])
            t->hi[k] = v[k], t->ihi[k] = i;
    }
    t->any = 1;
}

static int cmp_index(const void *a, const void *b)
{
    size_t x = *(const size_t *)a, y = *(const size_t *)b;
    return x < y ? -1 : x > y;
}

int hy_turns_end(hy_turns *t, size_t **idx, size_t *n)
{
    for (int k = 0; t->any && k < 2; k++) {
        push(t, t->ilo[k]);
        push(t, t->ihi[k]);
    }
    if (t->oom) {
        free(t->idx);
        *idx = NULL, *n = 0;
        return -1;
    }
    if (t->n) /* an empty series has no index array (qsort's argument must not be NULL) */
        qsort(t->idx, t->n, sizeof *t->idx, cmp_index);
    size_t m = 0;
    for (size_t i = 0; i < t->n; i++)
        if (!m || t->idx[i] != t->idx[m - 1])
            t->idx[m++] = t->idx[i];
    *idx = t->idx, *n = m;
    return 0;
}
