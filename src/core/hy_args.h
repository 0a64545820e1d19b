/* SPDX-License-Identifier: MIT */
/* hy_args.h: the refusals of hy_status.h's rule for pointer arguments, written
 * once for every installed header's functions.  Not an installed header.
 *
 *     int hy_x_run(const hy_x *x, double *y, hy_error *err)
 *     {
 *         HY_NONNULL(err, x);   // HY_EINVAL "hy_x_run: x must not be NULL"
 *         HY_NONNULL(err, y);
 *         ...
 */
#ifndef HY_ARGS_H
#define HY_ARGS_H

#include "hy_status.h"

/* Returns HY_EINVAL from the calling function, with the message
 * "FUNCTION: p must not be NULL", when the pointer argument p is NULL. */
#define HY_NONNULL(err, p)                                                                                            \
    do {                                                                                                              \
        if (!(p))                                                                                                     \
            return hy_error_set((err), HY_EINVAL, "%s: %s must not be NULL", __func__, #p);                          \
    } while (0)

/* As HY_NONNULL for an array p of n elements: NULL is refused only when n
 * is not 0 ("FUNCTION: p must not be NULL (n is N)"). */
#define HY_NONNULL_N(err, p, n)                                                                                       \
    do {                                                                                                              \
        if (!(p) && (n))                                                                                              \
            return hy_error_set((err), HY_EINVAL, "%s: %s must not be NULL (%s is %zu)", __func__, #p, #n,            \
                                (size_t)(n));                                                                         \
    } while (0)

#define HY__NO_PIECES "has no pieces (not made, or freed)"

/* Returns HY_EINVAL from the calling function when the hy_input pointer in
 * is NULL ("must not be NULL") or has no pieces ("has no pieces"). */
#define HY_INPUT_READY(err, in)                                                                                       \
    do {                                                                                                              \
        if (!hy__input_ready(in))                                                                                     \
            return hy_error_set((err), HY_EINVAL, "%s: %s %s", __func__, #in,                                         \
                                !(in) ? "must not be NULL" : HY__NO_PIECES);                                          \
    } while (0)

/* hy__input_ready: whether an input has pieces and runs (in not NULL, not
 * freed); hy__steady_ready: whether a steady state has its table and such an
 * input.  What the functions that read them check first (hy_input.c,
 * hy_limit.c). */
struct hy_input;
struct hy_steady;
struct hy_model;
int hy__input_ready(const struct hy_input *in);
int hy__steady_ready(const struct hy_steady *st);

/* The arguments every solver of Eq. (3) takes, checked in one place
 * (hy_gamma.c): m, in (with pieces) and the output y (called yname) not
 * NULL, nor t when n > 0; then the model and gamma.  fn names the caller in
 * the messages. */
int hy__solve_args(const char *fn, const struct hy_model *m, const struct hy_input *in, double gamma,
                   const double *t, size_t n, const double *y, const char *yname, hy_error *err);

#endif
