/* SPDX-License-Identifier: MIT */
/* cmd_render.c: `hystviz render SCENE...` (figures) and `hystviz data SCENE`
 * (every series as CSV), with --set overrides. */
#include "cmd_render.h"

#include <gsl/gsl_errno.h>
#include <stdlib.h>
#include <string.h>

#include "cli_util.h"
#include "hy_cost.h"
#include "hy_out.h"
#include "scene_run.h"

static const char render_usage[] =
    "usage: hystviz render SCENE... [-o DIR] [--set SECTION.KEY=VALUE]... [--format svg,pdf,png] [-v]\n"
    "                      [--include-dir DIR]... [--max-work N] [--print-work]\n"
    "       hystviz data SCENE [--set SECTION.KEY=VALUE]... [-o FILE] [--include-dir DIR]... [--max-work N]\n"
    "\n"
    "render draws each scene file (docs/SCENES.md) into DIR (default: the scene's\n"
    "[output] dir, relative to the scene's directory) as NAME.svg/.pdf/.png: all of\n"
    "a figure's files or none of them.\n"
    "data prints every series the scene draws as CSV 'series,x,y' (%.17g).\n"
    "--print-work prints each scene's work estimate, kind by kind, and computes\n"
    "nothing (docs/SCENES.md, \"Work budget\").\n"
    "\n";

enum { OPT_VERBOSE = CLI_FIRST, OPT_PRINT_WORK };
static const cli_opt render_opts[] = {
    {"output", 'o', "DIR|FILE", "output directory (render) or CSV file (data)", CLI_OUT, 0, NULL, NULL, NULL},
    {"set", 0, "S.K=V", "override a scene key, e.g. --set model.sigma0=1\n"
     "or --set series.ystar.style=dashed; repeatable", CLI_SET, CLI_SCENE_KEY, NULL, NULL, NULL},
    {"format", 0, "LIST", "formats to write instead of the scene's", CLI_FORMAT, 0, NULL, "render", NULL},
    {"verbose", 'v', NULL, "print the plan, each step's time and each series' error\n"
     "against the exact answer where one exists", OPT_VERBOSE, 0, NULL, NULL, NULL},
    {"print-work", 0, NULL, "print the work estimate (units, seconds, each kind's\n"
     "count and weight) and compute nothing", OPT_PRINT_WORK, 0, NULL, "render", NULL},
    {.group = cli_policy_opts},
    {0},
};
static const cli_cmd render_cli = {NULL, render_usage, NULL, "SCENE", render_opts};

/* Of two exit statuses the one to report: invalid input over failure. */
static int worse(int a, int b)
{
    return a == 2 || b == 2 ? 2 : a > b ? a : b;
}

/* Loads a scene and checks its outputs can be written (before computing);
 * the exit status (message printed). */
static int load(hy_scene_run *run, const char *scene, const char *formats, char **sets, size_t nsets,
                const hy_scene_policy *pol, int check)
{
    hy_error err = {0};
    if (hy_scene_run_load_policy(run, scene, sets, nsets, pol, &err)) {
        fprintf(stderr, "hystviz: %s\n", err.msg);
        return err.code == HY_ENOMEM ? 1 : 2; /* an unreadable or invalid scene: invalid input */
    }
    if (check && hy_scene_run_check_output(run, formats, &err)) {
        fprintf(stderr, "hystviz: %s\n", err.msg);
        hy_scene_run_free(run);
        return cli_exit_status(err.code);
    }
    return 0;
}

static int compute(hy_scene_run *run, int verbose)
{
    hy_error err = {0};
    if (hy_scene_run_compute(run, verbose ? stderr : NULL, &err)) {
        fprintf(stderr, "hystviz: %s\n", err.msg);
        return cli_exit_status(err.code);
    }
    return 0;
}

/* `render --print-work`: the scene's estimate on stdout, kind by kind
 * (hy_cost.h), nothing computed; the exit status. */
static int print_work(hy_scene_run *run, const char *scene)
{
    double counts[HY_COST_COUNT] = {0}, work;
    hy_error err = {0};
    char what[200] = "";
    run->cost_counts = counts;
    int rc = hy_scene_run_estimate(run, &work, what, sizeof what, &err);
    run->cost_counts = NULL;
    if (rc) {
        fprintf(stderr, "hystviz: %s\n", err.msg);
        return cli_exit_status(err.code);
    }
    double budget = run->budget > 0 ? run->budget : HY_SCENE_WORK_DEFAULT;
    printf("%s: work %.6g units, about %.3g s of CPU (%.3g units a second), budget %.3g (%s)\n", scene, work,
           work / HY_COST_UNITS_PER_S, HY_COST_UNITS_PER_S, budget, work > budget ? "over: refused" : "within");
    printf("  %s\n", what);
    for (int k = 0; k < HY_COST_COUNT; k++)
        if (counts[k] > 0)
            printf("  %-10s %14.6g x %-8.4g = %.6g units\n", hy_cost_name(k), counts[k], hy_cost_weight(k),
                   counts[k] * hy_cost_weight(k));
    return 0;
}

/* `render`: one scene's figure in every format, all or none (only_work:
 * its estimate only, print_work). */
static int render_one(const char *scene, const char *out, const char *formats, char **sets, size_t nsets,
                      const hy_scene_policy *pol, int verbose, int only_work)
{
    hy_scene_run run;
    hy_error err = {0};
    int st = load(&run, scene, formats, sets, nsets, pol, 1);
    if (st)
        return st;
    char written[8192] = "";
    run.figure_only = 1; /* figures only (`data` writes the points) */
    run.formats = formats; /* a PNG's raster is work */
    if (only_work)
        st = print_work(&run, scene);
    else if (!(st = compute(&run, verbose))) {
        if (hy_scene_run_write(&run, out, formats, written, sizeof written, &err)) {
            /* errors of the scene's [output] dir already start with file:line:col */
            if (!strncmp(err.msg, scene, strlen(scene)))
                fprintf(stderr, "hystviz: %s\n", err.msg);
            else
                fprintf(stderr, "hystviz: %s: %s\n", scene, err.msg);
            st = cli_exit_status(err.code);
        } else if (verbose)
            fprintf(stderr, "%s", written);
    }
    hy_scene_run_free(&run);
    return st;
}

/* `data`: the output is opened first (a directory, a missing folder or a
 * dangling link fail before computing) and written whole or not at all. */
static int render_data(const char *scene, const char *out, char **sets, size_t nsets, const hy_scene_policy *pol,
                       int verbose)
{
    hy_scene_run run;
    hy_error err = {0};
    hy_out o;
    int st = load(&run, scene, NULL, sets, nsets, pol, 0);
    if (st)
        return st;
    if (hy_out_open(&o, out ? out : "-", HY_OUT_FOLLOW, &err)) { /* the user's own file: as the shell's > */
        fprintf(stderr, "hystviz data: %s\n", err.msg);
        hy_scene_run_free(&run);
        return 1;
    }
    if (!(st = compute(&run, verbose))) {
        hy_scene_run_data(&run, hy_out_file(&o), NULL); /* a write error shows at commit, naming the file */
        if (hy_out_commit(&o, &err)) {
            fprintf(stderr, "hystviz data: %s\n", err.msg);
            st = 1;
        }
    }
    hy_out_abort(&o); /* no-op once committed */
    hy_scene_run_free(&run);
    return st;
}

int hy_cmd_render(int argc, char **argv)
{
    int is_data = !strcmp(argv[0], "data");
    int verbose = 0, only_work = 0;
    cli_outputs o = {.sets = calloc((size_t)argc, sizeof(char *))};
    char **scenes = calloc((size_t)argc, sizeof *scenes);
    const char **dirs = calloc((size_t)argc, sizeof *dirs);
    hy_scene_policy pol = hy_scene_policy_default();
    size_t nscenes = 0;
    if (!o.sets || !scenes || !dirs) {
        free(o.sets);
        free(scenes);
        free(dirs);
        fprintf(stderr, "hystviz %s: out of memory\n", argv[0]);
        return 1;
    }
    int rc = 0, failed = 0;
    cli_parser p;
    cli_parser_init(&p, &render_cli, argc, argv, 1);
    for (int id; !rc && (id = cli_next(&p)) != CLI_END;) {
        if (id == CLI_STOP || id == CLI_ERROR)
            rc = id == CLI_STOP ? -1 : 2;
        else if (cli_outputs_take(&o, id, p.val))
            continue;
        else if (id == OPT_VERBOSE)
            verbose = 1;
        else if (id == OPT_PRINT_WORK)
            only_work = 1;
        else if (id == CLI_ARG)
            scenes[nscenes++] = (char *)p.val;
        else if (cli_policy_take(&pol, dirs, argv[0], id, p.val) < 0)
            rc = 2;
    }
    if (!rc && (nscenes == 0 || (is_data && nscenes != 1))) {
        fprintf(stderr, "hystviz %s: give %s scene file (see hystviz %s --help)\n", argv[0], is_data ? "one" : "at least one",
                argv[0]);
        rc = 2;
    }
    int fmt[HY_FORMAT_COUNT];
    size_t nfmt;
    hy_error err = {0};
    if (!rc && o.formats && hy_scene_formats_parse(o.formats, fmt, &nfmt, &err)) {
        fprintf(stderr, "hystviz %s: %s\n", argv[0], err.msg);
        rc = 2;
    }
    gsl_set_error_handler_off();
    if (!rc && o.out && !is_data)
        hy_out_sweep(o.out); /* temporaries of killed runs */
    for (size_t k = 0; k < nscenes && !rc; k++) {
        int st = is_data ? render_data(scenes[k], o.out, o.sets, o.nsets, &pol, verbose)
                         : render_one(scenes[k], o.out, o.formats, o.sets, o.nsets, &pol, verbose, only_work);
        failed = worse(failed, st);
    }
    free(o.sets);
    free(scenes);
    free(dirs);
    return rc < 0 ? 0 : rc ? rc : failed;
}
