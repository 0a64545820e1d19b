/* SPDX-License-Identifier: MIT */
/* bench_forc: time and memory of the FORC distribution (issue 33, figures):
 * the measured 120-curve MicroMag file at SF = 3 (read, regression alone,
 * median of 21 runs, wall and CPU), variable smoothing, and a 400-curve
 * Preisach protocol (the protocol once, its regression), and the
 * least-squares Preisach density of the measured file (hy_preisach_table_fit,
 * median of 5).  Prints; asserts nothing.  argv[1]: tests/data/forc/conventional_example.forc. */
#include <gsl/gsl_errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <time.h>

#include "hy_file.h"
#include "hy_forc.h"
#include "hy_preisach_table.h"

static double clk(clockid_t c)
{
    struct timespec t;
    clock_gettime(c, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

enum { REPS = 21 };

/* Median wall and CPU ms of REPS regressions with o on d's auto grid. */
static void time_rho(const char *what, const hy_forc_data *d, const hy_forc_opts *o)
{
    double w[REPS], c[REPS];
    hy_forc_grid g;
    size_t nfit = 0;
    hy_error err;
    for (int r = 0; r < REPS; r++) {
        hy_forc_grid_auto(d, o, &g);
        double w0 = clk(CLOCK_MONOTONIC), c0 = clk(CLOCK_PROCESS_CPUTIME_ID);
        if (hy_forc_rho(d, o, &g, &nfit, &err)) {
            fprintf(stderr, "%s: %s\n", what, err.msg);
            exit(1);
        }
        w[r] = 1e3 * (clk(CLOCK_MONOTONIC) - w0);
        c[r] = 1e3 * (clk(CLOCK_PROCESS_CPUTIME_ID) - c0);
        hy_forc_grid_free(&g);
    }
    qsort(w, REPS, sizeof *w, cmp);
    qsort(c, REPS, sizeof *c, cmp);
    printf("%-44s %8.2f ms wall %8.2f ms CPU  (%zu x %zu nodes, %zu fitted; median of %d)\n", what, w[REPS / 2],
           c[REPS / 2], g.nc, g.nu, nfit, REPS);
}

/* Median wall and CPU ms of 5 least-squares densities of d (SF = 3's grid). */
static void time_fit(const hy_forc_data *d)
{
    enum { FREPS = 5 };
    double w[FREPS], c[FREPS];
    hy_forc_opts o = hy_forc_defaults();
    hy_forc_grid g;
    hy_error err;
    hy_forc_grid_auto(d, &o, &g);
    size_t nc, nu;
    hy_preisach_table_fit_shape(&g, &nc, &nu);
    hy_preisach_table_fitres res = {0};
    for (int r = 0; r < FREPS; r++) {
        double w0 = clk(CLOCK_MONOTONIC), c0 = clk(CLOCK_PROCESS_CPUTIME_ID);
        if (hy_preisach_table_fit(d, &g, nc, nu, &res, &err)) {
            fprintf(stderr, "fit: %s\n", err.msg);
            exit(1);
        }
        w[r] = 1e3 * (clk(CLOCK_MONOTONIC) - w0);
        c[r] = 1e3 * (clk(CLOCK_PROCESS_CPUTIME_ID) - c0);
        free(res.g.rho);
    }
    qsort(w, FREPS, sizeof *w, cmp);
    qsort(c, FREPS, sizeof *c, cmp);
    printf("%-44s %8.2f ms wall %8.2f ms CPU  (%zu x %zu nodes, %zu free, %zu sweeps, RMS %.4g; median of %d)\n",
           "measured file, least-squares Preisach density", w[FREPS / 2], c[FREPS / 2], nc, nu, res.nfree, res.iters,
           res.rms, FREPS);
    hy_forc_grid_free(&g);
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    if (argc < 2) {
        fprintf(stderr, "usage: bench_forc FILE.forc\n");
        return 2;
    }
    char *text, why[160];
    size_t len;
    if (hy_file_read(argv[1], 1u << 26, &text, &len, NULL, why, sizeof why)) {
        fprintf(stderr, "%s: %s\n", argv[1], why);
        return 1;
    }
    hy_forc_data d;
    hy_error err;
    double w[REPS];
    for (int r = 0; r < REPS; r++) {
        double w0 = clk(CLOCK_MONOTONIC);
        if (hy_forc_read(&d, text, len, argv[1], &err)) {
            fprintf(stderr, "%s\n", err.msg);
            return 1;
        }
        w[r] = 1e3 * (clk(CLOCK_MONOTONIC) - w0);
        if (r + 1 < REPS)
            hy_forc_data_free(&d);
    }
    qsort(w, REPS, sizeof *w, cmp);
    printf("%-44s %8.2f ms wall  (%zu curves, %zu points, %zu bytes of text)\n", "read MicroMag file", w[REPS / 2],
           d.ncurves, d.npoints, len);
    hy_forc_opts o = hy_forc_defaults();
    time_rho("measured file, SF = 3", &d, &o);
    o.sf = 5;
    time_rho("measured file, SF = 5", &d, &o);
    o.sc0 = 2, o.sc1 = 7;
    time_rho("measured file, SF 2 -> 7 (sc0, sc1)", &d, &o);
    time_fit(&d);
    hy_forc_data_free(&d);
    free(text);

    hy_preisach p;
    if (hy_preisach_symmetric(&p, HY_PREISACH_GAUSSIAN, 0.3, 0.1, 1.0, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    hy_forc_protocol pr = {.hsat = 1.5, .ha_lo = -0.7, .ha_hi = 0.7, .hb_max = 0.7, .ncurves = 400};
    double w0 = clk(CLOCK_MONOTONIC), c0 = clk(CLOCK_PROCESS_CPUTIME_ID);
    if (hy_forc_preisach(&d, &pr, &p, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    printf("%-44s %8.2f ms wall %8.2f ms CPU  (%zu curves, %zu points)\n", "Preisach protocol, 400 curves",
           1e3 * (clk(CLOCK_MONOTONIC) - w0), 1e3 * (clk(CLOCK_PROCESS_CPUTIME_ID) - c0), d.ncurves, d.npoints);
    o = hy_forc_defaults();
    time_rho("Preisach 400 curves, SF = 3", &d, &o);
    hy_forc_data_free(&d);
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    printf("%-44s %8ld kB\n", "peak resident memory (whole benchmark)", ru.ru_maxrss);
    return 0;
}
