/* SPDX-License-Identifier: MIT */
/* serve_frames.h: hystviz serve's pool of warm frame workers
 * (`hystviz-animate --worker`, the protocol of anim_worker.h).
 *
 * At most n workers, each started on first use and kept with its GL
 * context; a request takes an idle one (or waits for one), writes the
 * request and reads its records.  A worker that dies, answers out of step,
 * passes the time limit or whose client has gone is killed and reaped at
 * once, and the next request starts a fresh one.  sv_frames_free closes
 * their input (they exit at its end), then kills what is left and reaps
 * all.  The scene travels as text: a worker never opens a scene file.
 *
 *     sv_frames *f = sv_frames_new("/usr/bin/hystviz-animate", 2, extra, nextra);
 *     rc = sv_frames_run(f, &rq, emit, ctx, gone, ctx, NULL, msg, sizeof msg);
 *     sv_frames_free(f);
 */
#ifndef SERVE_FRAMES_H
#define SERVE_FRAMES_H

#include <stddef.h>

#include "anim_worker.h"

#define SV_FRAMES_MAX 8             /* workers of one pool at most */
#define SV_FRAME_TIMEOUT_S 60       /* a record must come within this, else the worker is killed */

typedef struct sv_frames sv_frames;

/* A pool of at most n (1..SV_FRAMES_MAX) workers of the program animate,
 * started as `animate animate --worker EXTRA...`; NULL when out of memory. */
sv_frames *sv_frames_new(const char *animate, int n, char *const *extra, size_t nextra);

/* Stops and reaps every worker (about 2 s at most) and frees the pool; NULL is allowed. */
void sv_frames_free(sv_frames *f);

/* Takes the malloc'd PNG of frame index (the callee frees it); non-zero
 * stops the request (the worker is then killed: it is out of step). */
typedef int (*sv_frame_emit)(void *ctx, long index, char *png, size_t len);
/* Whether the client of the request has gone (checked while waiting). */
typedef int (*sv_frame_gone)(void *ctx);

enum { SV_FRAMES_FAILED = -1, SV_FRAMES_GONE = -2 };

/* Runs rq on a worker: each frame record goes to emit (may be NULL for
 * info), an info record's text to *info (malloc'd; info may be NULL).
 * Returns 0 after the worker's "end"; its exit status (1..3) after "error",
 * the message (trailing newlines cut) in msg; SV_FRAMES_FAILED with msg when
 * no worker could answer (cannot start, died, out of step, timed out);
 * SV_FRAMES_GONE when gone(gctx) said so or emit refused. */
int sv_frames_run(sv_frames *f, const aw_request *rq, sv_frame_emit emit, void *ctx, sv_frame_gone gone, void *gctx,
                  char **info, char *msg, size_t size);

#endif
