/* SPDX-License-Identifier: MIT */
/* hy_child.h: running a helper program (hystviz-animate) from a program:
 * spawning it with the signals unblocked, and reading what it writes to a
 * pipe into a bounded buffer while draining the rest.
 *
 *     posix_spawn_file_actions_t fa;
 *     posix_spawn_file_actions_init(&fa);
 *     posix_spawn_file_actions_adddup2(&fa, fd[1], 1);
 *     pid_t pid;
 *     int sp = hy_child_spawn(&pid, argv, &fa);
 *     posix_spawn_file_actions_destroy(&fa);
 *     close(fd[1]);
 *     size_t n = 0;
 *     while (!sp && hy_child_read(fd[0], out, size, &n) > 0)
 *         ;
 *     out[n] = '\0';
 */
#ifndef HY_CHILD_H
#define HY_CHILD_H

#include <spawn.h>
#include <stddef.h>
#include <sys/types.h>

/* Initialises at to spawn with an empty signal mask (a program that blocks
 * signals for a signalfd or its threads does not hand that on); the caller
 * destroys it (posix_spawnattr_destroy). */
void hy_child_attr(posix_spawnattr_t *at);

/* posix_spawn of argv[0] with argv, this process's environment, the file
 * actions fa and hy_child_attr's empty signal mask.  Returns 0, or the
 * error number posix_spawn returned. */
int hy_child_spawn(pid_t *pid, char *const *argv, const posix_spawn_file_actions_t *fa);

/* One read of fd (retried on EINTR): what fits of it is appended to out at
 * *n, keeping out[size - 1] free for the caller's NUL; the rest is dropped,
 * so reading on drains the pipe.  Returns the bytes read, 0 at end of file,
 * -1 on error (errno set). */
ssize_t hy_child_read(int fd, char *out, size_t size, size_t *n);

#endif
