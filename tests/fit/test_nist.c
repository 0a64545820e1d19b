/* SPDX-License-Identifier: MIT */
/* test_nist.c: hy_fit against the NIST StRD nonlinear regression data sets
 * (https://www.itl.nist.gov/div898/strd/nls/nls_main.shtml): Misra1a (lower
 * difficulty), Thurber, MGH09, BoxBOD, Eckerle4 (higher), each from NIST's
 * start 1 and start 2.  The data, starts, certified estimates and certified
 * standard deviations below are typed in from NIST's .dat files; they are a
 * publication of the US government (NIST), in the public domain.
 *
 * Tolerances: the certified values are printed to 11 significant digits and
 * were computed in 128-bit arithmetic, so an estimate that agrees to 1e-6
 * relative is the same minimum (a different local minimum or a stalled
 * iteration differs in the 2nd-4th digit); the standard errors come from a
 * finite-difference Jacobian (central, step eps^(1/3): ~1e-10 relative
 * error) at an estimate good to ~1e-9, and depend on it to first order, so
 * 1e-4 relative leaves 5 orders of margin while still catching a wrong s^2
 * (n - p), a missing square root or a Jacobian in the wrong coordinates (all
 * are > 1e-2 off).  The RSS must match to 1e-8: at a minimum it is second
 * order in the estimate's error. */
#include "hy_fit.h"
#include "../core/tutil.h"

#include <gsl/gsl_errno.h>

typedef struct nist {
    const char *name;
    size_t n, p;
    const double *x, *y;
    double (*model)(const double *b, double x);
    double start[2][8], cert[8], se[8], rss;
} nist;

static double misra1a(const double *b, double x) { return b[0] * (1 - exp(-b[1] * x)); }
static double thurber(const double *b, double x)
{
    return (b[0] + b[1] * x + b[2] * x * x + b[3] * x * x * x) / (1 + b[4] * x + b[5] * x * x + b[6] * x * x * x);
}
static double mgh09(const double *b, double x) { return b[0] * (x * x + x * b[1]) / (x * x + x * b[2] + b[3]); }
static double boxbod(const double *b, double x) { return b[0] * (1 - exp(-b[1] * x)); }
static double eckerle4(const double *b, double x)
{
    return b[0] / b[1] * exp(-0.5 * ((x - b[2]) / b[1]) * ((x - b[2]) / b[1]));
}

static const double misra_x[] = {77.6, 114.9, 141.1, 190.8, 239.9, 289.0, 332.8,
                                 378.4, 434.8, 477.3, 536.8, 593.1, 689.1, 760.0};
static const double misra_y[] = {10.07, 14.73, 17.94, 23.93, 29.61, 35.18, 40.02,
                                 44.82, 50.76, 55.05, 61.01, 66.40, 75.47, 81.78};
static const double thurber_x[] = {-3.067, -2.981, -2.921, -2.912, -2.840, -2.797, -2.702, -2.699, -2.633, -2.481,
                                   -2.363, -2.322, -1.501, -1.460, -1.274, -1.212, -1.100, -1.046, -0.915, -0.714,
                                   -0.566, -0.545, -0.400, -0.309, -0.109, -0.103, 0.010,  0.119,  0.377,  0.790,
                                   0.963,  1.006,  1.115,  1.572,  1.841,  2.047,  2.200};
static const double thurber_y[] = {80.574,   84.248,   87.264,   87.195,   89.076,   89.608,   89.868,   90.101,
                                   92.405,   95.854,   100.696,  101.060,  401.672,  390.724,  567.534,  635.316,
                                   733.054,  759.087,  894.206,  990.785,  1090.109, 1080.914, 1122.643, 1178.351,
                                   1260.531, 1273.514, 1288.339, 1327.543, 1353.863, 1414.509, 1425.208, 1421.384,
                                   1442.962, 1464.350, 1468.705, 1447.894, 1457.628};
static const double mgh09_x[] = {4.0, 2.0, 1.0, 0.5, 0.25, 0.167, 0.125, 0.1, 0.0833, 0.0714, 0.0625};
static const double mgh09_y[] = {0.1957, 0.1947, 0.1735, 0.16, 0.0844, 0.0627, 0.0456, 0.0342, 0.0323, 0.0235, 0.0246};
static const double boxbod_x[] = {1, 2, 3, 5, 7, 10};
static const double boxbod_y[] = {109, 149, 149, 191, 213, 224};
static const double eck_x[] = {400.0, 405.0, 410.0, 415.0, 420.0, 425.0, 430.0, 435.0, 436.5, 438.0, 439.5, 441.0,
                               442.5, 444.0, 445.5, 447.0, 448.5, 450.0, 451.5, 453.0, 454.5, 456.0, 457.5, 459.0,
                               460.5, 462.0, 463.5, 465.0, 470.0, 475.0, 480.0, 485.0, 490.0, 495.0, 500.0};
static const double eck_y[] = {0.0001575, 0.0001699, 0.0002350, 0.0003102, 0.0004917, 0.0008710, 0.0017418,
                               0.0046400, 0.0065895, 0.0097302, 0.0149002, 0.0237310, 0.0401683, 0.0712559,
                               0.1264458, 0.2073413, 0.2902366, 0.3445623, 0.3698049, 0.3668534, 0.3106727,
                               0.2078154, 0.1164354, 0.0616764, 0.0337200, 0.0194023, 0.0117831, 0.0074357,
                               0.0022732, 0.0008800, 0.0004579, 0.0002345, 0.0001586, 0.0001143, 0.0000710};

static const nist sets[] = {
    {"Misra1a", 14, 2, misra_x, misra_y, misra1a, {{500, 1e-4}, {250, 5e-4}},
     {2.3894212918E+02, 5.5015643181E-04}, {2.7070075241E+00, 7.2668688436E-06}, 1.2455138894E-01},
    {"Thurber", 37, 7, thurber_x, thurber_y, thurber,
     {{1000, 1000, 400, 40, 0.7, 0.3, 0.03}, {1300, 1500, 500, 75, 1, 0.4, 0.05}},
     {1.2881396800E+03, 1.4910792535E+03, 5.8323836877E+02, 7.5416644291E+01, 9.6629502864E-01, 3.9797285797E-01,
      4.9727297349E-02},
     {4.6647963344E+00, 3.9571156086E+01, 2.8698696102E+01, 5.5675370270E+00, 3.1333340687E-02, 1.4984928198E-02,
      6.5842344623E-03},
     5.6427082397E+03},
    {"MGH09", 11, 4, mgh09_x, mgh09_y, mgh09, {{25, 39, 41.5, 39}, {0.25, 0.39, 0.415, 0.39}},
     {1.9280693458E-01, 1.9128232873E-01, 1.2305650693E-01, 1.3606233068E-01},
     {1.1435312227E-02, 1.9633220911E-01, 8.0842031232E-02, 9.0025542308E-02}, 3.0750560385E-04},
    {"BoxBOD", 6, 2, boxbod_x, boxbod_y, boxbod, {{1, 1}, {100, 0.75}}, {2.1380940889E+02, 5.4723748542E-01},
     {1.2354515176E+01, 1.0455993237E-01}, 1.1680088766E+03},
    {"Eckerle4", 35, 3, eck_x, eck_y, eckerle4, {{1, 10, 500}, {1.5, 5, 450}},
     {1.5543827178E+00, 4.0888321754E+00, 4.5154121844E+02}, {1.5408051163E-02, 4.6803020753E-02, 4.6800518816E-02},
     1.4635887487E-03},
};

static int resid(const double *b, double *r, void *ctx)
{
    const nist *d = ctx;
    for (size_t i = 0; i < d->n; i++)
        r[i] = d->model(b, d->x[i]) - d->y[i];
    return 0;
}

#define EST_TOL 1e-6
#define SE_TOL 1e-4
#define RSS_TOL 1e-8

static double rel(double a, double b) { return fabs(a - b) / fabs(b); }

static void run(const nist *d, int which, double *worst_est, double *worst_se)
{
    hy_fit_param prm[8];
    char names[8][24];
    for (size_t j = 0; j < d->p; j++) { /* NIST's problems are unbounded: the map is theta = u */
        snprintf(names[j], sizeof names[j], "b%zu", j + 1);
        prm[j] = (hy_fit_param){names[j], -INFINITY, INFINITY, HY_FIT_LINEAR};
    }
    hy_fit_problem pb = {d->n, d->p, prm, resid, (void *)d, d->start[which], d->y};
    hy_fit_opts o;
    hy_fit_opts_default(&o);
    o.max_iter = 1000;
    hy_fit_result res;
    hy_error err = {0};
    int rc = hy_fit_run(&pb, &o, &res, &err);
    CHECK(rc == 0, "%s start %d: %s", d->name, which + 1, err.msg);
    if (rc)
        return;
    double we = 0, ws = 0;
    for (size_t j = 0; j < d->p; j++) {
        we = fmax(we, rel(res.theta[j], d->cert[j]));
        ws = fmax(ws, rel(res.se[j], d->se[j]));
        CHECK(rel(res.theta[j], d->cert[j]) <= EST_TOL, "%s start %d: b%zu = %.12g, certified %.11g (rel %.2g)",
              d->name, which + 1, j + 1, res.theta[j], d->cert[j], rel(res.theta[j], d->cert[j]));
        CHECK(rel(res.se[j], d->se[j]) <= SE_TOL, "%s start %d: se(b%zu) = %.12g, certified %.11g (rel %.2g)",
              d->name, which + 1, j + 1, res.se[j], d->se[j], rel(res.se[j], d->se[j]));
        CHECK(res.unident[j] == 0, "%s: b%zu flagged %d", d->name, j + 1, res.unident[j]);
    }
    CHECK(rel(res.rss, d->rss) <= RSS_TOL, "%s start %d: RSS %.12g, certified %.11g", d->name, which + 1, res.rss,
          d->rss);
    CHECK(res.dof == d->n - d->p, "dof");
    printf("%-9s start %d: max rel error estimate %.2e, standard error %.2e; %zu iterations, %zu evaluations\n",
           d->name, which + 1, we, ws, res.iter, res.nevals);
    *worst_est = fmax(*worst_est, we);
    *worst_se = fmax(*worst_se, ws);
    hy_fit_result_free(&res);
}

int main(void)
{
    gsl_set_error_handler_off();
    double we = 0, ws = 0;
    for (size_t k = 0; k < sizeof sets / sizeof *sets; k++)
        for (int s = 0; s < 2; s++)
            run(&sets[k], s, &we, &ws);
    printf("NIST StRD, 5 sets x 2 starts: worst relative error %.2e (estimates), %.2e (standard errors)\n", we, ws);
    return tu_finish("fit-nist");
}
