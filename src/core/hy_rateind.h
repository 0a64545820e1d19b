/* SPDX-License-Identifier: MIT */
/* hy_rateind.h: driving rate-independent hysteresis models (Preisach,
 * Jiles-Atherton) with hystviz's inputs, and the record of a minor loop.
 *
 * A rate-independent model's output depends only on the sequence of values its
 * input passed through, not on time: between two reversals only the end value
 * matters.  So an input u(t) (hy_input.h: bimodal of Definition 1, multimodal,
 * triangle, sine, piecewise-linear, file) drives such a model exactly when the
 * model is fed every extremum of u between two output times, then u at the
 * output time.  hy_rateind_drive does that feeding through a callback.
 *
 *     static int feed(void *ctx, double u, double *y, hy_error *err) { ... }
 *     hy_rateind_drive(&in, t, n, feed, &model_state, y, &err);
 */
#ifndef HY_RATEIND_H
#define HY_RATEIND_H

#include <stddef.h>
#include "hy_cancel.h"
#include "hy_input.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Moves the model held in ctx to input value u (from wherever it is, along a
 * monotone path) and writes its output into *y.  Returns an hy_status code. */
typedef int (*hy_rateind_fn)(void *ctx, double u, double *y, hy_error *err);

/* For each ascending time t[i] >= 0 (i < n): feeds fn every extremum of u with
 * time in (t[i-1], t[i]] (t[-1] = 0) in order, then u(t[i]); y[i] is the
 * output after the last.  The model must already sit at u(0).  Extremum values
 * are taken from the input's runs exactly.  Returns the first nonzero status
 * of fn (y[i..] unwritten), or HY_EINVAL for times that are not ascending.
 * in (with pieces), fn and y must not be NULL, nor t when n > 0 (HY_EINVAL);
 * ctx may be NULL (handed to fn as it is). */
int hy_rateind_drive(const hy_input *in, const double *t, size_t n, hy_rateind_fn fn, void *ctx,
                     double *y, hy_error *err);

/* The extrema of a bimodal input of Definition 1 as hy_input_bimodal builds it
 * (four runs from t = 0: u_min,1 up to u_max,1, down to u_min,2, up to u_max,2,
 * down to u_min,1): e[0..3] = u_min,1, u_max,1, u_min,2, u_max,2.  HY_EINVAL
 * (naming what differs) for any other input; in and e must not be NULL
 * (HY_EINVAL). */
int hy_rateind_bimodal(const hy_input *in, double e[4], hy_error *err);

/* The minor loop of a bimodal input in the steady (periodic) state: it starts
 * at the reversal u_max,1, turns at u_min,2 and ends where the input comes back
 * up to u_max,1.  Areas are ∮ u dy (for a magnetic model u = H, y = B: the
 * energy per unit volume ∮ H dB), positive for the counter-clockwise loops of
 * these models; a loop that does not close is closed by the vertical chord
 * u = u_start, i.e. area = -∫ y du along it. */
typedef struct hy_minor_loop {
    double u_start, u_turn;    /* u_max,1 and u_min,2                              */
    double y_start, y_close;   /* output at the start and back at u_start         */
    double area;               /* ∮ u dy of the minor loop                         */
    double area_period;        /* ∮ u dy over one steady period (major + minor)   */
    int cycles;                /* periods driven before the state was periodic    */
} hy_minor_loop;

/* ---- model types (the form of GSL's gsl_odeiv2_step_type) ----------------
 *
 * A rate-independent model is a static const hy_rateind_type: its state's
 * size, what it can do (caps) and four functions on (parameters, state).
 * Generic code holds an hy_rateind (type, borrowed parameters, owned state,
 * the outputs after the last move) and never knows the model:
 *
 *     hy_rateind m;
 *     hy_rateind_alloc(&m, &my_type, &par, u0, &err);
 *     hy_rateind_settle(&m, &in, 1e-11, 1000, &periods, &err);
 *     hy_rateind_sample(&m, &in, 0, t, n, rows, &err);  // rows[0][i] = y(t[i])
 *     hy_rateind_free(&m);
 */

/* out[0] the output y, out[1] a second quantity the model can draw (NaN:
 * none; Jiles-Atherton: M), out[2] a path integral along the path so far
 * whose change over a closed path is ∮ y du (NaN: not tracked): ∫ y du, or,
 * for a model whose y is u plus a bounded lag (the play operator), ∫ (y - u) du
 * in the lag's scale, which neither overflows nor cancels at any |u|. */
enum { HY_RI_NOUT = 3 };

enum {
    HY_RI_RETURN_POINT = 1u << 0,  /* a minor loop closes at its reversal value */
    HY_RI_PATH_AREA = 1u << 1,     /* out[2] is tracked: any loop's area exactly */
    HY_RI_AREA_YDU = 1u << 2       /* loops dissipate ∮ y du (force against displacement,
                                    * clockwise) rather than ∮ u dy (H against B,
                                    * counter-clockwise): the sign of the area */
};

typedef struct hy_rateind_type {
    const char *name;
    size_t state_size;
    unsigned caps;   /* HY_RI_* */
    /* the state at input u0 (from the parameters' initial condition) */
    int (*init)(const void *par, void *st, double u0, double out[HY_RI_NOUT], hy_error *err);
    /* moves the input monotonically to u; on error the state is unchanged or
     * at the last good step (the type says which) */
    int (*apply)(const void *par, void *st, double u, double out[HY_RI_NOUT], hy_error *err);
    /* dst (uninitialised) becomes a copy of src; NULL: the state is plain
     * bytes (no pointers), copied whole */
    int (*copy)(const void *par, void *dst, const void *src, hy_error *err);
    void (*free)(void *st);   /* NULL: nothing to free */
    /* ∮ u dy of the closed loop between reversal values lo < hi (closed-form
     * minor loops), or NULL */
    int (*loop_area)(const void *par, double lo, double hi, double *area, hy_error *err);
} hy_rateind_type;

typedef struct hy_rateind {
    const hy_rateind_type *type;
    const void *par;          /* borrowed: must outlive the model  */
    void *st;                 /* type->state_size bytes, owned     */
    double out[HY_RI_NOUT];   /* after the last move               */
    const hy_cancel *cancel;  /* asked every HY_RI_CANCEL_MOVES moves
                               * (NULL, as alloc sets it: never); a
                               * clone shares it                     */
    unsigned tick;            /* moves since it was last asked       */
} hy_rateind;

/* Moves between two questions to hy_rateind.cancel (a Preisach move with
 * a long history costs tens of microseconds). */
#define HY_RI_CANCEL_MOVES 16

/* Allocates the state and puts the model at input u0 (cancel NULL).  On
 * error m owns nothing.  m, type and type->init must not be NULL (HY_EINVAL);
 * par may be NULL when the type reads none. */
int hy_rateind_alloc(hy_rateind *m, const hy_rateind_type *type, const void *par, double u0, hy_error *err);
/* Moves the input monotonically to u (m->out updated); HY_ECANCEL, the
 * state unchanged, when m->cancel says stop.  m must not be NULL, nor its
 * type or state (HY_EINVAL: not allocated, or freed). */
int hy_rateind_apply(hy_rateind *m, double u, hy_error *err);
/* dst becomes an independent copy of src (dst uninitialised).  dst and src
 * (allocated) must not be NULL (HY_EINVAL; dst->st NULL when dst is not). */
int hy_rateind_clone(hy_rateind *dst, const hy_rateind *src, hy_error *err);
/* Frees m's state (m may be NULL: nothing done; a second call is harmless). */
void hy_rateind_free(hy_rateind *m);

/* Drives the model (sitting at u(0), at a period's start) through whole
 * periods of in until its output at the period's end changes by at most
 * tol times the largest |y| of that period, twice in a row; *periods gets
 * how many were driven.  HY_ENUM (naming max_periods) when it does not settle.
 * m (allocated) and in (with pieces) must not be NULL; periods may be NULL
 * (not written); tol must be finite and >= 0 and max_periods >= 1 (else
 * HY_EINVAL). */
int hy_rateind_settle(hy_rateind *m, const hy_input *in, double tol, int max_periods, int *periods,
                      hy_error *err);

/* From the model at a period's start (u(0) = ψ_u(0)): at each ascending x[i]
 * >= 0 feeds every extremum of the input up to x[i], then its value there,
 * and stores out[q] in rows[q][i] (rows[q] NULL: not stored).  x are times t
 * (by_rho 0: values u(t)) or variations ϱ (by_rho 1: values ψ_u(ϱ), Eq. 10).
 * m (allocated) and in (with pieces) must not be NULL, nor x when n > 0
 * (HY_EINVAL); rows may be NULL (nothing stored). */
int hy_rateind_sample(hy_rateind *m, const hy_input *in, int by_rho, const double *x, size_t n,
                      double *const rows[HY_RI_NOUT], hy_error *err);

#ifdef __cplusplus
}
#endif

#endif
