/* SPDX-License-Identifier: MIT */
/* hy_child.c: spawning a helper program and reading its pipe (hy_child.h). */
#include "hy_child.h"

#include <errno.h>
#include <signal.h>
#include <string.h>
#include <unistd.h>

extern char **environ;

void hy_child_attr(posix_spawnattr_t *at)
{
    sigset_t none;
    sigemptyset(&none);
    posix_spawnattr_init(at);
    posix_spawnattr_setsigmask(at, &none);
    posix_spawnattr_setflags(at, POSIX_SPAWN_SETSIGMASK);
}

int hy_child_spawn(pid_t *pid, char *const *argv, const posix_spawn_file_actions_t *fa)
{
    posix_spawnattr_t at;
    hy_child_attr(&at);
    int sp = posix_spawn(pid, argv[0], fa, &at, argv, environ);
    posix_spawnattr_destroy(&at);
    return sp;
}

ssize_t hy_child_read(int fd, char *out, size_t size, size_t *n)
{
    char tmp[4096];
    ssize_t r;
    while ((r = read(fd, tmp, sizeof tmp)) < 0 && errno == EINTR)
        ;
    if (r > 0) {
        size_t k = (size_t)r < size - 1 - *n ? (size_t)r : size - 1 - *n;
        memcpy(out + *n, tmp, k);
        *n += k;
    }
    return r;
}
