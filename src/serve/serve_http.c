/* SPDX-License-Identifier: MIT */
/* serve_http.c: libmicrohttpd's callbacks and the daemon (serve_http.h). */
#include "serve_http.h"

#include <stdlib.h>
#include <string.h>

#include "serve_answer.h"
#include "serve_request.h"
#include "serve_routes.h"

#define MAX_QUERY 256       /* query arguments, counted before libmicrohttpd stores them */
#define MAX_BODY 4096       /* request body bytes (no request needs one) */
#define CONN_TIMEOUT_S 10   /* an idle connection (no bytes either way) is closed */
#define CONN_MAX 1000       /* connections in all, and from one address */
#define CONN_PER_IP 900

typedef struct conn_state {
    size_t body;
    int started;            /* handle() has seen the headers */
    int too_many;           /* more than MAX_QUERY query arguments: answered 400 */
} conn_state;

/* Called with the request line's URI before libmicrohttpd stores the query
 * arguments (each costs memory from the connection's pool; about 1,000 ran it
 * out and the connection was closed with no answer).  Past MAX_QUERY the
 * query is cut in place, in the buffer libmicrohttpd itself rewrites while
 * parsing, so none is stored, and handle() answers 400. */
static void *uri_seen(void *cls, const char *uri, struct MHD_Connection *c)
{
    (void)cls;
    (void)c;
    conn_state *cs = calloc(1, sizeof *cs);
    char *q = uri ? strchr(uri, '?') : NULL;
    size_t n = 0;
    for (const char *p = q; p && *p; p++)
        n += *p == '&';
    if (q && n + 1 > MAX_QUERY) {
        q[1] = '\0';
        if (cs)
            cs->too_many = 1;
    }
    return cs;
}

/* The checks every request passes before its route, in this order: its
 * body, its Host, another site's page, its method (*m).  0, else the HTTP
 * status with its message in *msg. */
static unsigned request_refused(const sv_server *s, struct MHD_Connection *c, const conn_state *cs, const char *method,
                                sv_method *m, const char **msg)
{
    if (cs->body > MAX_BODY)
        return *msg = "request body too large", 413;
    if (!sv_host_ok(s, MHD_lookup_connection_value(c, MHD_HEADER_KIND, "Host")))
        return *msg = "Host header not allowed (use http://localhost:PORT/ or the bound address)", 403;
    /* another site's page (an <img> flood, a form): chromium and firefox say
       so; nothing here is meant to be embedded, so it is refused before any work */
    const char *site = MHD_lookup_connection_value(c, MHD_HEADER_KIND, "Sec-Fetch-Site");
    if (site && strcmp(site, "same-origin") && strcmp(site, "none"))
        return *msg = "requests from other sites are refused", 403;
    int get = !strcmp(method, "GET") || !strcmp(method, "HEAD"), post = !strcmp(method, "POST");
    if (!get && !post)
        return *msg = "method not allowed", 405;
    *m = post ? SV_POST : SV_GET;
    return 0;
}

/* A request: its headers first (nothing to do), then its body (counted,
 * kept nowhere), then the checks, its arguments and its route's answer. */
static enum MHD_Result handle_request(void *cls, struct MHD_Connection *c, const char *url, const char *method,
                                      const char *version, const char *upload, size_t *upload_size, void **con_cls)
{
    (void)version;
    (void)upload;
    sv_server *s = cls;
    conn_state *cs = *con_cls;
    if (!cs)
        return MHD_NO; /* out of memory in uri_seen */
    if (!cs->started) {
        cs->started = 1;
        return MHD_YES;
    }
    if (*upload_size) { /* no request needs a body: count it, keep none */
        cs->body += *upload_size;
        *upload_size = 0;
        return MHD_YES;
    }
    const char *msg, *rest;
    sv_method m = SV_GET;
    unsigned st = request_refused(s, c, cs, method, &m, &msg);
    if (st)
        return sv_send_text(c, st, msg);
    sv_args a;
    memset(&a, 0, sizeof a);
    MHD_get_connection_values_n(c, MHD_GET_ARGUMENT_KIND, sv_arg_it, &a);
    if (a.too_many || cs->too_many)
        return sv_send_text(c, 400, "too many query arguments");
    if (a.bad_nul)
        return sv_send_text(c, 404, "not found");
    const sv_route *r = sv_route_find(m, url, &rest);
    if (!r) /* a path with no POST route (or none at all for GET) */
        return m == SV_POST ? sv_send_text(c, 405, "method not allowed") : sv_send_text(c, 404, "not found");
    if ((st = sv_route_refused(r, s, c, &msg)))
        return sv_send_text(c, st, msg);
    return r->handler(s, c, &a, rest);
}


/* The idle timeout is for the network: it is off while the request is being
 * answered (waiting for a render slot, rendering) and on again, counted from
 * now, for sending the answer (libmicrohttpd checks it after the handler
 * returns, and dropped answers that took longer than the timeout to make). */
static enum MHD_Result handle(void *cls, struct MHD_Connection *c, const char *url, const char *method,
                              const char *version, const char *upload, size_t *upload_size, void **con_cls)
{
    MHD_set_connection_option(c, MHD_CONNECTION_OPTION_TIMEOUT, 0u);
    enum MHD_Result ret = handle_request(cls, c, url, method, version, upload, upload_size, con_cls);
    MHD_set_connection_option(c, MHD_CONNECTION_OPTION_TIMEOUT, (unsigned)CONN_TIMEOUT_S);
    return ret;
}

static void done(void *cls, struct MHD_Connection *c, void **con_cls, enum MHD_RequestTerminationCode toe)
{
    (void)cls;
    (void)c;
    (void)toe;
    free(*con_cls);
    *con_cls = NULL;
}

struct MHD_Daemon *sv_http_start(sv_server *s, struct sockaddr *sa, int port)
{
    /* idle sockets are closed after CONN_TIMEOUT_S (a request's headers must
       come, and an answer must be read, at that pace); poll, not select, so
       descriptors past 1024 work */
    unsigned flags = MHD_USE_POLL_INTERNAL_THREAD | MHD_USE_THREAD_PER_CONNECTION | (s->ipv6 ? MHD_USE_IPv6 : 0);
    return MHD_start_daemon(flags, (uint16_t)port, NULL, NULL, handle, s, MHD_OPTION_SOCK_ADDR, sa,
                            MHD_OPTION_CONNECTION_LIMIT, (unsigned)CONN_MAX, MHD_OPTION_PER_IP_CONNECTION_LIMIT,
                            (unsigned)CONN_PER_IP, MHD_OPTION_CONNECTION_TIMEOUT, (unsigned)CONN_TIMEOUT_S,
                            MHD_OPTION_CONNECTION_MEMORY_LIMIT, (size_t)65536, MHD_OPTION_NOTIFY_COMPLETED, done, s,
                            MHD_OPTION_URI_LOG_CALLBACK, uri_seen, s, MHD_OPTION_END);
}
