/* SPDX-License-Identifier: MIT */
/* serve_run.c: `hystviz serve`: a live preview in the browser on
 * libmicrohttpd (one thread per connection), with a control per numeric
 * key, reload on save (inotify, Server-Sent Events), animation frames from
 * warm hystviz-animate workers (serve_frames.c: no OSMesa in serve) and
 * "save as new scene".  Every figure is rendered in memory by the same
 * pipeline as `hystviz render`, so the bytes are those render writes.
 * This file, the top of src/serve, starts and stops the server
 * (hy_serve.h: the options and the call, the bottom); the routes are in
 * serve_routes.c, the HTTP layer in serve_http.c. */
#include "hy_serve.h"

#include <stdio.h>

#include "hy_config.h"

void hy_serve_opts_default(hy_serve_opts *o)
{
    *o = (hy_serve_opts){.host = "127.0.0.1", .port = HY_SERVE_PORT_DEFAULT, .max_work = HY_SERVE_WORK_DEFAULT,
                         .pol = hy_scene_policy_default()};
}

#if !HY_HAVE_MICROHTTPD

int hy_serve_run(const hy_serve_opts *o)
{
    (void)o;
    fprintf(stderr, "hystviz serve: this hystviz was built without libmicrohttpd (Debian: apt-get install "
                    "libmicrohttpd-dev, then meson setup --reconfigure build -Dmicrohttpd=enabled)\n");
    return 3;
}

#else

#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <malloc.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
#include <string.h>
#include <sys/random.h>
#include <sys/signalfd.h>
#include <sys/stat.h>
#include <unistd.h>

#include "hy_child.h"
#include "hy_file.h"
#include "hy_jobs.h"
#include "serve_anim.h"
#include "serve_assets.h"
#include "serve_events.h"
#include "serve_http.h"
#include "serve_slots.h"

extern char **environ;

/* The address to bind from o->host and o->port, into sa4 or sa6 (s->ipv6);
 * 0, else 2 with the message said: not an address, or one reachable from
 * other machines without --public. */
static int server_addr(sv_server *s, const hy_serve_opts *o, struct sockaddr_in *sa4, struct sockaddr_in6 *sa6)
{
    memset(sa6, 0, sizeof *sa6);
    memset(sa4, 0, sizeof *sa4);
    if (inet_pton(AF_INET, o->host, &sa4->sin_addr) == 1) {
        sa4->sin_family = AF_INET;
        sa4->sin_port = htons((uint16_t)o->port);
    } else if (inet_pton(AF_INET6, o->host, &sa6->sin6_addr) == 1) {
        sa6->sin6_family = AF_INET6;
        sa6->sin6_port = htons((uint16_t)o->port);
        s->ipv6 = 1;
    } else {
        fprintf(stderr, "hystviz serve: --host '%s': give an IPv4 or IPv6 address (e.g. 127.0.0.1, ::1)\n", o->host);
        return 2;
    }
    int loopback = s->ipv6 ? IN6_IS_ADDR_LOOPBACK(&sa6->sin6_addr) : (ntohl(sa4->sin_addr.s_addr) >> 24) == 127;
    if (!loopback && !o->public_) {
        fprintf(stderr, "hystviz serve: --host %s is reachable from other machines: add --public if that is meant\n",
                o->host);
        return 2;
    }
    return 0;
}

/* The scenes directory (target, default "scenes", or the directory of
 * SCENE.scene, which the page opens first), resolved and opened once; 0,
 * else 2 with the message said. */
static int server_dir(sv_server *s, const char *target)
{
    const char *dir = target ? target : "scenes";
    struct stat st;
    if (stat(dir, &st)) {
        fprintf(stderr, "hystviz serve: %s: %s\n", dir, strerror(errno));
        return 2;
    }
    if (S_ISREG(st.st_mode)) {
        const char *slash = strrchr(dir, '/');
        snprintf(s->first, sizeof s->first, "%s", slash ? slash + 1 : dir);
        if (!sv_scene_name_ok(s->first)) {
            fprintf(stderr, "hystviz serve: %s: give a NAME.scene file (letters, digits, _ - .) or a directory\n", dir);
            return 2;
        }
        if (slash)
            snprintf(s->dir_given, sizeof s->dir_given, "%.*s", (int)(slash - dir), dir);
        else
            snprintf(s->dir_given, sizeof s->dir_given, ".");
        if (!s->dir_given[0])
            snprintf(s->dir_given, sizeof s->dir_given, "/");
        dir = s->dir_given;
    }
    if (!realpath(dir, s->dir)) {
        fprintf(stderr, "hystviz serve: %s: %s\n", dir, strerror(errno));
        return 2;
    }
    s->dir_arg = dir;
    if ((s->dirfd = open(s->dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC)) < 0) {
        fprintf(stderr, "hystviz serve: %s: %s\n", dir, strerror(errno));
        return 2;
    }
    return 0;
}

/* hystviz-animate (next to this program in the build tree, in libexec
 * installed) and its built-in animations; 1 when a signal came meanwhile.
 * Start-up's long step (hystviz-animate loads GL): a signal ends it, and
 * serve, at once (the signals are blocked since main: a signalfd sees them). */
static int server_animate(sv_server *s)
{
    hy_file_installed(HY_INSTALLED_LIBEXEC, "hystviz-animate", s->animate, sizeof s->animate);
    sigset_t stop;
    sigemptyset(&stop);
    sigaddset(&stop, SIGINT);
    sigaddset(&stop, SIGTERM);
    sigaddset(&stop, SIGHUP);
    int sfd = signalfd(-1, &stop, SFD_CLOEXEC);
    int stopped = sv_list_builtins(s, sfd);
    if (sfd >= 0)
        close(sfd);
    return stopped != 0;
}

/* The per-run token and the page that carries it; 0, else 1 with the message said. */
static int server_page(sv_server *s)
{
    unsigned char rnd[16];
    if (getrandom(rnd, sizeof rnd, 0) != (ssize_t)sizeof rnd) {
        fprintf(stderr, "hystviz serve: no random bytes for the page token: %s\n", strerror(errno));
        return 1;
    }
    for (int i = 0; i < 16; i++)
        snprintf(s->token + 2 * i, 3, "%02x", rnd[i]);
    if (sv_page_make(s)) {
        fprintf(stderr, "hystviz serve: out of memory\n");
        return 1;
    }
    return 0;
}

/* The render slots (the CPUs this process may use, as -j of sweep, + 1)
 * and the frame workers: one per CPU (at most 4), each a GL context kept
 * warm; an animation's frames together within animate's budget, or serve's
 * --max-work where that is larger.  0, else 1 with the message said. */
static int server_workers(sv_server *s)
{
    long ncpu = hy_jobs_default();
    s->nslots = (int)(ncpu > 0 && ncpu < 64 ? ncpu : ncpu > 0 ? 64 : 1) + 1;
    char work[64];
    snprintf(work, sizeof work, "%.17g", s->max_work > HY_SCENE_WORK_DEFAULT ? s->max_work : HY_SCENE_WORK_DEFAULT);
    char *extra[3 + 2 * HY_SERVE_INCLUDE_DIRS] = {"--quiet", "--max-work", work};
    int nextra = 3;
    for (size_t k = 0; k < s->pol.ninclude_dirs; k++) { /* the workers load the scenes as serve does */
        extra[nextra++] = "--include-dir";
        extra[nextra++] = (char *)s->incdirs[k];
    }
    if (s->animate[0] && !(s->frames = sv_frames_new(s->animate, s->nslots - 1 < 4 ? s->nslots - 1 : 4, extra, nextra))) {
        fprintf(stderr, "hystviz serve: out of memory\n");
        return 1;
    }
    return 0;
}

/* A server for o, up to listening: its address (sa4 or sa6), directory,
 * built-in animations, page, slots, workers and stop pipe.  *rc is -1 when
 * it may listen, else the exit status (0: a signal came during start-up);
 * the server is freed by server_free either way (NULL: out of memory). */
static sv_server *server_new(const hy_serve_opts *o, struct sockaddr_in *sa4, struct sockaddr_in6 *sa6, int *rc)
{
    sv_server *s = calloc(1, sizeof *s);
    if (!s) {
        fprintf(stderr, "hystviz serve: out of memory\n");
        return *rc = 1, NULL;
    }
    s->dirfd = s->stop_pipe[0] = s->stop_pipe[1] = -1;
    pthread_mutex_init(&s->mu, NULL);
    pthread_cond_init(&s->cond, NULL);
    snprintf(s->host, sizeof s->host, "%s", o->host);
    s->public_ = o->public_, s->allow_save = o->allow_save, s->max_work = o->max_work;
    for (size_t k = 0; k < o->pol.ninclude_dirs; k++)
        s->incdirs[k] = o->incdirs[k];
    s->pol = o->pol;
    s->pol.include_dirs = s->incdirs;
    s->pol.max_work = o->max_work;
    if ((*rc = server_addr(s, o, sa4, sa6)) || (*rc = server_dir(s, o->target)))
        return s;
    if (server_animate(s)) {
        fprintf(stderr, "hystviz serve: stopping (signal during start-up)\n");
        return *rc = 0, s;
    }
    if ((*rc = server_page(s)) || (*rc = server_workers(s)))
        return s;
    /* few arenas: the memory of a heavy request is given back (malloc_trim)
       rather than kept by each connection thread's arena */
    mallopt(M_ARENA_MAX, 2);
    if (pipe(s->stop_pipe)) {
        fprintf(stderr, "hystviz serve: pipe: %s\n", strerror(errno));
        return *rc = 1, s;
    }
    return *rc = -1, s;
}

/* Everything server_new made (a NULL frame pool and descriptors of -1 are none). */
static void server_free(sv_server *s)
{
    sv_frames_free(s->frames); /* after the daemon: no request uses a worker now */
    for (int i = 0; i < 2; i++)
        if (s->stop_pipe[i] >= 0)
            close(s->stop_pipe[i]);
    if (s->dirfd >= 0)
        close(s->dirfd);
    pthread_cond_destroy(&s->cond);
    pthread_mutex_destroy(&s->mu);
    free(s->page);
    free(s);
}

/* xdg-open url; the browser gets default signal handling, not this
 * process's blocked set. */
static void open_browser(const char *url)
{
    char *oargv[] = {"xdg-open", (char *)url, NULL};
    pid_t pid;
    posix_spawnattr_t at;
    hy_child_attr(&at);
    int sp = posix_spawnp(&pid, "xdg-open", NULL, &at, oargv, environ);
    posix_spawnattr_destroy(&at);
    if (sp)
        fprintf(stderr, "hystviz serve: --open: cannot run xdg-open; open the URL above\n");
}

/* Says where serve listens (and warns with --public), opens the page with
 * --open, then waits for a signal, giving idle memory back every second;
 * returns the signal. */
static int serve_until_signal(sv_server *s, const hy_serve_opts *o, const sigset_t *sigs)
{
    const char *host = o->host, *lb = s->ipv6 ? "[" : "", *rb = s->ipv6 ? "]" : "";
    if (o->public_)
        fprintf(stderr, "hystviz serve: warning: listening on %s: anyone who can reach port %d can read the "
                        "scenes in %s and render figures\n",
                host, s->port, s->dir);
    printf("hystviz serve: http://%s%s%s:%d/ (scenes: %s; Ctrl-C stops)\n", lb, host, rb, s->port, s->dir_arg);
    fflush(stdout);
    if (o->open_browser) {
        char url[128];
        snprintf(url, sizeof url, "http://%s%s%s:%d/", lb, host, rb, s->port);
        open_browser(url);
    }
    int sig;
    for (;;) {
        struct timespec tick = {1, 0};
        sig = sigtimedwait(sigs, NULL, &tick);
        if (sig > 0)
            break;
        if (errno == EAGAIN)
            sv_idle_trim(s);
    }
    return sig;
}

/* Stops: wakes every waiter, stops the watcher, then the daemon (it joins
 * the connection threads, which finish what they are writing); rc becomes
 * 1 if the watcher cannot be told. */
static void server_stop(sv_server *s, struct MHD_Daemon *d, pthread_t *wt, int *rc)
{
    pthread_mutex_lock(&s->mu);
    s->stopping = 1;
    pthread_cond_broadcast(&s->cond);
    pthread_mutex_unlock(&s->mu);
    if (write(s->stop_pipe[1], "x", 1) < 0)
        *rc = *rc ? *rc : 1;
    if (wt)
        pthread_join(*wt, NULL);
    if (d)
        MHD_stop_daemon(d);
}

int hy_serve_run(const hy_serve_opts *o)
{
    struct sockaddr_in sa4;
    struct sockaddr_in6 sa6;
    int rc;
    sv_server *s = server_new(o, &sa4, &sa6, &rc);
    if (!s || rc >= 0) {
        if (s)
            server_free(s);
        return rc;
    }
    /* every thread inherits the blocked signals (main blocked them before
       anything else: one sent during start-up is pending); this one waits */
    sigset_t sigs;
    sigemptyset(&sigs);
    sigaddset(&sigs, SIGINT);
    sigaddset(&sigs, SIGTERM);
    sigaddset(&sigs, SIGHUP);
    pthread_sigmask(SIG_BLOCK, &sigs, NULL);
    signal(SIGPIPE, SIG_IGN);
    struct MHD_Daemon *d = sv_http_start(s, s->ipv6 ? (struct sockaddr *)&sa6 : (struct sockaddr *)&sa4, o->port);
    pthread_t wt;
    int have_wt = 0;
    if (!d) {
        fprintf(stderr, "hystviz serve: cannot listen on %s port %d (in use? try --port 0)\n", o->host, o->port);
        rc = 1;
    } else {
        const union MHD_DaemonInfo *info = MHD_get_daemon_info(d, MHD_DAEMON_INFO_BIND_PORT);
        s->port = info ? (int)info->port : o->port;
        have_wt = !pthread_create(&wt, NULL, sv_watcher, s);
        fprintf(stderr, "hystviz serve: stopping (signal %d)\n", serve_until_signal(s, o, &sigs));
        rc = 0;
    }
    server_stop(s, d, have_wt ? &wt : NULL, &rc);
    server_free(s);
    return rc;
}

#endif
