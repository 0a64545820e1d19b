/* SPDX-License-Identifier: MIT */
/* cmd_watch.c: `hystviz watch SCENE...`: render, then render again on every
 * save of a scene or anything it includes (inotify on the scenes'
 * directories, so rename-saves count), one line per render; scene errors are
 * printed and watching goes on. */
#include "cmd_serve.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/signalfd.h>
#include <time.h>
#include <unistd.h>

#include "cli_opt.h"
#include "cli_util.h"
#include "dirwatch.h"
#include "hy_os.h"
#include "scene_run.h"

static const char watch_usage[] =
    "usage: hystviz watch SCENE... [-o DIR] [--set SECTION.KEY=VALUE]... [--format svg,pdf,png]\n"
    "\n"
    "Renders each scene as `hystviz render` does, then again whenever it or a file it\n"
    "includes changes on disk (editors that save by renaming are\n"
    "seen too), until Ctrl-C.  One line per render: the time, the scene, the files\n"
    "written and the render time, and the largest error measured against an exact\n"
    "answer; or the scene's error (the last good files stay, watching goes on).\n"
    "\n";

static const cli_opt watch_opts[] = {
    {"output", 'o', "DIR", "output directory (default: each scene's [output] dir)", CLI_OUT, 0, NULL, NULL, NULL},
    {"set", 0, "S.K=V", "override a scene key (as render); repeatable", CLI_SET, CLI_SCENE_KEY, NULL, NULL, NULL},
    {"format", 0, "LIST", "formats to write instead of the scene's", CLI_FORMAT, 0, NULL, NULL, NULL},
    {0},
};
static const cli_cmd watch_cli = {"watch", watch_usage,
    "Exit status: 0 after Ctrl-C, 1 if the directories cannot be watched, 2 for a bad option.\n", "SCENE",
    watch_opts};

typedef struct watched {
    const char *path;
    uint64_t hash;     /* of the last render attempt (0: none) */
} watched;

static void stamp(char *buf, size_t n)
{
    time_t t = time(NULL);
    struct tm tm;
    localtime_r(&t, &tm);
    strftime(buf, n, "%H:%M:%S", &tm);
}

/* Renders w if its text (with includes and overrides) changed since the last
 * attempt, or always with force; prints one line. */
static void render_one(watched *w, char *const *sets, size_t nsets, const char *out, const char *formats, int force)
{
    char ts[16];
    hy_error err = {0};
    hy_scene_run run;
    double t0 = hy_now();
    stamp(ts, sizeof ts);
    /* a cheap parse first: unchanged text is not rendered again */
    hy_scene *probe = NULL;
    int rc = hy_scene_parse_file(w->path, &probe, &err);
    for (size_t i = 0; !rc && i < nsets; i++)
        rc = hy_scene_set(probe, sets[i], &err);
    uint64_t h = rc ? 0 : hy_scene_hash(probe);
    hy_scene_free(probe);
    if (!rc && !force && h == w->hash)
        return;
    w->hash = h;
    if (!rc)
        rc = hy_scene_run_load(&run, w->path, sets, nsets, &err);
    if (rc) {
        printf("%s %s: error: %s\n", ts, w->path, err.msg);
        fflush(stdout);
        return;
    }
    char written[8192] = "";
    run.figure_only = 1;
    rc = hy_scene_run_compute(&run, NULL, &err);
    if (!rc)
        rc = hy_scene_run_write(&run, out, formats, written, sizeof written, &err);
    double dt = hy_now() - t0;
    if (rc)
        printf("%s %s: error: %s\n", ts, w->path, err.msg);
    else {
        for (char *p = written; (p = strchr(p, '\n'));)
            *p = p[1] ? ' ' : '\0';
        double emax = NAN;
        const char *ref = NULL;
        for (size_t i = 0; i < run.nseries; i++)
            if (!isnan(run.series[i].err) && !(run.series[i].err <= emax)) {
                emax = run.series[i].err;
                ref = run.series[i].err_ref;
            }
        printf("%s %s: %s in %.3f s", ts, w->path, written, dt);
        if (!isnan(emax))
            printf("; max error %.3g against the %s\n", emax, ref ? ref : "exact answer");
        else
            printf("; no exact answer to compare with\n");
    }
    fflush(stdout);
    hy_scene_run_free(&run);
}

/* Whether one of stop's signals is pending. */
static int stop_pending(const sigset_t *stop)
{
    sigset_t pend;
    if (sigpending(&pend))
        return 0;
    for (int sig = 1; sig < 32; sig++)
        if (sigismember(stop, sig) && sigismember(&pend, sig))
            return 1;
    return 0;
}

/* The directories to watch, each scene's (includes stay inside it), each
 * once: into dirs (nw long; NULL when it could not be allocated), their count
 * in *nd, the caller frees them.  0; 2 when a scene's directory cannot be
 * resolved or dirs is NULL, 1 out of memory (message printed). */
static int scene_dirs(const watched *ws, size_t nw, char **dirs, size_t *nd)
{
    int rc = 0;
    for (size_t i = 0; !rc && i < nw; i++) {
        char tmp[PATH_MAX], real[PATH_MAX];
        const char *slash = strrchr(ws[i].path, '/');
        snprintf(tmp, sizeof tmp, "%.*s", slash ? (int)(slash - ws[i].path) : 1, slash ? ws[i].path : ".");
        if (!tmp[0])
            snprintf(tmp, sizeof tmp, "/");
        if (!dirs || !realpath(tmp, real)) {
            fprintf(stderr, "hystviz watch: %s: %s\n", ws[i].path, dirs ? strerror(errno) : "out of memory");
            rc = 2;
            break;
        }
        size_t k = 0;
        while (k < *nd && strcmp(dirs[k], real))
            k++;
        if (k == *nd && !(dirs[(*nd)++] = strdup(real)))
            rc = 1;
    }
    return rc;
}

/* A signalfd for SIGINT, SIGTERM and SIGHUP (stop gets the set): the signals
 * main blocked before anything else, pending since then if one came, are
 * readable on it.  -1 on failure (message printed). */
static int stop_fd(sigset_t *stop)
{
    sigemptyset(stop);
    sigaddset(stop, SIGINT);
    sigaddset(stop, SIGTERM);
    sigaddset(stop, SIGHUP);
    int sfd = signalfd(-1, stop, SFD_CLOEXEC);
    if (sfd < 0)
        fprintf(stderr, "hystviz watch: signalfd: %s\n", strerror(errno));
    return sfd;
}

int hy_cmd_watch(int argc, char **argv)
{
    cli_outputs o = {.sets = calloc((size_t)argc, sizeof(char *))};
    watched *ws = calloc((size_t)argc, sizeof *ws);
    size_t nw = 0;
    if (!o.sets || !ws) {
        free(o.sets);
        free(ws);
        fprintf(stderr, "hystviz watch: out of memory\n");
        return 1;
    }
    int rc = 0;
    cli_parser p;
    cli_parser_init(&p, &watch_cli, argc, argv, 1);
    for (int id; !rc && (id = cli_next(&p)) != CLI_END;) {
        if (id == CLI_STOP) {
            free(o.sets);
            free(ws);
            return 0;
        } else if (id == CLI_ERROR)
            rc = 2;
        else if (!cli_outputs_take(&o, id, p.val))
            ws[nw++].path = p.val;
    }
    if (!rc && !nw) {
        fprintf(stderr, "hystviz watch: give at least one scene file (see hystviz watch --help)\n");
        rc = 2;
    }
    char **dirs = rc ? NULL : calloc(nw, sizeof *dirs);
    size_t nd = 0;
    if (!rc)
        rc = scene_dirs(ws, nw, dirs, &nd);
    hy_dirwatch *w = NULL;
    hy_error err = {0};
    if (!rc && !(w = hy_dirwatch_open((const char *const *)dirs, nd, &err))) {
        fprintf(stderr, "hystviz watch: %s\n", err.msg);
        rc = 1;
    }
    /* the signals main blocked before anything else (cli_signals_block),
     * pending since then if one came: readable here */
    sigset_t stop;
    sigemptyset(&stop);
    int sfd = rc ? -1 : stop_fd(&stop);
    if (!rc && sfd < 0)
        rc = 1;
    if (!rc) {
        /* Ctrl-C ends the wait, never a write: no partial file */
        fprintf(stderr, "hystviz watch: watching %zu scene%s (Ctrl-C stops)\n", nw, nw == 1 ? "" : "s");
        for (size_t i = 0; i < nw && !stop_pending(&stop); i++)
            render_one(&ws[i], o.sets, o.nsets, o.out, o.formats, 1);
        char names[4096];
        for (;;) {
            int r = hy_dirwatch_wait(w, sfd, -1, names, sizeof names, &err);
            if (r < 0) {
                fprintf(stderr, "hystviz watch: %s\n", err.msg);
                rc = 1;
            }
            if (r <= 0)
                break;
            for (size_t i = 0; i < nw; i++)
                render_one(&ws[i], o.sets, o.nsets, o.out, o.formats, 0);
        }
    }
    hy_dirwatch_close(w);
    if (sfd >= 0)
        close(sfd);
    for (size_t i = 0; i < nd; i++)
        free(dirs[i]);
    free(dirs);
    free(o.sets);
    free(ws);
    return rc;
}
