/* SPDX-License-Identifier: MIT */
/* hy_serve.h: `hystviz serve`, the live preview in the browser, as one call.
 *
 * The command line (src/app/cmd_serve.c) parses the options into a
 * hy_serve_opts and hands it here; nothing in src/serve reads argv.  serve
 * binds HOST:PORT, serves the scenes of the directory until SIGINT, SIGTERM
 * or SIGHUP (blocked by the caller before any thread starts) and returns the
 * exit status: 0 after a signal, 1 if the port cannot be bound (or out of
 * memory), 2 for a bad host or directory, 3 when built without
 * libmicrohttpd (with a message saying so).
 *
 *     hy_serve_opts o;
 *     hy_serve_opts_default(&o);
 *     o.target = "scenes";
 *     return hy_serve_run(&o);
 */
#ifndef HY_SERVE_H
#define HY_SERVE_H

#include "hy_scene_policy.h"

#define HY_SERVE_INCLUDE_DIRS 16     /* --include-dir, at most */
#define HY_SERVE_WORK_DEFAULT 5e6    /* serve's work budget per render, about 0.5 s of CPU (hy_cost.h; --max-work) */
#define HY_SERVE_PORT_DEFAULT 8017

typedef struct hy_serve_opts {
    const char *target;      /* SCENE.scene or DIR; NULL: "scenes" */
    const char *host;        /* address to bind, as text (IPv4 or IPv6) */
    int port;                /* 0 picks a free one (printed) */
    int public_;             /* a host reachable from other machines is meant */
    int open_browser;        /* xdg-open the page's URL */
    int allow_save;          /* "save as new scene" */
    double max_work;         /* work budget of one render */
    hy_scene_policy pol;     /* include directories (pol.include_dirs points into incdirs) */
    const char *incdirs[HY_SERVE_INCLUDE_DIRS];
} hy_serve_opts;

/* The defaults: 127.0.0.1:8017, HY_SERVE_WORK_DEFAULT, the default scene policy. */
void hy_serve_opts_default(hy_serve_opts *o);

/* Serves until a signal; returns the exit status above.  o is copied. */
int hy_serve_run(const hy_serve_opts *o);

#endif
