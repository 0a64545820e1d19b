/* SPDX-License-Identifier: MIT */
/* test_errors.c: bad parameters and inputs are refused with a message that
 * names what is wrong (NaN, σ0 <= 0, u_min,2 >= u_max,1, times not increasing,
 * bad files, γ <= 0, unknown stepper). */
#include <gsl/gsl_errno.h>
#include <stdlib.h>
#include <unistd.h>

#include "hy_gamma.h"
#include "hy_limit.h"
#include "hy_ode.h"
#include "tutil.h"
#include "../tmpdir.h"

static void model_errors(void)
{
    hy_model m;
    hy_error err;
    hy_model_lugre_init(&m, NAN, 1, 1, 2, 1, 1);
    CHECK_MSG(hy_model_validate(&m, &err), err, HY_EINVAL, "sigma0 must be a finite number");
    hy_model_lugre_init(&m, 0, 1, 1, 2, 1, 1);
    CHECK_MSG(hy_model_validate(&m, &err), err, HY_EINVAL, "sigma0 must be > 0");
    hy_model_lugre_init(&m, -3, 1, 1, 2, 1, 1);
    CHECK_MSG(hy_model_validate(&m, &err), err, HY_EINVAL, "sigma0 must be > 0 (got -3)");
    hy_model_lugre_init(&m, 1, -1, 1, 2, 1, 1);
    CHECK_MSG(hy_model_validate(&m, &err), err, HY_EINVAL, "sigma1 must be >= 0");
    hy_model_lugre_init(&m, 1, 1, 1, 0, 1, 1);
    CHECK_MSG(hy_model_validate(&m, &err), err, HY_EINVAL, "fs must be > 0");
    hy_model_lugre_init(&m, 1, 1, INFINITY, 2, 1, 1);
    CHECK_MSG(hy_model_validate(&m, &err), err, HY_EINVAL, "fc must be a finite number");
    hy_model_lugre_init(&m, 1, 1, 1, 2, 1, 1);
    m.x0 = NAN;
    CHECK_MSG(hy_model_validate(&m, &err), err, HY_EINVAL, "x0 must be a finite number");
    hy_model_dahl_init(&m, -1, 1);
    CHECK_MSG(hy_model_validate(&m, &err), err, HY_EINVAL, "rho must be > 0");
    hy_model_dahl_filter_init(&m, 1, 1, 0);
    CHECK_MSG(hy_model_validate(&m, &err), err, HY_EINVAL, "tau must be > 0");
}

static void input_errors(void)
{
    hy_input in;
    hy_error err;
    CHECK_MSG(hy_input_bimodal(&in, 0, 1.2, 1, 1.5, NULL, 0, &err), err, HY_EINVAL,
              "Definition 1 needs u_min,2 < u_max,1 (got u_min,2 = 1.2 >= u_max,1 = 1)");
    CHECK_MSG(hy_input_bimodal(&in, 0, 1, 1, 1.5, NULL, 0, &err), err, HY_EINVAL, "u_min,2 < u_max,1");
    CHECK_MSG(hy_input_bimodal(&in, 0.3, 0.2, 1, 1.5, NULL, 0, &err), err, HY_EINVAL, "u_min,1 <= u_min,2");
    CHECK_MSG(hy_input_bimodal(&in, 0, 0.2, 1.6, 1.5, NULL, 0, &err), err, HY_EINVAL, "u_max,1 <= u_max,2");
    CHECK_MSG(hy_input_bimodal(&in, 0, 0, 1, 1, NULL, 0, &err), err, HY_EINVAL, "both pairs are equal");
    CHECK_MSG(hy_input_bimodal(&in, NAN, 0, 1, 1, NULL, 0, &err), err, HY_EINVAL, "u_min,1 must be a finite number");
    CHECK_MSG(hy_input_bimodal(&in, 0, 0.2, 1, 1.5, (const double[]){1, 3, 2, 4}, 0, &err), err, HY_EINVAL,
              "0 < t1 < t2 < t3 < t4 (t3 = 2)");
    CHECK_MSG(hy_input_bimodal(&in, 0, 0.2, 1, 1.5, (const double[]){0, 1, 2, 3}, 0, &err), err, HY_EINVAL, "(t1 = 0)");
    CHECK_MSG(hy_input_pwl(&in, (const double[]){0, 1, 1, 2}, (const double[]){0, 1, 0.5, 0}, 4, &err), err, HY_EINVAL,
              "times must be strictly increasing: t[2] = 1 is not > t[1] = 1");
    CHECK_MSG(hy_input_pwl(&in, (const double[]){0, 1, 2}, (const double[]){0, 1, 0.5}, 3, &err), err, HY_EINVAL,
              "input is not periodic");
    CHECK_MSG(hy_input_multimodal(&in, (const double[]){0, 1, 2, 1}, 4, NULL, 0, &err), err, HY_EINVAL,
              "extrema must alternate");
    CHECK_MSG(hy_input_multimodal(&in, (const double[]){0, 1, 0}, 3, NULL, 0, &err), err, HY_EINVAL, "even number");
    CHECK_MSG(hy_input_sine(&in, 1, 0, 0, &err), err, HY_EINVAL, "sine period must be > 0");
    CHECK_MSG(hy_input_triangle(&in, 1, 1, 2, &err), err, HY_EINVAL, "triangle needs finite min < max");
    CHECK_MSG(hy_input_parse(&in, "bimodal:0,0.2,x,1.5", &err), err, HY_EINVAL, "'x,1.5' is not a number");
    CHECK_MSG(hy_input_parse(&in, "square:1,2", &err), err, HY_EINVAL, "unknown kind 'square'");
    CHECK_MSG(hy_input_parse(&in, "bimodal:0,0.2,1", &err), err, HY_EINVAL, "bimodal takes umin1,umin2,umax1,umax2");
    CHECK_MSG(hy_input_parse(&in, "bimodal:0,0.2,1,1.5:wavy", &err), err, HY_EINVAL, "unknown shape 'wavy'");
    CHECK_MSG(hy_input_parse(&in, "file:/nonexistent/u.txt", &err), err, HY_EIO, "/nonexistent/u.txt: cannot open input file");
    char path[4200];
    int fd = mkstemp(test_tmppath(path, sizeof path, "bad_XXXXXX"));
    FILE *f = fdopen(fd, "w");
    fprintf(f, "0 0\n1 1\n0.5 0\n");
    fclose(f);
    char want[4400];
    snprintf(want, sizeof want, "%s:3: time 0.5 is not greater than the previous time 1", path);
    CHECK_MSG(hy_input_file(&in, path, &err), err, HY_EINVAL, want);
    f = fopen(path, "w");
    fprintf(f, "0 0\n1 abc\n");
    fclose(f);
    snprintf(want, sizeof want, "%s:2: expected a second number", path);
    CHECK_MSG(hy_input_file(&in, path, &err), err, HY_EINVAL, want);
    f = fopen(path, "w");
    fclose(f);
    CHECK_MSG(hy_input_file(&in, path, &err), err, HY_EINVAL, "needs at least 2 samples");
    /* issue 10 item 17: a NUL byte ended the line for strtod, and the rest
       ("9 junk") was dropped without a word */
    static const char nul[] = "0 0\n1 1\0 9 junk\n2 0\n";
    f = fopen(path, "w");
    fwrite(nul, 1, sizeof nul - 1, f);
    fclose(f);
    snprintf(want, sizeof want, "%s:2:4: NUL byte in the line", path);
    CHECK_MSG(hy_input_file(&in, path, &err), err, HY_EINVAL, want);
    remove(path);
}

static void solver_errors(void)
{
    hy_model m;
    hy_input in;
    hy_error err;
    double t[2] = {0, 1}, y[2];
    hy_model_lugre_init(&m, 1, 1, 1, 2, 1, 1);
    hy_input_parse(&in, "sine:1,1", &err);
    CHECK_MSG(hy_gamma_exact(&m, &in, 0, t, 2, y, NULL, &err), err, HY_EINVAL, "gamma must be a finite number > 0 (got 0)");
    CHECK_MSG(hy_gamma_exact(&m, &in, 1, t, 2, y, NULL, &err), err, HY_EUNSUP, "choose an ODE solver");
    hy_ode_opts o = hy_ode_defaults();
    o.stepper = "euler";
    CHECK_MSG(hy_ode_solve(&m, &in, 1, &o, t, 2, y, NULL, &err), err, HY_EINVAL, "unknown ODE stepper 'euler'");
    o = hy_ode_defaults();
    o.rtol = NAN;
    CHECK_MSG(hy_ode_solve(&m, &in, 1, &o, t, 2, y, NULL, &err), err, HY_EINVAL, "ODE tolerances must be finite");
    o = hy_ode_defaults();
    o.max_steps = 3;
    o.rtol = 1e-12;
    CHECK_MSG(hy_ode_solve(&m, &in, 1, &o, t, 2, y, NULL, &err), err, HY_ENUM, "ODE step cap reached at t = ");
    double tb[2] = {1, 0.5};
    CHECK_MSG(hy_ode_solve(&m, &in, 1, &(hy_ode_opts){.stepper = "rkf45", .rtol = 1e-6, .atol = 1e-8, .restart = 1}, tb, 2, y, NULL, &err), err, HY_EINVAL,
              "ascending");
    hy_steady st;
    m.sigma0 = -1;
    CHECK_MSG(hy_steady_init(&st, &m, &in, &err), err, HY_EINVAL, "sigma0 must be > 0");
    hy_input_free(&in);
}

/* issue 20 item 10: a message is text a terminal shows as it is, whatever
 * bytes its arguments carry (ESC, BEL, DEL, C1 controls, invalid UTF-8);
 * printable UTF-8 stays. */
static void message_text(void)
{
    hy_error err = {0};
    hy_error_set(&err, HY_EINVAL, "got '%s'", "a\x1b]0;PWNED\x07\x1b[31mRED\x7f\xff\xc2\x9b\xce\xb3\xe2\x82");
    CHECK(!strcmp(err.msg, "got 'a\\x1b]0;PWNED\\x07\\x1b[31mRED\\x7f\\xff\\xc2\\x9b\xce\xb3\\xe2\\x82'"),
          "escaped message '%s'", err.msg);
    hy_error_prefix(&err, "f\x1b.scene:1:1");
    const char *want = "f\\x1b.scene:1:1: got 'a\\x1b]";
    CHECK(!strncmp(err.msg, want, strlen(want)), "prefixed message '%s'", err.msg);
    char big[2048];
    memset(big, 0x1b, sizeof big - 1);
    big[sizeof big - 1] = '\0';
    hy_error_set(&err, HY_EINVAL, "%s", big);
    CHECK(strlen(err.msg) < sizeof err.msg && !strchr(err.msg, 0x1b), "long escaped message not cut cleanly");
}

int main(void)
{
    gsl_set_error_handler_off();
    message_text();
    model_errors();
    input_errors();
    solver_errors();
    return tu_finish("errors");
}
