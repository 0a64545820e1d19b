/* SPDX-License-Identifier: MIT */
/* test_input.c: inputs, the variation ρ_u (Eq. 5) against quadrature of |u̇|,
 * ψ_u(ρ_u(t)) = u(t) (Eq. 9), ψ_u's slopes ±1 (Eq. 10), file inputs. */
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <stdlib.h>
#include <unistd.h>

#include "hy_input.h"
#include "tutil.h"
#include "../tmpdir.h"

static double absdu(double t, void *p) { return fabs(hy_input_du(p, t)); }

static void check_input(const char *name, hy_input *in, gsl_integration_workspace *w)
{
    gsl_function F = {absdu, in};
    for (int j = 0; j <= 200; j++) {
        double t = 2.5 * in->period * j / 200.0;
        /* ρ_u by quadrature, piece by piece over 2.5 periods (QAG 1e-12) */
        double rq = 0;
        for (int cyc = 0; cyc < 3; cyc++)
            for (size_t i = 0; i < in->npieces; i++) {
                double lo = cyc * in->period + in->pieces[i].t0, hi = fmin(t, cyc * in->period + in->pieces[i].t1);
                if (hi <= lo)
                    continue;
                double r, e;
                gsl_integration_qag(&F, lo, hi, 0, 1e-12, 1000, GSL_INTEG_GAUSS41, w, &r, &e);
                rq += r;
            }
        double r = hy_input_rho(in, t);
        CHECK(fabs(r - rq) <= 1e-10 * (1 + rq), "%s: ρ(%g) = %.17g vs quadrature %.17g", name, t, r, rq);
        /* Eq. 9: ψ_u(ρ_u(t)) = u(t) */
        CHECK_CLOSE(hy_input_psi(in, r), hy_input_u(in, t), 1e-12 * (1 + fabs(hy_input_u(in, t))), name);
    }
    /* Eq. 10: slopes of ψ are ±1 away from the extrema */
    for (size_t i = 0; i < in->nruns; i++) {
        const hy_run *run = &in->runs[i];
        double a = run->rho0 + 0.25 * (run->rho1 - run->rho0), b = run->rho0 + 0.75 * (run->rho1 - run->rho0);
        double slope = (hy_input_psi(in, b) - hy_input_psi(in, a)) / (b - a);
        CHECK(fabs(slope - run->sign) < 1e-12, "%s: ψ slope %.17g on run %zu", name, slope, i);
    }
}

int main(void)
{
    gsl_set_error_handler_off();
    gsl_integration_workspace *w = gsl_integration_workspace_alloc(1000);
    hy_input in;
    hy_error err;
    const char *specs[] = {"bimodal:0,0.2,1,1.5", "bimodal:0,0.5,1,1.5,0.3,1.1,2.5,4:cosine", "triangle:0,1,2",
                           "sine:1,1", "sine:2,3,0.5", "multimodal:0,3,1,2.8,1.5,2", "multimodal:-1,1,0,0.5:cosine",
                           "pwl:0,0,1,1,1.5,1,2,0.3,3,0"};
    for (size_t k = 0; k < sizeof specs / sizeof *specs; k++) {
        int rc = hy_input_parse(&in, specs[k], &err);
        CHECK(rc == HY_OK, "%s: %s", specs[k], err.msg);
        if (!rc) {
            check_input(specs[k], &in, w);
            hy_input_free(&in);
        }
    }
    /* Example 3: ϱ1..ϱ4 = 1, 1.8, 3.1, 4.6 (Section 4.3) */
    hy_input_parse(&in, "bimodal:0,0.2,1,1.5", &err);
    CHECK(in.nruns == 4 && in.runs[0].rho1 == 1 && fabs(in.runs[1].rho1 - 1.8) < 1e-15 && fabs(in.runs[2].rho1 - 3.1) < 1e-15 &&
              fabs(in.rho_T - 4.6) < 1e-15,
          "example 3 ϱ's");
    hy_input_free(&in);
    /* a smooth bimodal has ψ_u != u but the same ρ at the extrema */
    hy_input_parse(&in, "bimodal:0,0.2,1,1.5,1,3,4,6:cosine", &err);
    double t = 0.25, u = hy_input_u(&in, t);
    CHECK(fabs(u - t) > 0.1 && fabs(hy_input_psi(&in, hy_input_rho(&in, t)) - u) < 1e-14, "ψ_u differs from u");
    hy_input_free(&in);
    /* a sampled file: written here, read back, closed to u(0) */
    char path[4200];
    int fd = mkstemp(test_tmppath(path, sizeof path, "input_XXXXXX"));
    FILE *f = fdopen(fd, "w");
    fprintf(f, "# t u\n0 0\n0.5, 1\n1 0.25\n1.5 0.8\n");
    fclose(f);
    int rc = hy_input_file(&in, path, &err);
    CHECK(rc == HY_OK, "file input: %s", err.msg);
    if (!rc) {
        CHECK(in.npieces == 4 && hy_input_u(&in, in.period) == 0, "file input closed back to u(0)");
        check_input("file", &in, w);
        hy_input_free(&in);
    }
    remove(path);
    gsl_integration_workspace_free(w);
    return tu_finish("input");
}
