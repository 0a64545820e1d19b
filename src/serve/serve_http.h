/* SPDX-License-Identifier: MIT */
/* serve_http.h: the thin libmicrohttpd layer: a thread per connection, the
 * connection limits and idle timeout, and for each request the checks every
 * request passes (body, Host, another site's page, method, query
 * arguments), then the route table (serve_routes.h).  It names no endpoint. */
#ifndef SERVE_HTTP_H
#define SERVE_HTTP_H

#include <sys/socket.h>

#include "serve_types.h"

/* Listens on sa (IPv6 when s->ipv6) and port for s; NULL if it cannot. */
struct MHD_Daemon *sv_http_start(sv_server *s, struct sockaddr *sa, int port);

#endif
