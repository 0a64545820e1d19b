/* SPDX-License-Identifier: MIT */
/* serve_routes.h: serve's route table: each endpoint's method, path,
 * handler, guard and budget, in one place (serve_routes.c).  The HTTP layer
 * (serve_http.c) looks a request up here and names no endpoint itself; a new
 * endpoint is a handler in its own file and one row. */
#ifndef SERVE_ROUTES_H
#define SERVE_ROUTES_H

#include "serve_types.h"

typedef enum { SV_GET, SV_POST } sv_method;   /* SV_GET: GET or HEAD */
typedef enum { SV_OPEN, SV_SAVE } sv_guard;   /* SV_SAVE: --allow-save and the page's token */

typedef struct sv_route {
    sv_method method;
    const char *path;
    int prefix;             /* path is a prefix: the rest of the URL goes to the handler */
    sv_handler *handler;
    sv_guard guard;
    const char *budget;     /* what one request may take (the limits are the handler's) */
} sv_route;

/* The routes, ended by a row with a NULL path. */
extern const sv_route sv_routes[];

/* The route of method m and url, NULL if none; *rest is the url after the
 * route's path. */
const sv_route *sv_route_find(sv_method m, const char *url, const char **rest);

/* Whether r's guard refuses the request: 0, else the HTTP status with its message in *msg. */
unsigned sv_route_refused(const sv_route *r, const sv_server *s, struct MHD_Connection *c, const char **msg);

#endif
