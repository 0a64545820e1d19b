/* SPDX-License-Identifier: MIT */
/* hy_simplify.h: polylines at the output's resolution (issue 23 item 2).
 *
 * A curve of a million points draws the same pixels as a few hundred
 * vertices; stroking, placing labels around and writing the million costs
 * time and memory in proportion.  A simplifier takes the points of a
 * polyline one at a time (in device units, NaN breaks the line) and emits
 * the vertices of a polyline that stays within tol of every point it
 * replaces: a point is merged into a segment only when it lies within tol
 * of that segment (the cone of directions from the segment's start that
 * keeps every merged point within tol, and no merged point farther from the
 * start than the segment's end, so a turn back always ends a segment there).
 * Every emitted vertex is an input point, unchanged.  Points flagged `keep`
 * (turning points, extremes, see hy_turns) are always emitted.  O(1) memory,
 * one pass; the first and last point of each piece are emitted.
 *
 *     hy_simplify s;
 *     hy_simplify_begin(&s, 0.1, emit, ctx);
 *     for (i = 0; i < n; i++) hy_simplify_point(&s, x[i], y[i], 0);
 *     hy_simplify_end(&s);
 *
 * hy_turns finds the points to keep: the turning points of x and of y (a
 * local extreme that the curve leaves by more than tol afterwards, so noise
 * below tol does not count) and the global extremes of x and y. */
#ifndef HY_SIMPLIFY_H
#define HY_SIMPLIFY_H

#include <stddef.h>

/* Receives a vertex, or (NaN, NaN) where the line breaks. */
typedef void (*hy_simplify_emit)(void *ctx, double x, double y);

typedef struct hy_simplify {
    double tol;
    hy_simplify_emit emit;
    void *ctx;
    int state;             /* 0: no line open, 1: anchor emitted, 2: anchor + a candidate end */
    int cone;              /* 0: no constraint yet (every point within tol), 1: cone set */
    double ax, ay;         /* the segment's start (emitted) */
    double cx, cy;         /* its candidate end: the last point merged */
    double rmax2;          /* largest squared distance from the start of a merged point */
    double lx, ly, rx, ry; /* the cone's edges (unit vectors) */
} hy_simplify;

void hy_simplify_begin(hy_simplify *s, double tol, hy_simplify_emit emit, void *ctx);
/* A point; NaN in x or y breaks the line there. */
void hy_simplify_point(hy_simplify *s, double x, double y, int keep);
/* Emits what is pending (call before a break the caller makes, and at the end). */
void hy_simplify_end(hy_simplify *s);

/* Turning points and extremes of a polyline, streamed: feed every point
 * (NaN breaks) with its index; hy_turns_end returns the sorted, distinct
 * indices to keep (malloc'd in *idx, count in *n; 0, or -1 out of memory). */
typedef struct hy_turns {
    double tol;
    int dir[2];            /* per coordinate: 0 none yet, +1 rising, -1 falling */
    double start[2], ext[2];
    size_t at[2];
    int any;
    double lo[2], hi[2];   /* global extremes and where */
    size_t ilo[2], ihi[2];
    size_t *idx, n, cap;
    int oom;
} hy_turns;

void hy_turns_begin(hy_turns *t, double tol);
void hy_turns_point(hy_turns *t, double x, double y, size_t i);
int hy_turns_end(hy_turns *t, size_t **idx, size_t *n);

#endif
