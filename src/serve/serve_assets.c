/* SPDX-License-Identifier: MIT */
/* serve_assets.c: the page and its script and style (serve_assets.h). */
#include "serve_assets.h"

#include <stdlib.h>
#include <string.h>

#include "serve_answer.h"

/* the page (src/serve/page/, embedded at build time) */
extern const char hy_page_html[], hy_page_js[], hy_page_css[];
extern const size_t hy_page_html_len, hy_page_js_len, hy_page_css_len;

int sv_page_make(sv_server *s)
{
    const char *mark = strstr(hy_page_html, "@TOKEN@");
    if (!mark)
        return -1;
    /* without --allow-save the page gets no token (and shows no save button) */
    const char *token = s->allow_save ? s->token : "";
    size_t pre = (size_t)(mark - hy_page_html), tl = strlen(token);
    s->page_len = hy_page_html_len - 7 + tl;
    s->page = malloc(s->page_len + 1);
    if (!s->page)
        return -1;
    memcpy(s->page, hy_page_html, pre);
    memcpy(s->page + pre, token, tl);
    memcpy(s->page + pre + tl, mark + 7, hy_page_html_len - pre - 7 + 1);
    return 0;
}

/* GET / and /index.html: the page, with its own headers (a policy that
 * lets it load only its own script, style and images). */
enum MHD_Result sv_page_html(sv_server *s, struct MHD_Connection *c, const sv_args *a, const char *rest)
{
    (void)a;
    (void)rest;
    struct MHD_Response *r = MHD_create_response_from_buffer(s->page_len, s->page, MHD_RESPMEM_PERSISTENT);
    if (!r)
        return MHD_NO;
    MHD_add_response_header(r, "Content-Type", "text/html; charset=utf-8");
    MHD_add_response_header(r, "Cache-Control", "no-store");
    MHD_add_response_header(r, "X-Content-Type-Options", "nosniff");
    MHD_add_response_header(r, "X-Frame-Options", "DENY");
    MHD_add_response_header(r, "Referrer-Policy", "no-referrer");
    MHD_add_response_header(r, "Content-Security-Policy",
                            "default-src 'self'; img-src 'self' data: blob:; style-src 'self' 'unsafe-inline'; "
                            "script-src 'self'; frame-ancestors 'none'");
    enum MHD_Result ret = MHD_queue_response(c, 200, r);
    MHD_destroy_response(r);
    return ret;
}

enum MHD_Result sv_page_js(sv_server *s, struct MHD_Connection *c, const sv_args *a, const char *rest)
{
    (void)s;
    (void)a;
    (void)rest;
    return sv_send_buf(c, 200, "text/javascript; charset=utf-8", (void *)hy_page_js, hy_page_js_len, 0, NULL);
}

enum MHD_Result sv_page_css(sv_server *s, struct MHD_Connection *c, const sv_args *a, const char *rest)
{
    (void)s;
    (void)a;
    (void)rest;
    return sv_send_buf(c, 200, "text/css; charset=utf-8", (void *)hy_page_css, hy_page_css_len, 0, NULL);
}
