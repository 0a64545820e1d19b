/* SPDX-License-Identifier: MIT */
/* test_scene.c: a scene's [model] fitted to measured data (scene_fit.c; issue
 * 32 item 2, docs/FIT.md "Fitting a scene"): synthetic truth for every model
 * the data path drives (Jiles-Atherton in both variants, Preisach, play, the
 * Bouc-Wen operator; Dahl and LuGre through t).  For each: data made by
 * hystviz itself at known parameters (hy_scene_run_model_at_data, written to
 * a CSV in the test's directory) plus Gaussian noise of a stated sigma, then
 * hystviz fit's engine from a start 20-30 % off:
 *  - with noise, for 3 fixed seeds: every free parameter within 3 standard
 *    errors of the truth (a correct SE puts 99.7 % of estimates there) and
 *    none flagged unidentifiable;
 *  - noise-free: every parameter within 1e-8 relative (the models are
 *    computed exactly or to an ODE tolerance of 1e-13, so the minimum is the
 *    truth to far better than 1e-8; the solver's xtol is 1e-12);
 *  - LuGre's sigma1 under a quasi-static input (its term sigma1 dz/dt is
 *    1e-7 of the force, the noise 5e-3): flagged unidentifiable, sigma0
 *    and Fc not.
 * And a legend label's {SERIES.rms}.  The CLI's refusals (bad keys, bad data: one line, exit 2, nothing
 * written) are tests/fit/test_scene_cli.sh. */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../core/tutil.h"
#include "../tmpdir.h"
#include "scene_fit.h"
#include "scene_run.h"

typedef struct fcase {
    const char *name;
    const char *model;              /* [model] lines at the truth, less the free keys */
    const char *keys[6];            /* the free keys, NULL-ended */
    double truth[6], start[6];      /* their true values and the perturbed start */
    double amp[3];                  /* record amplitudes (0 ends) */
    size_t npts;                    /* samples per record */
    double sigma;                   /* noise added to y */
    int timed;                      /* Dahl, LuGre: one record, a t column (1 s a sample) */
    double period;                  /* timed: the sine's period in samples */
    double t_scale;                 /* timed: seconds a sample ([data] t_scale; 0: 1) */
} fcase;

static const fcase cases[] = {
    {"ja1986", "kind = jiles-atherton\nja_variant = jiles1986\n", {"ja_ms", "ja_a", "ja_k", "ja_c", "ja_alpha", NULL},
     {1.6e6, 1100, 400, 0.2, 1.6e-3}, {1.3e6, 1400, 300, 0.26, 1.3e-3}, {4000, 1500, 0}, 60, 5e-3, 0, 0, 0},
    {"jtd1992", "kind = jiles-atherton\nja_variant = jtd1992\n", {"ja_ms", "ja_a", "ja_k", "ja_c", "ja_alpha", NULL},
     {1.6e6, 1100, 400, 0.5, 1.6e-3}, {1.3e6, 1400, 300, 0.65, 1.3e-3}, {4000, 1500, 0}, 60, 5e-3, 0, 0, 0},
    {"preisach", "kind = preisach\n", {"pr_hc", "pr_width", "pr_ys", NULL}, {0.5, 0.2, 1}, {0.6, 0.25, 0.8},
     {1.2, 0.6, 0}, 60, 5e-3, 0, 0, 0},
    {"play", "kind = play\n", {"play_r", NULL}, {0.3}, {0.22}, {1, 0.5, 0}, 40, 1e-2, 0, 0, 0},
    {"boucwen-operator", "kind = boucwen-operator\nbw_beta = 1\nnu = 1\n", {"alpha", "bw_gamma", "delta", NULL},
     {1, 0.6, 0.4}, {1.25, 0.75, 0.3}, {3, 1.5, 0}, 60, 5e-3, 0, 0, 0},
    {"dahl", "kind = dahl\n", {"rho", "fc", NULL}, {2, 1}, {2.5, 0.8}, {3}, 200, 5e-3, 1, 100, 0},
    {"lugre", "kind = lugre\nsigma1 = 1\nsigma2 = 0.1\nbeta = 2\n", {"sigma0", "fc", "fs", "vs", NULL},
     {6, 1, 2, 0.05}, {7.5, 0.8, 2.4, 0.06}, {3}, 200, 5e-3, 1, 100, 0},
};

/* A fixed-seed Gaussian (xorshift64* and Box-Muller): the same noise on every machine. */
static double gauss(uint64_t *s)
{
    double u[2];
    for (int i = 0; i < 2; i++) {
        *s ^= *s >> 12, *s ^= *s << 25, *s ^= *s >> 27;
        u[i] = ((double)((*s * 2685821657736338717ull) >> 11) + 0.5) / 9007199254740992.0;
    }
    return sqrt(-2 * log(u[0])) * cos(2 * M_PI * u[1]);
}

/* The input of record k, sample i: a triangle 0 -> +A -> -A -> +A (rate-independent
 * models), or A sin(2 pi t / period) (timed). */
static double input(const fcase *c, size_t k, size_t i)
{
    double A = c->amp[k], x = (double)i / (double)(c->npts - 1);
    if (c->timed)
        return A * sin(2 * M_PI * (double)i / c->period);
    double ph = 4 * x; /* +A at x = 0 is the tip, as a measured loop starts */
    return ph < 2 ? A * (1 - ph) : A * (ph - 3);
}

static size_t nrec(const fcase *c)
{
    size_t n = 0;
    while (n < 3 && c->amp[n] > 0)
        n++;
    return n;
}

/* The data file name (y given: ny values) and the scene over it, with the
 * free keys at vals. */
static void write_case(const fcase *c, const double *y, const double *vals, const char *tag, char *scene, size_t size)
{
    char csv[4200], name[128];
    snprintf(name, sizeof name, "%s_%s.csv", c->name, tag);
    test_tmppath(csv, sizeof csv, name);
    FILE *f = fopen(csv, "w");
    fprintf(f, "rec,t,u,y\n");
    for (size_t k = 0, j = 0; k < nrec(c); k++)
        for (size_t i = 0; i < c->npts; i++, j++)
            fprintf(f, "%zu,%zu,%.17g,%.17g\n", k + 1, i, input(c, k, i), y ? y[j] : 0.0);
    fclose(f);
    snprintf(name, sizeof name, "%s_%s.scene", c->name, tag);
    test_tmppath(scene, size, name);
    f = fopen(scene, "w");
    fprintf(f, "[model]\n%s", c->model);
    for (size_t j = 0; c->keys[j]; j++)
        fprintf(f, "%s = %.17g\n", c->keys[j], vals[j]);
    fprintf(f, "[data d]\nfile = \"%s_%s.csv\"\nu = u\ny = y\n%s\nt_scale = %.17g\n[input]\nkind = data\ndata = d\n"
               "[figure]\nkind = %s\n[series m]\ndata = modelled\nof = d\n",
            c->name, tag, c->timed ? "t = t" : "split = rec", c->t_scale > 0 ? c->t_scale : 1.0,
            c->timed ? "timeseries" : "loop");
    fclose(f);
}

/* The model's output at the truth (n values, malloc'd). */
static double *truth_output(const fcase *c, size_t *n)
{
    char scene[4200];
    write_case(c, NULL, c->truth, "in", scene, sizeof scene);
    hy_scene_run r;
    hy_error err = {0};
    int rc = hy_scene_run_load(&r, scene, NULL, 0, &err);
    CHECK(rc == 0, "%s: load: %s", c->name, err.msg);
    if (rc)
        return NULL;
    hy_data_view v;
    hy_scene_run_driving(&r, &v, &err);
    *n = v.n;
    double *y = malloc(v.n * sizeof *y);
    rc = hy_scene_run_model_at_data(&r, y, &err);
    CHECK(rc == 0, "%s: the model at the data: %s", c->name, err.msg);
    hy_scene_run_free(&r);
    return y;
}

/* Fits the case to its truth plus noise of the seed (seed 0: none). */
static void fit_case(const fcase *c, const double *y0, size_t n, uint64_t seed)
{
    double *y = malloc(n * sizeof *y);
    uint64_t s = 0x9e3779b97f4a7c15ull ^ (seed * 0x2545f4914f6cdd1dull);
    for (size_t i = 0; i < n; i++)
        y[i] = y0[i] + (seed ? c->sigma * gauss(&s) : 0);
    char scene[4200], tag[32];
    snprintf(tag, sizeof tag, "s%llu", (unsigned long long)seed);
    write_case(c, y, c->start, tag, scene, sizeof scene);
    free(y);
    size_t p = 0;
    while (c->keys[p])
        p++;
    hy_scene_fit_opts o;
    hy_scene_fit_opts_default(&o);
    o.free_keys = c->keys;
    o.nfree = p;
    hy_scene_fit f;
    hy_error err = {0};
    int rc = hy_scene_fit_run(scene, &o, &f, &err);
    CHECK(rc == 0, "%s seed %llu: %s", c->name, (unsigned long long)seed, err.msg);
    if (rc)
        return;
    double worst = 0;
    for (size_t j = 0; j < p; j++) {
        double e = f.res.theta[j] - c->truth[j];
        if (seed) {
            CHECK(fabs(e) <= 3 * f.res.se[j] && !f.res.unident[j], "%s seed %llu: %s = %.10g, truth %g, SE %.3g (%.2f SE), flags %d",
                  c->name, (unsigned long long)seed, c->keys[j], f.res.theta[j], c->truth[j], f.res.se[j],
                  e / f.res.se[j], f.res.unident[j]);
            worst = fmax(worst, fabs(e) / f.res.se[j]);
        } else {
            CHECK(fabs(e) <= 1e-8 * fabs(c->truth[j]), "%s noise-free: %s = %.17g, truth %g (%.2e relative)", c->name,
                  c->keys[j], f.res.theta[j], c->truth[j], e / c->truth[j]);
            worst = fmax(worst, fabs(e / c->truth[j]));
        }
    }
    printf("%-16s %-5s %s %.3g, RMS %.3g, %zu iterations, %zu evaluations, %.2f s\n", c->name,
           seed ? tag : "exact", seed ? "worst |error|/SE" : "worst relative error", worst, f.res.rms, f.res.iter,
           f.res.nevals, f.res.seconds);
    hy_scene_fit_free(&f);
}

/* LuGre's sigma1 under a quasi-static input: flagged. */
static void lugre_sigma1(void)
{
    fcase c = cases[6];
    c.model = "kind = lugre\nsigma2 = 0.1\nbeta = 2\nfc = 1\nvs = 0.05\n";
    /* Fs, not Fc: at |v| <= 2e-7 << vs the sliding force g(v) is Fs, Fc is not seen either */
    c.keys[0] = "sigma0", c.keys[1] = "sigma1", c.keys[2] = "fs", c.keys[3] = NULL;
    c.truth[0] = 6, c.truth[1] = 1, c.truth[2] = 2;
    c.start[0] = 7, c.start[1] = 1.2, c.start[2] = 1.8;
    c.t_scale = 1e6; /* a sample a million seconds: |dz/dt| <= |du/dt| ~ 2e-7, so sigma1 dz/dt
                        (1e-7 of the force) is lost under the noise of 5e-3 */
    size_t n = 0;
    double *y0 = truth_output(&c, &n);
    if (!y0)
        return;
    uint64_t s = 7;
    for (size_t i = 0; i < n; i++)
        y0[i] += c.sigma * gauss(&s);
    char scene[4200];
    write_case(&c, y0, c.start, "s1", scene, sizeof scene);
    free(y0);
    hy_scene_fit_opts o;
    hy_scene_fit_opts_default(&o);
    o.free_keys = c.keys;
    o.nfree = 3;
    hy_scene_fit f;
    hy_error err = {0};
    int rc = hy_scene_fit_run(scene, &o, &f, &err);
    CHECK(rc == 0, "lugre sigma1: %s", err.msg);
    if (rc)
        return;
    CHECK(f.res.unident[1] != 0, "lugre quasi-static: sigma1 not flagged (SE %g, flags %d)", f.res.se[1], f.res.unident[1]);
    CHECK(!f.res.unident[0] && !f.res.unident[2], "lugre quasi-static: sigma0 %d, Fs %d flagged", f.res.unident[0],
          f.res.unident[2]);
    printf("lugre quasi-static: sigma1 flagged %d (relative singular value %.3g, rank tolerance %.3g)\n", f.res.unident[1],
           f.res.sv[2] / f.res.sv[0], f.res.rank_tol);
    hy_scene_fit_free(&f);
}

/* A legend label's {SERIES.rms} is the run's RMS of that modelled series
 * (expanded by the annotations' placeholder code), a {section.key} beside it
 * still the key's value. */
static void label_rms(void)
{
    const fcase *c = &cases[3]; /* play */
    size_t n = 0;
    double *y0 = truth_output(c, &n);
    if (!y0)
        return;
    for (size_t i = 0; i < n; i++)
        y0[i] += 0.01 * sin(7.0 * (double)i); /* a residual of known RMS */
    char scene[4200];
    write_case(c, y0, c->truth, "lab", scene, sizeof scene);
    FILE *f = fopen(scene, "a");
    fprintf(f, "label = \"r = {model.play_r}, RMS {m.rms}\"\n");
    fclose(f);
    hy_scene_run r;
    hy_error err = {0};
    int rc = hy_scene_run_load(&r, scene, NULL, 0, &err);
    if (!rc && (rc = hy_scene_run_compute(&r, NULL, &err)))
        hy_scene_run_free(&r);
    CHECK(rc == 0, "label scene: %s", err.msg);
    if (rc) {
        free(y0);
        return;
    }
    double ss = 0;
    for (size_t i = 0; i < n; i++)
        ss += 0.01 * sin(7.0 * (double)i) * 0.01 * sin(7.0 * (double)i);
    hy_scene_fig st;
    memset(&st, 0, sizeof st);
    rc = hy_scene_run_figure(&r, &st, &err);
    const char *lab = rc ? NULL : st.series[0].label;
    double rms = NAN;
    CHECK(lab && sscanf(lab, "r = 0.3, RMS %lf", &rms) == 1 && !strchr(lab, '{') &&
              fabs(rms / sqrt(ss / (double)n) - 1) < 5e-4, /* 4 significant digits printed */
          "label '%s': RMS %g, want %g", lab ? lab : "(none)", rms, sqrt(ss / (double)n));
    hy_scene_fig_free(&st);
    hy_scene_run_free(&r);
    free(y0);
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    const char *only = argc > 1 ? argv[1] : NULL;
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        const fcase *c = &cases[k];
        if (only && strcmp(only, c->name))
            continue;
        size_t n = 0;
        double *y0 = truth_output(c, &n);
        if (!y0)
            continue;
        fit_case(c, y0, n, 0);
        for (uint64_t seed = 1; seed <= 3; seed++)
            fit_case(c, y0, n, seed);
        free(y0);
    }
    if (!only || !strcmp(only, "lugre-sigma1"))
        lugre_sigma1();
    if (!only || !strcmp(only, "label"))
        label_rms();
    return tu_finish("fit-scene");
}
