/* SPDX-License-Identifier: MIT */
/* serve_answer.h: the answers every endpoint sends, with serve's headers
 * (no-store, nosniff, no referrer, no frames).  Each returns what the
 * handler returns to libmicrohttpd (MHD_NO: close the connection). */
#ifndef SERVE_ANSWER_H
#define SERVE_ANSWER_H

#include "serve_types.h"

/* The headers of every answer but the page's, a figure's and 503's. */
void sv_add_headers(struct MHD_Response *r, const char *type);

/* data (len bytes, freed by libmicrohttpd when must_free) as type, with
 * Content-Disposition when given. */
enum MHD_Result sv_send_buf(struct MHD_Connection *c, unsigned status, const char *type, void *data, size_t len,
                            int must_free, const char *disposition);
/* msg and a newline as text/plain. */
enum MHD_Result sv_send_text(struct MHD_Connection *c, unsigned status, const char *msg);
/* b's text as application/json (b's memory is taken; 500 if it ran out). */
enum MHD_Result sv_send_json(struct MHD_Connection *c, unsigned status, sv_buf *b);
/* {"error":msg}. */
enum MHD_Result sv_send_error(struct MHD_Connection *c, unsigned status, const char *msg);
/* 503 with Retry-After for SV_SLOT_FULL; nothing (MHD_NO) for a client gone or a stopping server. */
enum MHD_Result sv_send_busy(struct MHD_Connection *c, int why);

#endif
