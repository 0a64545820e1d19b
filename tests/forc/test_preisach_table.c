/* SPDX-License-Identifier: MIT */
/* test_preisach_table: the tabulated Preisach density (hy_preisach_table.h)
 * against exact answers.
 *   - the density file round trip: a grid written and read back gives the
 *     same relays, bit for bit, so every Everett sum is equal (==), on a
 *     hand grid with awkward spacings and on the density fitted to the
 *     measured file;
 *   - broken density files refused at the right file:line:col;
 *   - hy_preisach on a table against a direct simulation of its relays (an
 *     independent reference: each relay's state kept by hand), from negative
 *     saturation and from the demagnetised state, and its loop areas against
 *     the areas of the simulated loops' polygons;
 *   - the least-squares fit recovers a known table from its own FORCs.
 * argv[1]: the measured file (tests/data/forc/conventional_example.forc). */
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hy_file.h"
#include "hy_forc.h"
#include "hy_preisach.h"
#include "hy_preisach_table.h"
#include "hy_table.h"
#include "../core/tutil.h"

/* g written to memory and read back into *back (caller frees back->rho). */
static int write_read(const hy_forc_grid *g, hy_forc_grid *back)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    hy_error err = {0};
    CHECK(f && !hy_preisach_table_write(f, g, &err), "write: %s", err.msg);
    if (f)
        fclose(f);
    int rc = hy_preisach_table_read(buf, len, "mem.csv", back, &err);
    CHECK(!rc, "read back: %s", err.msg);
    free(buf);
    return rc;
}

/* The tables of a and b are the same relays bit for bit, and so are their
 * Everett sums at many (a, b). */
static void same_tables(const hy_forc_grid *a, const hy_forc_grid *b, const char *what)
{
    hy_preisach_table ta, tb;
    hy_error err = {0};
    CHECK(!hy_preisach_table_from_grid(&ta, a, &err) && !hy_preisach_table_from_grid(&tb, b, &err), "%s: %s", what,
          err.msg);
    CHECK(ta.n == tb.n && ta.n > 0, "%s: %zu vs %zu relays", what, ta.n, tb.n);
    if (ta.n == tb.n && ta.n) {
        CHECK(!memcmp(ta.alpha, tb.alpha, ta.n * sizeof *ta.alpha) && !memcmp(ta.beta, tb.beta, ta.n * sizeof *ta.beta) &&
                  !memcmp(ta.w, tb.w, ta.n * sizeof *ta.w),
              "%s: relays differ", what);
        double lo = a->hu0 - a->hc1, hi = a->hu1 + a->hc1;
        size_t differ = 0;
        for (int i = 0; i <= 40; i++)
            for (int j = 0; j <= i; j++) {
                double x = lo + (hi - lo) * i / 40.0, y = lo + (hi - lo) * j / 40.0;
                differ += hy_preisach_table_everett(&ta, x, y) != hy_preisach_table_everett(&tb, x, y);
            }
        differ += hy_preisach_table_everett(&ta, INFINITY, -INFINITY) != hy_preisach_table_everett(&tb, INFINITY, -INFINITY);
        CHECK(differ == 0, "%s: %zu Everett sums differ", what, differ);
    }
    hy_preisach_table_free(&ta);
    hy_preisach_table_free(&tb);
}

static void test_roundtrip_hand(void)
{
    enum { NC = 7, NU = 9 };
    double rho[NC * NU];
    for (int k = 0; k < NC * NU; k++) /* positive, negative (clipped), NaN (0) and tiny values */
        rho[k] = k % 11 == 3 ? NAN : k % 7 == 2 ? -0.3 : k % 5 == 1 ? 1e-300 : k == 4 ? 3e-310 : sin(0.37 * k) + 1.1;
    hy_forc_grid g = {0, 0.0211 * 3.1, -0.218002, 0.1731, NC, NU, rho}, back;
    if (!write_read(&g, &back)) {
        CHECK(back.nc == NC && back.nu == NU && back.hc0 == g.hc0 && back.hc1 == g.hc1 && back.hu0 == g.hu0 &&
                  back.hu1 == g.hu1,
              "grid read back: %zu x %zu, %.17g..%.17g, %.17g..%.17g", back.nc, back.nu, back.hc0, back.hc1, back.hu0,
              back.hu1);
        same_tables(&g, &back, "hand grid");
        free(back.rho);
    }
}

/* ---- broken files ------------------------------------------------------------ */

static void refused(const char *text, const char *where, const char *why)
{
    hy_forc_grid g;
    hy_error err = {0};
    int rc = hy_preisach_table_read(text, strlen(text), "d.csv", &g, &err);
    CHECK(rc == HY_EINVAL && !strncmp(err.msg, where, strlen(where)) && strstr(err.msg, why),
          "expected '%s ... %s', got rc %d '%s'", where, why, rc, err.msg);
    if (!rc)
        free(g.rho);
}

static void test_refusals(void)
{
    static const char ok[] = "# c\nhc,hu,mu\n0,0,1\n0.5,0,2\n0,1,3\n0.5,1,4\n";
    hy_forc_grid g;
    hy_error err = {0};
    CHECK(!hy_preisach_table_read(ok, strlen(ok), "d.csv", &g, &err) && g.nc == 2 && g.nu == 2 && g.rho[3] == 4,
          "a 2 x 2 file: %s", err.msg);
    if (!err.code)
        free(g.rho);
    refused("0,0,1\n", "d.csv:1:1:", "hc,hu,mu");
    refused("# only a comment\n", "d.csv:1:1:", "no column line");
    refused("hc,hu,mu\n0,0,1\n0.5,0,abc\n", "d.csv:3:7:", "finite decimal");
    refused("hc,hu,mu\n0,0,1\n0.5,0,nan\n", "d.csv:3:7:", "finite decimal");
    refused("hc,hu,mu\n0,0,1\n0.5,0,1e999\n", "d.csv:3:7:", "finite decimal");
    refused("hc,hu,mu\r\n0,0,1\r\n0.5,0,-2\r\n", "d.csv:3:7:", "not negative");
    refused("hc,hu,mu\n0,0,1\n0.5,0,0x1p3\n", "d.csv:3:7:", "finite decimal");
    refused("hc,hu,mu\n0,0,1\n0.5,0,0.0000000000000000000000000000000000000000000000000000000000000000001\n",
            "d.csv:3:7:", "finite decimal");
    refused("hc,hu,mu\n0,0,1,7\n", "d.csv:2:7:", "text after");
    refused("hc,hu,mu\n0,0\n", "d.csv:2:4:", "3 fields");
    refused("hc,hu,mu\n0,0,1\n0.5,0,2\n0,1,3\n0.6,1,4\n", "d.csv:5:1:", "H_c = 0.6");
    refused("hc,hu,mu\n0,0,1\n0.5,0,2\n0,1,3\n0.5,1,4\n0,3,5\n0.5,3,6\n", "d.csv:4:1:", "H_u = 1");
    refused("hc,hu,mu\n0,0,1\n0.5,0,2\n0,1,3\n0.5,1,4\n0,2,5\n", "d.csv:6:1:", "truncated?");
    refused("hc,hu,mu\n0,0,1\n0,1,3\n", "d.csv:3:1:", "at least 2 nodes");
    refused("hc,hu,mu\n-0.5,0,1\n0,0,1\n-0.5,1,1\n0,1,1\n", "d.csv:2:1:", "H_c = -0.5 < 0");
    char *big = malloc(5000);
    if (big) {
        strcpy(big, "hc,hu,mu\n0,0,1");
        memset(big + 14, ' ', 4200);
        strcpy(big + 4214, "\n");
        refused(big, "d.csv:2:4096:", "longer than 4095");
        free(big);
    }
}

/* ---- the model on a table against its relays simulated by hand ------------------- */

typedef struct sim {
    const hy_preisach_table *t;
    signed char *s; /* each relay's state, ±1 */
    double u;
} sim;

/* Moves the simulated relays monotonically from s->u to u; their output. */
static double sim_move(sim *s, double u)
{
    for (size_t k = 0; k < s->t->n; k++) {
        if (u > s->u && s->t->alpha[k] <= u)
            s->s[k] = 1;
        if (u < s->u && s->t->beta[k] >= u)
            s->s[k] = -1;
    }
    s->u = u;
    double y = 0;
    for (size_t k = 0; k < s->t->n; k++)
        y += s->t->w[k] * s->s[k];
    return y;
}

static void test_relays(void)
{
    enum { NC = 5, NU = 6 };
    double rho[NC * NU];
    for (int k = 0; k < NC * NU; k++)
        rho[k] = 0.5 + 0.4 * cos(1.3 * k) + (k % 4 == 0 ? 0 : 0.2);
    rho[7] = 0; /* a node without a relay */
    hy_forc_grid g = {0, 0.4, -0.5, 0.5, NC, NU, rho};
    hy_preisach_table t;
    hy_preisach p;
    hy_error err = {0};
    CHECK(!hy_preisach_table_from_grid(&t, &g, &err) && !hy_preisach_tabulated(&p, &t, &err), "table: %s", err.msg);
    double ys = 0;
    for (size_t k = 0; k < t.n; k++)
        ys += t.w[k];
    CHECK(p.ys == ys && t.n == NC * NU - 1, "ys %g vs %g, %zu relays", p.ys, ys, t.n);
    /* an input whose extrema avoid the nodes' fields, wiping out and nesting */
    static const double u[] = {-1.3, 0.61, -0.23, 0.37, -0.07, 0.19, -0.41, 0.83, -0.17, 0.29, -0.93, 1.2, -0.01};
    enum { N = sizeof u / sizeof u[0] };
    signed char st[NC * NU];
    for (int start = 0; start < 2; start++) {
        sim s = {&t, st, 0};
        for (size_t k = 0; k < t.n; k++) /* negative saturation, or demagnetised: up where α + β < 0 */
            st[k] = start == 0 ? -1 : t.alpha[k] + t.beta[k] < 0 ? 1 : -1;
        s.u = start == 0 ? -INFINITY : 0;
        p.start = start == 0 ? HY_PREISACH_NEGATIVE : HY_PREISACH_DEMAGNETISED;
        double y[N], worst = 0;
        CHECK(!hy_preisach_apply(&p, u, N, y, &err), "apply: %s", err.msg);
        for (size_t i = 0; i < N; i++)
            worst = fmax(worst, fabs(y[i] - sim_move(&s, u[i])));
        /* sums of the same weights in another order: rounding of a few ulps of ys */
        CHECK(worst <= 1e-14 * ys, "start %d: table model vs simulated relays: %.3g > 1e-14 ys", start, worst);
    }
    /* loop areas against the polygon of the simulated loop (fine steps: the jumps at the nodes) */
    double lo = -0.33, hi = 0.47, area;
    CHECK(!hy_preisach_loop_area(&p, lo, hi, &area, &err), "loop area: %s", err.msg);
    sim s = {&t, st, -INFINITY};
    for (size_t k = 0; k < t.n; k++)
        st[k] = -1;
    sim_move(&s, hi);
    sim_move(&s, lo);
    enum { M = 4001 };
    double *pu = malloc(2 * M * sizeof *pu), *py = malloc(2 * M * sizeof *py);
    if (pu && py) {
        for (size_t i = 0; i < M; i++) { /* up from lo to hi */
            pu[i] = lo + (hi - lo) * (double)i / (M - 1);
            py[i] = sim_move(&s, pu[i]);
        }
        for (size_t i = 0; i < M; i++) { /* then down */
            pu[M + i] = hi - (hi - lo) * (double)i / (M - 1);
            py[M + i] = sim_move(&s, pu[M + i]);
        }
        double poly = hy_table_area(pu, py, 2 * M); /* ∮ u dy of the staircase, jumps located to a step */
        /* each jump 2w sits within one step (hi − lo)/(M − 1) of its field: error <= 2 ys step */
        CHECK_CLOSE(area, poly, 2 * ys * (hi - lo) / (M - 1), "loop area vs the simulated polygon");
        CHECK(area > 0, "loop area %g", area);
    }
    free(pu);
    free(py);
    hy_preisach_table_free(&t);
}

/* ---- the fit ------------------------------------------------------------------ */

/* A table's own FORCs are fitted back to RMS ~ 0 on the same grid. */
static void test_fit_recovers(void)
{
    enum { NC = 4, NU = 7 };
    double rho[NC * NU];
    for (int k = 0; k < NC * NU; k++)
        rho[k] = k % 3 ? 1 + 0.5 * sin(0.7 * k) : 0;
    hy_forc_grid g = {0, 0.3, -0.45, 0.45, NC, NU, rho};
    hy_preisach_table t;
    hy_error err = {0};
    CHECK(!hy_preisach_table_from_grid(&t, &g, &err), "table: %s", err.msg);
    /* curves at H_a, H_b between the nodes' fields, from positive saturation */
    enum { NCURVE = 25, NPT = 25 };
    double ha[NCURVE], hb[NCURVE * NPT], m[NCURVE * NPT];
    size_t n[NCURVE], k = 0;
    for (int i = 0; i < NCURVE; i++) {
        ha[i] = -0.79 + 1.58 * i / (NCURVE - 1) + 0.0013;
        n[i] = 0;
        for (int j = 0; j < NPT; j++) {
            double b = ha[i] + (0.8 - ha[i]) * j / (NPT - 1);
            if (j && b <= hb[k - 1])
                continue;
            hb[k] = b;
            m[k] = 0.25 + 2 * hy_preisach_table_everett(&t, b, ha[i]) - 2 * hy_preisach_table_everett(&t, INFINITY, ha[i]);
            k++, n[i]++;
        }
    }
    hy_forc_data d;
    CHECK(!hy_forc_data_set(&d, NCURVE, ha, n, hb, m, &err), "data: %s", err.msg);
    hy_preisach_table_fitres res;
    double range = 0;
    for (size_t i = 0; i < k; i++)
        range = fmax(range, fabs(m[i] - m[0]));
    if (!hy_preisach_table_fit(&d, &g, NC, NU, &res, &err)) {
        /* the data are the model's own: the least squares reach 0 up to the ridge (1e-9) and the descent's stop */
        CHECK(res.rms <= 1e-6 * range, "fit of a table's own FORCs: RMS %.3g of range %.3g", res.rms, range);
        CHECK_CLOSE(res.offset, 0.25, 1e-6 * range, "offset (the data's saturation output)");
        free(res.g.rho);
    } else
        CHECK(0, "fit: %s", err.msg);
    hy_forc_data_free(&d);
    hy_preisach_table_free(&t);
}

/* The density fitted to the measured file: RMS well under the clipped
 * distribution's, and its file round trip bit for bit. */
static void test_measured(const char *path)
{
    char *text = NULL, why[256];
    size_t len;
    hy_forc_data d;
    hy_error err = {0};
    if (hy_file_read(path, 64u << 20, &text, &len, NULL, why, sizeof why)) {
        CHECK(0, "%s: %s", path, why);
        return;
    }
    CHECK(!hy_forc_read(&d, text, len, path, &err), "read: %s", err.msg);
    free(text);
    if (err.code)
        return;
    hy_forc_opts o = hy_forc_defaults();
    hy_forc_grid g;
    hy_forc_grid_auto(&d, &o, &g);
    CHECK(!hy_forc_rho(&d, &o, &g, NULL, &err), "rho: %s", err.msg);
    size_t nc, nu;
    hy_preisach_table_fit_shape(&g, &nc, &nu);
    CHECK(nc * nu <= HY_PREISACH_TABLE_FIT_NODES && nc >= 2 && nu >= 2, "fit grid %zu x %zu", nc, nu);
    hy_preisach_table_fitres res;
    if (!hy_preisach_table_fit(&d, &g, nc, nu, &res, &err)) {
        double lo = INFINITY, hi = -INFINITY;
        for (size_t k = 0; k < d.npoints; k++)
            lo = fmin(lo, d.m[k]), hi = fmax(hi, d.m[k]);
        /* 1.08 % measured (docs/FORC.md); the clipped distribution: 13.4 % */
        CHECK(res.rms < 0.015 * (hi - lo), "fitted RMS %.3g = %.3g %% of the range", res.rms,
              100 * res.rms / (hi - lo));
        hy_forc_grid back;
        if (!write_read(&res.g, &back)) {
            same_tables(&res.g, &back, "fitted density");
            free(back.rho);
        }
        free(res.g.rho);
    } else
        CHECK(0, "fit: %s", err.msg);
    hy_forc_grid_free(&g);
    hy_forc_data_free(&d);
}

int main(int argc, char **argv)
{
    gsl_set_error_handler_off();
    if (argc < 2) {
        fprintf(stderr, "usage: test_preisach_table FILE.forc\n");
        return 2;
    }
    test_roundtrip_hand();
    test_refusals();
    test_relays();
    test_fit_recovers();
    test_measured(argv[1]);
    return tu_finish("test_preisach_table");
}
