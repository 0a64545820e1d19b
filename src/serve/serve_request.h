/* SPDX-License-Identifier: MIT */
/* serve_request.h: a request's basics: the clock, its query arguments, the
 * Host and token checks, its scene read beneath the directory, and whether
 * its client has gone. */
#ifndef SERVE_REQUEST_H
#define SERVE_REQUEST_H

#include "serve_types.h"

/* Monotonic seconds; the calling thread's CPU seconds (a render runs on its
 * connection's thread: on a loaded machine its wall time is mostly waiting
 * for a core). */
double sv_now(void);
double sv_thread_cpu(void);

/* Waits on cond (mu held) for at most 0.2 s, so the caller can look at its
 * client or the stop flag between slices. */
void sv_cond_wait_slice(pthread_cond_t *cond, pthread_mutex_t *mu);

/* libmicrohttpd's iterator over the query arguments, into the sv_args cls;
 * MHD_NO (and too_many or bad_nul set) stops it. */
enum MHD_Result sv_arg_it(void *cls, enum MHD_ValueKind kind, const char *key, size_t key_size, const char *value,
                          size_t value_size);

/* Whether the Host header h names this server (DNS rebinding). */
int sv_host_ok(const sv_server *s, const char *h);

/* Whether the request carries the page's X-Hystviz-Token (constant time). */
int sv_token_ok(const sv_server *s, struct MHD_Connection *c);

/* The catalogue scene name's malloc'd text, its shown path in path; NULL if
 * name is not one (see serve_request.c). */
char *sv_scene_read(const sv_server *s, const char *name, char *path, size_t size, size_t *len);

/* Whether the peer of socket fd, or the client of c, has gone. */
int sv_peer_gone(int fd);
int sv_client_gone(struct MHD_Connection *c);

#endif
