/* SPDX-License-Identifier: MIT */
/* hy_ticks.h: axis tick selection at round numbers and compact tick labels.
 *
 * Linear axes get ticks at 1, 2, 2.5 or 5 x 10^k; log axes get decades with
 * labels "10^{k}" (markup, see hy_markup.h), falling back to 1-2-5 when the
 * range spans less than a decade.  hy_ticks_fit reduces the tick count until
 * the measured labels fit along the axis without overlapping.
 *
 *     hy_ticks t;
 *     hy_ticks_linear(0.0, 4.6, 6, &t);   // 0 1 2 3 4
 */
#ifndef HY_TICKS_H
#define HY_TICKS_H

#include <stddef.h>

#define HY_TICKS_MAX 32
#define HY_TICK_LABEL 40

typedef struct hy_ticks {
    int n;
    double v[HY_TICKS_MAX];            /* tick positions in data units, ascending */
    char label[HY_TICKS_MAX][HY_TICK_LABEL]; /* markup strings */
    double step;                        /* linear: spacing; log: decades per tick */
} hy_ticks;

/* Round step >= (hi - lo) / target from {1, 2, 2.5, 5} x 10^k; 0 if hi <= lo. */
double hy_ticks_nice_step(double lo, double hi, int target);

/* Ticks inside [lo, hi] at about target intervals, labelled with the fewest
 * decimals that tell them apart (scientific "2x10^{5}" for huge/tiny values).
 * Returns 0, or HY_EINVAL if the range is empty or not finite. */
int hy_ticks_linear(double lo, double hi, int target, hy_ticks *t);

/* Log ticks inside [lo, hi] (both > 0): every k-th decade so that at most
 * target ticks remain; 1-2-5 multiples when fewer than two decades show. */
int hy_ticks_log(double lo, double hi, int target, hy_ticks *t);

/* Measures a tick label's extent along the axis (width for a horizontal
 * axis, height for a vertical one), in points. */
typedef double (*hy_ticks_measure_fn)(void *ctx, const char *label);

/* Picks the largest tick count (<= max_target) whose labels, measured with
 * measure, are separated by at least gap points on an axis length points
 * long.  When no count fits it keeps the two extreme ticks, or one if
 * even those collide.  Returns HY_EINVAL for an empty or unusable range. */
int hy_ticks_fit(double lo, double hi, int log_scale, double length, double gap,
                 int max_target, hy_ticks_measure_fn measure, void *ctx, hy_ticks *t);

#endif
