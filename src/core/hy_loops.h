/* SPDX-License-Identifier: MIT */
/* hy_loops.h: the major loop and every minor loop of a periodic multimodal
 * input (seed 000, Theorem A(b), generalised as its Section 3.2.3 announces).
 *
 * The turning points of ψ_u, starting at the global maximum, are paired by a
 * rainflow stack: a pair (p, q) of consecutive turning points closes when the
 * signal after q travels back at least to u(p).  Each closed pair is a loop
 * from ϱ_start = ϱ(p) through ϱ_turn = ϱ(q) to ϱ_close, the first point after q
 * where ψ_u returns to u(p).  The pair of largest range is the major loop; the
 * others are minor loops (for a bimodal input exactly [ϱ1, ϱ5] of Theorem A).
 * Ties prefer loops that start at a maximum, as the paper's ϱ5 does.
 *
 * Areas are ∫ y° dψ_u along [ϱ_start, ϱ_close] (> 0 when dissipative): since ψ
 * returns to its start value, this is the loop's area closed by a vertical
 * chord.  The output does not return (no return-point memory): y_close != y_start.
 *
 *     hy_loops L;
 *     hy_loops_find(&steady, &L, &err);
 *     for (size_t i = 0; i < L.nminor; i++) printf("%g\n", L.minor[i].area);
 *     hy_loops_free(&L);
 */
#ifndef HY_LOOPS_H
#define HY_LOOPS_H

#include "hy_limit.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hy_loop {
    double rho_start, rho_turn, rho_close; /* absolute ϱ; may pass ρ_T (wrap) */
    double u_start, u_turn;
    double y_start, y_close;   /* y° at start and close                      */
    double area;               /* ∫ y° dψ over [rho_start, rho_close]         */
    double own_area;           /* area minus the loops nested directly in it  */
    int depth;                 /* 0: major loop; 1: inside it; 2: nested ...  */
    int starts_at_max;         /* 1: goes down first                          */
} hy_loop;

typedef struct hy_loops {
    hy_loop major;
    hy_loop *minor;            /* in order of rho_start                      */
    size_t nminor;
    double area_period;        /* ∮ y° du over one period: energy per cycle   */
} hy_loops;

/* Finds the loops of the steady state; HY_ENOMEM on allocation failure.  st
 * (initialised) and out must not be NULL (HY_EINVAL; out, when given, empty). */
int hy_loops_find(const hy_steady *st, hy_loops *out, hy_error *err);
/* The bytes of scratch hy_loops_find_buf needs for an input of nruns runs
 * (0 when that would not fit in a size_t). */
size_t hy_loops_work_size(size_t nruns);
/* As hy_loops_find, in the caller's work (hy_loops_work_size(st->in->nruns)
 * bytes, aligned as malloc's; out->minor points into it: do not
 * hy_loops_free out): no allocation, the same loops (hystviz sweep's
 * closed-form kernel).  HY_OK, or HY_EINVAL as hy_loops_find; work may be
 * NULL (allocated here, as hy_loops_find: hy_loops_free out). */
int hy_loops_find_buf(const hy_steady *st, hy_loops *out, void *work, hy_error *err);
/* Frees the minor loops of l and empties it (l may be NULL; a second call is
 * harmless). */
void hy_loops_free(hy_loops *l);

/* Any model: the same pairing of the input's turning points alone (ϱ and u
 * of every loop, depth, starts_at_max); areas 0, y_start/y_close and
 * area_period NaN, for the caller to fill from its model and then call
 * hy_loops_nest for own_area.  HY_ENOMEM on allocation failure; in (with
 * pieces) and out must not be NULL (HY_EINVAL). */
int hy_loops_pair(const hy_input *in, hy_loops *out, hy_error *err);
/* Recomputes depth and own_area from the loops' ϱ intervals and areas.  out
 * must not be NULL, nor out->minor when out->nminor > 0 (HY_EINVAL). */
int hy_loops_nest(hy_loops *out, hy_error *err);

/* ∫ y° dψ over [rho0, rho1] (rho1 >= rho0, any ϱ, periodic), exact.  NaN
 * for st NULL or not initialised, or rho0 or rho1 not finite. */
double hy_steady_area(const hy_steady *st, double rho0, double rho1);

/* An arc: one monotone stretch of a loop, y(ϱ) = e^{-a(ϱ-ϱ0)} y0 + s g0 (1 - e^{-a(ϱ-ϱ0)}),
 * ψ(ϱ) = u0 + s (ϱ - ϱ0) for ϱ in [rho0, rho1]. */
typedef struct hy_arc {
    double rho0, rho1, u0, y0;
    int sign;
} hy_arc;
/* Writes up to max arcs of [rho0, rho1] into arcs; returns how many it needs.
 * arcs may be NULL only when max is 0 (else 0 and nothing written); 0 for
 * st NULL or not initialised, or rho0 or rho1 not finite. */
size_t hy_steady_arcs(const hy_steady *st, double rho0, double rho1, hy_arc *arcs, size_t max);

#ifdef __cplusplus
}
#endif

#endif
