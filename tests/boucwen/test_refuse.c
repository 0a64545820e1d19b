/* test_refuse.c: invalid parameters, Newmark settings and input files are
 * refused with a message that names the parameter or file:line; a step that
 * cannot converge reports time and residual instead of returning NaN. */
#include "bw_test.h"
#include "hy_boucwen.h"
#include "hy_signal.h"

#include <math.h>
#include <unistd.h>

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
    expect(hy_boucwen_simulate(&p, &(hy_newmark_opts){0.5, 0.25, 0.5, 1e-12, 50},
                               1e-4, u, 2, NULL, y, NULL, &e),
           HY_EINVAL, &e, needle);
}

static void bad_file(const char *text, const char *needle)
{
    char path[] = "/tmp/hy_bw_refuse_XXXXXX";
    int fd = mkstemp(path);
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

int main(void)
{
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
    return bw_failures ? 1 : 0;
}
