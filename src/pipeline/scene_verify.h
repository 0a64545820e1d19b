/* SPDX-License-Identifier: MIT */
/* scene_verify.h: measured errors of the closed-form series of a scene
 * (issue 11: no printed error that was not computed).
 *
 * Each function compares the values a series drew with an independent
 * long-double evaluation (hy_ref.h) at the same parameters, 1 point in stride
 * point when there are more than HY_VERIFY_POINTS, and sets se->err (max
 * absolute difference) and se->err_ref (what it was compared with and the
 * sampling).  Where no independent reference exists, or the reference is not
 * accurate enough to judge, se->err is NaN and se->err_ref says "not measured"
 * and why.
 */
#ifndef HY_SCENE_VERIFY_H
#define HY_SCENE_VERIFY_H

#include "scene_run_types.h"

enum { HY_VERIFY_POINTS = 4096 };

/* minor/major loops: pieces i < k sampled on [a[i], b[i]] of ϱ with per
 * points each, followed by one gap point.  thinned: se holds only some of
 * those points (a figure's thinned loop, scene_run.h); the values measured
 * are then the closed form's at the same ϱ, as sampling computes them. */
void hy_verify_loops(const hy_scene_run *r, hy_run_series *se, const double *a, const double *b, int k, size_t per,
                     int thinned);
/* y°, y*_{u,k} (on one period) and y* (over the plan's times): y[i] (the
 * series' values, or its mark's) at time t[i], t ascending (t NULL: n points
 * evenly on [0, T]). */
void hy_verify_time(const hy_scene_run *r, hy_run_series *se, const double *t, const double *y, size_t n);
/* y_γ from the exact solver at times t (ascending): *err and *ref as above. */
void hy_verify_gamma(const hy_scene_run *r, double gamma, const double *t, const double *y, size_t n, double *err,
                     char *ref, size_t refsize);

#endif
