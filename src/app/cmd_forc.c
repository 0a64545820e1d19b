/* SPDX-License-Identifier: MIT */
/* cmd_forc.c: `hystviz forc`: a FORC file (MicroMag 2900/3900 or CSV) or the
 * FORC protocol on a Preisach model -> the FORC distribution on an (H_c, H_u)
 * grid as CSV (src/core/hy_forc.h; docs/FORC.md). */
#include "cmd_forc.h"

#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli_util.h"
#include "hy_file.h"
#include "hy_forc.h"
#include "hy_forc_plot.h"
#include "hy_out.h"
#include "hy_preisach_table.h"
#include "hy_plot.h"

#define FORC_FILE_MAX (64u << 20) /* bytes of a FORC file read */

static const char forc_usage[] =
    "usage: hystviz forc FILE [--sf N | --sc0 A --sc1 B [--ramp HC]] [--grid SPEC] [--drift]\n"
    "                    [--no-extend] [-o OUT.csv] [--figure OUT.svg|pdf|png [--levels L,...] [--vmax V]]\n"
    "                    [--density-out DENSITY.csv] [-v]\n"
    "       hystviz forc --preisach DIST:HC,SIGMA [--curves N] [--range LO:HI] [--hsat H] ...\n"
    "\n"
    "The FORC distribution rho(H_a, H_b) = -1/2 d2M/dH_a dH_b of a measured FORC\n"
    "file (MicroMag 2900/3900 text, or CSV rows H_a,H_b,M), or of the FORC protocol\n"
    "run on a classical Preisach model, by local second-order polynomial regression\n"
    "(Pike, Roberts & Verosub 1999) over the points within (SF + 1/2) field steps\n"
    "of each node in H_a and in H_b ((2 SF + 1)^2 points on a regular grid).\n"
    "Below each curve's first point M is extended as M(H_a, H_a) (constant\n"
    "extension) so that H_c = 0 is defined.  Writes CSV 'hc,hu,rho' on the grid\n"
    "H_c = (H_b - H_a)/2, H_u = (H_a + H_b)/2, H_u slowest; rho is 'nan' outside\n"
    "the data.  Units: the file's (Hybrid SI: fields in T, rho in A m2/T2; cgs:\n"
    "Oe and emu/Oe2).  A file that cannot be read exits 2 with file:line:col and\n"
    "writes nothing.  docs/FORC.md has the equations.\n"
    "\n";

static const char forc_tail[] =
    "grid SPEC: HC0:HC1:NC,HU0:HU1:NU (NC x NU nodes; default: the data's H_c >= 0\n"
    "  and H_u ranges, one node per field step)\n"
    "preisach DIST:HC,SIGMA or DIST:MA,SA,MB,SB (DIST gaussian or lorentzian): the\n"
    "  density of hy_preisach.h, saturation y_s = 1; the protocol: N curves with\n"
    "  H_a from HI down to LO, each from H_b = H_a up to HI in the same step, after\n"
    "  saturation at HSAT (default: LO, HI the centres -/+ 4 widths, HSAT = HI + 8\n"
    "  widths)\n"
    "examples:\n"
    "  hystviz forc tests/data/forc/conventional_example.forc --sf 3 -o rho.csv -v\n"
    "  hystviz forc --preisach gaussian:0.3,0.1 --curves 200 -o rho.csv\n";

enum {
    OPT_SF = CLI_FIRST, OPT_SC0, OPT_SC1, OPT_RAMP, OPT_GRID, OPT_DRIFT, OPT_NOEXT, OPT_OUT, OPT_VERB,
    OPT_PREISACH, OPT_CURVES, OPT_RANGE, OPT_HSAT, OPT_CURVES_OUT, OPT_FIGURE, OPT_LEVELS, OPT_VMAX, OPT_DENSITY_OUT
};
static const cli_opt forc_opts[] = {
    {"sf", 0, "N", "smoothing factor SF >= 1 (default 3; may be fractional)", OPT_SF, 0, NULL, NULL, NULL},
    {"sc0", 0, "A", "variable smoothing: SF = A at H_c = 0 ...", OPT_SC0, 0, NULL, NULL, NULL},
    {"sc1", 0, "B", "... growing linearly to B at H_c = --ramp and beyond", OPT_SC1, 0, NULL, NULL, NULL},
    {"ramp", 0, "HC", "where the variable SF reaches sc1 (default: the grid's largest H_c)", OPT_RAMP, 0, NULL,
     NULL, NULL},
    {"grid", 0, "SPEC", "the (H_c, H_u) grid (below)", OPT_GRID, 0, NULL, NULL, NULL},
    {"drift", 0, NULL, "drift correction: each curve's M times cal(first)/cal(curve)\n"
     "(the calibration points of a MicroMag file)", OPT_DRIFT, 0, NULL, NULL, NULL},
    {"no-extend", 0, NULL, "no extension below the curves' first points (H_c near 0 is then nan)", OPT_NOEXT, 0,
     NULL, NULL, NULL},
    {"preisach", 0, "SPEC", "run the FORC protocol on a Preisach model instead of reading a file", OPT_PREISACH, 0,
     NULL, NULL, NULL},
    {"curves", 0, "N", "curves of the --preisach protocol (default 100)", OPT_CURVES, 0, NULL, NULL, NULL},
    {"range", 0, "LO:HI", "reversal fields of the --preisach protocol", OPT_RANGE, 0, NULL, NULL, NULL},
    {"hsat", 0, "H", "saturating field of the --preisach protocol", OPT_HSAT, 0, NULL, NULL, NULL},
    {"curves-out", 0, "FILE", "also write the curves as CSV 'ha,hb,m' (after drift correction)", OPT_CURVES_OUT, 0,
     NULL, NULL, NULL},
    {"density-out", 0, "FILE", "also fit a Preisach density to the curves by least squares (mu >= 0 on a grid of\n"
     "at most 400 nodes over rho's ranges) and write it as a density file 'hc,hu,mu'\n"
     "(the tabulated density of a Preisach scene; docs/FORC.md); -v prints its RMS of M", OPT_DENSITY_OUT, 0, NULL, NULL, NULL},
    {"output", 'o', "FILE", "the CSV of rho (default: standard output unless --figure)", OPT_OUT, 0, NULL, NULL,
     NULL},
    {"figure", 0, "FILE", "also draw the FORC diagram (.svg, .pdf: the map an embedded image,\n"
     "contours and text vectors; .png): diverging colours centred at 0,\n"
     "contours, colour bar, axes mu0 H_c and mu0 H_u in mT when the file's units are known",
     OPT_FIGURE, 0, NULL, NULL, NULL},
    {"levels", 0, "L,...", "contour levels as fractions of the colour scale\n"
     "(default 0,+-0.1,+-0.3,+-0.5,+-0.7,+-0.9; 0 is grey)", OPT_LEVELS, 0, NULL, NULL, NULL},
    {"vmax", 0, "V", "colour scale -V..V in rho's unit (default: the largest |rho| at\n"
     "H_c >= (SF + 1/2) field steps, beyond the constant extension's reach,\n"
     "so the reversible ridge at H_c = 0 saturates; every node with --no-extend)", OPT_VMAX, 0, NULL, NULL, NULL},
    {"verbose", 'v', NULL, "print what was read and the time of the read and of the regression", OPT_VERB, 0, NULL,
     NULL, NULL},
    {0},
};
static const cli_cmd forc_cli = {"forc", forc_usage, forc_tail, "FILE", forc_opts};

typedef struct forc_args {
    const char *file, *out, *curves_out, *preisach, *grid, *range, *figure, *density_out;
    hy_forc_plot_opts po;
    int format;
    hy_forc_opts o;
    long curves;
    double hsat;
    int drift, verbose, have_hsat, have_sc;
} forc_args;

/* "A:B" or "A:B:N" numbers; 0 or -1 (message printed). */
static int parse_span(const char *opt, const char *s, double *a, double *b, long *n)
{
    char buf[256];
    if (strlen(s) >= sizeof buf) {
        fprintf(stderr, "hystviz forc: %s: too long\n", opt);
        return -1;
    }
    strcpy(buf, s);
    char *c1 = strchr(buf, ':'), *c2 = c1 ? strchr(c1 + 1, ':') : NULL;
    if (!c1 || (n ? !c2 : c2 != NULL)) {
        fprintf(stderr, "hystviz forc: %s: expected %s (got '%s')\n", opt, n ? "LO:HI:N" : "LO:HI", s);
        return -1;
    }
    *c1 = 0;
    if (c2)
        *c2 = 0;
    if (cli_num(opt, buf, a) || cli_num(opt, c1 + 1, b) || (n && cli_long(opt, c2 + 1, 1, 4000000, n)))
        return -1;
    if (!(*b > *a) && !(n && *n == 1 && *b == *a)) {
        fprintf(stderr, "hystviz forc: %s: %g:%g does not ascend\n", opt, *a, *b);
        return -1;
    }
    return 0;
}

static int parse_grid(const char *s, hy_forc_grid *g)
{
    const char *comma = strchr(s, ',');
    char first[256];
    if (!comma || (size_t)(comma - s) >= sizeof first) {
        fprintf(stderr, "hystviz forc: --grid: expected HC0:HC1:NC,HU0:HU1:NU (got '%s')\n", s);
        return -1;
    }
    memcpy(first, s, (size_t)(comma - s));
    first[comma - s] = 0;
    long nc, nu;
    if (parse_span("--grid", first, &g->hc0, &g->hc1, &nc) || parse_span("--grid", comma + 1, &g->hu0, &g->hu1, &nu))
        return -1;
    if (nc * nu > 4000000) {
        fprintf(stderr, "hystviz forc: --grid: %ld x %ld nodes (at most 4e6)\n", nc, nu);
        return -1;
    }
    g->nc = (size_t)nc;
    g->nu = (size_t)nu;
    return 0;
}

/* --levels: 0 or 2 (message printed). */
static int parse_levels(hy_forc_plot_opts *po, const char *v)
{
    po->nlevels = 0;
    for (const char *s = v;; s++) {
        char *end;
        double x = strtod(s, &end);
        if (end == s || !isfinite(x) || (*end && *end != ',') || po->nlevels == HY_FORC_PLOT_LEVELS) {
            fprintf(stderr, "hystviz forc: --levels: '%s' is not a list of at most %d numbers\n", v,
                    HY_FORC_PLOT_LEVELS);
            return 2;
        }
        po->levels[po->nlevels++] = x;
        if (!*end)
            return 0;
        s = end;
    }
}

static int take(forc_args *a, int id, const char *s, const char *v)
{
    switch (id) {
    case CLI_ARG:
        if (a->file) {
            fprintf(stderr, "hystviz forc: one FILE only (got '%s' and '%s')\n", a->file, v);
            return 2;
        }
        a->file = v;
        return 0;
    case OPT_SF: return cli_num(s, v, &a->o.sf) ? 2 : 0;
    case OPT_SC0: a->have_sc |= 1; return cli_num(s, v, &a->o.sc0) ? 2 : 0;
    case OPT_SC1: a->have_sc |= 2; return cli_num(s, v, &a->o.sc1) ? 2 : 0;
    case OPT_RAMP: return cli_num(s, v, &a->o.ramp) ? 2 : 0;
    case OPT_GRID: a->grid = v; return 0;
    case OPT_DRIFT: a->drift = 1; return 0;
    case OPT_NOEXT: a->o.extend = 0; return 0;
    case OPT_OUT: a->out = v; return 0;
    case OPT_VERB: a->verbose = 1; return 0;
    case OPT_PREISACH: a->preisach = v; return 0;
    case OPT_CURVES: return cli_long(s, v, 2, 20000, &a->curves) ? 2 : 0;
    case OPT_RANGE: a->range = v; return 0;
    case OPT_HSAT: a->have_hsat = 1; return cli_num(s, v, &a->hsat) ? 2 : 0;
    case OPT_CURVES_OUT: a->curves_out = v; return 0;
    case OPT_DENSITY_OUT: a->density_out = v; return 0;
    case OPT_FIGURE:
        a->figure = v;
        if ((a->format = hy_format_from_path(v)) < 0) {
            fprintf(stderr, "hystviz forc: --figure: '%s' does not end in .svg, .pdf or .png\n", v);
            return 2;
        }
        return 0;
    case OPT_VMAX:
        if (cli_num(s, v, &a->po.vmax))
            return 2;
        if (!(a->po.vmax > 0)) {
            fprintf(stderr, "hystviz forc: --vmax must be > 0 (got %s)\n", v);
            return 2;
        }
        return 0;
    case OPT_LEVELS: return parse_levels(&a->po, v);
    default: return 2;
    }
}

/* 0, 1 (help printed) or 2 (message printed). */
static int parse_args(int argc, char **argv, forc_args *a)
{
    memset(a, 0, sizeof *a);
    a->o = hy_forc_defaults();
    a->po = hy_forc_plot_defaults();
    a->curves = 100;
    cli_parser p;
    cli_parser_init(&p, &forc_cli, argc, argv, 1);
    for (int id; (id = cli_next(&p)) != CLI_END;) {
        if (id == CLI_STOP || id == CLI_ERROR)
            return id == CLI_STOP ? 1 : 2;
        if (take(a, id, p.optname, p.val))
            return 2;
    }
    if (!a->file == !a->preisach) {
        fprintf(stderr, "hystviz forc: give a FILE or --preisach SPEC%s (see hystviz forc --help)\n",
                a->file ? ", not both" : "");
        return 2;
    }
    if (a->have_sc && a->have_sc != 3) {
        fprintf(stderr, "hystviz forc: --sc0 and --sc1 go together\n");
        return 2;
    }
    if (!a->preisach && (a->range || a->have_hsat || a->curves != 100)) {
        fprintf(stderr, "hystviz forc: --curves, --range and --hsat belong to --preisach\n");
        return 2;
    }
    return 0;
}

/* Wall-clock (CLOCK_MONOTONIC) or this process's CPU time, in s: on a shared
 * machine the two differ by the time spent waiting for a core. */
static double now(clockid_t c)
{
    struct timespec t;
    clock_gettime(c, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* The Preisach model of --preisach and its protocol; 0 or 2 (message printed). */
static int preisach_data(const forc_args *a, hy_forc_data *d)
{
    char dist[32];
    const char *colon = strchr(a->preisach, ':');
    if (!colon || (size_t)(colon - a->preisach) >= sizeof dist) {
        fprintf(stderr, "hystviz forc: --preisach: expected DIST:HC,SIGMA or DIST:MA,SA,MB,SB (got '%s')\n",
                a->preisach);
        return 2;
    }
    memcpy(dist, a->preisach, (size_t)(colon - a->preisach));
    dist[colon - a->preisach] = 0;
    int kind = hy_preisach_dist_find(dist);
    if (kind < 0) {
        fprintf(stderr, "hystviz forc: --preisach: unknown distribution '%s' (gaussian or lorentzian)\n", dist);
        return 2;
    }
    double v[5];
    int n = 0;
    for (const char *s = colon + 1; n < 5; s++) {
        char *end;
        v[n++] = strtod(s, &end);
        if (end == s || !isfinite(v[n - 1]) || (*end && *end != ',')) {
            fprintf(stderr, "hystviz forc: --preisach: '%s' is not a list of numbers\n", colon + 1);
            return 2;
        }
        if (!*end)
            break;
        s = end;
    }
    if (n != 2 && n != 4) {
        fprintf(stderr, "hystviz forc: --preisach: 2 numbers (HC,SIGMA) or 4 (MA,SA,MB,SB), got %s%d\n",
                n == 5 ? "at least " : "", n);
        return 2;
    }
    hy_preisach p;
    hy_error err = {0};
    int rc = n == 2 ? hy_preisach_symmetric(&p, kind, v[0], v[1], 1.0, &err)
                    : hy_preisach_init(&p, kind, v[0], v[1], v[2], v[3], 1.0, &err);
    if (rc) {
        fprintf(stderr, "hystviz forc: --preisach: %s\n", err.msg);
        return 2;
    }
    double w = fmax(p.sa, p.sb), lo = fmin(p.mb - 4 * p.sb, p.ma - 4 * p.sa), hi = fmax(p.ma + 4 * p.sa, p.mb + 4 * p.sb);
    if (a->range && parse_span("--range", a->range, &lo, &hi, NULL))
        return 2;
    hy_forc_protocol pr = {.hsat = a->have_hsat ? a->hsat : hi + 8 * w, .ha_lo = lo, .ha_hi = hi, .hb_max = hi,
                           .ncurves = (size_t)a->curves};
    if ((rc = hy_forc_preisach(d, &pr, &p, &err))) {
        fprintf(stderr, "hystviz forc: %s\n", err.msg);
        return cli_exit_status(rc);
    }
    return 0;
}

static int read_data(const forc_args *a, hy_forc_data *d)
{
    char *buf, why[160];
    size_t len;
    if (hy_file_read(a->file, FORC_FILE_MAX, &buf, &len, NULL, why, sizeof why)) {
        fprintf(stderr, "hystviz forc: %s: %s\n", a->file, why);
        return 2;
    }
    hy_error err = {0};
    int rc = hy_forc_read(d, buf, len, a->file, &err);
    free(buf);
    if (rc) {
        fprintf(stderr, "hystviz forc: %s\n", err.msg);
        return cli_exit_status(rc);
    }
    return 0;
}

static void write_curves(FILE *f, const hy_forc_data *d)
{
    fprintf(f, "ha,hb,m\n");
    for (size_t i = 0; i < d->ncurves; i++)
        for (size_t j = 0; j < d->curve[i].n; j++)
            fprintf(f, "%.17g,%.17g,%.17g\n", d->curve[i].ha, d->hb[d->curve[i].first + j],
                    d->m[d->curve[i].first + j]);
}

/* --density-out: the least-squares density (hy_preisach_table_fit) on the fit
 * grid of rho's; 0 or an exit status (message printed). */
static int fit_density(const forc_args *a, const hy_forc_data *d, const hy_forc_grid *g,
                       hy_preisach_table_fitres *fit)
{
    size_t nc, nu;
    hy_error err = {0};
    hy_preisach_table_fit_shape(g, &nc, &nu);
    double t0 = now(CLOCK_PROCESS_CPUTIME_ID);
    int rc = hy_preisach_table_fit(d, g, nc, nu, fit, &err);
    if (rc) {
        fprintf(stderr, "hystviz forc: --density-out: %s\n", err.msg);
        return cli_exit_status(rc);
    }
    double lo = INFINITY, hi = -INFINITY;
    for (size_t k = 0; k < d->npoints; k++)
        lo = fmin(lo, d->m[k]), hi = fmax(hi, d->m[k]);
    if (a->verbose)
        fprintf(stderr, "hystviz forc: Preisach density by least squares on %zu x %zu nodes (%zu free parameters, %zu "
                "sweeps, CPU %.3f ms): RMS of M over all %zu points %.6g (%.3g %% of the range of M), saturation "
                "output %.6g\n", nc, nu, fit->nfree, fit->iters, 1e3 * (now(CLOCK_PROCESS_CPUTIME_ID) - t0),
                d->npoints, fit->rms, 100 * fit->rms / (hi > lo ? hi - lo : 1), fit->offset);
    return 0;
}

/* Every output or none; 0 or 1 (message printed). */
static int write_all(const forc_args *a, const hy_forc_data *d, const hy_forc_grid *g, const hy_forc_plot_opts *po,
                     const hy_forc_grid *density)
{
    hy_out o[4];
    hy_error err = {0};
    int n = 0, rc = 0;
    const char *path[4] = {a->out ? a->out : a->figure || a->density_out ? NULL : "-", a->curves_out, a->figure,
                           a->density_out};
    for (int i = 0; i < 4 && !rc; i++) {
        if (!path[i])
            continue;
        if (hy_out_open(&o[n], path[i], HY_OUT_FOLLOW | HY_OUT_HOLD, &err)) {
            rc = 1;
            break;
        }
        FILE *f = hy_out_file(&o[n++]);
        if (i == 0)
            hy_forc_write_csv(g, f);
        else if (i == 1)
            write_curves(f, d);
        else if (i == 2)
            rc = hy_forc_plot_write(g, po, f, a->format, &err) ? 1 : 0;
        else
            rc = hy_preisach_table_write(f, density, &err) ? 1 : 0;
    }
    for (int i = 0; i < n && !rc; i++)
        rc = hy_out_finish(&o[i], &err) ? 1 : 0;
    for (int i = 0; i < n && !rc; i++)
        rc = hy_out_publish(&o[i], &err) ? 1 : 0;
    for (int i = 0; i < n; i++)
        hy_out_abort(&o[i]);
    if (rc)
        fprintf(stderr, "hystviz forc: %s\n", err.msg);
    return rc;
}

int hy_cmd_forc(int argc, char **argv)
{
    forc_args a;
    int rc = parse_args(argc, argv, &a);
    if (rc)
        return rc == 1 ? 0 : 2;
    gsl_set_error_handler_off();
    hy_forc_grid g = {0};
    if (a.grid && parse_grid(a.grid, &g))
        return 2;
    hy_forc_data d;
    double t0 = now(CLOCK_MONOTONIC), c0 = now(CLOCK_PROCESS_CPUTIME_ID);
    rc = a.preisach ? preisach_data(&a, &d) : read_data(&a, &d);
    if (rc)
        return rc;
    double t1 = now(CLOCK_MONOTONIC), c1 = now(CLOCK_PROCESS_CPUTIME_ID);
    hy_error err = {0};
    if (a.drift && hy_forc_drift(&d, &err)) {
        fprintf(stderr, "hystviz forc: %s: %s\n", a.file ? a.file : "--preisach", err.msg);
        hy_forc_data_free(&d);
        return 2;
    }
    if (!a.grid)
        hy_forc_grid_auto(&d, &a.o, &g);
    size_t nfit = 0;
    double t2 = now(CLOCK_MONOTONIC), c2 = now(CLOCK_PROCESS_CPUTIME_ID);
    rc = hy_forc_rho(&d, &a.o, &g, &nfit, &err);
    double t3 = now(CLOCK_MONOTONIC), c3 = now(CLOCK_PROCESS_CPUTIME_ID);
    if (rc) {
        fprintf(stderr, "hystviz forc: %s\n", err.msg);
        hy_forc_data_free(&d);
        hy_forc_grid_free(&g);
        return cli_exit_status(rc);
    }
    if (a.verbose) {
        double da, db;
        hy_forc_steps(&d, &da, &db);
        fprintf(stderr, "hystviz forc: %s: %zu curves, %zu points, %zu calibration points, fields in %s, "
                "moments in %s, steps %.6g / %.6g\n", a.file ? a.file : "Preisach protocol", d.ncurves, d.npoints,
                d.ncal, *d.field_unit ? d.field_unit : "(no unit)", *d.moment_unit ? d.moment_unit : "(no unit)", da,
                db);
        fprintf(stderr, "hystviz forc: %s %.3f ms (CPU %.3f ms), regression %.3f ms (CPU %.3f ms; %zu x %zu "
                "nodes, %zu fitted)\n", a.preisach ? "protocol" : "read", 1e3 * (t1 - t0), 1e3 * (c1 - c0),
                1e3 * (t3 - t2), 1e3 * (c3 - c2), g.nc, g.nu, nfit);
    }
    hy_forc_plot_opts po = a.po;
    if (a.figure) {
        double da, db;
        hy_forc_steps(&d, &da, &db);
        double sf = a.o.sc1 > 0 ? a.o.sc0 : a.o.sf;
        if (!(po.vmax > 0))
            po.vmax = hy_forc_plot_max(&g, a.o.extend ? (sf + 0.5) * (a.o.db > 0 ? a.o.db : db) : -INFINITY);
        if (!(po.vmax > 0))
            po.vmax = hy_forc_plot_max(&g, -INFINITY);
        po.field_to_mt = isfinite(d.field_to_tesla) ? 1e3 * d.field_to_tesla : 0;
        po.rho_unit = d.units == HY_FORC_UNITS_HYBRID_SI ? "A m²/T²"
                      : d.units == HY_FORC_UNITS_CGS     ? "emu/Oe²"
                      : d.units == HY_FORC_UNITS_SI      ? "A m²/(A/m)²"
                                                         : "";
    }
    hy_preisach_table_fitres fit = {0};
    if (a.density_out && (rc = fit_density(&a, &d, &g, &fit))) {
        hy_forc_data_free(&d);
        hy_forc_grid_free(&g);
        return rc;
    }
    rc = write_all(&a, &d, &g, &po, &fit.g);
    free(fit.g.rho);
    hy_forc_data_free(&d);
    hy_forc_grid_free(&g);
    return rc;
}
