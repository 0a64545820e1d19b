/* SPDX-License-Identifier: MIT */
/* serve_slots.h: serve's budgets in time: cores + 1 render slots shared
 * fairly (per page id, per client address, a bounded queue), page slots
 * (latest wins per page: a drag never queues work), the cancellation a
 * running render polls, and the memory given back once idle. */
#ifndef SERVE_SLOTS_H
#define SERVE_SLOTS_H

#include "serve_types.h"

/* hy_scene_run.cancelled over an sv_render_watch (serve_types.h), polled
 * inside every series (hy_cancel.h): the work stops when its client has
 * gone, the server is stopping (issue 20 item 6), a newer request of its
 * page came (superseded) or another client's turn came (preempted, issue 36
 * item 2).  Cheap: it looks at the connection at most once a millisecond. */
int sv_render_unwanted(void *ctx);

/* Why w's render stopped: 409 (superseded), 503 (preempted: retry), or 0
 * (its client went or serve is stopping: nobody to answer). */
unsigned sv_render_stopped(sv_render_watch *w, const char **msg);

/* Whether w's render was stopped only for another client's turn (its
 * client is there, its page asked nothing newer, serve is not stopping):
 * then it is marked as running again, for the caller to give its slot back
 * and queue again. */
int sv_render_requeue(sv_render_watch *w);

/* As sv_slot_take for a render watched by w (w->s, w->c, w->page set):
 * its client is its page id, else its address, and it may be preempted
 * (see serve_slots.c).  SV_SLOT_OK must be given back by sv_render_leave. */
int sv_render_enter(sv_render_watch *w, int anon);
void sv_render_leave(sv_render_watch *w, int anon);

/* serve's memory for rasters (issue 36 item 1: a PNG at 20 in and 600 dpi
 * took 573 MB): one render's PNG surface at most SV_RASTER_MAX bytes
 * (refused before computing, 422), all renders' at most SV_MEM_TOTAL
 * (a render waits for its share). */
#define SV_RASTER_MAX ((size_t)64 << 20)
#define SV_MEM_TOTAL ((size_t)256 << 20)

/* Reserves bytes of serve's memory for rasters (SV_MEM_TOTAL) for w's
 * render, waiting while other renders hold it: SV_SLOT_OK (given back by
 * sv_render_leave), or why not. */
int sv_mem_take(sv_render_watch *w, size_t bytes);

/* The client address of c as a key: its family and the IPv4 address, or
 * the /64 prefix of an IPv6 address (all zero when unknown). */
void sv_addr_key(struct MHD_Connection *c, unsigned char key[17]);

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

/* sv_page_join for a render or a fit: when the request holds a page slot of
 * its own, w also stops on a newer request of the page (w->slot, w->seq).
 * Returns as sv_page_join. */
unsigned sv_page_watch(sv_server *s, const sv_args *a, sv_render_watch *w, sv_page_slot **slot, const char **msg);

#endif
