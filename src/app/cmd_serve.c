/* SPDX-License-Identifier: MIT */
/* cmd_serve.c: `hystviz serve [SCENE.scene|DIR]`: its options, parsed into
 * a hy_serve_opts for the server (src/serve, hy_serve.h), and one call. */
#include "cmd_serve.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cli_util.h"
#include "hy_config.h"
#include "hy_serve.h"

static const char serve_help[] =
    "usage: hystviz serve [SCENE.scene | DIR] [--port N] [--host ADDR [--public]] [--open]\n"
    "                     [--max-work W] [--include-dir DIR]... [--allow-save]\n"
    "\n"
    "Serves a live preview of the scenes in DIR (default: scenes) at http://127.0.0.1:PORT/\n"
    "until Ctrl-C: the catalogue, each figure as SVG with a slider and a number box per\n"
    "numeric key, the `hystviz render --set` line that writes the same figure, downloads\n"
    "(SVG, PDF, PNG, CSV), animations played at their frame rate (frames from warm\n"
    "hystviz-animate workers, the sliders applied), a reload of every open page when a\n"
    "scene file or one it includes is saved, and (with --allow-save) \"save as new scene\".\n"
    "With SCENE.scene, the page opens that scene (the others in its directory stay reachable).\n"
    "\n";

static const char serve_tail[] =
    "A page may set (as `render --set`) numbers, switches, choices, lengths and colours of\n"
    "[model], [input], [compute], [series], [figure], [annotation] and [param]; never a file path,\n"
    "text, [output] or an animation.  Budgets: one answer is at most 32 MB, one PNG's raster\n"
    "64 MB; renders run a few at a time, one per page (else per address) while another\n"
    "waits (requests without a page id get half of them; 64 wait, more get 503 with\n"
    "Retry-After); a page's newer request stops its running render; a request whose\n"
    "client has gone is stopped; idle connections close after 10 s; 32 event streams in\n"
    "all, 16 per address, 2 per page.\n"
    "\n"
    "Only the directory's *.scene files and their renders are served; requests whose\n"
    "Host header is not the bound address or localhost are refused (DNS rebinding), as\n"
    "are requests another site's page makes (Sec-Fetch-Site).  Exit status: 0 after\n"
    "Ctrl-C, 1 if the port cannot be bound, 2 for a bad option, 3 if built without\n"
    "libmicrohttpd.\n";

enum { OPT_PORT = CLI_FIRST, OPT_HOST, OPT_PUBLIC, OPT_OPEN, OPT_MAX_WORK, OPT_ALLOW_SAVE };
static const cli_opt serve_opts[] = {
    {"port", 0, "N", "port (default 8017; 0 picks a free one, printed)", OPT_PORT, 0, NULL, NULL, NULL},
    {"host", 0, "ADDR", "address to bind (default 127.0.0.1); any other needs --public", OPT_HOST, 0, NULL, NULL,
     NULL},
    {"public", 0, NULL, "allow --host to be reachable from other machines: anyone who can\n"
     "reach the port reads every scene file of DIR (and what they include)\n"
     "and makes this machine render figures (CPU and memory within the\n"
     "budgets below); with --allow-save also writes new scenes into DIR", OPT_PUBLIC, 0, NULL, NULL, NULL},
    {"open", 0, NULL, "open the page in the desktop's browser (xdg-open)", OPT_OPEN, 0, NULL, NULL, NULL},
    {"max-work", 0, "W", "work budget of one render (default 5e6, about 0.5 s [bench cost]\n"
     "of CPU, docs/SCENES.md; `hystviz render` allows 1e8):\n"
     "a page's request for more is refused before computing (422);\n"
     "a fit (the page's fit button) stops past W measured points\n"
     "summed over its model evaluations (422)", OPT_MAX_WORK, 0, NULL, NULL, NULL},
    {"include-dir", 0, "DIR", "a directory scenes may include from and read input files\n"
     "from, besides their own (as for hystviz render); repeatable", CLI_INCLUDE_DIR, 0, NULL, NULL, NULL},
    {"allow-save", 0, NULL, "enable \"save as new scene\": the page carries a token that lets it\n"
     "write NEW.scene files into DIR (never replacing one), at most 100\n"
     "per run and one a second; anyone who can load the page can save", OPT_ALLOW_SAVE, 0, NULL, NULL, NULL},
    {0},
};
static const cli_cmd serve_cli = {"serve", serve_help, serve_tail, "SCENE.scene|DIR", serve_opts};

static int parse_port(const char *v, int *port)
{
    char *end;
    errno = 0;
    long p = v ? strtol(v, &end, 10) : -1;
    if (!v || errno || *end || end == v || p < 0 || p > 65535)
        return -1;
    *port = (int)p;
    return 0;
}

static int parse_max_work(const char *v, double *w)
{
    char *end;
    errno = 0;
    *w = strtod(v, &end);
    return errno || *end || end == v || !(*w >= 1) || !isfinite(*w) ? -1 : 0;
}

/* Takes option id (value p->val) into o: -1 to go on, else the exit status (2). */
static int serve_opt(hy_serve_opts *o, cli_parser *p, int id)
{
    const char *v = p->val;
    switch (id) {
    case CLI_INCLUDE_DIR: /* as render's */
        if (o->pol.ninclude_dirs == HY_SERVE_INCLUDE_DIRS) {
            fprintf(stderr, "hystviz serve: at most %d --include-dir\n", HY_SERVE_INCLUDE_DIRS);
            return 2;
        }
        return cli_policy_take(&o->pol, o->incdirs, "serve", id, v) < 0 ? 2 : -1;
    case OPT_PORT:
        if (parse_port(v, &o->port)) {
            fprintf(stderr, "hystviz serve: --port '%s': give a port from 0 to 65535\n", v);
            return 2;
        }
        return -1;
    case OPT_HOST: o->host = v; return -1;
    case OPT_MAX_WORK:
        if (parse_max_work(v, &o->max_work)) {
            fprintf(stderr, "hystviz serve: --max-work '%s': give a number of at least 1 (e.g. 1e8)\n", v);
            return 2;
        }
        return -1;
    case OPT_ALLOW_SAVE: o->allow_save = 1; return -1;
    case OPT_PUBLIC: o->public_ = 1; return -1;
    case OPT_OPEN: o->open_browser = 1; return -1;
    default: /* CLI_ARG */
        if (o->target)
            return cli_unexpected(p), 2;
        o->target = v;
        return -1;
    }
}

int hy_cmd_serve(int argc, char **argv)
{
    hy_serve_opts o;
    hy_serve_opts_default(&o);
    cli_parser p;
    cli_parser_init(&p, &serve_cli, argc, argv, 1);
    for (int id; (id = cli_next(&p)) != CLI_END;) {
        if (id == CLI_STOP || id == CLI_ERROR)
            return id == CLI_STOP ? 0 : 2;
        if (!HY_HAVE_MICROHTTPD)
            continue; /* built without it, hy_serve_run says so (exit 3) whatever the values */
        int rc = serve_opt(&o, &p, id);
        if (rc >= 0)
            return rc;
    }
    return hy_serve_run(&o);
}
