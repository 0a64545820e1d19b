/* SPDX-License-Identifier: MIT */
/* serve_events.h: reload on save: a thread watches the scenes directory
 * (dirwatch.h), bumps the server's generation and wakes GET /events, the
 * pages' Server-Sent-Events streams (at most 32 in all, 2 a page), which
 * push "change" with the files that changed. */
#ifndef SERVE_EVENTS_H
#define SERVE_EVENTS_H

#include "serve_types.h"

sv_handler sv_api_events;

/* The watcher thread (pthread_create's start routine, arg the server): it
 * ends when s->stop_pipe becomes readable. */
void *sv_watcher(void *arg);

#endif
