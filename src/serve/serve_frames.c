/* SPDX-License-Identifier: MIT */
/* serve_frames.c: hystviz serve's bounded pool of warm frame workers
 * (hystviz-animate --worker over a socket pair; protocol in anim_worker.h). */
#include "serve_frames.h"

#include <errno.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

extern char **environ;

typedef struct sv_worker {
    pid_t pid;                /* 0: not running */
    int fd;                   /* our end of its stdin/stdout socket pair; -1: none */
    int busy;                 /* lent to a request */
} sv_worker;

struct sv_frames {
    pthread_mutex_t mu;
    pthread_cond_t cv;        /* a worker was given back, or the pool is closing */
    int n, closing;
    sv_worker w[SV_FRAMES_MAX];
    char *argv[40];           /* animate "animate" "--worker" extra... NULL */
};

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

sv_frames *sv_frames_new(const char *animate, int n, char *const *extra, size_t nextra)
{
    sv_frames *f = calloc(1, sizeof *f);
    if (!f || nextra > 30)
        return free(f), NULL;
    f->n = n < 1 ? 1 : n > SV_FRAMES_MAX ? SV_FRAMES_MAX : n;
    for (int i = 0; i < SV_FRAMES_MAX; i++)
        f->w[i].fd = -1;
    const char *head[] = {animate, "animate", "--worker"};
    int a = 0, bad = 0;
    for (size_t i = 0; i < 3 + nextra; i++)
        bad |= !(f->argv[a++] = strdup(i < 3 ? head[i] : extra[i - 3]));
    if (bad) {
        for (int i = 0; i < a; i++)
            free(f->argv[i]);
        free(f);
        return NULL;
    }
    pthread_mutex_init(&f->mu, NULL);
    pthread_cond_init(&f->cv, NULL);
    return f;
}

/* Kills the worker (if running), reaps it and closes its socket. */
static void worker_kill(sv_worker *w)
{
    if (w->pid > 0) {
        kill(w->pid, SIGKILL);
        while (waitpid(w->pid, NULL, 0) < 0 && errno == EINTR)
            ;
    }
    if (w->fd >= 0)
        close(w->fd);
    w->pid = 0, w->fd = -1;
}

/* Starts a worker on a socket pair (its stdin and stdout; stderr is ours),
 * with default signal handling; 0 or errno. */
static int worker_spawn(sv_frames *f, sv_worker *w)
{
    int sv[2];
    if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv))
        return errno;
    posix_spawn_file_actions_t fa;
    posix_spawnattr_t at;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, sv[1], 0);
    posix_spawn_file_actions_adddup2(&fa, sv[1], 1);
    posix_spawnattr_init(&at);
    sigset_t none, def;
    sigemptyset(&none);
    sigemptyset(&def);
    sigaddset(&def, SIGPIPE);
    posix_spawnattr_setsigmask(&at, &none);
    posix_spawnattr_setsigdefault(&at, &def);
    posix_spawnattr_setflags(&at, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
    pid_t pid;
    int e = posix_spawn(&pid, f->argv[0], &fa, &at, f->argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    posix_spawnattr_destroy(&at);
    close(sv[1]);
    if (e) {
        close(sv[0]);
        return e;
    }
    w->pid = pid, w->fd = sv[0];
    return 0;
}

/* Reaps idle workers that died meanwhile (mu held): a zombie lives until
 * the next request at most. */
static void reap_idle(sv_frames *f)
{
    for (int i = 0; i < f->n; i++)
        if (!f->w[i].busy && f->w[i].pid > 0 && waitpid(f->w[i].pid, NULL, WNOHANG) == f->w[i].pid) {
            f->w[i].pid = 0;
            close(f->w[i].fd);
            f->w[i].fd = -1;
        }
}

/* An idle worker's index (a running one first), or -1 when closing or gone. */
static int take(sv_frames *f, sv_frame_gone gone, void *gctx)
{
    pthread_mutex_lock(&f->mu);
    int got = -1;
    while (!f->closing) {
        reap_idle(f);
        for (int i = 0; i < f->n; i++)
            if (!f->w[i].busy && (got < 0 || (f->w[got].fd < 0 && f->w[i].fd >= 0)))
                got = i;
        if (got >= 0 || (gone && gone(gctx)))
            break;
        struct timespec until;
        clock_gettime(CLOCK_REALTIME, &until);
        until.tv_nsec += 200000000L;
        if (until.tv_nsec >= 1000000000L)
            until.tv_sec++, until.tv_nsec -= 1000000000L;
        pthread_cond_timedwait(&f->cv, &f->mu, &until);
    }
    if (got >= 0)
        f->w[got].busy = 1;
    pthread_mutex_unlock(&f->mu);
    return got;
}

static void give(sv_frames *f, int i)
{
    pthread_mutex_lock(&f->mu);
    f->w[i].busy = 0;
    pthread_cond_broadcast(&f->cv);
    pthread_mutex_unlock(&f->mu);
}

/* Waits until fd is ready for ev, in 0.2 s slices; 0, -1 past the deadline
 * or on an error, SV_FRAMES_GONE when gone says so. */
static int ready(int fd, short ev, double deadline, sv_frame_gone gone, void *gctx)
{
    for (;;) {
        struct pollfd p = {.fd = fd, .events = ev};
        double left = deadline - now_s();
        if (left <= 0)
            return -1;
        int r = poll(&p, 1, left < 0.2 ? (int)(left * 1000) + 1 : 200);
        if (r > 0)
            return 0;
        if (r < 0 && errno != EINTR)
            return -1;
        if (gone && gone(gctx))
            return SV_FRAMES_GONE;
    }
}

static int send_all(int fd, const char *p, size_t n, double deadline)
{
    while (n) {
        int r = ready(fd, POLLOUT, deadline, NULL, NULL);
        if (r)
            return r;
        ssize_t k = send(fd, p, n, MSG_NOSIGNAL);
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0)
            return -1;
        p += k, n -= (size_t)k;
    }
    return 0;
}

static int recv_all(int fd, char *p, size_t n, double deadline, sv_frame_gone gone, void *gctx)
{
    while (n) {
        int r = ready(fd, POLLIN, deadline, gone, gctx);
        if (r)
            return r;
        ssize_t k = read(fd, p, n);
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0)
            return -1; /* the worker died */
        p += k, n -= (size_t)k;
    }
    return 0;
}

/* One record: its header and malloc'd bytes (NUL-terminated). */
static int read_record(int fd, char tag[8], long *num, char **data, size_t *len, sv_frame_gone gone, void *gctx)
{
    double deadline = now_s() + SV_FRAME_TIMEOUT_S;
    char line[64];
    size_t n = 0;
    for (;;) {
        int r = recv_all(fd, line + n, 1, deadline, gone, gctx);
        if (r)
            return r;
        if (line[n] == '\n')
            break;
        if (++n == sizeof line)
            return -1;
    }
    line[n] = '\0';
    if (aw_record_head(line, tag, num, len) || !(*data = malloc(*len + 1)))
        return -1;
    int r = recv_all(fd, *data, *len, deadline, gone, gctx);
    if (r) {
        free(*data);
        *data = NULL;
        return r;
    }
    (*data)[*len] = '\0';
    return 0;
}

/* Reads the answer's records up to "end" or "error"; see sv_frames_run. */
static int read_answer(sv_worker *w, sv_frame_emit emit, void *ctx, sv_frame_gone gone, void *gctx, char **info,
                       char *msg, size_t size, int *records)
{
    for (;; ++*records) {
        char tag[8], *data = NULL;
        long num;
        size_t len;
        int r = read_record(w->fd, tag, &num, &data, &len, gone, gctx);
        if (r) {
            if (r != SV_FRAMES_GONE)
                snprintf(msg, size, "the frame worker stopped answering (it was restarted): try again");
            return r == SV_FRAMES_GONE ? r : SV_FRAMES_FAILED;
        }
        if (!strcmp(tag, "frame")) {
            if (emit && emit(ctx, num, data, len))
                return SV_FRAMES_GONE;
            if (!emit)
                free(data);
            continue;
        }
        if (!strcmp(tag, "info") && info && !*info) {
            *info = data;
            continue;
        }
        if (!strcmp(tag, "end") || !strcmp(tag, "error")) {
            while (len && data[len - 1] == '\n')
                data[--len] = '\0';
            snprintf(msg, size, "%s", data);
            free(data);
            return !strcmp(tag, "end") ? 0 : num >= 1 && num <= 3 ? (int)num : 1;
        }
        free(data);
        snprintf(msg, size, "the frame worker answered out of step (record '%s')", tag);
        return SV_FRAMES_FAILED;
    }
}

int sv_frames_run(sv_frames *f, const aw_request *rq, sv_frame_emit emit, void *ctx, sv_frame_gone gone, void *gctx,
                  char **info, char *msg, size_t size)
{
    msg[0] = '\0';
    size_t len;
    char *req = aw_request_encode(rq, &len);
    if (!req)
        return snprintf(msg, size, "out of memory"), SV_FRAMES_FAILED;
    int i = take(f, gone, gctx);
    if (i < 0) {
        free(req);
        return f->closing ? (snprintf(msg, size, "the server is stopping"), SV_FRAMES_FAILED) : SV_FRAMES_GONE;
    }
    sv_worker *w = &f->w[i];
    int rc = SV_FRAMES_FAILED;
    /* a worker that died while idle fails the write or ends before its
       first record: one fresh start */
    int records = 0;
    for (int attempt = 0; attempt < 2 && rc == SV_FRAMES_FAILED && !records; attempt++) {
        int e = w->fd < 0 ? worker_spawn(f, w) : 0;
        if (e) {
            snprintf(msg, size, "cannot run %s: %s", f->argv[0], strerror(e));
            break;
        }
        if (send_all(w->fd, req, len, now_s() + SV_FRAME_TIMEOUT_S)) {
            worker_kill(w);
            snprintf(msg, size, "the frame worker did not take the request");
            continue;
        }
        rc = read_answer(w, emit, ctx, gone, gctx, info, msg, size, &records);
        if (rc < 0) /* out of step, hung, dead or its client gone: it goes */
            worker_kill(w);
    }
    free(req);
    give(f, i);
    return rc;
}

void sv_frames_free(sv_frames *f)
{
    if (!f)
        return;
    pthread_mutex_lock(&f->mu);
    f->closing = 1;
    pthread_cond_broadcast(&f->cv);
    for (int i = 0; i < f->n; i++) /* the end of its input ends a worker */
        if (f->w[i].fd >= 0 && !f->w[i].busy)
            shutdown(f->w[i].fd, SHUT_WR);
    pthread_mutex_unlock(&f->mu);
    double deadline = now_s() + 2.0;
    for (int i = 0; i < f->n; i++) {
        sv_worker *w = &f->w[i];
        while (w->pid > 0 && !w->busy) {
            pid_t r = waitpid(w->pid, NULL, WNOHANG);
            if (r == w->pid || (r < 0 && errno != EINTR)) {
                w->pid = 0; /* exited at the end of its input, reaped */
                break;
            }
            if (now_s() >= deadline)
                break;
            usleep(10000);
        }
        worker_kill(w);
    }
    for (int i = 0; f->argv[i]; i++)
        free(f->argv[i]);
    pthread_cond_destroy(&f->cv);
    pthread_mutex_destroy(&f->mu);
    free(f);
}
