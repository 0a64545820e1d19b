/* SPDX-License-Identifier: MIT */
/* test_forc: hy_forc against exact answers.
 *   - the Preisach FORC protocol against the Everett closed form;
 *   - the regression's FORC distribution against the Preisach density, with
 *     the observed order over three field steps;
 *   - exactness on a quadratic M (irregular data), the (H_c, H_u) rotation and
 *     the factor −½ on a hand example;
 *   - the MicroMag reader on the measured file and on crafted broken copies
 *     (in memory: the reader takes text), the CSV reader, drift correction.
 * argv[1]: the measured file (tests/data/forc/conventional_example.forc). */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hy_file.h"
#include "hy_forc.h"
#include "../core/tutil.h"

/* ---- Preisach: closed form ---------------------------------------------------- */

/* μ = K f(α) f(β) on α >= β with the same Gaussian f (centre m, width s) for
 * both: mass ½, K = 2 y_s and E(a, b) = y_s (F(a) − F(b))², so from positive
 * saturation M(H_a, H_b) = y_s − 2 y_s (1 − F(H_a))² + 2 y_s (F(H_b) − F(H_a))². */
static double F(double x, double m, double s) { return 0.5 * erfc(-(x - m) / (s * M_SQRT2)); }
static double Fc(double x, double m, double s) { return 0.5 * erfc((x - m) / (s * M_SQRT2)); }

static void test_closed_form(void)
{
    const double m = 0.1, s = 0.3, ys = 1.5;
    hy_preisach p;
    hy_error err = {0};
    CHECK(!hy_preisach_init(&p, HY_PREISACH_GAUSSIAN, m, s, m, s, ys, &err), "init: %s", err.msg);
    hy_forc_protocol pr = {.hsat = 6, .ha_lo = -1.2, .ha_hi = 1.4, .hb_max = 1.4, .ncurves = 27};
    hy_forc_data d;
    int rc = hy_forc_preisach(&d, &pr, &p, &err);
    CHECK(!rc, "protocol: %s", err.msg);
    if (rc)
        return;
    CHECK(d.ncurves == 27 && d.curve[0].n == 1 && d.curve[26].n == 27, "curves %zu, n %zu .. %zu", d.ncurves,
          d.curve[0].n, d.curve[d.ncurves - 1].n);
    double worst = 0;
    for (size_t i = 0; i < d.ncurves; i++) {
        const hy_forc_curve *c = &d.curve[i];
        double a = Fc(c->ha, m, s);
        for (size_t j = 0; j < c->n; j++) {
            double hb = d.hb[c->first + j], dF = F(hb, m, s) - F(c->ha, m, s);
            double exact = ys - 2 * ys * a * a + 2 * ys * dF * dF;
            worst = fmax(worst, fabs(d.m[c->first + j] - exact));
        }
    }
    /* Everett quadrature to 1e-13 relative (hy_preisach.h) over a staircase of
     * at most 3 edges and the closed form's erfc (a few ulps): 1e-12 of y_s */
    printf("closed form: largest |M - M_exact| = %.3g (y_s = %g) over %zu points\n", worst, ys, d.npoints);
    CHECK(worst <= 1e-12 * ys, "Preisach FORCs vs the Everett closed form: %.3g > 1e-12 y_s", worst);
    /* the diagonal M(H_a, H_a) is the descending major branch: −y_s at H_a → −∞ side */
    CHECK(d.m[d.curve[26].first] < -0.9 * ys, "M at H_a = -1.2: %g", d.m[d.curve[26].first]);
    hy_forc_data_free(&d);
}

/* ---- Preisach: the distribution converges to the density --------------------------- */

static double density(const hy_preisach *p, double ha, double hb)
{
    double za = (hb - p->ma) / p->sa, zb = (ha - p->mb) / p->sb; /* α = H_b, β = H_a */
    return hb >= ha ? p->scale * exp(-0.5 * (za * za + zb * zb)) / (2 * M_PI * p->sa * p->sb) : 0;
}

/* Largest |ρ − μ| on a fixed grid of nodes for the protocol with n curves over [−1, 1]. */
static double rho_error(const hy_preisach *p, size_t n, double *peak, double *secs)
{
    hy_error err = {0};
    hy_forc_protocol pr = {.hsat = 3, .ha_lo = -1, .ha_hi = 1, .hb_max = 1, .ncurves = n};
    hy_forc_data d;
    if (hy_forc_preisach(&d, &pr, p, &err)) {
        CHECK(0, "protocol %zu: %s", n, err.msg);
        return NAN;
    }
    hy_forc_opts o = hy_forc_defaults();
    hy_forc_grid g = {.hc0 = 0.1, .hc1 = 0.5, .hu0 = -0.3, .hu1 = 0.3, .nc = 17, .nu = 25};
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    size_t nfit = 0;
    int rc = hy_forc_rho(&d, &o, &g, &nfit, &err);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    *secs = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    CHECK(!rc && nfit == g.nc * g.nu, "rho %zu: %s (%zu of %zu nodes)", n, err.msg, nfit, g.nc * g.nu);
    double e = 0;
    *peak = 0;
    for (size_t iu = 0; !rc && iu < g.nu; iu++)
        for (size_t ic = 0; ic < g.nc; ic++) {
            double hc = g.hc0 + (double)ic * (g.hc1 - g.hc0) / (double)(g.nc - 1);
            double hu = g.hu0 + (double)iu * (g.hu1 - g.hu0) / (double)(g.nu - 1);
            double mu = density(p, hu - hc, hu + hc);
            *peak = fmax(*peak, mu);
            e = fmax(e, fabs(g.rho[iu * g.nc + ic] - mu));
        }
    hy_forc_grid_free(&g);
    hy_forc_data_free(&d);
    return rc ? NAN : e;
}

static void test_convergence(void)
{
    hy_preisach p;
    hy_error err = {0};
    /* α around +0.3, β around −0.3, width 0.15: the density is 1e-6 of its
     * peak on α = β, i.e. smooth where the nodes' neighbourhoods reach */
    CHECK(!hy_preisach_symmetric(&p, HY_PREISACH_GAUSSIAN, 0.3, 0.15, 1.0, &err), "init: %s", err.msg);
    const size_t n[3] = {41, 81, 161}; /* field steps 0.05, 0.025, 0.0125 */
    double e[3], peak = 0, secs = 0;
    for (int i = 0; i < 3; i++) {
        e[i] = rho_error(&p, n[i], &peak, &secs);
        printf("convergence: step %.4g: max |rho - mu| = %.4g (%.3g of the peak %.4g), regression %.2f ms\n",
               2.0 / (double)(n[i] - 1), e[i], e[i] / peak, peak, 1e3 * secs);
    }
    /* SF = 3 neighbourhoods shrink with the step: the fit's error is the
     * fourth-order Taylor terms (x³y, xy³) that project on xy, O((SF h)²),
     * the cubic ones being odd on a centred box: ratio 4 per halving; ≥ 3
     * allows for the box not centred on the data at every node */
    for (int i = 0; i < 2; i++) {
        double ratio = e[i] / e[i + 1];
        printf("convergence: ratio %.3f (observed order %.2f)\n", ratio, log2(ratio));
        CHECK(ratio >= 3 && ratio <= 5.5, "error ratio %g per halving (expected about 4)", ratio);
    }
    /* and it is small: 1.6 % of the peak at the finest step (SF h = 0.0375
     * against the density's width 0.15): 2 % */
    CHECK(e[2] <= 0.02 * peak, "finest error %g of peak %g", e[2], peak);
}

/* ---- exactness on a quadratic, rotation, −½ --------------------------------------------- */

static void test_quadratic(void)
{
    /* irregular data: H_a jittered by ±20 % of the step, H_b by ±20 % too */
    enum { NC = 60, NMAX = 60 };
    double ha[NC], hb[NC * NMAX], m[NC * NMAX];
    size_t n[NC], k = 0;
    const double h = 0.05;
    for (int i = 0; i < NC; i++) {
        ha[i] = 1.5 - i * h + tu_unif(-0.2, 0.2) * h;
        n[i] = 0;
        for (int j = 0; j < NMAX; j++) {
            double b = ha[i] + j * h + (j ? tu_unif(-0.2, 0.2) * h : 0);
            if (b > 1.5)
                break;
            hb[k] = b;
            m[k] = 1 + 2 * ha[i] - 3 * b + 0.5 * ha[i] * ha[i] - 0.7 * b * b + 1.3 * ha[i] * b;
            k++, n[i]++;
        }
        if (!n[i]) { /* keep every curve at least one point */
            hb[k] = ha[i];
            m[k] = 1 + 2 * ha[i] - 3 * ha[i] + 0.5 * ha[i] * ha[i] - 0.7 * ha[i] * ha[i] + 1.3 * ha[i] * ha[i];
            k++, n[i]++;
        }
    }
    hy_forc_data d;
    hy_error err = {0};
    CHECK(!hy_forc_data_set(&d, NC, ha, n, hb, m, &err), "data: %s", err.msg);
    hy_forc_opts o = hy_forc_defaults();
    o.extend = 0; /* the extension is not the quadratic */
    hy_forc_grid g;
    hy_forc_grid_auto(&d, &o, &g);
    size_t nfit = 0;
    CHECK(!hy_forc_rho(&d, &o, &g, &nfit, &err), "rho: %s", err.msg);
    double worst = 0;
    for (size_t i = 0; i < g.nc * g.nu; i++)
        if (isfinite(g.rho[i]))
            worst = fmax(worst, fabs(g.rho[i] - (-0.65)));
    /* Householder QR is backward stable; in units of the step the design
     * matrix's condition is below 1e3 and M is O(10): 1e-10 */
    printf("quadratic: %zu nodes fitted, largest |rho + 0.65| = %.3g\n", nfit, worst);
    CHECK(nfit > 500 && worst <= 1e-10, "quadratic not exact: %zu nodes, error %g", nfit, worst);
    hy_forc_grid_free(&g);
    hy_forc_data_free(&d);

    /* hand example: M = H_a² H_b on a regular grid, ∂²M/∂H_a∂H_b = 2 H_a, so
     * ρ = −H_a = −(H_u − H_c) (the cubic term is odd on a centred box, so the
     * fit's x·y coefficient is exact).  (H_c, H_u) = (0.2, 0.1) is (H_a, H_b) =
     * (−0.1, 0.3): ρ = +0.1; (0.2, 0.3) is (0.1, 0.5): ρ = −0.1.  Swapping the
     * rotation (H_a = H_u + H_c) would give −0.3 and −0.5; dropping −½, −2 times
     * the values. */
    size_t k2 = 0;
    double ha2[41], *hb2 = malloc(41 * 41 * sizeof *hb2), *m2 = malloc(41 * 41 * sizeof *m2);
    size_t n2[41];
    for (int i = 0; i < 41; i++) {
        ha2[i] = 1 - i * h;
        n2[i] = (size_t)i + 1;
        for (int j = 0; j <= i; j++, k2++) {
            hb2[k2] = ha2[i] + j * h;
            m2[k2] = ha2[i] * ha2[i] * hb2[k2];
        }
    }
    CHECK(!hy_forc_data_set(&d, 41, ha2, n2, hb2, m2, &err), "data: %s", err.msg);
    /* H_c >= 0.2: the boxes (half-width 3.5 h = 0.175) lie wholly in H_b > H_a */
    hy_forc_grid g2 = {.hc0 = 0.2, .hc1 = 0.4, .hu0 = 0.1, .hu1 = 0.3, .nc = 2, .nu = 2};
    CHECK(!hy_forc_rho(&d, &o, &g2, NULL, &err), "rho: %s", err.msg);
    if (g2.rho) {
        /* nodes (H_c, H_u) = (0.2, 0.1) (0.4, 0.1) (0.2, 0.3) (0.4, 0.3), i.e.
         * H_a = −0.1, −0.3, 0.1, −0.1: ρ = −H_a; to rounding (1e-12, values O(1)) */
        CHECK_CLOSE(g2.rho[0], 0.1, 1e-12, "rho(H_c = 0.2, H_u = 0.1)");
        CHECK_CLOSE(g2.rho[1], 0.3, 1e-12, "rho(H_c = 0.4, H_u = 0.1)");
        CHECK_CLOSE(g2.rho[2], -0.1, 1e-12, "rho(H_c = 0.2, H_u = 0.3)");
        CHECK_CLOSE(g2.rho[3], 0.1, 1e-12, "rho(H_c = 0.4, H_u = 0.3)");
    }
    hy_forc_grid_free(&g2);
    /* SF = 9: 361 points in the box, more than the workspace's first 256
     * rows, so it grows in the middle of a gather; (H_c, H_u) = (0.5, 0) is
     * (H_a, H_b) = (−0.5, 0.5), the box wholly inside: ρ = −H_a = 0.5 */
    hy_forc_grid g3 = {.hc0 = 0.5, .hc1 = 0.5, .hu0 = 0, .hu1 = 0, .nc = 1, .nu = 1};
    hy_forc_opts o9 = o;
    o9.sf = 9;
    CHECK(!hy_forc_rho(&d, &o9, &g3, NULL, &err), "rho SF 9: %s", err.msg);
    if (g3.rho)
        CHECK_CLOSE(g3.rho[0], 0.5, 1e-11, "rho with SF = 9 (workspace grown mid-gather)");
    hy_forc_grid_free(&g3);
    hy_forc_data_free(&d);
    free(hb2);
    free(m2);
}

/* ---- readers ---------------------------------------------------------------------- */

static char *text_of(const char *path, size_t *len)
{
    char *buf, why[160];
    if (hy_file_read(path, 1u << 24, &buf, len, NULL, why, sizeof why)) {
        fprintf(stderr, "%s: %s\n", path, why);
        exit(1);
    }
    return buf;
}

/* The text with the line-th line (1-based) replaced by rep (NULL: cut the text
 * before that line; "": keep up to col bytes of it). */
static char *edit(const char *t, size_t len, size_t line, const char *rep, size_t keep, size_t *out)
{
    char *r = malloc(len + 256);
    size_t l = 1, i = 0, o = 0;
    while (i < len && l < line) {
        if (t[i] == '\n')
            l++;
        r[o++] = t[i++];
    }
    if (rep) {
        if (*rep) {
            memcpy(r + o, rep, strlen(rep));
            o += strlen(rep);
        } else {
            memcpy(r + o, t + i, keep);
            o += keep;
        }
        while (i < len && t[i] != '\n')
            i++;
        if (*rep)
            while (i < len)
                r[o++] = t[i++];
    }
    *out = o;
    r[o] = 0;
    return r;
}

static void expect_refused(const char *t, size_t len, const char *where, const char *what)
{
    hy_forc_data d;
    hy_error err = {0};
    int rc = hy_forc_read_micromag(&d, t, len, "x.forc", &err);
    CHECK(rc == HY_EINVAL && strstr(err.msg, where) == err.msg && strstr(err.msg, what),
          "expected '%s ... %s', got %d '%s'", where, what, rc, err.msg);
    if (!rc)
        hy_forc_data_free(&d);
}

static void test_micromag(const char *path)
{
    size_t len;
    char *t = text_of(path, &len);
    hy_forc_data d;
    hy_error err = {0};
    int rc = hy_forc_read(&d, t, len, "conventional_example.forc", &err);
    CHECK(!rc, "read: %s", err.msg);
    if (rc)
        return;
    CHECK(d.ncurves == 120 && d.npoints == 8394 && d.ncal == 120, "%zu curves, %zu points, %zu calibrations",
          d.ncurves, d.npoints, d.ncal);
    CHECK(d.units == HY_FORC_UNITS_HYBRID_SI && !strcmp(d.field_unit, "T") && !strcmp(d.moment_unit, "A m2") &&
              d.field_to_tesla == 1,
          "units %d '%s' '%s'", d.units, d.field_unit, d.moment_unit);
    CHECK(d.ncrv == 120 && d.ndata == 8514 && d.hsat == 0.3 && d.hncr == 2.803741e-3 && d.hcal == 0.2350512,
          "header %ld %ld %g %g %g", d.ncrv, d.ndata, d.hsat, d.hncr, d.hcal);
    CHECK(d.curve[0].cal_h == 0.2370455 && d.curve[0].cal_m == 7.842043e-07 && d.curve[0].n == 1 &&
              d.curve[0].ha == 0.1182822 && d.curve[0].line == 37,
          "curve 1: cal (%g, %g) n %zu H_a %g line %zu", d.curve[0].cal_h, d.curve[0].cal_m, d.curve[0].n,
          d.curve[0].ha, d.curve[0].line);
    CHECK(d.curve[1].n == 3 && d.curve[1].cal_m == 7.840866e-07 && d.hb[d.curve[1].first + 2] == 0.1211815,
          "curve 2: n %zu", d.curve[1].n);
    size_t n85 = 0;
    for (size_t i = 0; i < d.ncurves; i++)
        n85 += d.curve[i].n == 85;
    CHECK(n85 == 78 && d.curve[119].n == 85, "curves of 85 points: %zu", n85); /* curves 43..120 */
    double da, db;
    hy_forc_steps(&d, &da, &db);
    printf("micromag: %zu curves, %zu points, steps %.6g / %.6g T (HNcr %.6g)\n", d.ncurves, d.npoints, da, db,
           d.hncr);
    CHECK(fabs(da / d.hncr - 1) < 0.02 && fabs(db / d.hncr - 1) < 0.02, "steps %g %g vs HNcr", da, db);

    /* the distribution at SF = 3: a positive maximum, small where the sample
     * has no remanence carriers (checked loosely: this is measured data) */
    hy_forc_opts o = hy_forc_defaults();
    hy_forc_grid g;
    hy_forc_grid_auto(&d, &o, &g);
    size_t nfit = 0;
    rc = hy_forc_rho(&d, &o, &g, &nfit, &err);
    CHECK(!rc && nfit > 1000, "rho: %s (%zu nodes)", err.msg, nfit);
    double best = -INFINITY, bc = 0, bu = 0;
    for (size_t iu = 0; !rc && iu < g.nu; iu++)
        for (size_t ic = 0; ic < g.nc; ic++) {
            double r = g.rho[iu * g.nc + ic];
            if (isfinite(r) && r > best && ic >= 4) /* H_c >= 4 steps: off the reversible ridge */
                best = r, bc = g.hc0 + (double)ic * (g.hc1 - g.hc0) / (double)(g.nc - 1),
                bu = g.hu0 + (double)iu * (g.hu1 - g.hu0) / (double)(g.nu - 1);
        }
    printf("micromag: grid %zu x %zu, %zu fitted, peak rho (H_c >= 4 steps) %.4g A m2/T2 at H_c = %.4g T, H_u = %.4g T\n", g.nc,
           g.nu, nfit, best, bc, bu);
    CHECK(best > 0 && fabs(bu) < 0.02, "peak at H_u = %g", bu);
    /* variable smoothing with sc0 = sc1 = 3 is SF = 3, bit for bit; growing
     * SF smooths: fewer sign changes along H_c at H_u = 0 than at SF = 3 */
    hy_forc_opts ov = o;
    ov.sc0 = ov.sc1 = 3;
    hy_forc_grid gv = g;
    gv.rho = NULL;
    CHECK(!hy_forc_rho(&d, &ov, &gv, NULL, &err) && !memcmp(gv.rho, g.rho, g.nc * g.nu * sizeof *g.rho),
          "sc0 = sc1 = 3 differs from SF = 3");
    ov.sc0 = 3, ov.sc1 = 8;
    CHECK(!hy_forc_rho(&d, &ov, &gv, NULL, &err) && gv.rho[0] == g.rho[0], "variable SF at H_c = 0 is sc0");
    double tv3 = 0, tv8 = 0; /* total variation along H_c over the upper half of H_c */
    for (size_t iu = 0; iu < g.nu; iu++)
        for (size_t ic = g.nc / 2; ic + 1 < g.nc; ic++) {
            double a3 = g.rho[iu * g.nc + ic], b3 = g.rho[iu * g.nc + ic + 1];
            double a8 = gv.rho[iu * g.nc + ic], b8 = gv.rho[iu * g.nc + ic + 1];
            if (isfinite(a3) && isfinite(b3) && isfinite(a8) && isfinite(b8))
                tv3 += fabs(b3 - a3), tv8 += fabs(b8 - a8);
        }
    printf("micromag: total variation along H_c (upper half): SF 3 %.4g, SF 3 -> 8 %.4g\n", tv3, tv8);
    CHECK(tv8 < 0.6 * tv3, "variable smoothing does not smooth: %g vs %g", tv8, tv3);
    hy_forc_grid_free(&gv);
    hy_forc_grid_free(&g);

    /* drift correction: every curve's M scaled by cal(1)/cal(i) */
    double m_last = d.m[d.curve[119].first], f = d.curve[0].cal_m / d.curve[119].cal_m;
    CHECK(!hy_forc_drift(&d, &err), "drift: %s", err.msg);
    CHECK(d.m[d.curve[119].first] == m_last * f && f != 1, "drift factor %.17g", f);
    hy_forc_data_free(&d);

    /* LF line ends read the same */
    char *lf = malloc(len + 1);
    size_t k = 0;
    for (size_t i = 0; i < len; i++)
        if (t[i] != '\r')
            lf[k++] = t[i];
    CHECK(!hy_forc_read(&d, lf, k, "lf.forc", &err) && d.ncurves == 120 && d.npoints == 8394, "LF: %s", err.msg);
    hy_forc_data_free(&d);
    free(lf);

    size_t n;
    char *x;
    /* truncated in curve 50's points (line 2000 is inside one): the file ends at line 1999 */
    x = edit(t, len, 2000, NULL, 0, &n);
    expect_refused(x, n, "x.forc:1999:", "truncated");
    free(x);
    /* cut inside line 2000 ("+2.061685E-01,+7.412731E-07"): after the field
     * (col 8 of "+2.0616"), inside the exponent of the moment, and inside the
     * moment's digits (still two numbers: the counts catch it) */
    x = edit(t, len, 2000, "", 7, &n);
    expect_refused(x, n, "x.forc:2000:8:", "a number is missing");
    free(x);
    x = edit(t, len, 2000, "", 25, &n);
    expect_refused(x, n, "x.forc:2000:15:", "cut short");
    free(x);
    x = edit(t, len, 2000, "", 18, &n);
    expect_refused(x, n, "x.forc:2000:", "truncated");
    free(x);
    /* broken header lines */
    x = edit(t, len, 19, "NCrv           = 12O\r", 0, &n);
    expect_refused(x, n, "x.forc:19:18:", "NCrv must be a whole number");
    free(x);
    x = edit(t, len, 19, "NCrv           = \r", 0, &n);
    expect_refused(x, n, "x.forc:19:", "has no value");
    free(x);
    x = edit(t, len, 6, "Units of measure:  furlongs\r", 0, &n);
    expect_refused(x, n, "x.forc:6:20:", "unknown units");
    free(x);
    x = edit(t, len, 1, "MacroMag\r", 0, &n);
    expect_refused(x, n, "x.forc:1:1:", "not a MicroMag");
    free(x);
    /* a NaN, a descending field, a stray word */
    x = edit(t, len, 42, "+1.154643E-01,nan\r", 0, &n);
    expect_refused(x, n, "x.forc:42:15:", "NaN");
    free(x);
    x = edit(t, len, 43, "+1.054643E-01,+6.057562E-07\r", 0, &n);
    expect_refused(x, n, "x.forc:43:1:", "does not ascend");
    free(x);
    x = edit(t, len, 43, "+1.183070E-01;+6.057562E-07 x\r", 0, &n);
    expect_refused(x, n, "x.forc:43:29:", "unexpected text");
    free(x);
    /* NCrv larger than the curves present */
    x = edit(t, len, 19, "NCrv           = 121\r", 0, &n);
    expect_refused(x, n, "x.forc:", "NCrv = 121");
    free(x);
    free(t);
}

static void test_csv(void)
{
    const char csv[] = "H_a,H_b,M\n# a comment\n0,0,1\n0,0.1,2\n-0.1,-0.1,0.5\n-0.1,0,0.7\n-0.1,0.1,1.9\n";
    hy_forc_data d;
    hy_error err = {0};
    int rc = hy_forc_read(&d, csv, sizeof csv - 1, "a.csv", &err);
    CHECK(!rc && d.ncurves == 2 && d.npoints == 5 && d.curve[1].ha == -0.1 && d.curve[1].n == 3 &&
              d.curve[1].line == 5 && d.units == HY_FORC_UNITS_NONE,
          "csv: %s", err.msg);
    if (!rc)
        hy_forc_data_free(&d);
    const char bad[] = "H_a,H_b,M\n0,0,1\n0,0.1,x2\n";
    CHECK_MSG(hy_forc_read(&d, bad, sizeof bad - 1, "b.csv", &err), err, HY_EINVAL, "b.csv:3:7: expected a number");
    const char desc[] = "0,0,1\n0,-0.1,2\n";
    CHECK_MSG(hy_forc_read(&d, desc, sizeof desc - 1, "c.csv", &err), err, HY_EINVAL, "c.csv:2:1: H_b does not");
    const char inf[] = "0,0,1\n0,0.1,1e999\n";
    CHECK_MSG(hy_forc_read(&d, inf, sizeof inf - 1, "d.csv", &err), err, HY_EINVAL, "d.csv:2:7: a number that is");
    CHECK_MSG(hy_forc_read(&d, "", 0, "e.csv", &err), err, HY_EINVAL, "no data rows");
    /* drift needs calibration points */
    const char ok[] = "0,0,1\n-0.1,-0.1,1\n";
    CHECK(!hy_forc_read(&d, ok, sizeof ok - 1, "f.csv", &err), "f.csv: %s", err.msg);
    CHECK_MSG(hy_forc_drift(&d, &err), err, HY_EINVAL, "no calibration point");
    hy_forc_data_free(&d);
}

/* Untrusted input: random mutations (a byte changed, inserted or deleted,
 * a cut, a line duplicated) of the measured file and of a CSV are read or
 * refused with HY_EINVAL and a "name:line:col: " message; what is read holds
 * finite, ascending curves.  Fixed seed; valgrind/ASan catch what a check
 * cannot. */
static void check_read(const char *t, size_t n, int *accepted)
{
    hy_forc_data d;
    hy_error err = {0};
    int rc = hy_forc_read(&d, t, n, "m.forc", &err);
    if (rc) {
        CHECK(rc == HY_EINVAL && !strncmp(err.msg, "m.forc:", 7), "mutation: %d '%s'", rc, err.msg);
        return;
    }
    (*accepted)++;
    int ok = d.ncurves >= 1;
    for (size_t i = 0; ok && i < d.ncurves; i++)
        for (size_t j = 0; ok && j < d.curve[i].n; j++) {
            size_t q = d.curve[i].first + j;
            ok = isfinite(d.hb[q]) && isfinite(d.m[q]) && (!j || d.hb[q] > d.hb[q - 1]);
        }
    CHECK(ok, "a mutation read into a bad data set");
    hy_forc_data_free(&d);
}

static void test_mutations(const char *t, size_t len)
{
    char *x = malloc(len + 256);
    int accepted = 0, total = 0;
    const char csv[] = "ha,hb,m\n0,0,1\n0,0.1,2\n-0.1,-0.1,0\n-0.1,0,1\n-0.1,0.1,2\n";
    for (int r = 0; r < 600; r++, total++) {
        const char *src = r % 3 == 2 ? csv : t;
        size_t n = r % 3 == 2 ? sizeof csv - 1 : (r % 3 ? 3000 : len); /* the whole file, or its head */
        memcpy(x, src, n);
        size_t at = (size_t)(tu_next() % n);
        static const char bytes[] = "0123456789+-.,eE \t\r\n=:NaIf\x00\xff";
        char c = bytes[tu_next() % (sizeof bytes - 1)];
        switch (tu_next() % 5) {
        case 0: x[at] = c; break;
        case 1: memmove(x + at + 1, x + at, n - at); x[at] = c; n++; break;
        case 2: memmove(x + at, x + at + 1, n - at - 1); n--; break;
        case 3: n = at; break;
        default: { /* duplicate the line at `at` */
            size_t b = at, e = at;
            while (b > 0 && x[b - 1] != '\n') b--;
            while (e < n && x[e] != '\n') e++;
            if (e < n && e - b < 200) {
                memmove(x + e + 1 + (e - b), x + e + 1, n - e - 1);
                memcpy(x + e + 1, x + b, e - b);
                x[e + 1 + (e - b)] = '\n';
                n += e - b + 1;
            }
        }
        }
        check_read(x, n, &accepted);
    }
    printf("mutations: %d of %d read, the rest refused with file:line:col\n", accepted, total);
    free(x);
}

/* The newer layout (section titles, `Key  value` lines, a "Field Moment"
 * column header and a units line), cgs units, a curve without calibration,
 * and the line cap. */
static void test_micromag_variants(void)
{
    const char txt[] = "MicroMag 2900/3900 Data File (Series 0016.002)\r\n"
                       "First-order reversal curves\r\n\r\nINSTRUMENT\r\n"
                       "Units of measure                cgs\r\n\r\nSETTINGS\r\n"
                       "HCal                           +5.000000E+03\r\nNCrv                            2\r\n\r\n"
                       "      Field         Moment\r\n        (Oe)          (emu)\r\n\r\n"
                       "+5.01E+03,+1.0E-03\r\n\r\n-1.00E+02,-2.0E-04\r\n-5.00E+01,-1.0E-04\r\n\r\n"
                       "-2.00E+02,-4.0E-04\r\n-1.50E+02,-3.0E-04\r\n-1.00E+02,-2.0E-04\r\n\r\n";
    hy_forc_data d;
    hy_error err = {0};
    int rc = hy_forc_read(&d, txt, sizeof txt - 1, "new.forc", &err);
    CHECK(!rc, "newer layout: %s", err.msg);
    if (!rc) {
        CHECK(d.units == HY_FORC_UNITS_CGS && !strcmp(d.field_unit, "Oe") && !strcmp(d.moment_unit, "emu") &&
                  d.field_to_tesla == 1e-4,
              "cgs units %d %s %s", d.units, d.field_unit, d.moment_unit);
        CHECK(d.ncurves == 2 && d.ncal == 1 && d.curve[0].cal_m == 1e-3 && isnan(d.curve[1].cal_m) &&
                  d.curve[1].n == 3 && d.curve[1].ha == -200 && d.curve[0].line == 16,
              "curves %zu cal %zu line %zu", d.ncurves, d.ncal, d.curve[0].line);
        hy_forc_data_free(&d);
    }
    /* without NCrv/NData and without the end line: refused as truncated */
    const char noend[] = "MicroMag 2900/3900 Data File\n\n1,2\n2,3\n";
    CHECK_MSG(hy_forc_read(&d, noend, sizeof noend - 1, "n.forc", &err), err, HY_EINVAL, "n.forc:4:");
    const char end[] = "MicroMag 2900/3900 Data File\n\n1,2\n2,3\nMicroMag 2900/3900 Data File ends\n";
    CHECK(!hy_forc_read(&d, end, sizeof end - 1, "e.forc", &err) && d.ncurves == 1, "end line: %s", err.msg);
    hy_forc_data_free(&d);
    /* a line past the cap */
    size_t n = HY_FORC_MAX_LINE + 100;
    char *big = malloc(n + 64);
    strcpy(big, "MicroMag 2900/3900 Data File\n");
    size_t k = strlen(big);
    memset(big + k, ' ', n);
    strcpy(big + k + n, "\n");
    CHECK_MSG(hy_forc_read(&d, big, strlen(big), "big.forc", &err), err, HY_EINVAL, "big.forc:2:1: line longer");
    free(big);
}

/* The generic protocol: the callback sees H_sat, H_a, then the H_b ascending. */
typedef struct trace {
    double u[64];
    int n;
} trace;

static int trace_fn(void *ctx, double u, double *y, hy_error *err)
{
    (void)err;
    trace *t = ctx;
    if (t->n < 64)
        t->u[t->n] = u;
    t->n++;
    *y = 10 * u;
    return HY_OK;
}

static void test_protocol(void)
{
    trace t = {{0}, 0};
    hy_forc_protocol pr = {.hsat = 5, .ha_lo = -1, .ha_hi = 1, .hb_max = 1, .ncurves = 3};
    hy_forc_data d;
    hy_error err = {0};
    CHECK(!hy_forc_protocol_run(&d, &pr, trace_fn, &t, &err), "protocol: %s", err.msg);
    /* curves H_a = 1, 0, -1 with 1, 2, 3 points: 3 x 2 moves + 6 points */
    const double want[] = {5, 1, 5, 0, 1, 5, -1, 0, 1};
    CHECK(t.n == 9 && !memcmp(t.u, want, sizeof want), "sequence of %d moves", t.n);
    CHECK(d.ncurves == 3 && d.npoints == 6 && d.m[5] == 10 && d.curve[2].ha == -1, "data %zu %zu", d.ncurves,
          d.npoints);
    hy_forc_data_free(&d);
    pr.hsat = 0.5; /* below hb_max */
    CHECK_MSG(hy_forc_protocol_run(&d, &pr, trace_fn, &t, &err), err, HY_EINVAL, "hb_max <= hsat");
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    if (argc < 2) {
        fprintf(stderr, "usage: test_forc FILE.forc\n");
        return 2;
    }
    test_closed_form();
    test_quadratic();
    test_csv();
    test_protocol();
    test_micromag_variants();
    test_micromag(argv[1]);
    {
        size_t len;
        char *t = text_of(argv[1], &len);
        test_mutations(t, len);
        free(t);
    }
    test_convergence();
    return tu_finish("test_forc");
}
