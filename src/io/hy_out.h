/* SPDX-License-Identifier: MIT */
/* hy_out.h: the one output writer of hystviz.  Every file hystviz writes
 * (figures, CSV, frames, the gallery's index and manifest, the report) goes
 * through it, so every output is whole or absent and none replaces what it
 * should not.
 *
 *     hy_out o;
 *     if (hy_out_open(&o, "fig.csv", 0, &err)) return err.code;
 *     fprintf(hy_out_file(&o), "x,y\n");
 *     if (hy_out_commit(&o, &err)) fprintf(stderr, "hystviz: %s\n", err.msg);
 *
 * What a target path gets:
 *   "-"                 standard output (flushed and checked, never closed).
 *   missing or regular  a temporary file in the same directory, named
 *                       ".NAME.hystviz-tmp.XXXXXX" (O_EXCL with a random suffix, never a
 *                       predictable name), mode 0666 & ~umask, flock'ed while
 *                       it is written, renamed onto the path when complete.
 *   FIFO, char device   written directly and never replaced (-o /dev/null,
 *                       /dev/stdout, a named pipe).
 *   symbolic link       followed only to a file in the path's own directory
 *                       or below it (after resolving every link; the check is
 *                       made on the open directory, and the file is created
 *                       and renamed relative to it, so a link planted after
 *                       the check is replaced, never followed); a link out of
 *                       it is refused by name (HY_EINVAL).  This is the rule
 *                       for every name that comes from a scene or an output
 *                       directory (docs/SCENES.md).  With HY_OUT_FOLLOW (the
 *                       user's own -o FILE) a link is followed wherever it
 *                       leads, as the shell's '>' does: the file it names is
 *                       replaced atomically (the link stays), a link to a
 *                       FIFO or device (/dev/stdout into a pipe) is opened as
 *                       it is.  A link to a missing file is refused.
 *   directory, socket,  refused with a message.
 *   block device
 *
 * All or nothing over several files: open each with HY_OUT_HOLD, write them,
 * hy_out_finish each; when every one succeeded hy_out_publish each, else
 * hy_out_abort each.  HY_OUT_HOLD keeps what goes to a direct target (stdout,
 * FIFO, device) in memory until publish, so nothing reaches it on failure.
 *
 * Signals: a command ending at SIGINT/SIGTERM removes its temporaries first
 * (hy_out_end, called by cli_util.c's signal thread).
 * Stale temporaries: a writer killed by kill -9 leaves its temporary behind.
 * hy_out_sweep(DIR) removes the ones whose writer is gone (their flock is
 * free); a running writer's file is never touched.  Opening the user's own
 * file (HY_OUT_FOLLOW: `data -o FILE`) removes the stale temporaries of that
 * name the same way, so a killed run's leftovers go at the next run.
 *
 * Errors: HY_EIO (HY_ENOMEM) with "cannot write 'PATH': reason"; after any
 * failure no temporary is left.  Not thread-safe per object; distinct objects
 * may be used from distinct threads.
 */
#ifndef HY_OUT_H
#define HY_OUT_H

#include <stdio.h>
#include <sys/types.h>

#include "hy_status.h"

/* HY_OUT_HOLD: all or nothing over several files (below).
 * HY_OUT_FOLLOW: the path is the user's own (-o FILE): links followed anywhere. */
enum { HY_OUT_HOLD = 1, HY_OUT_FOLLOW = 2 };

typedef struct hy_out {
    char *path;   /* the path as given, for messages                      */
    char *final;  /* where the data goes (a symbolic link resolved)        */
    char *tmp;    /* the temporary file, NULL for a direct target          */
    FILE *fp;     /* what the caller writes to                             */
    int fd;       /* direct: the target; temporary: a dup holding the lock */
    int dfd;      /* the directory final lies in (O_PATH), or -1           */
    int follow;   /* HY_OUT_FOLLOW                                         */
    int direct;   /* 0 temporary + rename, 1 standard output, 2 device/FIFO */
    int hold;     /* a direct target's bytes are held in membuf            */
    char *membuf;
    size_t memlen;
    int state;    /* 0 unused, 1 open, 2 finished, 3 done                  */
} hy_out;

/* Opens an output for path (see above); flags: 0, HY_OUT_HOLD, HY_OUT_FOLLOW.
 * On failure o needs no cleanup. */
int hy_out_open(hy_out *o, const char *path, int flags, hy_error *err);

/* The stream to write to (valid until finish/commit/abort). */
FILE *hy_out_file(hy_out *o);

/* The name an external program may write to instead of hy_out_file (the
 * temporary file, or the target itself when direct); e.g. ffmpeg's output. */
const char *hy_out_tmp_path(const hy_out *o);

/* Flushes and closes the stream: the data is complete on disk (or in memory
 * for HY_OUT_HOLD).  On failure the temporary is removed and o is done. */
int hy_out_finish(hy_out *o, hy_error *err);

/* Renames the finished temporary onto its target (or sends the held bytes
 * to a direct target).  On failure nothing is left at the temporary name. */
int hy_out_publish(hy_out *o, hy_error *err);

/* finish + publish. */
int hy_out_commit(hy_out *o, hy_error *err);

/* Drops the output: the temporary is removed, a held buffer freed; no-op
 * on an unused or done object. */
void hy_out_abort(hy_out *o);

/* Removes DIR's stale temporaries of killed hystviz writers (flock free):
 * ".NAME.hystviz-tmp.XXXXXX", and the "NAME.EXT.tmp.XXXXXX" files of
 * earlier hystviz versions (EXT svg, pdf, png, csv, html, manifest).
 * Returns how many it removed; a missing DIR is 0. */
int hy_out_sweep(const char *dir);

/* Starts argv[0] (searched on PATH) as a program that writes a temporary
 * of this writer (ffmpeg filling hy_out_tmp_path), with default signal
 * handling and nothing blocked whatever this process blocks.  Its standard
 * input is a pipe whose write end (close-on-exec) goes to *in_fd, or
 * /dev/null when in_fd is NULL.  Returns 0 or an errno value; a started
 * program is waited for with hy_out_wait. */
int hy_out_spawn(char *const argv[], int *in_fd, pid_t *pid);

/* Waits for a program of hy_out_spawn; its waitpid status, -1 on error. */
int hy_out_wait(pid_t pid);

/* For a process that ends now (at a signal, cli_util.c): kills the programs
 * of hy_out_spawn, waits until they are gone, and removes every temporary
 * still open.  Afterwards no temporary can be opened (hy_out_open blocks);
 * the caller ends the process.  Not for signal handlers (it takes a mutex). */
void hy_out_end(void);

/* Whether name is a temporary of this writer (".NAME.hystviz-tmp.XXXXXX"). */
int hy_out_is_tmp_name(const char *name);

#endif
