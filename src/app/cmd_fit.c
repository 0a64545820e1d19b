/* SPDX-License-Identifier: MIT */
/* cmd_fit.c: `hystviz fit`: a scene's [model] keys fitted to its measured
 * data (`hystviz fit SCENE --free KEY,...`, src/pipeline/scene_fit.c; issue
 * 32 item 2, docs/FIT.md "Fitting a scene"), and the Bouc-Wen benchmark as an
 * identification task (`--benchmark boucwen`: seeds/001, Sections 4-5; issue
 * 32 item 4): training data as Section 4 prescribes, a grey-box fit of
 * Table 1 (src/core/hy_bwfit.c over the least-squares engine hy_fit.c), then
 * e_RMS (Eq. 6) on the two test sets, touched only after the fit. */
#include "cmd_fit.h"

#include "cli_opt.h"
#include "cli_util.h"
#include "cmd_boucwen.h"
#include "hy_bwfit.h"
#include "hy_jobs.h"
#include "hy_os.h"
#include "hy_out.h"
#include "hy_plot.h"
#include "hy_signal.h"
#include "scene_fit.h"
#include "scene_run.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static const char usage[] =
    "usage: hystviz fit SCENE --free KEY[,KEY...] [options]\n"
    "       hystviz fit --benchmark boucwen [options]\n"
    "\n"
    "Identifies a model's parameters from data by nonlinear least squares\n"
    "(GSL multifit_nlinear: Levenberg-Marquardt with geodesic acceleration;\n"
    "bounds kept by a smooth map; standard errors, 95 % intervals,\n"
    "correlations and unidentifiable parameters from the Jacobian at the\n"
    "optimum; docs/FIT.md).\n"
    "\n"
    "SCENE --free KEY,...: fits the scene's [model] number keys KEY (KEY or\n"
    "model.KEY) to its measured data: the model driven by the measured\n"
    "inputs of the [data] that [input] names (or of each --data NAME in turn,\n"
    "all at once), each record from [input] start, against the measured\n"
    "outputs.  Each key is kept in the range a page's slider gives it (the\n"
    "schema's bounds; an open one 1/100 to 100 times the scene's value),\n"
    "logarithmic when that spans a factor 50 or more.  --set S.K=V applies\n"
    "to the scene first, as render's --set: a free key's start and range,\n"
    "a fixed key's value.  Start 0 is the scene's values; --starts N more\n"
    "come from a Latin hypercube over the ranges (--seed).  A start the\n"
    "model refuses is reported and skipped.\n"
    "Prints the estimates, standard errors, 95 % intervals, correlations,\n"
    "condition number, unidentifiable keys and fit statistics; -o writes the\n"
    "scene with the estimates written in (hystviz render draws data and\n"
    "fit), --residuals a figure of the residuals against the measured input.\n"
    "\n"
    "--benchmark boucwen: the Bouc-Wen benchmark (Noel & Schoukens) as the\n"
    "identification task it was made for.  Training data: R realisations of\n"
    "the random-phase multisine (5-150 Hz, std 50 N, 8192 samples a period at\n"
    "750 Hz, phases seeded S+q), each simulated from rest for 1+P periods at\n"
    "15 kHz (Newmark) and decimated, output noise of 8e-3 mm RMS (Gaussian,\n"
    "0-375 Hz, seeded (S+q) xor 0x6e6f697365), the first period dropped:\n"
    "realisation q is rows 8192.. of\n"
    "  hystviz boucwen data --signal multisine --seed S+q --periods P+1\n"
    "Fitted: m, c, k, alpha, beta*gamma, beta*delta and nu (beta, gamma and\n"
    "delta enter the model only as beta*gamma and beta*delta: beta cannot be\n"
    "told apart; the eight of Table 1 are checked at the optimum and flagged,\n"
    "or fitted with --params all), from a start 50 % off every parameter\n"
    "(m x1.5, c x0.5, k x1.5, alpha x0.5, beta*gamma x1.5, beta*delta x0.5,\n"
    "nu x1.5).  Then, and only then, e_RMS on the official test multisine\n"
    "(yval_multisine.txt) and on the test sine sweep (validation-sweep, the\n"
    "fitted model against Table 1's), beside the best published black-box\n"
    "model (PNLSS, 1.21e-5 m).  Progress goes to standard error.\n"
    "\n";

static const char tail[] =
    "Exit status: 0 done, 1 the fit or a test set failed, 2 usage error (a\n"
    "bad key, a bad data file: nothing written).\n"
    "\n"
    "examples:\n"
    "  hystviz fit friction.scene --free sigma0,fc,fs,vs -o fitted.scene --residuals resid.svg\n"
    "  hystviz fit --benchmark boucwen          (minutes: 165 s in all in docs/FIT.md's run [bench fit-boucwen])\n";

enum { OPT_BENCH = CLI_FIRST, OPT_SEED, OPT_REAL, OPT_PERIODS, OPT_NOISE, OPT_PARAMS, OPT_FIXNU, OPT_STARTS,
       OPT_DATA_DIR, OPT_QUIET, OPT_FREE, OPT_DATA, OPT_OUT, OPT_RESID, OPT_SET };
static const cli_opt fit_opts[] = {
    {"free", 0, "KEY,...", "the [model] keys to fit (repeatable)", OPT_FREE, 0, NULL, NULL, NULL},
    {"data", 0, "NAME,...", "the [data] sets fitted at once, each driving the\n"
     "model in turn (default: [input] data; repeatable)", OPT_DATA, 0, NULL, NULL, NULL},
    {"set", 0, "S.K=V", "override a scene key before fitting, as render's\n"
     "--set: a free key's start, a fixed key's value (repeatable)", OPT_SET, CLI_SCENE_KEY, NULL, NULL, NULL},
    {"output", 'o', "FILE", "the fitted scene: SCENE with the estimates written in", OPT_OUT, 0, NULL, NULL, NULL},
    {"residuals", 0, "FIG", "a figure (.svg, .png, .pdf) of the residuals", OPT_RESID, 0, NULL, NULL, NULL},
    {"benchmark", 0, "NAME", "the identification benchmark to run: boucwen", OPT_BENCH, 0, NULL, NULL, NULL},
    {"seed", 0, "S", "seed of the design of starts; --benchmark: of the\n"
     "training data (1)", OPT_SEED, 0, NULL, NULL, NULL},
    {"realisations", 0, "R", "multisine realisations in the training data (1)", OPT_REAL, 0, NULL, NULL, NULL},
    {"periods", 0, "P", "steady-state periods kept per realisation (1)", OPT_PERIODS, 0, NULL, NULL, NULL},
    {"noise", 0, "RMS", "output noise RMS in metres (8e-6 = 8e-3 mm)", OPT_NOISE, 0, NULL, NULL, NULL},
    {"params", 0, "SET", "identifiable: m c k alpha beta*gamma beta*delta nu\n"
     "(default); all: the eight of Table 1 (beta, gamma and\n"
     "delta come out unidentifiable)", OPT_PARAMS, 0, NULL, NULL, NULL},
    {"fix-nu", 0, NULL, "keep nu at Table 1's 1 instead of fitting it", OPT_FIXNU, 0, NULL, NULL, NULL},
    {"starts", 0, "N", "Latin-hypercube starts over the bounds besides the\n"
     "scene's values or the documented one (0)", OPT_STARTS, 0, NULL, NULL, NULL},
    {"data-dir", 0, "DIR", "folder of uval_multisine.txt and yval_multisine.txt\n"
     "(default $HY_BOUCWEN_DATA, the installed copy, the source tree's)", OPT_DATA_DIR, 0, NULL, NULL, NULL},
    {"quiet", 'q', NULL, "no progress on standard error", OPT_QUIET, 0, NULL, NULL, NULL},
    {.group = cli_policy_opts},
    {.group = cli_jobs_opts}, /* the starts in parallel, spare threads difference the Jacobian */
    {0},
};
static const cli_cmd fit_cli = {"fit", usage, tail, "SCENE", fit_opts};

enum { MAX_KEYS = 16, MAX_DATA = 16 };

typedef struct fopts {
    const char *bench, *data_dir, *scene, *out, *resid;
    char keys[MAX_KEYS][64], data[MAX_DATA][64];
    size_t nkeys, ndata;
    hy_bwfit_opts bw;
    int all, quiet, seed_set;
    hy_scene_policy pol; /* --include-dir, --max-work */
    const char **dirs;
    char **sets;         /* --set, as given (argv's) */
    size_t nsets;
} fopts;

typedef struct prog {
    double t0;
    pthread_mutex_t mu;
    const char *unit; /* of the RSS: " m^2" (the benchmark), "" (a scene: the data's units squared) */
} prog;

static void progress(const hy_fit_progress *pr, void *ctx)
{
    prog *pg = ctx;
    pthread_mutex_lock(&pg->mu);
    if (pr->done)
        fprintf(stderr, "hystviz fit: start %zu/%zu %s after %zu iterations, RSS %.6g%s (%zu evaluations, %.1f s)\n",
                pr->start + 1, pr->nstarts, pr->status ? "failed" : "ended", pr->iter, pr->rss, pg->unit, pr->nevals,
                hy_now() - pg->t0);
    else
        fprintf(stderr, "hystviz fit: start %zu/%zu iteration %zu: RSS %.6g%s (%zu evaluations, %.1f s)\n",
                pr->start + 1, pr->nstarts, pr->iter, pr->rss, pg->unit, pr->nevals, hy_now() - pg->t0);
    pthread_mutex_unlock(&pg->mu);
}

static int bad(const char *fmt, const char *v)
{
    fprintf(stderr, "hystviz fit: ");
    fprintf(stderr, fmt, v);
    fprintf(stderr, " (see hystviz fit --help)\n");
    return CLI_USAGE;
}

/* A comma-separated list appended to list[*n] (at most max); 0 or 2. */
static int split_list(const char *opt, const char *v, char (*list)[64], size_t *n, size_t max)
{
    for (const char *p = v;;) {
        size_t l = strcspn(p, ",");
        if (!l || l >= 64 || *n >= max) {
            fprintf(stderr, "hystviz fit: %s '%s': %s (see hystviz fit --help)\n", opt, v,
                    !l ? "an empty name" : l >= 64 ? "a name longer than 63 characters" : "too many names (16)");
            return CLI_USAGE;
        }
        snprintf(list[(*n)++], 64, "%.*s", (int)l, p);
        if (!p[l])
            return 0;
        p += l + 1;
    }
}

/* One option; 0 or 2 (message printed). */
static int take(fopts *o, int id, const char *v)
{
    long l;
    switch (id) {
    case OPT_BENCH: o->bench = v; return 0;
    case OPT_DATA_DIR: o->data_dir = v; return 0;
    case OPT_QUIET: o->quiet = 1; return 0;
    case OPT_FIXNU: o->bw.fit_nu = 0; return 0;
    case CLI_ARG: o->scene = v; return 0;
    case OPT_OUT: o->out = v; return 0;
    case OPT_RESID: o->resid = v; return 0;
    case OPT_SET: o->sets[o->nsets++] = (char *)v; return 0; /* checked where it is applied (hy_scene_set) */
    case OPT_FREE: return split_list("--free", v, o->keys, &o->nkeys, MAX_KEYS);
    case OPT_DATA: return split_list("--data", v, o->data, &o->ndata, MAX_DATA);
    case OPT_PARAMS:
        if (strcmp(v, "all") && strcmp(v, "identifiable"))
            return bad("--params '%s' must be identifiable or all", v);
        o->all = strcmp(v, "all") == 0;
        return 0;
    case OPT_NOISE:
        if (cli_num("--noise", v, &o->bw.noise) || o->bw.noise < 0)
            return bad("--noise '%s' must be a finite RMS >= 0 in metres", v);
        return 0;
    case OPT_SEED:
        if (cli_long("--seed", v, 0, 1L << 40, &l))
            return CLI_USAGE;
        o->bw.seed = (uint64_t)l;
        o->seed_set = 1;
        return 0;
    case OPT_REAL:
    case OPT_PERIODS:
    case OPT_STARTS:
    case CLI_JOBS:
        if (cli_long(id == OPT_REAL ? "--realisations" : id == OPT_PERIODS ? "--periods" : id == OPT_STARTS ? "--starts"
                     : "--jobs", v, id == OPT_STARTS ? 0 : 1, id == CLI_JOBS ? 64 : 100, &l))
            return CLI_USAGE;
        if (id == OPT_REAL)
            o->bw.realisations = (size_t)l;
        else if (id == OPT_PERIODS)
            o->bw.periods = (size_t)l;
        else if (id == OPT_STARTS)
            o->bw.fit.starts = (size_t)l;
        else
            o->bw.fit.jobs = (int)l;
        return 0;
    }
    int pt = cli_policy_take(&o->pol, o->dirs, "fit", id, v);
    return pt > 0 ? 0 : CLI_USAGE;
}

/* Reads the file `name` of the benchmark's data folder (n values). */
static int read_set(const fopts *o, const char *name, double **x, size_t *n)
{
    char path[4200];
    double fs;
    hy_error err = {0};
    if (hy_cmd_boucwen_data_file(o->data_dir, name, path, sizeof path)) {
        fprintf(stderr, "hystviz fit: %s not found; give --data-dir DIR\n", name);
        return -1;
    }
    if (hy_signal_read(path, x, n, &fs, &err)) {
        fprintf(stderr, "hystviz fit: %s\n", err.msg);
        return -1;
    }
    return 0;
}

static void print_training(const fopts *o)
{
    const hy_bwfit_opts *b = &o->bw;
    printf("Bouc-Wen benchmark as an identification task (Noel & Schoukens; seeds/001, Sections 4-5)\n");
    printf("training data: %zu realisation(s) x %zu period(s) of %zu samples at 750 Hz = %zu samples: random-phase\n"
           "  multisine 5-150 Hz, std 50 N (phase seeds %llu..%llu), simulated from rest for %zu periods at 15 kHz\n"
           "  (Newmark, Table 1), decimated 2-2-5, output noise %g m RMS (Gaussian, 0-375 Hz), first period dropped\n",
           b->realisations, b->periods, b->n, b->realisations * b->periods * b->n, (unsigned long long)b->seed,
           (unsigned long long)(b->seed + b->realisations - 1), b->periods + 1, b->noise);
}

/* The table against Table 1: estimate, error, its standard error. */
static void print_truth(const fopts *o, const hy_fit_param *prm, const double *xt, const double *x0,
                        const hy_fit_result *res)
{
    (void)o;
    printf("\n%-11s %13s %13s %13s %10s %11s %8s\n", "parameter", "Table 1", "start", "estimate", "error %",
           "std error", "err/SE");
    for (size_t j = 0; j < res->p; j++)
        printf("%-11s %13.6g %13.6g %13.9g %10.2e %11.4g %8.2f\n", prm[j].name, xt[j], x0[j], res->theta[j],
               100 * (res->theta[j] / xt[j] - 1), res->se[j], (res->theta[j] - xt[j]) / res->se[j]);
}

/* All eight of Table 1 at the optimum of the seven (beta at Table 1's value,
 * gamma and delta from the products): the engine's rank test flags them. */
static void check_all_eight(const fopts *o, const hy_bwfit_train *tr, const hy_fit_result *res7)
{
    hy_bwfit_opts o8 = o->bw;
    o8.set = HY_BWFIT_ALL;
    hy_boucwen_params p;
    hy_bwfit_to_params(&o->bw, res7->theta, &p);
    hy_boucwen_params t;
    hy_boucwen_params_default(&t);
    double th8[8] = {p.m, p.c, p.k, p.alpha, t.beta, p.gamma / t.beta, p.delta / t.beta, p.nu};
    hy_fit_param prm[8];
    size_t n8 = hy_bwfit_params(&o8, prm, NULL, NULL);
    hy_fit_result r8;
    hy_error err = {0};
    printf("\nall eight of Table 1 at this optimum (beta = %g, gamma = beta*gamma / beta, delta = beta*delta / beta):\n",
           t.beta);
    if (hy_bwfit_evaluate(&o8, tr, th8, &r8, &err)) {
        printf("  not evaluated: %s\n", err.msg);
        return;
    }
    for (size_t j = 0; j < n8; j++)
        if (r8.unident[j])
            printf("  %-6s unidentifiable (%s)\n", prm[j].name,
                   r8.unident[j] & HY_FIT_NULLDIR ? "a direction the data do not see" : "error wider than its range");
    printf("  smallest relative singular value %.3g (rank tolerance %.3g from the Jacobian's estimated error\n"
           "  %.3g), condition number %.3g\n", r8.sv[n8 - 1] / r8.sv[0], r8.rank_tol, r8.jac_err, r8.cond);
    hy_fit_result_free(&r8);
}

static int boucwen(fopts *o)
{
    double t0 = hy_now();
    double *uv = NULL, *yv = NULL;
    size_t nu_, ny_;
    /* the test files are located (not read) first, so that a missing one
       stops the command before minutes of fitting */
    char path[4200];
    if (hy_cmd_boucwen_data_file(o->data_dir, "yval_multisine.txt", path, sizeof path)) {
        fprintf(stderr, "hystviz fit: yval_multisine.txt not found; give --data-dir DIR\n");
        return CLI_USAGE;
    }
    if (o->all)
        o->bw.set = HY_BWFIT_ALL;
    prog pg = {t0, PTHREAD_MUTEX_INITIALIZER, " m^2"};
    if (!o->quiet) {
        o->bw.fit.progress = progress;
        o->bw.fit.progress_ctx = &pg;
    }
    hy_boucwen_params truth;
    hy_boucwen_params_default(&truth);
    hy_bwfit_train tr;
    hy_error err = {0};
    if (hy_bwfit_make_train(&o->bw, &truth, &tr, &err)) {
        fprintf(stderr, "hystviz fit: %s\n", err.msg);
        return cli_exit_status(err.code);
    }
    print_training(o);
    hy_fit_param prm[8];
    double x0[8], xt[8];
    size_t p = hy_bwfit_params(&o->bw, prm, x0, xt);
    printf("free: %zu parameters%s; start: each 50 %% off Table 1; %zu design start(s) besides\n", p,
           o->bw.fit_nu ? "" : " (nu fixed at 1)", o->bw.fit.starts);
    fflush(stdout);
    hy_fit_result res;
    double tf = hy_now();
    if (hy_bwfit_run(&o->bw, &tr, NULL, &res, &err)) {
        fprintf(stderr, "hystviz fit: %s\n", err.msg);
        hy_bwfit_train_free(&tr);
        return CLI_FAILED;
    }
    double fit_s = hy_now() - tf;
    hy_fit_problem shown = {res.n, p, prm, NULL, NULL, NULL, NULL};
    printf("\n");
    hy_fit_report(stdout, &shown, &res);
    print_truth(o, prm, xt, x0, &res);
    if (!o->all)
        check_all_eight(o, &tr, &res);
    hy_bwfit_train_free(&tr);
    /* the test sets: read and used only now */
    hy_boucwen_params fitted;
    hy_bwfit_to_params(&o->bw, res.theta, &fitted);
    double e_ms = NAN, e_sw = NAN;
    int rc = read_set(o, "uval_multisine.txt", &uv, &nu_) || read_set(o, "yval_multisine.txt", &yv, &ny_);
    if (!rc && nu_ != ny_) {
        fprintf(stderr, "hystviz fit: uval_multisine.txt has %zu values, yval_multisine.txt %zu\n", nu_, ny_);
        rc = -1;
    }
    if (!rc && (hy_bwfit_erms_multisine(&fitted, uv, yv, nu_, &e_ms, &err) ||
                hy_bwfit_erms_sweep(&fitted, &truth, &e_sw, &err))) {
        fprintf(stderr, "hystviz fit: %s\n", err.msg);
        rc = -1;
    }
    if (!rc) {
        printf("\ntest sets (noiseless; touched only after the fit), e_RMS of Eq. (6), simulation:\n");
        printf("  multisine (official yval_multisine, 8192 samples)        %.3e m\n", e_ms);
        printf("  sine sweep (validation-sweep, fitted vs Table 1's model)  %.3e m\n", e_sw);
        printf("  best published black-box model (PNLSS, 217 parameters)   1.21e-05 m\n");
        printf("time: fit %.1f s wall (%zu model evaluations, %zu iterations, -j %d), whole command %.1f s\n", fit_s,
               res.nevals, res.iter, o->bw.fit.jobs, hy_now() - t0);
    }
    free(uv);
    free(yv);
    hy_fit_result_free(&res);
    return rc ? CLI_FAILED : CLI_OK;
}

/* ---- hystviz fit SCENE --free KEY,... (src/pipeline/scene_fit.c) ---- */

/* The residual figure: residual against the measured input, one series per
 * data set, markers. */
static int write_residuals(const hy_scene_fit *f, const char *path, hy_error *err)
{
    int fmt = hy_format_from_path(path);
    if (fmt < 0)
        return hy_error_set(err, HY_EINVAL, "--residuals %s: the name must end in .svg, .png or .pdf", path);
    hy_series *se = calloc(f->ndata, sizeof *se);
    char (*lab)[128] = calloc(f->ndata, sizeof *lab);
    if (!se || !lab) {
        free(se);
        free(lab);
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    }
    for (size_t d = 0; d < f->ndata; d++) {
        size_t a = f->off[d];
        snprintf(lab[d], sizeof lab[d], "%s: model - measured", f->dname[d]);
        se[d] = (hy_series){f->u + a, f->res.resid + a, f->off[d + 1] - a, HY_LINE_NONE, {(int)d + 1, {0, 0, 0}},
                            0, HY_MARKER_CIRCLE, 2.5, 1, lab[d]};
    }
    hy_axes ax = {0};
    ax.series = se;
    ax.nseries = f->ndata;
    ax.xlabel = "measured input";
    ax.ylabel = "residual";
    ax.title = "hystviz fit: residuals at the estimate";
    ax.legend = HY_LEGEND_TOP_RIGHT;
    ax.grid = 1;
    hy_figure fig = {0};
    fig.axes = &ax;
    hy_out out;
    int rc = hy_out_open(&out, path, HY_OUT_FOLLOW, err);
    if (!rc) {
        rc = hy_figure_write_out(&fig, &out, fmt, err); /* finished, or aborted */
        if (!rc)
            rc = hy_out_publish(&out, err);
    }
    free(se);
    free(lab);
    return rc;
}

/* The fitted scene through the one writer; it must parse and load where it
 * goes (its relative paths: next to the scene, or where they still resolve). */
static int write_fitted(const hy_scene_fit *f, const char *path, const hy_scene_policy *pol, hy_error *err)
{
    hy_scene_run chk;
    int rc = hy_scene_run_load_text(&chk, path, f->text, strlen(f->text), NULL, 0, pol, err);
    if (rc)
        return hy_error_set(err, HY_EINVAL, "-o %s: the fitted scene would not load there (%s); write it next to the "
                            "scene, whose relative paths it keeps", path, err->msg);
    hy_scene_run_free(&chk);
    hy_out out;
    if ((rc = hy_out_open(&out, path, HY_OUT_FOLLOW, err)))
        return rc;
    fputs(f->text, hy_out_file(&out));
    return hy_out_commit(&out, err);
}

static void print_fit(const fopts *o, const hy_scene_fit *f, double secs)
{
    printf("hystviz fit %s: %zu free key(s), %zu measured points in", o->scene, f->pb.p, f->pb.n);
    for (size_t d = 0; d < f->ndata; d++)
        printf("%s [data %s] (%zu record%s)", d ? "," : "", f->dname[d], f->nrec[d], f->nrec[d] == 1 ? "" : "s");
    printf("\n%-12s %13s %13s %13s %s\n", "key", "start", "lower bound", "upper bound", "scale");
    for (size_t j = 0; j < f->pb.p; j++)
        printf("%-12s %13.6g %13.6g %13.6g %s\n", f->prm[j].name, f->x0[j], f->prm[j].lo, f->prm[j].hi,
               f->prm[j].scale == HY_FIT_LOG ? "log" : "linear");
    printf("starts: the scene's values and %zu from the design (seed %llu); %zu failed\n\n", f->res.nstarts - 1,
           (unsigned long long)o->bw.fit.seed, f->res.nfailed);
    for (size_t s = 0; s < f->res.nstarts; s++)
        if (f->res.start[s].status)
            printf("start %zu skipped: %s\n", s + 1, f->res.start[s].msg);
    hy_fit_report(stdout, &f->pb, &f->res);
    printf("time: %.2f s for the fit (-j %d), %.2f s in all\n", f->res.seconds, o->bw.fit.jobs, secs);
}

static int hy_cmd_fit_scene(fopts *o)
{
    if (!o->scene)
        return bad("%sgive a SCENE and --free KEY,... (or --benchmark boucwen)", "");
    if (!o->nkeys)
        return bad("%s: --free KEY,... names the [model] keys to fit", o->scene);
    if (o->resid && hy_format_from_path(o->resid) < 0)
        return bad("--residuals '%s': the name must end in .svg, .png or .pdf", o->resid);
    double t0 = hy_now();
    hy_scene_fit_opts so;
    hy_scene_fit_opts_default(&so);
    const char *keys[MAX_KEYS], *data[MAX_DATA];
    for (size_t j = 0; j < o->nkeys; j++)
        keys[j] = o->keys[j];
    for (size_t d = 0; d < o->ndata; d++)
        data[d] = o->data[d];
    so.pol = &o->pol;
    so.free_keys = keys, so.nfree = o->nkeys, so.data = data, so.ndata = o->ndata;
    so.sets = o->sets, so.nsets = o->nsets;
    so.fit.starts = o->bw.fit.starts;
    so.fit.jobs = o->bw.fit.jobs;
    so.fit.seed = o->seed_set ? o->bw.seed : 1;
    o->bw.fit.seed = so.fit.seed;
    prog pg = {t0, PTHREAD_MUTEX_INITIALIZER, ""};
    if (!o->quiet) {
        so.fit.progress = progress;
        so.fit.progress_ctx = &pg;
    }
    hy_scene_fit f;
    hy_error err = {0};
    int rc = hy_scene_fit_run(o->scene, &so, &f, &err);
    if (rc) {
        fprintf(stderr, "hystviz fit: %s\n", err.msg);
        return rc == HY_ENUM ? CLI_FAILED : cli_exit_status(rc);
    }
    print_fit(o, &f, hy_now() - t0);
    rc = o->out ? write_fitted(&f, o->out, &o->pol, &err) : HY_OK;
    if (!rc && o->resid)
        rc = write_residuals(&f, o->resid, &err);
    if (rc)
        fprintf(stderr, "hystviz fit: %s\n", err.msg);
    else if (o->out || o->resid)
        printf("wrote%s%s%s%s\n", o->out ? " " : "", o->out ? o->out : "", o->resid ? " " : "",
               o->resid ? o->resid : "");
    hy_scene_fit_free(&f);
    return rc ? cli_exit_status(rc) : CLI_OK;
}


/* The command once its options are read: a scene fit or the benchmark. */
static int fit_main(fopts *o)
{
    if (!o->bench)
        return hy_cmd_fit_scene(o);
    if (strcmp(o->bench, "boucwen"))
        return bad("unknown benchmark '%s' (boucwen)", o->bench);
    if (o->scene)
        return bad("--benchmark takes no scene ('%s')", o->scene);
    if (o->nsets)
        return bad("--benchmark takes no --set ('%s'): it has no scene", o->sets[0]);
    return boucwen(o);
}

int hy_cmd_fit(int argc, char **argv)
{
    fopts o = {0};
    o.pol = hy_scene_policy_default();
    o.dirs = calloc((size_t)argc + 1, sizeof *o.dirs); /* --include-dir: one per argument at most */
    o.sets = calloc((size_t)argc + 1, sizeof *o.sets); /* --set: likewise */
    if (!o.dirs || !o.sets) {
        free(o.dirs);
        free(o.sets);
        fprintf(stderr, "hystviz fit: out of memory\n");
        return CLI_FAILED;
    }
    hy_bwfit_opts_default(&o.bw);
    long j = hy_jobs_default();
    o.bw.fit.jobs = (int)(j > 64 ? 64 : j);
    cli_parser p;
    cli_parser_init(&p, &fit_cli, argc, argv, 1);
    int rc = -1;
    for (int id; rc < 0 && (id = cli_next(&p)) != CLI_END;) {
        if (id == CLI_STOP || id == CLI_ERROR)
            rc = id == CLI_STOP ? CLI_OK : CLI_USAGE;
        else if (take(&o, id, p.val))
            rc = CLI_USAGE;
    }
    if (rc < 0)
        rc = fit_main(&o);
    free(o.dirs);
    free(o.sets);
    return rc;
}
