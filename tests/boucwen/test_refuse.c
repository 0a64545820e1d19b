/* SPDX-License-Identifier: MIT */
/* test_refuse.c: invalid parameters, Newmark settings and input files are
 * refused with a message that names the parameter or file:line; a step that
 * cannot converge reports time and residual instead of returning NaN. */
#include "bw_test.h"
#include "hy_boucwen.h"
#include "hy_signal.h"

#include <math.h>
#include <unistd.h>
#include "../tmpdir.h"

static void expect(int rc, int code, const hy_error *e, const char *needle)
{
    CHECK(rc == code, "status %d, expected %d (%s)", rc, code, e->msg);
    CHECK(strstr(e->msg, needle) != NULL, "message '%s' lacks '%s'", e->msg, needle);
}

static void bad_param(const char *name, double v, const char *needle)
{
    hy_boucwen_params p;
    hy_error e = {0, ""};
    hy_boucwen_params_default(&p);
    CHECK(hy_boucwen_params_set(&p, name, v, &e) == HY_OK, "%s", e.msg);
    expect(hy_boucwen_params_validate(&p, &e), HY_EINVAL, &e, needle);
    double u[2] = {0, 0}, y[2];
    expect(hy_boucwen_simulate(&p, &(hy_newmark_opts){0.5, 0.25, 0.5, 1e-12, 50, NULL},
                               1e-4, u, 2, NULL, y, NULL, &e),
           HY_EINVAL, &e, needle);
}

static void bad_file(const char *text, const char *needle)
{
    char path[4200];
    int fd = mkstemp(test_tmppath(path, sizeof path, "refuse_XXXXXX"));
    CHECK(fd >= 0, "mkstemp");
    if (fd < 0)
        return;
    FILE *f = fdopen(fd, "w");
    fputs(text, f);
    fclose(f);
    double *u = NULL, fs;
    size_t n = 0;
    hy_error e = {0, ""};
    int rc = hy_signal_read(path, &u, &n, &fs, &e);
    CHECK(rc != HY_OK, "file '%s' accepted", text);
    CHECK(strstr(e.msg, path) != NULL, "message '%s' lacks the file name", e.msg);
    CHECK(strstr(e.msg, needle) != NULL, "message '%s' lacks '%s'", e.msg, needle);
    CHECK(u == NULL, "output set on failure");
    free(u);
    unlink(path);
}

/* Writes len bytes to a temporary file; returns its path in path. */
static int temp_file(char path[4200], const char *bytes, size_t len)
{
    int fd = mkstemp(test_tmppath(path, 4200, "file_XXXXXX"));
    FILE *f = fd >= 0 ? fdopen(fd, "w") : NULL;
    if (!f)
        return -1;
    fwrite(bytes, 1, len, f);
    fclose(f);
    return 0;
}

/* issue 10 item 17: times printed to 6 or 10 significant digits are uniform
 * to their printed precision (they were refused); a sample missing from them
 * is not; a NUL byte (which cut the line short unseen) is refused. */
static void printed_times(void)
{
    struct { const char *fmt; long i0, n; } cases[] = {
        {"%.6g,%.17g\n", 0, 7500},             /* 0 .. 9.99867 s, resolution 1e-5 s       */
        {"%.10g,%.17g\n", 2790000, 35600},     /* 3720 .. 3767.5 s, resolution 1e-6 s     */
        {"%.6f,%.17g\n", 0, 7500},             /* fixed decimals: resolution 1e-6 s       */
    };
    for (size_t k = 0; k < sizeof cases / sizeof *cases; k++) {
        size_t cap = (size_t)cases[k].n * 48, len = 0;
        char *text = malloc(cap), path[4200];
        for (long i = cases[k].i0; i < cases[k].i0 + cases[k].n; i++) {
            double t = (double)i / 750;
            len += (size_t)snprintf(text + len, cap - len, cases[k].fmt, t, 40 * sin(2 * M_PI * (18 * t + t * t / 12)));
        }
        double *u = NULL, fs = 0;
        size_t n = 0;
        hy_error e = {0, ""};
        CHECK(temp_file(path, text, len) == 0, "temp file");
        int rc = hy_signal_read(path, &u, &n, &fs, &e);
        /* fs from the first and last times: each within half their resolution q,
           so 1/fs is within q / (n - 1) of 1/750 */
        CHECK(rc == HY_OK && n == (size_t)cases[k].n && fabs(fs - 750) < 1e-6 * 750,
              "%s: rc %d, %zu samples, fs %.17g: %s", cases[k].fmt, rc, n, fs, e.msg);
        unlink(path);
        free(u);
        u = NULL;
        /* drop the 101st line: a gap of one sample is refused at its line */
        char *l100 = text;
        for (int j = 0; j < 100; j++)
            l100 = strchr(l100, '\n') + 1;
        char *l101 = strchr(l100, '\n') + 1;
        memmove(l100, l101, len - (size_t)(l101 - text) + 0);
        len -= (size_t)(l101 - l100);
        temp_file(path, text, len);
        rc = hy_signal_read(path, &u, &n, &fs, &e);
        CHECK(rc == HY_EINVAL && strstr(e.msg, ":101: time") && strstr(e.msg, "breaks the uniform spacing"),
              "%s with a gap: %s", cases[k].fmt, e.msg);
        CHECK(u == NULL, "output set on failure");
        unlink(path);
        free(text);
    }
    /* times too coarse for the spacing: 6 digits at 3720 s are 0.01 s apart */
    char path[4200], want[4300];
    const char coarse[] = "3720,1\n3720,2\n3720.01,3\n";
    double *u = NULL, fs;
    size_t n;
    hy_error e = {0, ""};
    temp_file(path, coarse, sizeof coarse - 1);
    CHECK(hy_signal_read(path, &u, &n, &fs, &e) == HY_EINVAL && strstr(e.msg, ":2: time 3720 is not after"), "%s",
          e.msg);
    unlink(path);
    const char nul[] = "1.0\n2.0\0 junk\n3.0\n";
    temp_file(path, nul, sizeof nul - 1);
    snprintf(want, sizeof want, "%s:2:4: NUL byte", path);
    CHECK(hy_signal_read(path, &u, &n, &fs, &e) == HY_EINVAL && strstr(e.msg, want), "%s", e.msg);
    CHECK(u == NULL, "output set on failure");
    unlink(path);
}

int main(void)
{
    printed_times();
    bad_param("m", NAN, "parameter m = nan");
    bad_param("m", 0.0, "parameter m = 0 must be finite and > 0");
    bad_param("m", -2.0, "parameter m = -2");
    bad_param("c", -1.0, "parameter c = -1");
    bad_param("k", INFINITY, "parameter k = inf");
    bad_param("alpha", -5.0, "parameter alpha");
    bad_param("beta", -1.0, "parameter beta");
    bad_param("gamma", NAN, "parameter gamma");
    bad_param("delta", -INFINITY, "parameter delta");
    bad_param("nu", 0.0, "parameter nu = 0");
    bad_param("nu", -1.5, "parameter nu = -1.5");
    {   /* k = α = 0 is no spring at all */
        hy_boucwen_params p;
        hy_error e;
        hy_boucwen_params_default(&p);
        p.k = 0;
        p.alpha = 0;
        expect(hy_boucwen_params_validate(&p, &e), HY_EINVAL, &e, "k + alpha");
        hy_boucwen_params_default(&p);
        expect(hy_boucwen_params_parse(&p, "mu=3", &e), HY_EINVAL, &e, "unknown Bouc-Wen parameter 'mu'");
        expect(hy_boucwen_params_parse(&p, "nu=abc", &e), HY_EINVAL, &e, "parameter nu");
        expect(hy_boucwen_params_parse(&p, "nu", &e), HY_EINVAL, &e, "name=value");
        CHECK(hy_boucwen_params_parse(&p, "nu=1.5", &e) == HY_OK && p.nu == 1.5, "nu=1.5");
    }
    {   /* Newmark settings and the step size */
        hy_boucwen_params p;
        hy_newmark_opts o;
        hy_error e;
        double u[3] = {0, 1, 2}, y[3];
        hy_boucwen_params_default(&p);
        hy_newmark_opts_default(&o);
        expect(hy_boucwen_simulate(&p, &o, 0.0, u, 3, NULL, y, NULL, &e), HY_EINVAL, &e, "time step h");
        expect(hy_boucwen_simulate(&p, &o, NAN, u, 3, NULL, y, NULL, &e), HY_EINVAL, &e, "time step h");
        o.b = NAN;
        expect(hy_boucwen_simulate(&p, &o, 1e-4, u, 3, NULL, y, NULL, &e), HY_EINVAL, &e, "constant b");
        hy_newmark_opts_default(&o);
        u[1] = NAN;
        expect(hy_boucwen_simulate(&p, &o, 1e-4, u, 3, NULL, y, NULL, &e), HY_EINVAL, &e, "u[1]");
    }
    {   /* no convergence: one Newton iteration cannot meet tol on a nonlinear
         * step; the message gives the time and the residuals, y stays finite */
        hy_boucwen_params p;
        hy_newmark_opts o;
        hy_error e;
        double u[4] = {0, 100, 200, 300}, y[4] = {0, 0, 0, 0};
        hy_boucwen_params_default(&p);
        hy_newmark_opts_default(&o);
        o.max_iter = 1;
        expect(hy_boucwen_simulate(&p, &o, 1e-3, u, 4, NULL, y, NULL, &e), HY_ENUM, &e,
               "did not converge");
        CHECK(strstr(e.msg, "t = 0.00") && strstr(e.msg, "residuals"), "message '%s'", e.msg);
        for (int i = 0; i < 4; i++)
            CHECK(isfinite(y[i]), "y[%d] = %g", i, y[i]);
        hy_boucwen_state s, s0;
        hy_boucwen_state_init(&p, 0, 0, 0, 0, &s);
        s0 = s;
        CHECK(hy_boucwen_step(&p, &o, 1e-3, 100, &s, &e) == HY_ENUM, "step converged");
        CHECK(memcmp(&s, &s0, sizeof s) == 0, "failed step changed the state");
    }
    {   /* ν = 2.5 with Table 1's γ + δ < 0: ż ~ 0.3 β |ẏ| |z|^ν grows without
         * bound in finite time; the integrator must say so, not return NaN */
        hy_boucwen_params p;
        hy_newmark_opts o;
        hy_error e = {0, ""};
        hy_boucwen_params_default(&p);
        hy_newmark_opts_default(&o);
        p.nu = 2.5;
        size_t n = 15000;
        double *u = malloc(n * sizeof *u), *y = malloc(n * sizeof *y);
        hy_sine_fill(120, 1, 15000, u, n, &e);
        int rc = hy_boucwen_simulate(&p, &o, 1.0 / 15000, u, n, NULL, y, NULL, &e);
        CHECK(rc == HY_ENUM, "blow-up not reported (status %d)", rc);
        CHECK(strstr(e.msg, "t = ") && strstr(e.msg, "did not converge"), "message '%s'", e.msg);
        free(u);
        free(y);
    }
    bad_file("", "no samples");
    bad_file("# only a comment\n\n", "no samples");
    bad_file("1.0\nabc\n", ":2:");
    bad_file("1.0\n2.0 junk\n", ":2:");
    bad_file("0,1\n0.1,2\n0.2\n", ":3: 1 column(s)");
    bad_file("0,1\n0.1,2\n0.25,3\n", ":3: time");
    bad_file("0,1\n0,2\n", ":2: time");
    bad_file("1,2,3\n", ":1:");
    bad_file("1e999\n", ":1:");
    {
        hy_error e;
        double *u = NULL, fs;
        size_t n;
        expect(hy_signal_read("/nonexistent/u.txt", &u, &n, &fs, &e), HY_EIO, &e, "/nonexistent/u.txt: cannot open");
    }
    return hy_test_finish("test_refuse");
}
