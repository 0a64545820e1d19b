/* SPDX-License-Identifier: MIT */
/* main.c: the hystviz command; wires subcommands, owns no numerics. */
#include "hy_config.h"
#include "hy_file.h"

#include <gsl/gsl_errno.h>
#include <errno.h>
#include <limits.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>
#include <string.h>

#include "cli_util.h"
#include "cmd_boucwen.h"
#include "cmd_check.h"
#include "cmd_export.h"
#include "cmd_fit.h"
#include "cmd_forc.h"
#include "cmd_gallery.h"
#include "cmd_loop.h"
#include "cmd_render.h"
#include "cmd_report.h"
#include "cmd_serve.h"
#include "cmd_sweep.h"

static const char usage[] =
    "usage: hystviz COMMAND [OPTIONS]\n"
    "\n"
    "hystviz renders figures and animations of hysteresis models (Dahl, LuGre,\n"
    "Bouc-Wen, Jiles-Atherton, Preisach, play) from declarative scene files,\n"
    "with exact reference solutions, measured data and fitted parameters.\n"
    "\n"
    "commands:\n"
    "  render    draw scene files into SVG, PDF and PNG figures\n"
    "  data      print every series a scene draws as CSV\n"
    "  animate   render an animation (off-screen OpenGL: OSMesa or EGL) as PNG frames or a video\n"
    "  gallery   render every scene into gallery/ (parallel, skips unchanged) with an index page\n"
    "  sweep     a parameter study: a figure and a table row per point of a grid, in shards\n"
    "  export    an interactive figure as one offline HTML file: a slider per grid key\n"
    "  loop      print a steady hysteresis loop, y*_{u,k} or y_gamma as CSV\n"
    "  loops     print the major and minor loops of an input with their areas\n"
    "  boucwen   the Bouc-Wen benchmark: Table 2, synthetic data sets as CSV\n"
    "  fit       identify a scene's parameters from its measured data (least squares)\n"
    "  forc      FORC distribution of a measured FORC file or a Preisach model as CSV\n"
    "  report    work-precision of every solver on the paper's problems (CSV, Markdown, plots)\n"
    "  check     stiff and extreme cases: finite, invariants, errors within bounds\n"
    "  serve     live preview in the browser: sliders, reload on save, animation scrubber\n"
    "  watch     re-render scene files on every save (one line per render)\n"
    "\n"
    "Each command takes --help (its options), --version and its options as\n"
    "--name VALUE, --name=VALUE or -n VALUE; '--' ends the options.\n"
    "\n";

static const char tail[] =
    "exit status (every command):\n"
    "  0  done\n"
    "  1  failure while running (a file could not be written, a computation failed)\n"
    "  2  usage error or invalid input (bad option, bad scene, refused parameter);\n"
    "     found before anything is computed or written\n"
    "  3  feature not built into this hystviz (animations without OSMesa or EGL, serve without libmicrohttpd)\n"
    "A failure prints what failed and leaves no partial file: a command's files\n"
    "are written whole, all of them or none (FILE '-' is standard output).\n"
    "SIGINT/SIGTERM: serve and watch exit 0; any other command removes its\n"
    "temporaries and ends by the signal (status 130/143 in the shell).\n"
    "\n"
    "example:\n"
    "  hystviz loop --model lugre --sigma0 6 --fc 1 --fs 2 --vs 1 --beta 1 \\\n"
    "               --input bimodal:0,0.5,1,1.5 --points 200\n";

static const cli_opt no_opts[] = {{0}}; /* -h/--help and --version: every command's */
static const cli_cmd main_cli = {"", usage, tail, NULL, no_opts};

typedef struct command {
    const char *name;
    int (*run)(int argc, char **argv);
    int own_signals; /* 1: takes SIGINT/SIGTERM itself (sigwait) and exits 0 */
} command;

static const command commands[] = {
    {"render", hy_cmd_render, 0},
    {"data", hy_cmd_render, 0},
    {"gallery", hy_cmd_gallery, 0},
    {"sweep", hy_cmd_sweep, 0},
    {"export", hy_cmd_export, 0},
    {"loop", hy_cmd_loop, 0},
    {"loops", hy_cmd_loop, 0},
    {"boucwen", hy_cmd_boucwen, 0},
    {"fit", hy_cmd_fit, 0},
    {"forc", hy_cmd_forc, 0},
    {"report", hy_cmd_report, 0},
    {"check", hy_cmd_check, 0},
    {"watch", hy_cmd_watch, 1},
};

/* Runs the program prog (hystviz-animate, hystviz-serve: next to this
 * executable in the build tree, in libexec when installed:
 * hy_file_installed) with this argv: "animate" or "serve" ...; returns only
 * on failure.  Animations (OpenGL) and serve (libmicrohttpd, gnutls) live in
 * their own programs so that no other command loads those libraries. */
static int run_sibling(const char *prog, char **argv)
{
    char path[4200];
    if (hy_file_installed(HY_INSTALLED_LIBEXEC, prog, path, sizeof path)) {
        fprintf(stderr, "hystviz %s: %s not found next to hystviz nor in %s\n", argv[1], prog, HY_LIBEXECDIR);
        return 1;
    }
    argv[0] = path;
    execv(path, argv);
    fprintf(stderr, "hystviz %s: cannot run %s: %s\n", argv[1], path, strerror(errno));
    return 1;
}

int main(int argc, char **argv)
{
    sigset_t stop;
    cli_signals_block(&stop); /* first: a signal at any moment of start-up is taken (README "Signals") */
    gsl_set_error_handler_off(); /* every GSL status is checked where it is returned */
    if (argc < 2) {
        cli_help(stderr, &main_cli, "");
        return 2;
    }
    if (!strcmp(argv[1], "help")) {
        cli_help(stdout, &main_cli, "");
        return cli_stdout_status(NULL, 0);
    }
    if (argv[1][0] == '-') { /* --help, --version, --options-json; a command's are its own */
        cli_parser p;
        cli_parser_init(&p, &main_cli, argc, argv, 1);
        int id = cli_next(&p);
        return id == CLI_STOP ? cli_stdout_status(NULL, 0) : 2; /* nothing else is accepted */
    }
    if (!strcmp(argv[1], "animate")) {
        /* malloc's large blocks (frames, llvmpipe's colour and depth
         * buffers) in transparent huge pages where the kernel offers them
         * (madvise mode): a 720p clip took 5 % of its time touching fresh
         * 4-kB pages.  A setting of the user's is left alone. */
        setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=1", 0);
        return run_sibling("hystviz-animate", argv); /* the signals stay blocked (and pending) across exec */
    }
    if (!strcmp(argv[1], "serve"))
        return run_sibling("hystviz-serve", argv);
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        if (!strcmp(argv[1], commands[i].name)) { /* every command's output checked here */
            if (!commands[i].own_signals && cli_signals_end())
                pthread_sigmask(SIG_UNBLOCK, &stop, NULL); /* no thread: the default action, at least */
            int rc = commands[i].run(argc - 1, argv + 1);
            cli_leak_check_release(); /* the command's threads have ended */
            return cli_stdout_status(argv[1], rc);
        }
    fprintf(stderr, "hystviz: unknown command '%s' (try hystviz --help)\n", argv[1]);
    return 2;
}
