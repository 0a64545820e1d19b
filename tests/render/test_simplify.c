/* SPDX-License-Identifier: MIT */
/* test_simplify.c: lines at the output's resolution (hy_simplify.h, issue 23 item 2).
 *
 * The simplifier's promise is checked by brute force, independently of how
 * it decides: on curves of known shape (a circle arc sampled densely, a
 * sine, a zigzag reversing on itself, a noisy ramp, pieces between NaN
 * breaks) every input point lies within tol of the emitted polyline of its
 * piece (distance to the nearest segment, computed here), every emitted
 * vertex is an input point unchanged and in input order, the first and last
 * point of every piece are emitted, and every point hy_turns keeps (turning
 * points past tol, the extremes of x and y) is emitted.  Also: a dense arc
 * shrinks to about what its curvature needs (a chord of length L between
 * two points of an arc of radius R deviates L^2 / 8R from it, so with tol
 * 0.1 and R 100 one vertex per sqrt(8 R tol) = 8.9 of length; at most 20 %
 * more), the reversals of a curve drawn back and forth are kept, and a
 * straight line of a million points becomes its two ends. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "hy_simplify.h"

#include "rcheck.h"

typedef struct out {
    double *x, *y;
    size_t n, cap;
} out;

static void emit(void *ctx, double x, double y)
{
    out *o = ctx;
    if (o->n == o->cap) {
        o->cap = o->cap ? 2 * o->cap : 64;
        o->x = realloc(o->x, o->cap * sizeof *o->x);
        o->y = realloc(o->y, o->cap * sizeof *o->y);
        if (!o->x || !o->y) {
            puts("out of memory");
            exit(1);
        }
    }
    o->x[o->n] = x, o->y[o->n] = y, o->n++;
}

static double seg_dist(double px, double py, double ax, double ay, double bx, double by)
{
    double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
    double t = l2 > 0 ? ((px - ax) * dx + (py - ay) * dy) / l2 : 0.0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return hypot(px - ax - t * dx, py - ay - t * dy);
}

/* Runs the simplifier over n points (NaN breaks) with hy_turns' keeps and
 * checks every promise; returns the number of vertices emitted. */
static size_t check_curve(const char *name, const double *x, const double *y, size_t n, double tol,
                          size_t must_every)
{
    hy_turns t;
    hy_turns_begin(&t, tol);
    for (size_t i = 0; i < n; i++)
        hy_turns_point(&t, x[i], y[i], i);
    size_t *keep, nkeep, k = 0;
    CHECK(hy_turns_end(&t, &keep, &nkeep) == 0, "%s: hy_turns_end failed", name);
    out o = {0};
    hy_simplify s;
    hy_simplify_begin(&s, tol, emit, &o);
    for (size_t i = 0; i < n; i++) {
        while (k < nkeep && keep[k] < i)
            k++;
        hy_simplify_point(&s, x[i], y[i], k < nkeep && keep[k] == i);
    }
    hy_simplify_end(&s);
    /* match every emitted vertex to an input point, in order */
    size_t *at = malloc((o.n + 1) * sizeof *at), j = 0, vertices = 0;
    int order_ok = 1;
    for (size_t v = 0; v < o.n; v++) {
        if (isnan(o.x[v])) {
            at[v] = (size_t)-1;
            continue;
        }
        while (j < n && !(x[j] == o.x[v] && y[j] == o.y[v]))
            j++;
        if (j == n) {
            order_ok = 0;
            break;
        }
        at[v] = j++;
        vertices++;
    }
    CHECK(order_ok, "%s: an emitted vertex is not an input point in input order", name);
    if (!order_ok) {
        free(at), free(keep), free(o.x), free(o.y);
        return vertices;
    }
    /* every input point within tol of its piece's polyline; ends and keeps emitted */
    double worst = 0.0;
    size_t v = 0, missing_end = 0, missing_keep = 0, q = 0;
    for (size_t i = 0; i < n; i++) {
        if (isnan(x[i]))
            continue;
        int first = i == 0 || isnan(x[i - 1]), last = i + 1 == n || isnan(x[i + 1]);
        /* v: the last vertex emitted at or before point i (vertices are in input order) */
        while (v + 1 < o.n && (isnan(o.x[v + 1]) || at[v + 1] <= i))
            v++;
        while (isnan(o.x[v]) && v > 0)
            v--;
        int emitted = !isnan(o.x[v]) && at[v] == i;
        if ((first || last) && !emitted)
            missing_end++;
        while (q < nkeep && keep[q] < i)
            q++;
        if (q < nkeep && keep[q] == i && !emitted)
            missing_keep++;
        if (must_every && i % must_every == 0 && !emitted)
            missing_keep++;
        double d = 0.0;
        if (!emitted)
            d = !isnan(o.x[v]) && at[v] < i && v + 1 < o.n && !isnan(o.x[v + 1])
                    ? seg_dist(x[i], y[i], o.x[v], o.y[v], o.x[v + 1], o.y[v + 1])
                    : INFINITY;
        worst = d > worst ? d : worst;
    }
    CHECK(worst <= tol * (1 + 1e-9), "%s: a point lies %.3g from the polyline, tol %g", name, worst, tol);
    CHECK(!missing_end, "%s: %zu piece ends not emitted", name, missing_end);
    CHECK(!missing_keep, "%s: %zu turning points or extremes not emitted", name, missing_keep);
    printf("%-14s %8zu points -> %6zu vertices (tol %g, %zu kept, worst %.3g)\n", name, n, vertices, tol, nkeep,
           worst);
    free(at), free(keep), free(o.x), free(o.y);
    return vertices;
}

int main(void)
{
    size_t n = 200000;
    double *x = malloc(n * sizeof *x), *y = malloc(n * sizeof *y);
    if (!x || !y)
        return 1;
    /* a half circle of radius 100, densely sampled */
    for (size_t i = 0; i < n; i++) {
        double a = M_PI * (double)i / (double)(n - 1);
        x[i] = 100 * cos(a), y[i] = 100 * sin(a);
    }
    size_t m = check_curve("arc", x, y, n, 0.1, 0);
    double per = sqrt(8 * 100 * 0.1), len = M_PI * 100;
    CHECK((double)m <= 1.2 * len / per + 4, "arc: %zu vertices, curvature needs about %.0f", m, len / per);
    /* a sine with reversals of x every 5000 points (a loop drawn back and forth) */
    for (size_t i = 0; i < n; i++) {
        double ph = (double)(i % 10000) / 5000.0;
        x[i] = 300 * (ph < 1 ? ph : 2 - ph), y[i] = 50 * sin(0.001 * (double)i);
    }
    check_curve("sine-loop", x, y, n, 0.1, 5000); /* x's reversals: every 5000th point */
    /* zigzag: a spike every 7 points, deeper than tol */
    for (size_t i = 0; i < 2000; i++)
        x[i] = 0.05 * (double)i, y[i] = i % 7 == 3 ? 1.0 : 0.0;
    m = check_curve("zigzag", x, y, 2000, 0.1, 0);
    CHECK(m >= 2 * (2000 / 7), "zigzag: %zu vertices for %d spikes", m, 2000 / 7);
    /* a noisy ramp (noise below and above tol) with NaN breaks */
    srand(7);
    for (size_t i = 0; i < n; i++) {
        double r = (double)rand() / RAND_MAX - 0.5;
        x[i] = 0.01 * (double)i, y[i] = 0.002 * (double)i + (i < n / 2 ? 0.05 : 0.5) * r;
        if (i % 30011 == 17)
            x[i] = y[i] = NAN;
    }
    check_curve("noisy-ramp", x, y, n, 0.1, 0);
    free(x), free(y);
    /* a straight line of a million points: its two ends */
    size_t big = 1000000;
    x = malloc(big * sizeof *x), y = malloc(big * sizeof *y);
    if (!x || !y)
        return 1;
    for (size_t i = 0; i < big; i++)
        x[i] = 3.0 + 1e-4 * (double)i, y[i] = 2.0 - 0.5e-4 * (double)i;
    m = check_curve("line", x, y, big, 0.1, 0);
    CHECK(m == 2, "line: %zu vertices, want its 2 ends", m);
    free(x), free(y);
    return hy_test_finish("simplify");
}
