/* SPDX-License-Identifier: MIT */
/* cmd_sweep.c: `hystviz sweep SCENE --grid KEY=SPEC ...`: renders the scene at
 * every point of a parameter grid (hy_grid.h) exactly as `hystviz render SCENE
 * --set KEY=VALUE ... --set output.name=NAME` would, and streams one table row
 * per point, in point order, into DIR/sweep.csv.  With --shard K/N it does only
 * the points i with i mod N = K and writes their rows into the shard manifest
 * DIR/sweep.shard-K-of-N.csv; `sweep --merge DIR` joins the N manifests into
 * the sweep.csv the unsharded run writes, byte for byte. */
#include "cmd_sweep.h"

#include <errno.h>
#include <inttypes.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cli_util.h"
#include "hy_config.h"
#include "hy_dtoa.h"
#include "hy_grid.h"
#include "hy_jobs.h"
#include "hy_os.h"
#include "hy_out.h"
#include "hy_sweep.h"
#include "scene_run.h"
#include "sweep_merge.h"
#include "sweep_plot.h"

#define VERIFY_EVERY HY_SWEEP_VERIFY_EVERY
#define STR_(x) #x
#define STR(x) STR_(x)

static const char sweep_help[] =
    "usage: hystviz sweep SCENE --grid SECTION.KEY=SPEC... [-o DIR] [-j N] [--shard K/N]\n"
    "                     [--formats LIST|none] [--set SECTION.KEY=VALUE]... [--verify] [--times]\n"
    "                     [--plot COLUMN] [-q]\n"
    "       hystviz sweep --merge DIR [--plot COLUMN]\n"
    "\n"
    "A parameter study: the scene is rendered at every point of the grid, the\n"
    "Cartesian product of the --grid axes, and DIR/sweep.csv gets one row per point.\n"
    "SPEC is a list (1,2,5), a linear range FROM:TO:COUNT (0.1:0.5:5 = 0.1, 0.2, ...,\n"
    "0.5) or a log range FROM:TO:logCOUNT (1:1e3:log4 = 1, 10, 100, 1000).  Points\n"
    "are numbered in row-major order: the first --grid is the outermost axis, the\n"
    "last varies fastest.  Point i is written as DIR/pINDEX_KEY-VALUE_....FORMAT and\n"
    "is byte for byte what `hystviz render SCENE --set ... --set KEY=VALUE ...\n"
    "--set output.name=NAME -o DIR` writes (VALUE as in the table).\n"
    "\n"
    "sweep.csv columns: index, status (ok, invalid: the scene refused the point,\n"
    "failed: computing or writing failed), name, one column per grid key, [compute_s],\n"
    "ysteady_min, ysteady_max (y° extremes), nminor, major_area, minor1_area,\n"
    "minor_areas (every minor loop's area, ';'-separated), energy (the loop area of a\n"
    "period; areas are the dissipated energy: ∮ y du, or ∮ u dy for Jiles-Atherton,\n"
    "Preisach and play, docs/SCENES.md \"Loop areas\"), err_measured_1_in_K (1 where\n"
    "the errors were measured, else 0),\n"
    "SERIES.err (error against the exact answer) for every series,\n"
    "SERIES.dist (max |y_γ - y*_u|) for every ygamma/transient series, message.\n"
    "Errors are measured, as render -v measures them (closed forms against\n"
    "long-double references, a GSL solve against the exact solution where one\n"
    "exists), on a sample: the points whose index is a multiple of K = "
    STR(VERIFY_EVERY) ", or\n"
    "every point (K = 1) with --verify; elsewhere SERIES.err is empty, and with\n"
    "--formats none no curve is sampled there: only the table's scalars are computed.\n"
    "Empty: not computed by this scene.  Numbers are the shortest decimal that reads\n"
    "back to the same double, laid out as %.17g.  --include-dir and --max-work apply\n"
    "to each point as render's; a point over the work budget is an invalid row.\n"
    "\n"
    "\n";

static const char sweep_tail[] =
    "exit status: 0 every point ok; 2 usage error, invalid scene or grid value (nothing\n"
    "written), or a point the scene refused (its row says why); 1 a point failed to\n"
    "compute or a file could not be written.\n";

enum { OPT_GRID = CLI_FIRST, OPT_SET, OPT_OUT, OPT_FORMATS, OPT_SHARD, OPT_MERGE, OPT_PLOT, OPT_VERIFY, OPT_TIMES,
       OPT_QUIET, OPT_TABLE };
static const cli_opt sweep_opts_table[] = {
    {"grid", 0, "K=SPEC", "a grid axis (repeatable)", OPT_GRID, CLI_SCENE_KEY, NULL, NULL, NULL},
    {"set", 0, "S.K=V", "a fixed override applied to every point before the grid", OPT_SET, CLI_SCENE_KEY, NULL,
     NULL, NULL},
    {"output", 'o', "DIR", "the study directory (default: sweep)", OPT_OUT, 0, NULL, NULL, NULL},
    {.group = cli_jobs_opts},
    {"formats", 0, "LIST", "svg,pdf,png (default: the scene's), or none: the table only", OPT_FORMATS, 0, NULL, NULL,
     NULL},
    {"table", 0, "csv|npy", "the table's format: sweep.csv (default) or sweep.npy, NumPy's\n"
     "array file (a structured array, a field per column)", OPT_TABLE, 0, NULL, NULL, NULL},
    {"shard", 0, "K/N", "only points with index mod N = K (0 <= K < N); the rows go\n"
     "to DIR/sweep.shard-K-of-N.csv for --merge", OPT_SHARD, 0, NULL, NULL, NULL},
    {"merge", 0, "DIR", "join DIR's N shard manifests into DIR/sweep.csv (refused,\n"
     "with the missing shards listed, unless all N are there,\n"
     "and the commands that re-run them, by hand and sbatch)", OPT_MERGE, 0, NULL, NULL, NULL},
    {"plot", 0, "COLUMN", "also draw DIR/sweep_COLUMN.svg and .png: the table's COLUMN\n"
     "(e.g. minor1_area) against the first grid key, one curve per\n"
     "value of the second (with --shard: give it to --merge)", OPT_PLOT, 0, NULL, NULL, NULL},
    {.group = cli_policy_opts}, /* a point over --max-work is an invalid row */
    {"verify", 0, NULL, "measure the errors at every point (default: 1 in " STR(VERIFY_EVERY) ")", OPT_VERIFY, 0,
     NULL, NULL, NULL},
    {"times", 0, NULL, "add compute_s (compute time of the point, seconds); the\n"
     "table is then no longer byte-stable between runs", OPT_TIMES, 0, NULL, NULL, NULL},
    {"quiet", 'q', NULL, "print only errors", OPT_QUIET, 0, NULL, NULL, NULL},
    {0},
};
static const cli_cmd sweep_cli = {"sweep", sweep_help, sweep_tail, "SCENE", sweep_opts_table};


/* ---- options ---------------------------------------------------------- */

static int refused_key(const char *opt, const char *assignment)
{
    if (!strncmp(assignment, "output.name", 11) || !strncmp(assignment, "output.dir", 10)) {
        fprintf(stderr, "hystviz sweep: %s %s: the sweep names each point's files itself (-o sets the directory)\n",
                opt, assignment);
        return 1;
    }
    return 0;
}

/* Checks how the options read into o combine and the --formats list: 0 ok,
 * 2 usage error (message printed). */
static int finish_opts(hy_sweep_opts *o)
{
    if (o->merge && (o->scene || o->grid.naxes || o->sharded)) {
        fprintf(stderr, "hystviz sweep: --merge DIR takes no scene, --grid or --shard\n");
        return 2;
    }
    if (o->npy && o->plot) {
        fprintf(stderr, "hystviz sweep: --plot reads a CSV table: give it without --table npy\n");
        return 2;
    }
    if (o->merge && o->npy) {
        fprintf(stderr, "hystviz sweep: --merge DIR finds the shards' table format itself (no --table)\n");
        return 2;
    }
    if (!o->merge && !o->scene) {
        fprintf(stderr, "hystviz sweep: give a scene file (see hystviz sweep --help)\n");
        return 2;
    }
    if (o->formats && !strcmp(o->formats, "none"))
        o->figures = 0;
    else if (o->formats) {
        char buf[64];
        snprintf(buf, sizeof buf, "%s", o->formats);
        char *save = NULL;
        size_t n = 0;
        static const char *const ext[] = {HY_FIGURE_FORMATS(HY_FORMAT_EXT) NULL};
        for (char *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save), n++) {
            size_t k = 0;
            while (ext[k] && strcmp(t, ext[k]))
                k++;
            if (!ext[k]) {
                fprintf(stderr, "hystviz sweep: --formats: unknown format '%s' (%s, or none)\n", t, HY_FORMAT_NAMES);
                return 2;
            }
        }
        if (!n || strlen(o->formats) >= sizeof buf) {
            fprintf(stderr, "hystviz sweep: --formats '%s': expected a list of %s, or none\n", o->formats, HY_FORMAT_NAMES);
            return 2;
        }
    }
    return 0;
}

/* 0 ok, 1 help printed, 2 usage error (message printed). */
static int parse_opts(int argc, char **argv, hy_sweep_opts *o)
{
    memset(o, 0, sizeof *o);
    hy_grid_init(&o->grid);
    o->out = "sweep";
    o->figures = 1;
    o->verify_every = VERIFY_EVERY;
    o->jobs = hy_jobs_default();
    o->pol = hy_scene_policy_default();
    o->sets = calloc((size_t)argc, sizeof *o->sets);
    o->dirs = calloc((size_t)argc, sizeof *o->dirs);
    if (!o->sets || !o->dirs) {
        fprintf(stderr, "hystviz sweep: out of memory\n");
        return 2;
    }
    hy_error err = {0};
    cli_parser p;
    cli_parser_init(&p, &sweep_cli, argc, argv, 1);
    for (int id; (id = cli_next(&p)) != CLI_END;) {
        const char *v = p.val;
        if (id == CLI_STOP || id == CLI_ERROR)
            return id == CLI_STOP ? 1 : 2;
        if (id == OPT_GRID) {
            if (refused_key(p.optname, v))
                return 2;
            if (hy_grid_add(&o->grid, v, &err)) {
                fprintf(stderr, "hystviz sweep: %s\n", err.msg);
                return 2;
            }
        } else if (id == OPT_SET) {
            if (refused_key(p.optname, v))
                return 2;
            o->sets[o->nsets++] = (char *)v;
        } else if (id == OPT_OUT)
            o->out = v;
        else if (id == CLI_JOBS) {
            if (cli_long(p.optname, v, 1, 1024, &o->jobs))
                return 2;
        } else if (id == OPT_FORMATS)
            o->formats = v;
        else if (id == OPT_SHARD) {
            if (hy_shard_parse(v, &o->shard_k, &o->shard_n, &err)) {
                fprintf(stderr, "hystviz sweep: %s\n", err.msg);
                return 2;
            }
            o->sharded = 1;
        } else if (id == OPT_MERGE)
            o->merge = v;
        else if (id == OPT_PLOT)
            o->plot = v;
        else if (id == OPT_TIMES)
            o->times = 1;
        else if (id == OPT_VERIFY)
            o->verify_every = 1;
        else if (id == OPT_QUIET)
            o->quiet = 1;
        else if (id == OPT_TABLE) {
            if (strcmp(v, "csv") && strcmp(v, "npy")) {
                fprintf(stderr, "hystviz sweep: --table '%s': expected csv or npy\n", v);
                return 2;
            }
            o->npy = !strcmp(v, "npy");
        }
        else if (id == CLI_ARG && o->scene)
            return cli_unexpected(&p), 2;
        else if (id == CLI_ARG)
            o->scene = v;
        else if (cli_policy_take(&o->pol, o->dirs, "sweep", id, v) < 0)
            return 2;
    }
    return finish_opts(o);
}

/* ---- the study -------------------------------------------------------- */

static int make_dir(const char *dir)
{
    char buf[4096];
    if (snprintf(buf, sizeof buf, "%s", dir) >= (int)sizeof buf) {
        errno = ENAMETOOLONG;
        return -1;
    }
    for (char *p = buf + 1; *p; p++)
        if (*p == '/') {
            *p = '\0';
            if (mkdir(buf, 0755) && errno != EEXIST)
                return -1;
            *p = '/';
        }
    return mkdir(buf, 0755) && errno != EEXIST ? -1 : 0;
}

/* --plot names a result column of this study's table (not index, status,
 * name, a grid key or message)?  1 with a message if not. */
static int plot_column_unknown(const hy_sweep_study *s)
{
    char *head = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&head, &len);
    if (!f)
        return 1;
    hy_sweep_write_header(s, f);
    fclose(f);
    int found = 0;
    size_t skip = 3 + s->o->grid.naxes, col = 0;
    char *names = head ? strdup(head) : NULL;
    for (char *save = NULL, *t = names ? strtok_r(names, ",\n", &save) : NULL; t; t = strtok_r(NULL, ",\n", &save), col++)
        found |= col >= skip && strcmp(t, "message") && !strcmp(t, s->o->plot);
    if (!found)
        fprintf(stderr, "hystviz sweep: --plot %s: not a result column of this study (the table: %.*s)\n", s->o->plot,
                head ? (int)strcspn(head, "\n") : 1, head ? head : "?");
    free(names);
    free(head);
    return !found;
}

/* Checks the study s->o describes and plans its points (hy_sweep_check,
 * hy_sweep_prepare), its hash in *hash, and that --plot names a column of its
 * table: 0 ok, else the exit status (message printed). */
static int prepare_study(hy_sweep_study *s, uint64_t *hash)
{
    hy_error msg = {0};
    int rc = hy_sweep_check(s, hash, &msg);
    if (rc)
        fprintf(stderr, "hystviz sweep: %s\n", msg.msg);
    else if (hy_sweep_prepare(s, &msg)) {
        fprintf(stderr, "hystviz sweep: %s\n", msg.msg);
        rc = 2;
    }
    if (!rc && s->o->plot && !s->o->sharded && plot_column_unknown(s))
        rc = 2;
    return rc;
}

/* Runs the study o describes and writes its table; returns the exit status. */
static int sweep(const hy_sweep_opts *o)
{
    hy_sweep_study s;
    memset(&s, 0, sizeof s);
    s.o = o;
    uint64_t hash = 0;
    size_t npoints = hy_grid_points(&o->grid);
    int rc = prepare_study(&s, &hash);
    if (rc) {
        hy_sweep_study_free(&s);
        return rc;
    }
    static char npy_head[65536 + 64];
    size_t npy_hl = 0;
    if (o->npy && (!(npy_hl = hy_npy_header(s.descr, s.nmine, npy_head, sizeof npy_head)))) {
        fprintf(stderr, "hystviz sweep: the .npy header would pass 64 KiB (too many or too long columns), or out of memory\n");
        hy_sweep_study_free(&s);
        return 2;
    }
    if (make_dir(o->out)) {
        fprintf(stderr, "hystviz sweep: %s: cannot create the study directory: %s\n", o->out, strerror(errno));
        hy_sweep_study_free(&s);
        return 1;
    }
    if (o->sharded)
        hy_sweep_shard_path(o->out, o->shard_k, o->shard_n, o->npy ? "npy" : "csv", s.table_path,
                            sizeof s.table_path);
    else
        snprintf(s.table_path, sizeof s.table_path, "%s/sweep.%s", o->out, o->npy ? "npy" : "csv");
    hy_out_sweep(o->out); /* temporaries of killed runs (a running shard's are locked: kept) */
    hy_error err = {0};
    if (hy_out_open(&s.out, s.table_path, 0, &err)) {
        fprintf(stderr, "hystviz sweep: %s\n", err.msg);
        hy_sweep_study_free(&s);
        return 1;
    }
    s.table = hy_out_file(&s.out);
    if (s.table != stdout) /* the rows leave in 1 MiB writes, not 4 KiB ones (a tenth of the CPU at 10^5 rows) */
        setvbuf(s.table, NULL, _IOFBF, (size_t)1 << 20);
    if (o->sharded)
        hy_sweep_shard_head(s.table, o->shard_k, o->shard_n, npoints, hash, o->rerun);
    if (o->npy)
        fwrite(npy_head, 1, npy_hl, s.table); /* a short write shows in the commit's check */
    else
        hy_sweep_write_header(&s, s.table);
    double t0 = hy_now();
    tzset(); /* cairo's PDF writer reads the time zone: set it up before the threads */
    if (hy_sweep_run_pool(&s))
        s.io_error = 1;
    if (s.io_error || s.written != s.nmine) {
        hy_out_abort(&s.out);
        fprintf(stderr, "hystviz sweep: cannot write '%s' (out of memory or a write error)\n", s.table_path);
        rc = 1;
    } else if (hy_out_commit(&s.out, &err)) {
        fprintf(stderr, "hystviz sweep: %s\n", err.msg);
        rc = 1;
    }
    if (!o->quiet) {
        fprintf(stderr, "sweep: %zu of %zu points", s.nmine, npoints);
        if (o->sharded)
            fprintf(stderr, " (shard %ld/%ld)", o->shard_k, o->shard_n);
        fprintf(stderr, ": %zu ok (%zu by the closed-form kernel), %zu invalid, %zu failed in %.2f s; %s\n", s.nok,
                s.nclosed, s.ninvalid, s.nfailed, hy_now() - t0, rc ? "no table written" : s.table_path);
    }
    if (!rc && o->plot && !o->sharded) {
        hy_error perr = {0};
        if (hy_sweep_plot(o->out, o->plot, &perr)) {
            fprintf(stderr, "hystviz sweep: %s\n", perr.msg);
            rc = perr.code == HY_EINVAL ? 2 : 1;
        }
    }
    hy_sweep_study_free(&s);
    return rc ? rc : s.ninvalid ? 2 : s.nfailed ? 1 : 0;
}

int hy_cmd_sweep(int argc, char **argv)
{
    hy_sweep_opts o;
    int rc = parse_opts(argc, argv, &o);
    if (!rc && o.sharded)
        o.rerun = hy_sweep_shard_rerun(argc, argv);
    if (!rc)
        rc = o.merge ? hy_sweep_merge(o.merge, o.plot, o.quiet) : sweep(&o);
    else if (rc == 1)
        rc = 0;
    hy_grid_free(&o.grid);
    free(o.rerun);
    free(o.sets);
    free(o.dirs);
    return rc;
}
