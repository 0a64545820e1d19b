/* SPDX-License-Identifier: MIT */
/* cli_util.c: option parsing and exit statuses for the hystviz commands. */
#include "cli_util.h"

#include <errno.h>
#include <pthread.h>
#include <signal.h>
#include <stddef.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifdef HY_LSAN_RELEASE
#include <cairo.h>
#include <fontconfig/fontconfig.h>
#endif

#include "hy_jobs.h"
#include "hy_out.h"

int cli_num(const char *opt, const char *s, double *out)
{
    char *end;
    if (!s) {
        fprintf(stderr, "hystviz: %s needs a value\n", opt);
        return -1;
    }
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end || !isfinite(v)) {
        fprintf(stderr, "hystviz: %s: '%s' is not a finite number\n", opt, s);
        return -1;
    }
    *out = v;
    return 0;
}

int cli_long(const char *opt, const char *s, long lo, long hi, long *out)
{
    char *end;
    if (!s) {
        fprintf(stderr, "hystviz: %s needs a value\n", opt);
        return -1;
    }
    errno = 0;
    long v = strtol(s, &end, 10);
    if (end == s || *end || errno || v < lo || v > hi) {
        fprintf(stderr, "hystviz: %s: '%s' is not an integer in [%ld, %ld]\n", opt, s, lo, hi);
        return -1;
    }
    *out = v;
    return 0;
}

void cli_model_defaults(cli_model *cm)
{
    memset(cm, 0, sizeof *cm);
    cm->kind = "lugre";
    cm->sigma0 = 1;
    cm->sigma1 = 1; /* Example 2: σ0 = σ1 = Fc = vs = β = 1, Fs = 2 */
    cm->fc = 1;
    cm->fs = 2;
    cm->vs = 1;
    cm->beta = 1;
    cm->rho = 1;
    cm->tau = 1;
}

enum { M_MODEL = CLI_MODEL_FIRST, M_SIGMA0, M_SIGMA1, M_SIGMA2, M_FC, M_FS, M_VS, M_BETA, M_RHO, M_TAU, M_X0 };

const cli_opt cli_model_opts[] = {
    {"model", 0, "dahl|lugre|dahl-filter", "the model (default lugre)", M_MODEL, 0, NULL, NULL, NULL},
    {"sigma0", 0, "S0", "bristle stiffness sigma0 (LuGre; default 1)", M_SIGMA0, 0, NULL, NULL, NULL},
    {"sigma1", 0, "S1", "bristle damping sigma1 (LuGre; default 1)", M_SIGMA1, 0, NULL, NULL, NULL},
    {"sigma2", 0, "S2", "viscous friction sigma2 (LuGre; default 0)", M_SIGMA2, 0, NULL, NULL, NULL},
    {"fc", 0, "FC", "Coulomb level (default 1)", M_FC, 0, NULL, NULL, NULL},
    {"fs", 0, "FS", "static level (LuGre; default 2):\ng(v) = FC + (FS-FC) e^{-|v/VS|^B}", M_FS, 0, NULL, NULL, NULL},
    {"vs", 0, "VS", "Stribeck velocity (LuGre; default 1)", M_VS, 0, NULL, NULL, NULL},
    {"beta", 0, "B", "Stribeck exponent (LuGre; default 1)", M_BETA, 0, NULL, NULL, NULL},
    {"rho", 0, "R", "Dahl's rate (Dahl, dahl-filter; default 1)", M_RHO, 0, NULL, NULL, NULL},
    {"tau", 0, "T", "time constant of the filter of system (16) (default 1)", M_TAU, 0, NULL, NULL, NULL},
    {"x0", 0, "Z0", "initial state (default 0)", M_X0, 0, NULL, NULL, NULL},
    {0},
};

int cli_model_take(cli_model *cm, int id, const char *v)
{
    static const size_t off[] = {
        offsetof(cli_model, sigma0), offsetof(cli_model, sigma1), offsetof(cli_model, sigma2),
        offsetof(cli_model, fc),     offsetof(cli_model, fs),     offsetof(cli_model, vs),
        offsetof(cli_model, beta),   offsetof(cli_model, rho),    offsetof(cli_model, tau),
        offsetof(cli_model, x0),
    };
    if (id == M_MODEL) {
        if (!hy_model_type_find(v)) {
            fprintf(stderr, "hystviz: --model: unknown model '%s' (dahl, lugre, dahl-filter)\n", v);
            return -1;
        }
        cm->kind = v;
        return 1;
    }
    if (id < M_SIGMA0 || id > M_X0)
        return 0;
    const char *name = cli_model_opts[id - M_MODEL].lng;
    char opt[16];
    snprintf(opt, sizeof opt, "--%s", name);
    if (cli_num(opt, v, (double *)((char *)cm + off[id - M_SIGMA0])))
        return -1;
    cm->set_sigma0 |= id == M_SIGMA0;
    cm->set_fs |= id == M_FS;
    return 1;
}

int cli_model_build(const cli_model *cm, hy_model *m)
{
    const hy_model_type *type = hy_model_type_find(cm->kind);
    if (type == hy_model_lugre) {
        hy_model_lugre_init(m, cm->sigma0, cm->sigma1, cm->fc, cm->fs, cm->vs, cm->beta);
        m->sigma2 = cm->sigma2;
    } else if (type == hy_model_dahl)
        hy_model_dahl_init(m, cm->rho, cm->fc);
    else
        hy_model_dahl_filter_init(m, cm->rho, cm->fc, cm->tau);
    m->x0 = cm->x0;
    hy_error err = {0};
    if (hy_model_validate(m, &err)) {
        fprintf(stderr, "hystviz: model %s: %s\n", cm->kind, err.msg);
        return -1;
    }
    return 0;
}

int cli_exit_status(int code)
{
    return code == HY_OK ? 0 : code == HY_EINVAL ? 2 : 1;
}

int cli_stdout_status(const char *cmd, int rc)
{
    int e = fflush(stdout) ? errno : 0;
    if (!e && ferror(stdout))
        e = EIO;
    if (e && rc == 0) {
        fprintf(stderr, "hystviz%s%s: cannot write standard output: %s\n", cmd ? " " : "", cmd ? cmd : "", strerror(e));
        return 1;
    }
    return rc;
}

int cli_program_run(char *name, int (*cmd)(int, char **), int argc, char **argv)
{
    if (argc < 2) {
        char *args[] = {name, NULL};
        return cli_stdout_status(name, cmd(1, args));
    }
    if (argv[1][0] == '-') {
        argv[0] = name;
        return cli_stdout_status(name, cmd(argc, argv));
    }
    return cli_stdout_status(name, cmd(argc - 1, argv + 1));
}

void cli_leak_check_release(void)
{
#ifdef HY_LSAN_RELEASE
    cairo_debug_reset_static_data();
    FcFini();
#endif
}

const cli_opt cli_policy_opts[] = {
    {"include-dir", 0, "DIR", "a directory scenes may include from (and read input files\n"
     "below), besides their own; repeatable", CLI_INCLUDE_DIR, 0, NULL, NULL, NULL},
    {"max-work", 0, "N", "the work budget of one scene (default 1e8; docs/SCENES.md)", CLI_MAX_WORK, 0, NULL, NULL, NULL},
    {0},
};

int cli_policy_take(hy_scene_policy *pol, const char **dirs, const char *cmd, int id, const char *v)
{
    if (id == CLI_INCLUDE_DIR) {
        if (!*v) {
            fprintf(stderr, "hystviz %s: --include-dir needs a directory\n", cmd);
            return -1;
        }
        dirs[pol->ninclude_dirs++] = v;
        pol->include_dirs = dirs;
        return 1;
    }
    if (id != CLI_MAX_WORK)
        return 0;
    double w;
    if (cli_num("--max-work", v, &w))
        return -1;
    if (!(w >= 1)) {
        fprintf(stderr, "hystviz %s: --max-work must be >= 1 (units of work, docs/SCENES.md), got %s\n", cmd, v);
        return -1;
    }
    pol->max_work = w;
    return 1;
}

int cli_outputs_take(cli_outputs *o, int id, const char *v)
{
    if (id == CLI_OUT)
        o->out = v;
    else if (id == CLI_SET)
        o->sets[o->nsets++] = (char *)v;
    else if (id == CLI_FORMAT)
        o->formats = v;
    else
        return 0;
    return 1;
}

/* The default of -j as --help states it (here) or a manual page (doc). */
static const char *jobs_more(char *buf, size_t size, int doc)
{
    if (doc)
        return ")";
    snprintf(buf, size, ": here %ld)", hy_jobs_default());
    return buf;
}

const cli_opt cli_jobs_opts[] = {
    {"jobs", 'j', "N", "worker threads (default: the CPUs this process may run on,\n"
     "its CPU affinity (taskset, a Slurm task's CPUs) capped by\n"
     "its cgroup's CPU quota (cpu.max), rounded up", CLI_JOBS, 0, jobs_more, NULL, NULL},
    {0},
};

/* The signals a command takes: INT and TERM (and HUP where not ignored). */
static void stop_signals(sigset_t *set)
{
    sigemptyset(set);
    sigaddset(set, SIGINT);
    sigaddset(set, SIGTERM);
    sigaddset(set, SIGHUP);
}

void cli_signals_block(sigset_t *set)
{
    stop_signals(set);
    pthread_sigmask(SIG_BLOCK, set, NULL);
    /* an ignored signal is discarded even while blocked: a background job of
     * a non-interactive shell starts with SIGINT ignored (SIGHUP ignored is
     * nohup's wish and stays) */
    struct sigaction sa;
    int stop[] = {SIGINT, SIGTERM};
    for (int i = 0; i < 2; i++)
        if (!sigaction(stop[i], NULL, &sa) && sa.sa_handler == SIG_IGN)
            signal(stop[i], SIG_DFL);
}

/* The thread of cli_signals_end: the first signal removes the temporaries
 * and ends the process by that signal. */
static void *ender(void *arg)
{
    (void)arg;
    sigset_t set;
    stop_signals(&set);
    int sig = 0;
    while (sigwait(&set, &sig))
        ;
    hy_out_end();
    signal(sig, SIG_DFL);
    sigset_t one;
    sigemptyset(&one);
    sigaddset(&one, sig);
    pthread_sigmask(SIG_UNBLOCK, &one, NULL);
    raise(sig);
    _exit(128 + sig); /* not reached: the default action of sig ends the process */
}

int cli_signals_end(void)
{
    pthread_t t;
    if (pthread_create(&t, NULL, ender, NULL))
        return -1;
    pthread_detach(t);
    return 0;
}
