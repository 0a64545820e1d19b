/* SPDX-License-Identifier: MIT */
/* test_workprec.c: the work-precision module: error norms, the long-double
 * reference against hy_gamma_exact on every piecewise-linear problem, Example
 * 1's reference against a second stepper, a run's status under a step cap. */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "hy_gamma.h"
#include "hy_workprec.h"

#include "../hy_test.h"

#define CHECK HY_CHECK /* tests/hy_test.h */

static void test_norms(void)
{
    const double y[4] = {1, 2, 3, 4}, r[4] = {1, 2, 3, 2};
    double mx, l2;
    hy_wp_error(y, r, 4, &mx, &l2);
    CHECK(mx == 2 && fabs(l2 - 1) < 1e-15, "norms %g %g (want 2, 1)", mx, l2);
    const double bad[2] = {NAN, 0}, z[2] = {0, 0};
    hy_wp_error(bad, z, 2, &mx, &l2);
    CHECK(isinf(mx) && isinf(l2), "non-finite output gives inf");
    CHECK(!strcmp(hy_wp_status_name(HY_WP_STEPCAP), "stepcap"), "status name");
}

static void test_problems(void)
{
    for (const char *const *n = hy_wp_problem_names(); *n; n++) {
        hy_wp_problem p;
        hy_error err;
        int rc = hy_wp_problem_init(&p, *n, 1, &err);
        CHECK(rc == 0, "%s: %s", *n, err.msg);
        if (rc)
            continue;
        CHECK(p.n >= 100 && p.ref_method[0], "%s: grid and reference named", *n);
        for (size_t i = 0; i < p.n; i++)
            CHECK(isfinite(p.yref[i]), "%s: reference finite", *n);
        if (hy_wp_solver_applies(&p, "exact")) {
            hy_wp_cfg cfg = hy_wp_cfg_defaults();
            hy_wp_run r;
            cfg.repeats = 1;
            hy_wp_run_solver(&p, "exact", -1, 0, &cfg, &r);
            double scale = 1;
            for (size_t i = 0; i < p.n; i++)
                scale = fmax(scale, fabs(p.yref[i]));
            /* two independent evaluations of the exponential formula */
            CHECK(r.status == HY_WP_OK && r.err_max <= 1e-15 * scale, "%s: exact vs long double %.3e", *n,
                  r.err_max);
        }
        hy_wp_problem_free(&p);
    }
}

static void test_caps(void)
{
    hy_wp_problem p;
    hy_wp_cfg cfg = hy_wp_cfg_defaults();
    hy_wp_run r;
    hy_error err;
    if (hy_wp_problem_init(&p, "ex3-g10", 1, &err)) {
        CHECK(0, "ex3-g10: %s", err.msg);
        return;
    }
    cfg.repeats = 1;
    cfg.max_steps = 1;
    CHECK(hy_wp_run_solver(&p, "rk4", 1, 1e-6, &cfg, &r) == HY_WP_STEPCAP && strstr(r.msg, "step cap"),
          "step cap 1: status %s (%s)", hy_wp_status_name(r.status), r.msg);
    CHECK(isnan(r.err_max), "no error reported for a capped run");
    cfg.max_steps = 200000;
    cfg.time_cap = 1e-9;
    /* rtol 1e-6: the steps are good to 5.6e-8, the Hermite grid to 3.8e-6 */
    CHECK(hy_wp_run_solver(&p, "rkf45", 1, 1e-6, &cfg, &r) == HY_WP_TIMECAP && r.repeats == 1 &&
              r.err_steps < 1e-6 && r.err_max < 1e-4,
          "time cap: status %s, %d repeats, error %g at the steps, %g on the grid", hy_wp_status_name(r.status),
          r.repeats, r.err_steps, r.err_max);
    /* the tolerance moves rkf45's error with restarts (one run for every
     * tolerance when each output time ended a step: 5.18e-12 throughout) */
    hy_wp_run loose, tight;
    cfg.time_cap = 2;
    hy_wp_run_solver(&p, "rkf45", 1, 1e-2, &cfg, &loose);
    hy_wp_run_solver(&p, "rkf45", 1, 1e-8, &cfg, &tight);
    CHECK(loose.status == HY_WP_OK && tight.status == HY_WP_OK && loose.err_steps > 1e3 * tight.err_steps &&
              loose.err_max > 10 * tight.err_max && loose.steps < tight.steps,
          "rkf45 with restarts, rtol 1e-2 vs 1e-8: error at steps %g vs %g, on the grid %g vs %g, %lu vs %lu steps",
          loose.err_steps, tight.err_steps, loose.err_max, tight.err_max, loose.steps, tight.steps);
    hy_wp_problem_free(&p);
    CHECK(hy_wp_problem_init(&p, "ex4-g1", 1, &err) == HY_EINVAL, "unknown problem refused");
    hy_wp_problem_free(&p);
}

int main(void)
{
    gsl_set_error_handler_off();
    test_norms();
    test_problems();
    test_caps();
    return hy_test_finish("workprec");
}
