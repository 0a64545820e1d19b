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
#include "hy_input.h"

/* Moves the model held in ctx to input value u (from wherever it is, along a
 * monotone path) and writes its output into *y.  Returns an hy_status code. */
typedef int (*hy_rateind_fn)(void *ctx, double u, double *y, hy_error *err);

/* For each ascending time t[i] >= 0 (i < n): feeds fn every extremum of u with
 * time in (t[i-1], t[i]] (t[-1] = 0) in order, then u(t[i]); y[i] is the
 * output after the last.  The model must already sit at u(0).  Extremum values
 * are taken from the input's runs exactly.  Returns the first nonzero status
 * of fn (y[i..] unwritten), or HY_EINVAL for times that are not ascending. */
int hy_rateind_drive(const hy_input *in, const double *t, size_t n, hy_rateind_fn fn, void *ctx,
                     double *y, hy_error *err);

/* The extrema of a bimodal input of Definition 1 as hy_input_bimodal builds it
 * (four runs from t = 0: u_min,1 up to u_max,1, down to u_min,2, up to u_max,2,
 * down to u_min,1): e[0..3] = u_min,1, u_max,1, u_min,2, u_max,2.  HY_EINVAL
 * (naming what differs) for any other input. */
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

#endif
