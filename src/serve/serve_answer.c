/* SPDX-License-Identifier: MIT */
/* serve_answer.c: the answers of every endpoint (serve_answer.h). */
#include "serve_answer.h"

#include <stdlib.h>
#include <string.h>

/* The headers of every answer but the page's and 503's. */
void sv_add_headers(struct MHD_Response *r, const char *type)
{
    MHD_add_response_header(r, "Content-Type", type);
    MHD_add_response_header(r, "Cache-Control", "no-store");
    MHD_add_response_header(r, "X-Content-Type-Options", "nosniff");
    MHD_add_response_header(r, "Referrer-Policy", "no-referrer");
    MHD_add_response_header(r, "X-Frame-Options", "DENY");
}

enum MHD_Result sv_send_buf(struct MHD_Connection *c, unsigned status, const char *type, void *data, size_t len,
                                int must_free, const char *disposition)
{
    struct MHD_Response *r =
        MHD_create_response_from_buffer(len, data, must_free ? MHD_RESPMEM_MUST_FREE : MHD_RESPMEM_PERSISTENT);
    if (!r) {
        if (must_free)
            free(data);
        return MHD_NO;
    }
    sv_add_headers(r, type);
    if (disposition)
        MHD_add_response_header(r, "Content-Disposition", disposition);
    enum MHD_Result ret = MHD_queue_response(c, status, r);
    MHD_destroy_response(r);
    return ret;
}

enum MHD_Result sv_send_text(struct MHD_Connection *c, unsigned status, const char *msg)
{
    size_t n = strlen(msg);
    char *m = malloc(n + 2);
    if (!m)
        return MHD_NO;
    memcpy(m, msg, n);
    memcpy(m + n, "\n", 2);
    return sv_send_buf(c, status, "text/plain; charset=utf-8", m, n + 1, 1, NULL);
}

enum MHD_Result sv_send_json(struct MHD_Connection *c, unsigned status, sv_buf *b)
{
    if (b->oom) {
        free(b->s);
        return sv_send_text(c, 500, "out of memory");
    }
    return sv_send_buf(c, status, "application/json", b->s, b->len, 1, NULL);
}

enum MHD_Result sv_send_error(struct MHD_Connection *c, unsigned status, const char *msg)
{
    sv_buf b = {0};
    sv_puts(&b, "{\"error\":");
    sv_json(&b, msg);
    sv_puts(&b, "}");
    return sv_send_json(c, status, &b);
}

enum MHD_Result sv_send_busy(struct MHD_Connection *c, int why)
{
    if (why == SV_SLOT_GONE || why == SV_SLOT_STOP)
        return MHD_NO; /* nobody to answer */
    sv_buf b = {0};
    sv_puts(&b, "{\"error\":\"the server is busy: try again in a second\"}");
    if (b.oom)
        return MHD_NO;
    struct MHD_Response *r = MHD_create_response_from_buffer(b.len, b.s, MHD_RESPMEM_MUST_FREE);
    if (!r) {
        free(b.s);
        return MHD_NO;
    }
    MHD_add_response_header(r, "Content-Type", "application/json");
    MHD_add_response_header(r, "Cache-Control", "no-store");
    MHD_add_response_header(r, "Retry-After", "1");
    enum MHD_Result ret = MHD_queue_response(c, 503, r);
    MHD_destroy_response(r);
    return ret;
}
