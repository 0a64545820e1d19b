/* SPDX-License-Identifier: MIT */
/* cmd_report.c: `hystviz report`: work-precision diagrams (error vs time,
 * log-log, one line per solver, DiffEqDevTools conventions) for the problems
 * of hy_workprec.h, written as CSV, a Markdown summary and SVG+PNG plots. */
#include "cmd_report.h"

#include "cli_util.h"
#include "hy_ode.h"
#include "hy_os.h"
#include "hy_out.h"
#include "hy_plot.h"
#include "hy_workprec.h"

#include <errno.h>
#include <gsl/gsl_errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static const char usage[] =
    "usage: hystviz report [-o DIR] [--quick] [--problems LIST] [--solvers LIST]\n"
    "                      [--repeats N] [--max-steps N] [--time-cap S]\n"
    "\n"
    "Work-precision benchmark: every solver at tolerances 1e-2 ... 1e-13 (GSL\n"
    "steppers with and without restarts at the input's breakpoints; the exact\n"
    "solver; Newmark at h = 1/750 ... 1/(750*2^8) s for Bouc-Wen), error against\n"
    "a reference, median wall time.  The GSL steppers choose their own steps\n"
    "between breakpoints; their error is measured at those step ends (CSV\n"
    "err_steps, plotted) and on a 300-point grid served by the cubic Hermite\n"
    "interpolant of the step ends (err_max, err_l2); see docs/SOLVERS.md.\n"
    "\n";

static const char tail[] =
    "Runs that fail or hit a cap are rows with status fail/stepcap/timecap/\n"
    "skipped; the report goes on.  Exit status 0 when the report is written.\n";

#define MAX_LIST 32

typedef struct ropts {
    const char *dir;
    int quick;
    char *problems[MAX_LIST], *solvers[MAX_LIST];
    int nproblems, nsolvers;
    hy_wp_cfg cfg;
    int set_repeats, set_steps, set_cap;
    char buf_p[1024], buf_s[1024];
} ropts;

static const char *problems_more(char *buf, size_t size, int doc);
static const char *solvers_more(char *buf, size_t size, int doc);

enum { OPT_DIR = CLI_FIRST, OPT_QUICK, OPT_PROBLEMS, OPT_SOLVERS, OPT_REPEATS, OPT_STEPS, OPT_CAP };
static const cli_opt report_opts[] = {
    {NULL, 'o', "DIR", "output folder (default gallery/report): report.csv,\n"
     "report.md, wp-PROBLEM.svg and .png", OPT_DIR, 0, NULL, NULL, NULL},
    {"quick", 0, NULL, "tolerances 1e-2, 1e-4, 1e-6, 2 repeats, caps 2e4 steps\n"
     "and 0.2 s (a few seconds in all; for tests)", OPT_QUICK, 0, NULL, NULL, NULL},
    {"problems", 0, "LIST", NULL, OPT_PROBLEMS, 0, problems_more, NULL, NULL},
    {"solvers", 0, "LIST", NULL, OPT_SOLVERS, 0, solvers_more, NULL, NULL},
    {"repeats", 0, "N", "timed repeats per run, median reported (default 5)", OPT_REPEATS, 0, NULL, NULL, NULL},
    {"max-steps", 0, "N", "ODE step cap between two breakpoints (default 2e5)", OPT_STEPS, 0, NULL, NULL, NULL},
    {"time-cap", 0, "S", "a run slower than S seconds is not repeated and tighter\n"
     "tolerances of that solver are skipped (default 2)", OPT_CAP, 0, NULL, NULL, NULL},
    {0},
};
static const cli_cmd report_cli = {"report", usage, tail, NULL, report_opts};

typedef struct runlist {
    hy_wp_run *r;
    size_t n, cap;
} runlist;

static int split_list(const char *s, char *buf, size_t bufsz, char **out, int *n)
{
    snprintf(buf, bufsz, "%s", s);
    *n = 0;
    for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ","))
        if (*n < MAX_LIST && *tok)
            out[(*n)++] = tok;
    return *n ? 0 : -1;
}

static int usage_error(const char *what, const char *arg)
{
    fprintf(stderr, "hystviz report: %s '%s' (try hystviz report --help)\n", what, arg);
    return 2;
}

/* Parses the options; returns 0, 1 for --help, or 2 (message printed). */
static int parse_opts(int argc, char **argv, ropts *o)
{
    long v;
    double d;
    cli_parser p;
    cli_parser_init(&p, &report_cli, argc, argv, 1);
    for (int id; (id = cli_next(&p)) != CLI_END;) {
        const char *a = p.optname, *val = p.val;
        if (id == CLI_STOP || id == CLI_ERROR)
            return id == CLI_STOP ? 1 : 2;
        if (id == OPT_QUICK) {
            o->quick = 1;
        } else if (id == OPT_DIR) {
            o->dir = val;
        } else if (id == OPT_PROBLEMS) {
            if (split_list(val, o->buf_p, sizeof o->buf_p, o->problems, &o->nproblems))
                return usage_error("empty problem list", val);
        } else if (id == OPT_SOLVERS) {
            if (split_list(val, o->buf_s, sizeof o->buf_s, o->solvers, &o->nsolvers))
                return usage_error("empty solver list", val);
        } else if (id == OPT_REPEATS) {
            if (cli_long(a, val, 1, 64, &v))
                return 2;
            o->cfg.repeats = (int)v;
            o->set_repeats = 1;
        } else if (id == OPT_STEPS) {
            if (cli_long(a, val, 1, 1000000000L, &v))
                return 2;
            o->cfg.max_steps = (unsigned long)v;
            o->set_steps = 1;
        } else if (id == OPT_CAP) {
            if (cli_num(a, val, &d) || !(d > 0))
                return usage_error("--time-cap needs seconds > 0, not", val);
            o->cfg.time_cap = d;
            o->set_cap = 1;
        }
    }
    for (int i = 0; i < o->nsolvers; i++)
        if (strcmp(o->solvers[i], "exact") && strcmp(o->solvers[i], "newmark") &&
            !hy_ode_stepper_known(o->solvers[i]))
            return usage_error("unknown solver", o->solvers[i]);
    return 0;
}

/* The error a run is ranked and plotted by: at the GSL stepper's own step
 * ends where measured (what its tolerance controls), else on the grid. */
static double run_err(const hy_wp_run *r)
{
    return isnan(r->err_steps) ? r->err_max : r->err_steps;
}

static int push_run(runlist *L, const hy_wp_run *r)
{
    hy_wp_run *p = hy_grow(L->r, L->n, &L->cap, sizeof *p, 256);
    if (!p)
        return -1;
    L->r = p;
    L->r[L->n++] = *r;
    return 0;
}

/* Tolerances of a solver on a problem: rtol decades, or Newmark steps. */
static int tolerances(const hy_wp_problem *p, const char *solver, int quick, double *tol)
{
    int n = 0;
    if (!strcmp(solver, "exact")) {
        tol[0] = 0;
        return 1;
    }
    if (p->kind == HY_WP_BOUCWEN) {
        for (int k = 0; k <= (quick ? 4 : 8); k++)
            tol[n++] = 1.0 / (750.0 * (double)(1 << k));
        return n;
    }
    if (quick) {
        tol[0] = 1e-2, tol[1] = 1e-4, tol[2] = 1e-6;
        return 3;
    }
    for (int e = 2; e <= 13; e++)
        tol[n++] = pow(10, -e);
    return n;
}

/* Every tolerance of one solver (one restart mode); after a step or time cap
 * the tighter tolerances are recorded as skipped. */
static int run_series(const hy_wp_problem *p, const char *solver, int restart, const ropts *o, runlist *L)
{
    double tol[16];
    int nt = tolerances(p, solver, o->quick, tol), stop = 0;
    hy_wp_run r;
    for (int k = 0; k < nt; k++) {
        if (stop) {
            r.tol = tol[k];
            r.status = HY_WP_SKIPPED;
            snprintf(r.msg, sizeof r.msg, "skipped: a looser tolerance hit the %s",
                     stop == HY_WP_STEPCAP ? "step cap" : "time cap");
            r.repeats = 0;
            r.err_max = r.err_l2 = r.err_steps = r.t_med = r.t_min = r.t_max = NAN;
            r.nfev = r.njev = r.steps = r.fails = 0;
        } else {
            hy_wp_run_solver(p, solver, restart, tol[k], &o->cfg, &r);
            if (r.status == HY_WP_STEPCAP || r.status == HY_WP_TIMECAP)
                stop = r.status;
        }
        if (push_run(L, &r))
            return -1;
    }
    return 0;
}

/* Every solver, in the order of the plots' colours and markers: exact, the
 * GSL steppers (hy_ode.h's list), newmark.  Returns how many (<= MAX_LIST). */
static int all_solvers(char **out)
{
    int n = 0;
    out[n++] = "exact";
    for (const char *const *s = hy_ode_stepper_names(); *s && n < MAX_LIST - 1; s++)
        out[n++] = (char *)*s;
    out[n++] = "newmark";
    return n;
}

/* Position of a solver in all_solvers (its colour and marker in every plot). */
static int solver_index(const char *name)
{
    char *all[MAX_LIST];
    int n = all_solvers(all);
    for (int i = 0; i < n; i++)
        if (!strcmp(all[i], name))
            return i;
    return 0;
}

static int run_problem(const hy_wp_problem *p, const ropts *o, runlist *L)
{
    char *all[MAX_LIST];
    int nall = all_solvers(all);
    char *const *sv = o->nsolvers ? o->solvers : all;
    int ns = o->nsolvers ? o->nsolvers : nall;
    for (int i = 0; i < ns; i++) {
        if (!hy_wp_solver_applies(p, sv[i]))
            continue;
        /* GSL steppers with and without restarts at the input's breakpoints;
         * Jiles-Atherton restarts at every reversal by its nature */
        int straight = hy_ode_stepper_known(sv[i]) && p->kind != HY_WP_JILES;
        if (run_series(p, sv[i], 1, o, L) || (straight && run_series(p, sv[i], 0, o, L)))
            return -1;
    }
    return 0;
}

/* Opens DIR/NAME through the output writer; message printed on failure. */
static FILE *open_out(hy_out *o, const char *dir, const char *name)
{
    char path[1100];
    hy_error err = {0};
    snprintf(path, sizeof path, "%s/%s", dir, name);
    if (hy_out_open(o, path, 0, &err)) {
        fprintf(stderr, "hystviz report: %s\n", err.msg);
        return NULL;
    }
    return hy_out_file(o);
}

static int close_out(hy_out *o)
{
    hy_error err = {0};
    if (hy_out_commit(o, &err)) {
        fprintf(stderr, "hystviz report: %s\n", err.msg);
        return -1;
    }
    return 0;
}

static int write_csv(const char *dir, const runlist *L)
{
    hy_out o;
    FILE *f = open_out(&o, dir, "report.csv");
    if (!f)
        return -1;
    hy_wp_csv_header(f);
    for (size_t i = 0; i < L->n; i++)
        hy_wp_csv_row(f, &L->r[i]);
    return close_out(&o);
}

/* The plot title as plain text: the markup names \gamma and \sigma_0 as letters. */
static void plain_title(const char *in, char *out, size_t size)
{
    static const char *const from[] = {"\\gamma", "\\sigma_0"}, *const to[] = {"γ", "σ0"};
    size_t j = 0;
    while (*in && j + 4 < size) {
        int hit = 0;
        for (int k = 0; k < 2 && !hit; k++)
            if (!strncmp(in, from[k], strlen(from[k]))) {
                j += (size_t)snprintf(out + j, size - j, "%s", to[k]);
                in += strlen(from[k]);
                hit = 1;
            }
        if (!hit)
            out[j++] = *in++;
    }
    out[j] = 0;
}

/* Markdown summary of one problem: a row per solver and restart mode. */
static void md_problem(FILE *f, const hy_wp_problem *p, const runlist *L)
{
    char title[160];
    plain_title(p->title, title, sizeof title);
    fprintf(f, "\n## %s\n\n%s; reference: %s.\n\n![work-precision %s](wp-%s.png)\n\n", p->name, title,
            p->ref_method, p->name, p->name);
    fputs("| solver | restarts | ok/runs | smallest max error | its tol | its time (ms) | its RHS evals "
          "| its grid error (Hermite) | time to 1e-6 (ms) | not ok |\n|---|---|---|---|---|---|---|---|---|---|\n", f);
    for (size_t i = 0; i < L->n;) {
        size_t j = i, ok = 0;
        const hy_wp_run *best = NULL, *to6 = NULL;
        char bad[96] = "";
        for (; j < L->n && !strcmp(L->r[j].problem, L->r[i].problem) && !strcmp(L->r[j].solver, L->r[i].solver) &&
               L->r[j].restart == L->r[i].restart;
             j++) {
            const hy_wp_run *r = &L->r[j];
            if (r->status == HY_WP_OK || r->status == HY_WP_TIMECAP) {
                ok += r->status == HY_WP_OK;
                if (!best || run_err(r) < run_err(best))
                    best = r;
                if (run_err(r) <= 1e-6 && (!to6 || r->t_med < to6->t_med))
                    to6 = r;
            }
            if (r->status != HY_WP_OK && strlen(bad) < 60)
                snprintf(bad + strlen(bad), sizeof bad - strlen(bad), "%s%s@%.0e", bad[0] ? " " : "",
                         hy_wp_status_name(r->status), r->tol);
        }
        if (!strcmp(L->r[i].problem, p->name)) {
            const hy_wp_run *r = &L->r[i];
            fprintf(f, "| %s | %s | %zu/%zu | ", r->solver, r->restart < 0 ? "-" : r->restart ? "on" : "off", ok, j - i);
            if (best && !isnan(best->err_steps))
                fprintf(f, "%.2e | %.0e | %.3f | %lu | %.2e | ", best->err_steps, best->tol, 1e3 * best->t_med,
                        best->nfev, best->err_max);
            else if (best)
                fprintf(f, "%.2e | %.0e | %.3f | %lu | - | ", best->err_max, best->tol, 1e3 * best->t_med, best->nfev);
            else
                fputs("- | - | - | - | - | ", f);
            if (to6)
                fprintf(f, "%.3f | %s |\n", 1e3 * to6->t_med, bad[0] ? bad : "-");
            else
                fprintf(f, "- | %s |\n", bad[0] ? bad : "-");
        }
        i = j;
    }
}

static int write_md(const ropts *o, const hy_wp_problem *P, int np, const runlist *L, double total)
{
    hy_out out;
    FILE *f = open_out(&out, o->dir, "report.md");
    if (!f)
        return -1;
    fprintf(f, "# hystviz work-precision report%s\n\n", o->quick ? " (--quick)" : "");
    fprintf(f, "%zu runs in %.1f s; %d timed repeats (median), step cap %lu between breakpoints, time cap %g s.\n"
               "Error: max norm against the reference (absolute, in N; Bouc-Wen in m).  The GSL steppers choose\n"
               "their own steps between the input's breakpoints; their error is taken at those step ends (what\n"
               "the tolerance controls), and 'its grid error' is that of the 300-point output grid served by the\n"
               "cubic Hermite interpolant of the step ends (its cost is in the time).  exact and newmark: the\n"
               "300-point grid.  GSL steppers: atol = rtol * 1e-2 * g(0)/sigma0 (the scale of z); 'tol' of\n"
               "newmark is h in s.\n"
               "Full data: report.csv.\n",
            L->n, total, o->cfg.repeats, o->cfg.max_steps, o->cfg.time_cap);
    for (int i = 0; i < np; i++)
        md_problem(f, &P[i], L);
    return close_out(&out);
}

/* Plot data: x (error) and y (time) of the OK runs of one series. */
typedef struct pseries {
    double x[16], y[16];
    char label[32];
} pseries;

static void fill_series(const runlist *L, size_t i0, size_t i1, pseries *ps, hy_series *s, int idx)
{
    size_t n = 0;
    for (size_t i = i0; i < i1 && n < 16; i++)
        if (L->r[i].status == HY_WP_OK || L->r[i].status == HY_WP_TIMECAP) {
            ps->x[n] = fmax(run_err(&L->r[i]), 1e-17);
            ps->y[n++] = L->r[i].t_med;
        }
    snprintf(ps->label, sizeof ps->label, "%s", L->r[i0].solver);
    memset(s, 0, sizeof *s);
    s->x = ps->x;
    s->y = ps->y;
    s->n = n;
    s->colour.palette = idx % HY_PALETTE_SIZE;
    s->style = n == 1 ? HY_LINE_NONE : idx / HY_PALETTE_SIZE ? HY_LINE_DASHED : HY_LINE_SOLID;
    s->marker = idx % 2 ? HY_MARKER_SQUARE : HY_MARKER_CIRCLE;
    s->marker_filled = idx / HY_PALETTE_SIZE == 0;
    s->marker_size = 3;
    s->label = ps->label;
}

static int plot_problem(const ropts *o, const hy_wp_problem *p, const runlist *L)
{
    pseries ps[2][16];
    hy_series ser[2][16];
    size_t ns[2] = {0, 0};
    for (size_t i = 0; i < L->n;) {
        size_t j = i;
        while (j < L->n && !strcmp(L->r[j].solver, L->r[i].solver) && L->r[j].restart == L->r[i].restart &&
               !strcmp(L->r[j].problem, L->r[i].problem))
            j++;
        int panel = L->r[i].restart == 0;
        if (!strcmp(L->r[i].problem, p->name) && ns[panel] < 16) {
            fill_series(L, i, j, &ps[panel][ns[panel]], &ser[panel][ns[panel]], solver_index(L->r[i].solver));
            ns[panel]++;
        }
        i = j;
    }
    int npanels = ns[1] ? 2 : 1;
    /* shared time range, stretched upwards by 80 % of its decades: room for the legend */
    double tlo = INFINITY, thi = 0;
    for (int k = 0; k < 2; k++)
        for (size_t i = 0; i < ns[k]; i++)
            for (size_t j = 0; j < ser[k][i].n; j++) {
                tlo = fmin(tlo, ser[k][i].y[j]);
                thi = fmax(thi, ser[k][i].y[j]);
            }
    hy_range yr = {.log = 1};
    if (thi > 0 && tlo < thi) {
        yr.lo = tlo / 1.5;
        yr.hi = thi * 1.5 * pow(thi / tlo, 0.8);
    }
    char title[2][200];
    hy_axes ax[2];
    for (int k = 0; k < npanels; k++) {
        snprintf(title[k], sizeof title[k], "%s%s", p->title,
                 npanels == 1 ? "" : k ? ": straight through" : ": restarts at breakpoints");
        ax[k] = (hy_axes){.series = ser[k], .nseries = ns[k], .xlabel = p->kind == HY_WP_JILES ? "max error of B (T) on the output grid"
                                                                    : "max error (GSL: at its own steps)",
                          .ylabel = "time (s)",
                          .title = title[k], .x = {.log = 1}, .y = yr, .legend = HY_LEGEND_BEST, .grid = 1};
    }
    hy_figure fig = {.width = hy_cm(npanels * 11.0), .height = hy_cm(10), .dpi = 150, .axes = ax, .nrows = 1,
                     .ncols = npanels, .font_size = 8};
    const char *ext[2] = {"svg", "png"};
    int fmt[2] = {HY_FORMAT_SVG, HY_FORMAT_PNG};
    for (int k = 0; k < 2; k++) {
        char path[1100];
        hy_error err = {0};
        snprintf(path, sizeof path, "%s/wp-%s.%s", o->dir, p->name, ext[k]);
        if (hy_figure_write(&fig, path, fmt[k], &err)) {
            fprintf(stderr, "hystviz report: %s\n", err.msg);
            return -1;
        }
    }
    return 0;
}

/* mkdir -p for dir. */
static int make_dir(const char *dir)
{
    char buf[1024];
    snprintf(buf, sizeof buf, "%s", dir);
    for (char *s = buf + 1;; s++) {
        char c = *s;
        if (c == '/' || c == 0) {
            *s = 0;
            if (mkdir(buf, 0777) && errno != EEXIST) {
                fprintf(stderr, "hystviz report: cannot create %s: %s\n", buf, strerror(errno));
                return -1;
            }
            *s = c;
            if (!c)
                return 0;
        }
    }
}

static int run_all(ropts *o, hy_wp_problem *P, int np)
{
    runlist L = {0};
    double t0 = hy_wp_now();
    int rc = 0;
    for (int i = 0; i < np && !rc; i++) {
        fprintf(stderr, "hystviz report: %s (reference: %s) ...\n", P[i].name, P[i].ref_method);
        if (run_problem(&P[i], o, &L)) {
            fprintf(stderr, "hystviz report: out of memory\n");
            rc = 1;
        }
    }
    double total = hy_wp_now() - t0;
    if (!rc && (write_csv(o->dir, &L) || write_md(o, P, np, &L, total)))
        rc = 1;
    for (int i = 0; i < np && !rc; i++)
        if (plot_problem(o, &P[i], &L))
            rc = 1;
    size_t bad = 0;
    for (size_t i = 0; i < L.n; i++)
        bad += L.r[i].status != HY_WP_OK;
    if (!rc)
        printf("report: %zu runs (%zu not ok) on %d problems in %.1f s; wrote %s/report.csv, report.md, wp-*.svg/png\n",
               L.n, bad, np, total, o->dir);
    free(L.r);
    return rc;
}

/* Into buf: "comma-separated, of:", the words and tail, broken into lines
 * that fit the help's description column. */
static const char *wrapped(char *buf, size_t size, char *const *words, int n, const char *tail)
{
    char t[256], *w[MAX_LIST * 2], *save = NULL;
    snprintf(t, sizeof t, "%s", tail);
    int m = 0;
    for (; m < n && m < MAX_LIST; m++)
        w[m] = words[m];
    for (char *tok = strtok_r(t, " ", &save); tok && m < MAX_LIST * 2; tok = strtok_r(NULL, " ", &save))
        w[m++] = tok;
    size_t len = (size_t)snprintf(buf, size, "comma-separated, of:"), col = len;
    for (int i = 0; i < m && len < size; i++) {
        int brk = col + 1 + strlen(w[i]) > 56;
        len += (size_t)snprintf(buf + len, size - len, "%s%s", brk ? "\n" : " ", w[i]);
        col = (brk ? 0 : col + 1) + strlen(w[i]);
    }
    return buf;
}

/* --problems, --solvers: listed from their tables */
static const char *problems_more(char *buf, size_t size, int doc)
{
    char *probs[MAX_LIST];
    int np = 0;
    (void)doc;
    for (const char *const *n = hy_wp_problem_names(); *n && np < MAX_LIST; n++)
        probs[np++] = (char *)*n;
    return wrapped(buf, size, probs, np,
                   "(default all; jiles: Fig. 1's Jiles-Atherton system, each GSL stepper, always "
                   "restarted at reversals)");
}

static const char *solvers_more(char *buf, size_t size, int doc)
{
    char *solv[MAX_LIST];
    (void)doc;
    return wrapped(buf, size, solv, all_solvers(solv), "(default all)");
}

int hy_cmd_report(int argc, char **argv)
{
    gsl_set_error_handler_off();
    ropts o = {.dir = "gallery/report", .cfg = hy_wp_cfg_defaults()};
    int rc = parse_opts(argc, argv, &o);
    if (rc == 1)
        return 0;
    if (rc)
        return rc;
    if (o.quick) {
        o.cfg.repeats = o.set_repeats ? o.cfg.repeats : 2;
        o.cfg.max_steps = o.set_steps ? o.cfg.max_steps : 20000;
        o.cfg.time_cap = o.set_cap ? o.cfg.time_cap : 0.2;
    }
    const char *const *names = hy_wp_problem_names();
    int np = 0;
    if (!o.nproblems)
        for (; names[o.nproblems]; o.nproblems++)
            o.problems[o.nproblems] = (char *)names[o.nproblems];
    hy_wp_problem *P = calloc((size_t)o.nproblems, sizeof *P);
    if (!P || make_dir(o.dir)) {
        free(P);
        return 1;
    }
    hy_out_sweep(o.dir); /* temporaries of killed runs */
    for (; np < o.nproblems; np++) {
        hy_error err = {0};
        if (hy_wp_problem_init(&P[np], o.problems[np], o.quick, &err)) {
            fprintf(stderr, "hystviz report: %s\n", err.msg);
            rc = err.code == HY_EINVAL ? 2 : 1;
            np++;
            break;
        }
    }
    if (!rc)
        rc = run_all(&o, P, np);
    for (int i = 0; i < np; i++)
        hy_wp_problem_free(&P[i]);
    free(P);
    return rc;
}
