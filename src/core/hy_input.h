/* SPDX-License-Identifier: MIT */
/* hy_input.h: periodic piecewise-monotone inputs u(t) (seed 000, Definition 1,
 * Eqs. (5), (9)-(10)).
 *
 * An input is a list of pieces covering one period [0, T].  Each piece is
 * monotone: linear (u̇ constant, the case the exact finite-γ solver needs) or a
 * sine arc c + A sin(ωt + φ) between two consecutive extrema or parts of one
 * (smooth pieces, so that ψ_u ≠ u can be shown).  Consecutive pieces moving the
 * same way form a run; runs are separated by the extrema of u.
 *
 *     hy_input in;
 *     if (hy_input_parse(&in, "bimodal:0,0.5,1,1.5", &err)) ...
 *     double u = hy_input_u(&in, t), r = hy_input_rho(&in, t);
 *     double psi = hy_input_psi(&in, r);        // ψ_u(ρ_u(t)) == u(t)
 *     hy_input_free(&in);
 */
#ifndef HY_INPUT_H
#define HY_INPUT_H

#include <stddef.h>
#include "hy_status.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { HY_PIECE_LINEAR = 0, HY_PIECE_SINE = 1 };
enum { HY_SHAPE_LINEAR = 0, HY_SHAPE_COSINE = 1 };

typedef struct hy_piece {
    double t0, t1;      /* time interval, t0 < t1                          */
    double u0, u1;      /* values at the ends (u0 == u1: a dwell)          */
    int shape;          /* HY_PIECE_LINEAR or HY_PIECE_SINE                */
    double c, amp, omega, phase; /* sine pieces: u = c + amp sin(ω t + φ)  */
    double rho0;        /* ρ_u(t0)                                          */
} hy_piece;

typedef struct hy_run {
    size_t p0, p1;      /* pieces [p0, p1) of this run                     */
    double rho0, rho1;  /* variation at its ends                            */
    double u0, u1;      /* values at its ends                               */
    int sign;           /* +1 rising, -1 falling                            */
} hy_run;

typedef struct hy_input {
    hy_piece *pieces;
    size_t npieces;
    hy_run *runs;
    size_t nruns;
    double period;      /* T                                                */
    double rho_T;       /* ρ_u(T), the variation over one period            */
    int all_linear;     /* every piece has constant u̇                       */
    char desc[160];     /* what was asked for, for messages and legends    */
} hy_input;

/* Piecewise-linear periodic input through (t[i], u[i]), i < n, t[0] = 0,
 * t strictly increasing, u[n-1] == u[0].  HY_EINVAL names the bad index.
 * in, t and u must not be NULL (HY_EINVAL "hy_input_pwl: X must not be
 * NULL"). */
int hy_input_pwl(hy_input *in, const double *t, const double *u, size_t n, hy_error *err);

/* Bimodal input of Definition 1: umin1 <= umin2 < umax1 <= umax2, not both
 * equalities, 0 < t1 < t2 < t3 < t4 (t == NULL: normalised, slopes ±1).
 * shape HY_SHAPE_COSINE makes each monotone piece a half-cosine.  in must not
 * be NULL; t may be NULL (as said). */
int hy_input_bimodal(hy_input *in, double umin1, double umin2, double umax1, double umax2,
                     const double t[4], int shape, hy_error *err);

/* As hy_input_bimodal, into the caller's pieces and runs (in points to them:
 * do not hy_input_free in), with no allocation and an empty desc; the same
 * pieces, runs, T and ρ_T (hystviz sweep's closed-form kernel).  in,
 * pieces and runs must not be NULL; t may be NULL. */
int hy_input_bimodal_buf(hy_input *in, hy_piece pieces[4], hy_run runs[4], double umin1, double umin2, double umax1,
                         double umax2, const double t[4], int shape, hy_error *err);
/* Multimodal input through the alternating extrema e[0..n-1] (e[0] repeated at
 * the period's end), reached at times tm[1..n] (tm == NULL: slopes ±1; tm[0] = 0).
 * in and e must not be NULL. */
int hy_input_multimodal(hy_input *in, const double *e, size_t n, const double *tm,
                        int shape, hy_error *err);

/* Triangle from umin (t = 0) up to umax (t = T/2) and back (in not NULL). */
int hy_input_triangle(hy_input *in, double umin, double umax, double period, hy_error *err);

/* offset + amp sin(2π t / period), split at its extrema into sine pieces (in
 * not NULL). */
int hy_input_sine(hy_input *in, double amp, double period, double offset, hy_error *err);

/* Input files are read whole; larger ones are refused (docs/SCENES.md). */
#define HY_INPUT_FILE_MAX ((size_t)128 << 20)

/* Sampled signal from a text file the user named: lines "t u" or "t,u" (#
 * comments allowed), t from 0 strictly increasing; closed back to u(0) if it
 * does not end there.  A regular file of at most HY_INPUT_FILE_MAX bytes;
 * errors name path:line and quote at most 20 bytes of a line, escaped.  in
 * and path must not be NULL. */
int hy_input_file(hy_input *in, const char *path, hy_error *err);

/* As hy_input_file, from len bytes of text named name in messages; quote = 0
 * (a file a scene named) keeps every byte and value of the text out of the
 * messages.  in must not be NULL; text may be NULL only when len is 0; name
 * may be NULL ("input"). */
int hy_input_text(hy_input *in, const char *text, size_t len, const char *name, int quote,
                  hy_error *err);

/* Parses "bimodal:umin1,umin2,umax1,umax2[,t1,t2,t3,t4]", "multimodal:e0,e1,...",
 * "triangle:min,max,T", "sine:amp,T[,offset]", "pwl:t0,u0,t1,u1,...",
 * "file:PATH"; a trailing ":cosine" on bimodal/multimodal selects half-cosines.
 * in and spec must not be NULL. */
int hy_input_parse(hy_input *in, const char *spec, hy_error *err);

/* Frees what in holds (its pieces and runs) and empties it, so a second call
 * is harmless; in may be NULL. */
void hy_input_free(hy_input *in);

/* t - k T, the time within period k, with k T carried exactly (an fma gives
 * the product's rounding error), so it is as accurate as t itself for any k:
 * no error grows with the number of periods.  in NULL: NaN. */
double hy_input_reduce(const hy_input *in, double t, double k);
/* Width within which an output time counts as a breakpoint at time tb (or as
 * the current time of an integrator): 8 ulps of tb.  Both solvers serve such
 * a time on the piece that starts at the breakpoint. */
double hy_input_snap(double tb);
/* Index of the piece containing t modulo the period (t in [t0, t1)); tmod
 * and kcycles may be NULL (not written).  in NULL or without pieces (freed):
 * 0, with *tmod and *kcycles NaN. */
size_t hy_input_piece_at(const hy_input *in, double t, double *tmod, double *kcycles);
/* u(t), u̇(t), ü(t) for any t >= 0 (periodic extension): hy_input_u,
 * hy_input_du, hy_input_ddu.  in NULL or without pieces (freed): NaN. */
double hy_input_u(const hy_input *in, double t);
double hy_input_du(const hy_input *in, double t);
double hy_input_ddu(const hy_input *in, double t);
/* u, u̇ on piece p at absolute time t inside it (no search): hy_piece_u,
 * hy_piece_du.  p NULL: NaN. */
double hy_piece_u(const hy_piece *p, double t);
double hy_piece_du(const hy_piece *p, double t);
/* ρ_u(t) = ∫_0^t |u̇| (Eq. 5), including whole periods.  in NULL or without
 * pieces (freed): NaN. */
double hy_input_rho(const hy_input *in, double t);
/* ψ_u(ϱ) (Eqs. 9-10): the normalised input, slopes ±1, ϱ_T-periodic.  in
 * NULL or without pieces (freed): NaN. */
double hy_input_psi(const hy_input *in, double rho);
/* Index of the run containing ϱ modulo ρ_T; rmod may be NULL (not written).
 * in NULL or without pieces (freed): 0, with *rmod NaN. */
size_t hy_input_run_at(const hy_input *in, double rho, double *rmod);

#ifdef __cplusplus
}
#endif

#endif
