/* SPDX-License-Identifier: MIT */
/* serve_slots.h: serve's budgets in time: cores + 1 render slots shared
 * fairly (per page id, per client address, a bounded queue), page slots
 * (latest wins per page: a drag never queues work), the cancellation a
 * running render polls, and the memory given back once idle. */
#ifndef SERVE_SLOTS_H
#define SERVE_SLOTS_H

#include "serve_types.h"

/* What a render polls between its steps (hy_scene_run.cancelled): the work
 * stops when its client has gone or the server is stopping (issue 20 item 6:
 * requests sent and closed at once kept computing for nobody). */
typedef struct {
    sv_server *s;
    struct MHD_Connection *c;
} sv_render_watch;

/* hy_scene_run.cancelled over an sv_render_watch. */
int sv_render_unwanted(void *ctx);

/* Counts a stopped render and says so on stderr, at most once a second. */
void sv_cancelled_count(sv_server *s);

/* Waits for one of the render slots (anon: a request without a page id);
 * SV_SLOT_OK, or why not (see serve_slots.c).  SV_SLOT_OK must be given back. */
int sv_slot_take(sv_server *s, struct MHD_Connection *c, int anon);
void sv_slot_give(sv_server *s, struct MHD_Connection *c, int anon);

/* Gives freed memory back to the kernel after a while without a render;
 * the main thread calls it every second. */
void sv_idle_trim(sv_server *s);

/* Latest wins per page id (see serve_slots.c): the slot, or NULL if
 * superseded; the slot may be the server itself (every slot busy), which
 * sv_page_leave ignores. */
sv_page_slot *sv_page_enter(sv_server *s, const char *id, unsigned long seq);
void sv_page_leave(sv_server *s, sv_page_slot *p);

/* A request's page slot from its page and seq arguments: *slot NULL for a
 * request without a page id.  0, else the HTTP status (400: a bad id, 409:
 * superseded) with its message in *msg. */
unsigned sv_page_join(sv_server *s, const sv_args *a, sv_page_slot **slot, const char **msg);

#endif
