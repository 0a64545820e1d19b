/* SPDX-License-Identifier: MIT */
/* dirwatch.c: inotify on directories with debouncing (see dirwatch.h). */
#include "dirwatch.h"

#include <errno.h>
#include <limits.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/inotify.h>
#include <time.h>
#include <unistd.h>

#define QUIET_MS 80
#define BURST_MS 400

struct hy_dirwatch {
    int fd;
    size_t n;
    int *wd;
    char **dir;
};

hy_dirwatch *hy_dirwatch_open(const char *const *dirs, size_t n, hy_error *err)
{
    hy_dirwatch *w = calloc(1, sizeof *w);
    if (w)
        w->fd = -1;
    if (!w || !(w->wd = calloc(n ? n : 1, sizeof *w->wd)) || !(w->dir = calloc(n ? n : 1, sizeof *w->dir))) {
        hy_dirwatch_close(w);
        hy_error_set(err, HY_ENOMEM, "out of memory");
        return NULL;
    }
    w->fd = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
    if (w->fd < 0) {
        hy_error_set(err, HY_EIO, "inotify: %s", strerror(errno));
        hy_dirwatch_close(w);
        return NULL;
    }
    for (size_t i = 0; i < n; i++) {
        w->wd[i] = inotify_add_watch(w->fd, dirs[i], IN_CLOSE_WRITE | IN_MOVED_TO | IN_MOVED_FROM | IN_CREATE |
                                                         IN_DELETE | IN_ONLYDIR);
        if (w->wd[i] < 0 || !(w->dir[i] = strdup(dirs[i]))) {
            hy_error_set(err, HY_EIO, "%s: cannot watch the directory: %s", dirs[i], strerror(errno));
            w->n = i + 1;
            hy_dirwatch_close(w);
            return NULL;
        }
        w->n = i + 1;
    }
    return w;
}

void hy_dirwatch_close(hy_dirwatch *w)
{
    if (!w)
        return;
    if (w->fd >= 0)
        close(w->fd);
    for (size_t i = 0; w->dir && i < w->n; i++)
        free(w->dir[i]);
    free(w->dir);
    free(w->wd);
    free(w);
}

static int ignored(const char *name)
{
    size_t n = strlen(name);
    return name[0] == '.' || (n && name[n - 1] == '~') || strstr(name, ".tmp.") ||
           (n > 4 && !strcmp(name + n - 4, ".swp"));
}

static long long now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (long long)ts.tv_sec * 1000 + ts.tv_nsec / 1000000;
}

/* Reads the pending events; appends the names that count.  Returns how many
 * counted, or -1 on a read error. */
static int drain(hy_dirwatch *w, char *names, size_t size)
{
    int counted = 0;
    for (;;) {
        char buf[8192] __attribute__((aligned(__alignof__(struct inotify_event))));
        ssize_t len = read(w->fd, buf, sizeof buf);
        if (len < 0)
            return errno == EAGAIN || errno == EINTR ? counted : -1;
        if (len == 0)
            return counted;
        for (char *p = buf; p < buf + len;) {
            const struct inotify_event *ev = (const struct inotify_event *)(void *)p;
            p += sizeof *ev + ev->len;
            if (ev->mask & IN_Q_OVERFLOW) {
                counted++;
                continue;
            }
            if (!ev->len || ignored(ev->name))
                continue;
            const char *dir = "";
            for (size_t i = 0; i < w->n; i++)
                if (w->wd[i] == ev->wd)
                    dir = w->dir[i];
            char one[PATH_MAX + NAME_MAX + 2];
            int k = snprintf(one, sizeof one, "%s/%s", dir, ev->name);
            size_t have = strlen(names);
            /* each name once; those that do not fit are dropped */
            int dup = 0;
            for (const char *q = names; (q = strstr(q, one)); q++)
                if ((q == names || q[-1] == '\n') && (q[k] == '\n' || q[k] == '\0'))
                    dup = 1;
            if (!dup && have + (size_t)k + 2 < size)
                snprintf(names + have, size - have, "%s%s", have ? "\n" : "", one);
            counted++;
        }
    }
}

int hy_dirwatch_wait(hy_dirwatch *w, int stop_fd, int timeout_ms, char *names, size_t size, hy_error *err)
{
    if (size)
        names[0] = '\0';
    long long start = now_ms(), first = -1, last = -1;
    for (;;) {
        int wait_ms = -1;
        long long t = now_ms();
        if (first >= 0) {
            long long until = last + QUIET_MS < first + BURST_MS ? last + QUIET_MS : first + BURST_MS;
            if (t >= until)
                return 1;
            wait_ms = (int)(until - t);
        } else if (timeout_ms >= 0) {
            if (t - start >= timeout_ms)
                return 0;
            wait_ms = (int)(timeout_ms - (t - start));
        }
        struct pollfd pf[2] = {{w->fd, POLLIN, 0}, {stop_fd, POLLIN, 0}};
        int r = poll(pf, stop_fd >= 0 ? 2 : 1, wait_ms);
        if (r < 0) {
            if (errno == EINTR)
                continue;
            return hy_error_set(err, HY_EIO, "poll: %s", strerror(errno)), -1;
        }
        if (stop_fd >= 0 && (pf[1].revents & (POLLIN | POLLHUP | POLLERR)))
            return 0;
        if (pf[0].revents & POLLIN) {
            int c = drain(w, names, size);
            if (c < 0)
                return hy_error_set(err, HY_EIO, "inotify: %s", strerror(errno)), -1;
            if (c > 0) {
                last = now_ms();
                if (first < 0)
                    first = last;
            }
        }
    }
}
