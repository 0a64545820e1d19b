/* SPDX-License-Identifier: MIT */
/* cli_util.h: small helpers shared by the hystviz subcommands (strict number
 * parsing, model options, exit statuses).  Files are written through
 * hy_out.h. */
#ifndef HY_CLI_UTIL_H
#define HY_CLI_UTIL_H

#include <signal.h>
#include <stdio.h>
#include "cli_opt.h"
#include "hy_model.h"
#include "hy_scene_policy.h"

/* Parses a finite double; on failure prints "hystviz: OPTION: ..." and returns -1. */
int cli_num(const char *opt, const char *s, double *out);
/* Parses an integer in [lo, hi]; on failure prints a message and returns -1. */
int cli_long(const char *opt, const char *s, long lo, long hi, long *out);

/* Model options: --model --sigma0 --sigma1 --sigma2 --fc --fs --vs --beta --rho --tau --x0
 * (the table cli_model_opts; ids CLI_MODEL_FIRST..). */
typedef struct cli_model {
    const char *kind;
    double sigma0, sigma1, sigma2, fc, fs, vs, beta, rho, tau, x0;
    int set_sigma0, set_fs;
} cli_model;
enum { CLI_MODEL_FIRST = 1000, CLI_INCLUDE_DIR = 1100, CLI_MAX_WORK, CLI_JOBS = 1200 };
extern const cli_opt cli_model_opts[];
void cli_model_defaults(cli_model *cm);
/* Takes option id (from cli_next) with value v: 1 if it was a model option,
 * 0 if not, -1 on error (message printed, naming the option). */
int cli_model_take(cli_model *cm, int id, const char *v);
/* Builds and validates the model; prints the message and returns nonzero on error. */
int cli_model_build(const cli_model *cm, hy_model *m);

/* Exit statuses of every command (README "Exit status"): 0 ok, 1 failure
 * while running (I/O, computation), 2 usage error or invalid input (bad
 * option, bad scene, refused parameter), 3 feature not built. */
enum { CLI_OK = 0, CLI_FAILED = 1, CLI_USAGE = 2, CLI_NOT_BUILT = 3 };

/* The exit status for an hy_error code: HY_EINVAL 2, any other failure 1. */
int cli_exit_status(int code);

/* Flushes standard output; when that (or an earlier write) failed and rc is
 * 0, prints "hystviz CMD: cannot write standard output: reason" and returns
 * 1, else rc.  Every command's last step (main). */
int cli_stdout_status(const char *cmd, int rc);

/* The rest of main in a program that runs one command (hystviz-animate,
 * hystviz-serve; argv as after "hystviz"): the command cmd named name on
 * argv[1..] (none: no arguments), or on argv with argv[0] = name when
 * argv[1] is an option (--help, --version: the command's own, as every
 * command answers them); its status through cli_stdout_status.  name must
 * outlive the call (it becomes argv[0]). */
int cli_program_run(char *name, int (*cmd)(int, char **), int argc, char **argv);

/* In a build under AddressSanitizer (-DHY_LSAN_RELEASE, src/app/meson.build):
 * frees cairo's and fontconfig's process-lifetime caches, so that the leak
 * check at exit has no block of theirs to match against a suppression (the
 * match symbolizes libasan's allocator frame first: about 0.2 s of CPU in
 * every process that drew text).  Elsewhere nothing.  Only after the command
 * returned: no cairo object alive, no other thread. */
void cli_leak_check_release(void);

/* Scene policy options (the table cli_policy_opts): --include-dir DIR
 * (repeatable; dirs has room for one per argument) and --max-work N.  Takes
 * option id with value v: 1 if it was one, 0 if not, -1 on error (message
 * printed, prefixed with "hystviz cmd"). */
extern const cli_opt cli_policy_opts[];
int cli_policy_take(hy_scene_policy *pol, const char **dirs, const char *cmd, int id, const char *v);

/* What a command that renders scene files takes alike (render, data, watch):
 * --output (id CLI_OUT), --set, repeatable (CLI_SET; sets has room for one
 * per argument) and --format (CLI_FORMAT); each command's table says what
 * they mean for it. */
enum { CLI_OUT = 1300, CLI_SET, CLI_FORMAT };
typedef struct cli_outputs {
    const char *out, *formats; /* NULL: not given */
    char **sets;
    size_t nsets;
} cli_outputs;
/* Takes option id with value v: 1 if it was one of them, 0 if not. */
int cli_outputs_take(cli_outputs *o, int id, const char *v);

/* -j, --jobs N (id CLI_JOBS), its help describing the default (hy_jobs). */
extern const cli_opt cli_jobs_opts[];

/* Signals, from the first instruction of main (README "Signals"): blocks
 * SIGINT, SIGTERM and SIGHUP in the calling thread, so every thread started
 * later has them blocked, and sets SIGINT and SIGTERM back to their default
 * action where the parent left them ignored (a background job of a shell
 * script); a signal sent at any moment of start-up stays pending until the
 * command takes it.  *set receives the three. */
void cli_signals_block(sigset_t *set);

/* For a command without its own signal handling (all but serve and watch,
 * which sigwait): a thread takes the blocked signals; at the first one it
 * stops the programs writing this process's temporaries, removes the
 * temporaries (hy_out_end) and ends the process by that signal (status
 * 128 + N in the shell).  0, or -1 when the thread cannot start. */
int cli_signals_end(void);

#endif
