/* SPDX-License-Identifier: MIT */
/* serve_events.c: Server-Sent Events and the directory watcher (serve_events.h). */
#include "serve_events.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dirwatch.h"
#include "serve_answer.h"
#include "serve_request.h"
#include "serve_slots.h"

#define SSE_PING_S 5        /* below the idle timeout (serve_http.c): a live stream is never idle that long */
#define SSE_PER_PAGE 2      /* event streams per page (SSE_MAX in all) (?page=ID; streams without one share "") */

typedef struct sse_client {
    sv_server *s;
    unsigned long seen;
    int hello;
    int fd;                 /* the connection's socket: a closed peer frees the slot at once */
    sv_sse_page *page;         /* the slot counted in s->sse */
    double last;            /* when something was last sent */
} sse_client;


static ssize_t sse_read(void *cls, uint64_t pos, char *buf, size_t max)
{
    (void)pos;
    sse_client *cl = cls;
    sv_server *s = cl->s;
    if (max < 64)
        return 0;
    pthread_mutex_lock(&s->mu);
    if (s->stopping) {
        pthread_mutex_unlock(&s->mu);
        return MHD_CONTENT_READER_END_OF_STREAM;
    }
    if (!cl->hello) {
        cl->hello = 1;
        cl->seen = s->gen;
        int n = snprintf(buf, max, "retry: 1000\nevent: hello\ndata: {\"gen\":%lu}\n\n", s->gen);
        pthread_mutex_unlock(&s->mu);
        return n;
    }
    /* wait for a change in slices of 0.2 s, looking at the peer between them */
    int gone = 0;
    while (cl->seen == s->gen && !s->stopping && sv_now() - cl->last < SSE_PING_S && !gone) {
        sv_cond_wait_slice(&s->cond, &s->mu);
        gone = sv_peer_gone(cl->fd);
    }
    if (gone) {
        pthread_mutex_unlock(&s->mu);
        return MHD_CONTENT_READER_END_WITH_ERROR;
    }
    if (s->stopping) {
        pthread_mutex_unlock(&s->mu);
        return MHD_CONTENT_READER_END_OF_STREAM;
    }
    cl->last = sv_now();
    if (cl->seen == s->gen) {
        pthread_mutex_unlock(&s->mu);
        return snprintf(buf, max, ": ping\n\n");
    }
    cl->seen = s->gen;
    sv_buf b = {0};
    sv_printf(&b, "event: change\ndata: {\"gen\":%lu,\"files\":", s->gen);
    sv_json(&b, s->changed);
    sv_puts(&b, "}\n\n");
    pthread_mutex_unlock(&s->mu);
    ssize_t n = 0;
    if (!b.oom && b.len <= max) {
        memcpy(buf, b.s, b.len);
        n = (ssize_t)b.len;
    } else
        n = snprintf(buf, max, "event: change\ndata: {\"gen\":%lu,\"files\":\"\"}\n\n", cl->seen);
    free(b.s);
    return n;
}

static void sse_free(void *cls)
{
    sse_client *cl = cls;
    sv_server *s = cl->s;
    pthread_mutex_lock(&s->mu);
    if (cl->page && --cl->page->n == 0)
        cl->page->id[0] = '\0';
    s->nsse--;
    pthread_mutex_unlock(&s->mu);
    free(cl);
}

/* Counts a new stream of page id from address addr; NULL when over SSE_MAX
 * in all, SSE_PER_ADDR for the address (so that one client cannot take
 * every stream: other addresses keep live reload) or SSE_PER_PAGE for the
 * page.  Local pages all come from 127.0.0.1 and share its SSE_PER_ADDR. */
static sv_sse_page *sse_enter(sv_server *s, const char *id, const unsigned char addr[17])
{
    pthread_mutex_lock(&s->mu);
    sv_sse_page *p = NULL, *free_slot = NULL;
    int from_addr = 0;
    for (int i = 0; i < SSE_MAX; i++) {
        int same = s->sse[i].n && !memcmp(s->sse[i].addr, addr, sizeof s->sse[i].addr);
        from_addr += same ? s->sse[i].n : 0;
        if (same && !strcmp(s->sse[i].id, id))
            p = &s->sse[i];
        else if (!s->sse[i].n && !free_slot)
            free_slot = &s->sse[i];
    }
    if (s->nsse >= SSE_MAX || from_addr >= SSE_PER_ADDR || (p && p->n >= SSE_PER_PAGE) || (!p && !free_slot)) {
        pthread_mutex_unlock(&s->mu);
        return NULL;
    }
    if (!p) {
        p = free_slot;
        snprintf(p->id, sizeof p->id, "%s", id);
        memcpy(p->addr, addr, sizeof p->addr);
    }
    p->n++;
    s->nsse++;
    pthread_mutex_unlock(&s->mu);
    return p;
}

/* GET /events?page=P: a stream of "hello", then "change" (the files) at
 * each generation, ": ping" every SSE_PING_S; 503 over the stream limits
 * (SSE_MAX in all, SSE_PER_ADDR an address, SSE_PER_PAGE a page). */
enum MHD_Result sv_api_events(sv_server *s, struct MHD_Connection *c, const sv_args *a, const char *rest)
{
    (void)rest;
    const char *id = a->page ? a->page : "";
    if (strlen(id) >= sizeof s->sse[0].id)
        return sv_send_text(c, 400, "page: at most 39 characters");
    unsigned char addr[17];
    sv_addr_key(c, addr);
    sv_sse_page *pg = sse_enter(s, id, addr);
    if (!pg)
        return sv_send_busy(c, SV_SLOT_FULL);
    sse_client *cl = calloc(1, sizeof *cl);
    if (!cl) {
        pthread_mutex_lock(&s->mu);
        if (--pg->n == 0)
            pg->id[0] = '\0';
        s->nsse--;
        pthread_mutex_unlock(&s->mu);
        return MHD_NO;
    }
    cl->s = s;
    cl->page = pg;
    cl->last = sv_now();
    const union MHD_ConnectionInfo *ci = MHD_get_connection_info(c, MHD_CONNECTION_INFO_CONNECTION_FD);
    cl->fd = ci ? ci->connect_fd : -1;
    struct MHD_Response *r = MHD_create_response_from_callback(MHD_SIZE_UNKNOWN, 4096, sse_read, cl, sse_free);
    if (!r) {
        sse_free(cl);
        return MHD_NO;
    }
    MHD_add_response_header(r, "Content-Type", "text/event-stream");
    MHD_add_response_header(r, "Cache-Control", "no-store");
    enum MHD_Result ret = MHD_queue_response(c, 200, r);
    MHD_destroy_response(r);
    return ret;
}

void *sv_watcher(void *arg)
{
    sv_server *s = arg;
    const char *dirs[1] = {s->dir};
    hy_error err;
    hy_dirwatch *w = hy_dirwatch_open(dirs, 1, &err);
    if (!w) {
        fprintf(stderr, "hystviz serve: %s; pages will not reload on save\n", err.msg);
        return NULL;
    }
    char names[2048];
    for (;;) {
        int r = hy_dirwatch_wait(w, s->stop_pipe[0], -1, names, sizeof names, &err);
        if (r <= 0) {
            if (r < 0)
                fprintf(stderr, "hystviz serve: %s; pages will not reload on save\n", err.msg);
            break;
        }
        pthread_mutex_lock(&s->mu);
        s->gen++;
        /* the names relative to the directory */
        sv_buf b = {0};
        size_t dl = strlen(s->dir);
        for (char *p = names; *p;) {
            char *nl = strchr(p, '\n');
            size_t n = nl ? (size_t)(nl - p) : strlen(p);
            if (n > dl && !strncmp(p, s->dir, dl) && p[dl] == '/') {
                if (b.len)
                    sv_puts(&b, "\n");
                sv_add(&b, p + dl + 1, n - dl - 1);
            }
            p += n + (nl ? 1 : 0);
        }
        snprintf(s->changed, sizeof s->changed, "%s", b.s ? b.s : "");
        free(b.s);
        pthread_cond_broadcast(&s->cond);
        pthread_mutex_unlock(&s->mu);
    }
    hy_dirwatch_close(w);
    return NULL;
}
