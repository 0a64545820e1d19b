/* SPDX-License-Identifier: MIT */
/* test_scenes.c: the Bouc-Wen scenes through the scene pipeline (what `hystviz
 * data` prints): Fig. 1(b) against the linear oscillator's exact steady state,
 * the decay of Fig. 2(b)'s transient, and malformed scenes refused at
 * file:line:col. */
#include "bw_test.h"
#include "hy_signal.h"
#include "scene_run.h"

#include <complex.h>
#include <math.h>
#include <unistd.h>
#include "../tmpdir.h"

#define SCENES HY_SOURCE_DIR "/scenes/"

/* One series of a `hystviz data` CSV. */
typedef struct col {
    double *x, *y;
    size_t n;
} col;

/* Loads and computes path with the overrides, then prints it with
 * hy_scene_run_data (the `hystviz data` output) and reads back series name. */
static int data_of(const char *path, const char *const *sets, size_t nsets, const char *name, col *c)
{
    hy_scene_run r;
    hy_error err;
    memset(c, 0, sizeof *c);
    if (hy_scene_run_load(&r, path, (char *const *)sets, nsets, &err) ||
        (hy_scene_run_compute(&r, NULL, &err) && (hy_scene_run_free(&r), 1))) {
        fprintf(stderr, "%s: %s\n", path, err.msg);
        return -1;
    }
    FILE *f = tmpfile();
    int rc = f ? hy_scene_run_data(&r, f, &err) : -1;
    hy_scene_run_free(&r);
    if (rc) {
        if (f)
            fclose(f);
        return -1;
    }
    rewind(f);
    char line[256], want[64];
    snprintf(want, sizeof want, "%s,", name);
    size_t cap = 0;
    while (fgets(line, sizeof line, f)) {
        if (strncmp(line, want, strlen(want)))
            continue;
        if (c->n == cap) {
            cap = cap ? 2 * cap : 1024;
            c->x = realloc(c->x, cap * sizeof *c->x);
            c->y = realloc(c->y, cap * sizeof *c->y);
        }
        if (sscanf(line + strlen(want), "%lf,%lf", &c->x[c->n], &c->y[c->n]) == 2)
            c->n++;
    }
    fclose(f);
    return c->n ? 0 : -1;
}

static void col_free(col *c)
{
    free(c->x);
    free(c->y);
}

/* Gain of MATLAB decimate's zero-phase fir1(30, 1/q) at f Hz, sampling rate fs. */
static double fir_gain(size_t q, double f, double fs)
{
    double b[HY_DECIMATE_TAPS], g = 0;
    hy_fir1_lowpass(q, b);
    for (int i = 0; i < HY_DECIMATE_TAPS; i++)
        g += b[i] * cos(2 * M_PI * f / fs * (double)(i - HY_DECIMATE_TAPS / 2));
    return g;
}

/* Fig. 1(b): bw_beta = 0 makes z = alpha y, a linear oscillator of stiffness
 * K = k + alpha, whose steady state to 120 sin(2 pi t) is Im(120 H e^{i w t}),
 * H = 1 / (K - m w^2 + i c w).  Newmark (a 1/2, b 1/4) is the trapezoidal
 * rule, so its discrete steady state is exactly H at the warped frequency
 * w' = (2/h) tan(w h / 2) = w (1 + (w h)^2 / 12 + ...): an O(h^2) error of
 * size (w h)^2 / 12 |w H'(w)| A.  Decimation multiplies by the FIR gains. */
static void test_linear(void)
{
    const double m = 2, c = 10, K = 1e5, A = 120, w = 2 * M_PI, h = 1.0 / 15000;
    double complex H = 1 / (K - m * w * w + I * c * w);
    double complex dH = -(I * c - 2 * m * w) * H * H; /* dH/dw */
    double wp = 2 / h * tan(w * h / 2);
    double complex Hp = 1 / (K - m * wp * wp + I * c * wp);
    double newmark_bound = 2 * (w * h) * (w * h) / 12 * w * cabs(dH) * A * 1e3; /* mm, factor 2 margin */
    double settle_bound = 1e-9 * cabs(H) * A * 1e3; /* e^{-zeta w0 20 s} = 2e-22, far below */

    /* undecimated: every 15 kHz Newmark sample against the exact answers */
    const char *raw[] = {"figure.kind=timeseries", "compute.decimate=none"};
    col y;
    CHECK(data_of(SCENES "bw_fig1b_linear_loop.scene", raw, 2, "y", &y) == 0, "data of fig1b");
    CHECK(y.n == 10 * 15000, "%zu samples at 15 kHz over 10 cycles", y.n);
    double e_exact = 0, e_warp = 0;
    for (size_t i = 0; i < y.n; i++) {
        double ye = 1e3 * cimag(A * H * cexp(I * w * y.x[i]));
        double yw = 1e3 * cimag(A * Hp * cexp(I * w * y.x[i]));
        e_exact = fmax(e_exact, fabs(y.y[i] - ye));
        e_warp = fmax(e_warp, fabs(y.y[i] - yw));
    }
    fprintf(stderr, "fig1b raw: max error %.3g mm vs exact (O(h^2) bound %.3g), %.3g vs warped\n", e_exact,
            newmark_bound, e_warp);
    CHECK(e_exact <= newmark_bound + settle_bound, "error %.3g mm > O(h^2) bound %.3g", e_exact, newmark_bound);
    CHECK(e_warp <= 1e-12 * cabs(H) * A * 1e3 + settle_bound, "error %.3g mm vs the trapezoidal steady state",
          e_warp);
    col_free(&y);

    /* as the scene is: decimated to 750 Hz in stages 2, 2, 5 */
    const char *ts[] = {"figure.kind=timeseries"};
    CHECK(data_of(SCENES "bw_fig1b_linear_loop.scene", ts, 1, "y", &y) == 0, "data of fig1b");
    CHECK(y.n == 10 * 750, "%zu samples at 750 Hz", y.n);
    double g = fir_gain(2, 1, 15000) * fir_gain(2, 1, 7500) * fir_gain(5, 1, 3750);
    double fir_bound = fabs(1 - g) * cabs(H) * A * 1e3;
    e_exact = e_warp = 0;
    for (size_t i = 0; i < y.n; i++) {
        double ye = 1e3 * cimag(A * H * cexp(I * w * y.x[i]));
        double yw = 1e3 * cimag(g * A * Hp * cexp(I * w * y.x[i]));
        e_exact = fmax(e_exact, fabs(y.y[i] - ye));
        e_warp = fmax(e_warp, fabs(y.y[i] - yw));
    }
    fprintf(stderr, "fig1b 750 Hz: max error %.3g mm vs exact (bound %.3g = O(h^2) + FIR gain %.3g), %.3g vs model\n",
            e_exact, newmark_bound + fir_bound, 1 - g, e_warp);
    CHECK(e_exact <= newmark_bound + fir_bound + settle_bound, "error %.3g mm", e_exact);
    CHECK(e_warp <= 1e-11 * cabs(H) * A * 1e3, "error %.3g mm vs FIR x trapezoidal", e_warp);
    col_free(&y);

    /* the loop itself: x = u = 120 sin(2 pi t) */
    CHECK(data_of(SCENES "bw_fig1b_linear_loop.scene", NULL, 0, "y", &y) == 0, "data of fig1b");
    double e_u = 0;
    for (size_t i = 0; i < y.n; i++)
        e_u = fmax(e_u, fabs(y.x[i] - A * sin(w * (20 + (double)i / 750))));
    CHECK(e_u < 1e-9, "loop x differs from u by %.3g N", e_u);
    col_free(&y);

    /* the spectrum of the last period: the 1 Hz line is |g H'| A */
    const char *sp[] = {"figure.kind=timeseries", "series.y.quantity=spectrum"};
    CHECK(data_of(SCENES "bw_fig1b_linear_loop.scene", sp, 2, "y", &y) == 0, "spectrum of fig1b");
    CHECK(y.n == 376 && fabs(y.x[1] - 1) < 1e-12, "%zu lines, line 1 at %g Hz", y.n, y.n > 1 ? y.x[1] : NAN);
    if (y.n > 2)
        CHECK(fabs(y.y[1] - 20 * log10(g * cabs(Hp) * A * 1e3)) < 1e-9 && y.y[2] < y.y[1] - 200,
              "1 Hz line %.12g dB, 2 Hz line %.3g dB", y.y[1], y.y[2]);
    col_free(&y);
}

/* Fig. 2(b): from the second period on, the transient is below 1e-12 of the
 * output's largest value in the last period (-240 dB), while it starts near
 * the output's level. */
static void test_transient(void)
{
    col out, tr;
    const char *deep[] = {"series.transient.floor=-1000"}; /* the scene's -340 dB floor out of the way */
    CHECK(data_of(SCENES "bw_fig2b_transient_db.scene", NULL, 0, "output", &out) == 0, "output of fig2b");
    CHECK(data_of(SCENES "bw_fig2b_transient_db.scene", deep, 1, "transient", &tr) == 0, "transient of fig2b");
    const size_t N = 8192;
    CHECK(out.n == 5 * N && tr.n == 4 * N, "%zu output and %zu transient samples", out.n, tr.n);
    if (out.n != 5 * N || tr.n != 4 * N)
        return;
    double top = -INFINITY, late = -INFINITY, early = -INFINITY;
    for (size_t i = 4 * N; i < 5 * N; i++)
        top = fmax(top, out.y[i]);
    for (size_t i = 0; i < N; i++)
        early = fmax(early, tr.y[i]);
    for (size_t i = N; i < 4 * N; i++)
        late = fmax(late, isnan(tr.y[i]) ? -INFINITY : tr.y[i]);
    fprintf(stderr, "fig2b: output peak %.1f dB, transient %.1f dB in period 1, %.1f dB after\n", top, early, late);
    CHECK(top > -20 && top < 20, "output peak %.3g dB re 1 mm", top);
    CHECK(early > top - 40, "the transient starts at %.3g dB", early);
    CHECK(late < top - 240, "transient %.3g dB after the first period, output %.3g dB", late, top);
    col_free(&out);
    col_free(&tr);
}

/* [compute] noise: the output moves by noise of exactly that RMS (in mm). */
static void test_noise(void)
{
    col a, b;
    const char *noisy[] = {"compute.noise=8e-3"};
    CHECK(data_of(SCENES "bw_fig2a_output_periods.scene", NULL, 0, "y", &a) == 0, "fig2a");
    CHECK(data_of(SCENES "bw_fig2a_output_periods.scene", noisy, 1, "y", &b) == 0, "fig2a with noise");
    CHECK(a.n == b.n && a.n == 5 * 8192, "%zu and %zu samples", a.n, b.n);
    if (a.n == b.n && a.n)
        CHECK(fabs(hy_signal_erms(a.y, b.y, a.n) - 8e-3) < 1e-12, "noise RMS %.17g mm",
              hy_signal_erms(a.y, b.y, a.n));
    col_free(&a);
    col_free(&b);
}

/* Writes text to dir/name and expects hy_scene_run_load to fail with a
 * message starting "dir/name:want_loc: " and containing want. */
static void refused(const char *dir, const char *text, const char *want_loc, const char *want)
{
    static int k;
    char path[512], prefix[600];
    snprintf(path, sizeof path, "%s/bad%d.scene", dir, ++k);
    FILE *f = fopen(path, "w");
    if (!f)
        return;
    fputs(text, f);
    fclose(f);
    hy_scene_run r;
    hy_error err;
    int rc = hy_scene_run_load(&r, path, NULL, 0, &err);
    if (!rc) {
        rc = hy_scene_run_compute(&r, NULL, &err);
        hy_scene_run_free(&r);
    }
    snprintf(prefix, sizeof prefix, "%s:%s: ", path, want_loc);
    CHECK(rc != 0, "bad%d.scene was accepted", k);
    CHECK(rc == 0 || (!strncmp(err.msg, prefix, strlen(prefix)) && strstr(err.msg, want)),
          "bad%d.scene: got '%s', want '%s...%s'", k, err.msg, prefix, want);
    remove(path);
}

static void test_refused(void)
{
    char dir[200];
    if (!mkdtemp(test_tmppath(dir, sizeof dir, "scenes_XXXXXX"))) {
        CHECK(0, "mkdtemp");
        return;
    }
    const char *bw = "[model]\nkind = boucwen\n";
    char t[1024];
#define BAD(extra, loc, want)                       \
    do {                                            \
        snprintf(t, sizeof t, "%s%s", bw, extra);   \
        refused(dir, t, loc, want);                 \
    } while (0)
    BAD("m = -2\n", "3:5", "'m' in [model] must be > 0, got -2");
    BAD("nu = 0\n", "3:6", "'nu' in [model] must be > 0, got 0");
    BAD("k = 0\nalpha = 0\n[input]\nkind = sine\n", "3:1", "k + alpha");
    BAD("[input]\nkind = sine\n[series y]\ndata = boucwen\nquantity = velocity\n", "7:12",
        "'quantity' in [series y] must be one of output, input");
    BAD("[input]\nkind = bimodal\n", "4:1", "a boucwen model takes [input] kind = sine, multisine or sweep");
    BAD("[input]\nkind = sine\nperiod = 1.0001\n", "5:1", "whole number");
    BAD("[input]\nkind = sine\nperiod = 1\n[series y]\ndata = ystar\n", "7:1", "a boucwen model draws data = boucwen, not ystar");
    BAD("[input]\nkind = sine\nperiod = 1\n[series y]\ndata = boucwen\nquantity = transient-db\n", "8:1",
        "cycles >= 2");
    BAD("[input]\nkind = sweep\nband = 20, 50\n[series s]\ndata = boucwen\nquantity = spectrum\n", "8:1",
        "periodic input");
    BAD("[input]\nkind = sweep\nband = 20, 50\n[compute]\ncycles = 3\n", "7:1", "a sweep is not periodic");
    BAD("[input]\nkind = sine\nperiod = 1\n[series e]\ndata = boucwen\nquantity = sinc-output-error\n", "8:1",
        "it needs [input] kind = sweep");
    BAD("[input]\nkind = sweep\n[figure]\nkind = loop\n[series e]\ndata = boucwen\nquantity = envelope\n", "9:1",
        "not in a loop figure");
    BAD("[input]\nkind = multisine\nband = 5, 400\n", "5:1", "below fs/2");
    BAD("[input]\nkind = sine\nperiod = 1\n[figure]\nkind = psi\n", "7:1", "timeseries or loop");
    /* issue 10 items 1 and 4: rates at the ends of the doubles, before any cast */
    BAD("[input]\nkind = multisine\nfs = 1e-15\n", "5:1", "multisine fmax = 150 Hz must stay below fs/2 = 5e-16 Hz");
    BAD("[input]\nkind = multisine\nfs = 1e308\n", "5:1", "band 5 .. 150 Hz holds no DFT line");
    BAD("[input]\nkind = multisine\nband = 1e299, 1e300\n", "5:1", "must stay below fs/2");
    BAD("[input]\nkind = sine\nfs = 1e300\n", "5:1", "period x fs = 2 x 1e+300 = 2e+300 samples is more than");
    BAD("[input]\nkind = sweep\nrate = 1e-300\n", "5:1", "more than the 1099511627776 a sweep may hold");
    /* issue 20 item 4: shorter than one sample passed the check and printed an unset message */
    BAD("[input]\nkind = sweep\nrate = 1e20\n", "5:1", "less than one sample at fs = 750 Hz");
    BAD("[input]\nkind = sine\nperiod = 1\n[compute]\ncycles = 100000\n", "7:1", "integration samples");
    BAD("[input]\nkind = sine\nperiod = 1\n[annotation a]\ntext = \"{energy}\"\nx = 0\ny = 0\n", "7:1",
        "placeholders");
    refused(dir, "[model]\nkind = lugre\n[input]\nkind = multisine\n", "4:1", "kind = boucwen");
    /* band = 1e-12, 150 excited line 0 and wrote u[-1]: now lines 1 .. 1639 */
    snprintf(t, sizeof t, "%s[input]\nkind = multisine\nband = 1e-12, 150\n[series u]\ndata = boucwen\n"
             "quantity = input\n", bw);
    hy_scene_run r;
    hy_error err = {0, ""};
    char path[512];
    snprintf(path, sizeof path, "%s/band.scene", dir);
    FILE *f = fopen(path, "w");
    if (f) {
        fputs(t, f);
        fclose(f);
    }
    int rc = hy_scene_run_load(&r, path, NULL, 0, &err);
    if (!rc) {
        rc = hy_scene_run_compute(&r, NULL, &err);
        hy_scene_run_free(&r);
    }
    CHECK(rc == 0, "band = 1e-12, 150: %s", err.msg);
    remove(path);
    refused(dir, "[model]\nkind = lugre\n[series y]\ndata = boucwen\n", "4:1", "needs [model] kind = boucwen");
    rmdir(dir);
#undef BAD
}

int main(void)
{
    test_linear();
    test_transient();
    test_noise();
    test_refused();
    return hy_test_finish("test_scenes");
}
