/* SPDX-License-Identifier: MIT */
/* hy_cancel.h: a cancellation hook that long loops poll (issue 36 item 2:
 * serve stops a render whose client has gone or was superseded inside a
 * series, not only between series).
 *
 *     unsigned tick = 0;
 *     for (size_t i = 0; i < n; i++) {
 *         if (hy_cancel_poll(o->cancel, &tick, 1024))
 *             return hy_cancel_error(err);
 *         ...one unit of work...
 *     }
 *
 * The loop keeps its own count and asks the hook once every `every` units,
 * so a unit costs a call, an increment and a compare; choose `every` so that
 * that many units take well under a millisecond.  The hook itself should be
 * cheap (serve's reads a clock and looks at the connection at most once a
 * millisecond).  A NULL hook, or one that never says stop, changes no
 * result: the work is the same, bit for bit. */
#ifndef HY_CANCEL_H
#define HY_CANCEL_H

#include "hy_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hy_cancel {
    int (*fn)(void *ctx);   /* nonzero: stop the work */
    void *ctx;
} hy_cancel;

/* 1 when c (may be NULL: never) says stop; asks it once every `every`
 * calls (*tick counts them; start it at 0).  c NULL, c->fn NULL or tick
 * NULL: 0 (never stops); every 0 asks on every call. */
int hy_cancel_poll(const hy_cancel *c, unsigned *tick, unsigned every);

/* HY_ECANCEL with the message every stopped loop gives. */
#define hy_cancel_error(err) hy_error_set((err), HY_ECANCEL, "stopped: the work is no longer wanted")

#ifdef __cplusplus
}
#endif

#endif
