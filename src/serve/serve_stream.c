/* SPDX-License-Identifier: MIT */
/* serve_stream.c: one frame, or a stream of frames, of an animation from
 * the frame workers, in render slots and page slots (serve_stream.h). */
#include "serve_stream.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hy_scene.h"
#include "serve_anim.h"
#include "serve_answer.h"
#include "serve_request.h"
#include "serve_slots.h"

/* A frame request's animation: a built-in (@NAME) or a catalogue scene,
 * whose text is read once here, checked, and sent to the worker with the
 * path it is shown under (never opened by the worker).  The page's
 * overrides pass the allow-list as a render's do.  0, else an HTTP status
 * with the message in msg. */
static unsigned frame_source(sv_server *s, const sv_args *a, aw_request *rq, char *path, size_t psize, char *msg,
                             size_t msize)
{
    memset(rq, 0, sizeof *rq);
    int bi = sv_builtin_index(s, a->scene);
    if (bi >= 0) {
        if (a->nsets)
            return snprintf(msg, msize, "a built-in animation has no keys to set"), 400;
        snprintf(path, psize, "%s", s->builtin[bi]);
        rq->name = path;
        return 0;
    }
    hy_error err = {0};
    for (size_t i = 0; i < a->nsets; i++)
        if (sv_set_ok(a->sets[i], &err))
            return snprintf(msg, msize, "%s", err.msg), 400;
    size_t tl;
    char *text = sv_scene_read(s, a->scene, path, psize, &tl);
    if (!text)
        return snprintf(msg, msize, "no such scene"), 404;
    hy_scene *chk = NULL;
    if (hy_scene_parse_buffer_policy(path, text, tl, &s->pol, &chk, &err)) {
        free(text);
        return snprintf(msg, msize, "%s", err.msg), 422;
    }
    hy_scene_free(chk);
    rq->name = path, rq->text = text, rq->len = tl;
    for (size_t i = 0; i < a->nsets; i++)
        rq->sets[rq->nsets++] = (char *)a->sets[i];
    return 0;
}

/* A frame index from 0 in text; -1 if it is not one. */
static long frame_index(const char *text)
{
    char *end;
    errno = 0;
    long i = text ? strtol(text, &end, 10) : -1;
    return !text || !*text || *end || errno || i < 0 || i > 9999999 ? -1 : i;
}

/* The HTTP status of a worker's answer: 501 without GL, 503 for no worker, 422. */
static unsigned frame_status(int rc)
{
    return rc == 3 ? 501 : rc == SV_FRAMES_FAILED ? 503 : 422;
}

typedef struct one_frame {
    char *png;
    size_t len;
} one_frame;

static int keep_frame(void *ctx, long index, char *png, size_t len)
{
    (void)index;
    one_frame *f = ctx;
    free(f->png);
    f->png = png, f->len = len;
    return 0;
}

static int conn_gone(void *ctx) { return sv_client_gone(ctx); }

/* GET /api/frame?scene=S&frame=I[&set=K=V]...: the PNG of one frame, byte
 * for byte what `hystviz animate S --frames I:I+1 --set K=V` writes. */
enum MHD_Result sv_api_frame(sv_server *s, struct MHD_Connection *c, const sv_args *a, const char *rest)
{
    (void)rest;
    char path[PATH_MAX + 300], msg[4096];
    aw_request rq;
    unsigned bad = frame_source(s, a, &rq, path, sizeof path, msg, sizeof msg);
    if (bad)
        return sv_send_error(c, bad, msg);
    long frame = frame_index(a->frame);
    if (!s->frames) {
        free(rq.text);
        return sv_send_error(c, 501, "cannot run hystviz-animate (it is built next to hystviz)");
    }
    if (frame < 0) {
        free(rq.text);
        return sv_send_error(c, 400, "frame: a frame index from 0");
    }
    sv_page_slot *slot;
    const char *why;
    if ((bad = sv_page_join(s, a, &slot, &why))) {
        free(rq.text);
        return sv_send_error(c, bad, why);
    }
    snprintf(rq.op, sizeof rq.op, "frames");
    rq.first = frame, rq.last = frame + 1;
    one_frame got = {0};
    int taken = sv_slot_take(s, c, !a->page), rc = SV_FRAMES_GONE;
    if (taken == SV_SLOT_OK) {
        rc = sv_frames_run(s->frames, &rq, keep_frame, &got, conn_gone, c, NULL, msg, sizeof msg);
        sv_slot_give(s, c, !a->page);
    }
    free(rq.text);
    if (slot)
        sv_page_leave(s, slot);
    if (taken != SV_SLOT_OK)
        return sv_send_busy(c, taken);
    if (rc == 0 && got.png)
        return sv_send_buf(c, 200, "image/png", got.png, got.len, 1, NULL);
    free(got.png);
    if (rc == SV_FRAMES_GONE)
        return MHD_NO;
    return sv_send_error(c, frame_status(rc), msg[0] ? msg : "hystviz animate failed");
}

/* ---- a stream of frames (playback) ---- */

/* GET /api/frames?scene=S&from=A&to=B[&set=K=V]...&page=P&seq=N streams
 * frames A .. B-1 as records "frame I LEN\n<PNG>" (anim_worker.h), then
 * "end N 0\n", or "error STATUS LEN\n<message>" at the first failure.  Each
 * frame is rendered when the connection can take it, in a render slot, by
 * a warm worker; the stream ends when its client goes, the server stops or
 * a newer stream of the same page (seq) starts. */
typedef struct frame_stream {
    sv_server *s;
    struct MHD_Connection *c;
    aw_request rq;
    char path[PATH_MAX + 300];
    char page[48];
    unsigned long seq;
    long next, to, sent;
    char *buf;                /* the record being sent */
    size_t len, off;
    int ended;
} frame_stream;

static void stream_free(void *cls)
{
    frame_stream *st = cls;
    free(st->rq.text);
    free(st->buf);
    free(st);
}

/* The record "TAG NUM LEN\n" + data as st's buffer (data is the callee's). */
static int stream_record(frame_stream *st, const char *tag, long num, char *data, size_t len)
{
    char head[64];
    int h = snprintf(head, sizeof head, "%s %ld %zu\n", tag, num, len);
    char *b = malloc((size_t)h + len);
    if (b) {
        memcpy(b, head, (size_t)h);
        if (len)
            memcpy(b + h, data, len);
    }
    free(data);
    free(st->buf);
    st->buf = b, st->len = b ? (size_t)h + len : 0, st->off = 0;
    return b ? 0 : -1;
}

static int stream_frame(void *ctx, long index, char *png, size_t len)
{
    frame_stream *st = ctx;
    st->sent++;
    return stream_record(st, "frame", index, png, len);
}

/* Renders the next frame into st's buffer; -1 ends the stream at once. */
static int stream_next(frame_stream *st)
{
    sv_server *s = st->s;
    if (st->next >= st->to) {
        st->ended = 1;
        return stream_record(st, "end", st->sent, NULL, 0);
    }
    sv_page_slot *slot = sv_page_enter(s, st->page, st->seq);
    if (!slot)
        return -1; /* a newer stream of the page: this one's frames are stale */
    int taken = sv_slot_take(s, st->c, 0), rc = SV_FRAMES_GONE;
    char msg[4096] = "";
    if (taken == SV_SLOT_OK) {
        st->rq.first = st->next, st->rq.last = st->next + 1;
        rc = sv_frames_run(s->frames, &st->rq, stream_frame, st, conn_gone, st->c, NULL, msg, sizeof msg);
        sv_slot_give(s, st->c, 0);
    }
    sv_page_leave(s, slot);
    if (taken != SV_SLOT_OK || rc == SV_FRAMES_GONE)
        return -1;
    if (rc) {
        st->ended = 1;
        char *m = strdup(msg[0] ? msg : "hystviz animate failed");
        return stream_record(st, "error", (long)frame_status(rc), m, m ? strlen(m) : 0);
    }
    st->next++;
    return 0;
}

static ssize_t stream_read(void *cls, uint64_t pos, char *out, size_t max)
{
    (void)pos;
    frame_stream *st = cls;
    if (st->off == st->len) {
        if (st->ended)
            return MHD_CONTENT_READER_END_OF_STREAM;
        if (st->s->stopping || sv_client_gone(st->c) || stream_next(st))
            return MHD_CONTENT_READER_END_WITH_ERROR;
    }
    size_t n = st->len - st->off < max ? st->len - st->off : max;
    memcpy(out, st->buf + st->off, n);
    st->off += n;
    return (ssize_t)n;
}

enum MHD_Result sv_api_frames(sv_server *s, struct MHD_Connection *c, const sv_args *a, const char *rest)
{
    (void)rest;
    frame_stream *st = calloc(1, sizeof *st);
    if (!st)
        return sv_send_text(c, 500, "out of memory");
    char msg[4096];
    unsigned bad = frame_source(s, a, &st->rq, st->path, sizeof st->path, msg, sizeof msg);
    if (!bad && ((st->next = frame_index(a->from)) < 0 || (st->to = frame_index(a->to)) <= st->next))
        bad = 400, snprintf(msg, sizeof msg, "from, to: frames from .. to-1, 0 <= from < to");
    if (!bad && !s->frames)
        bad = 501, snprintf(msg, sizeof msg, "cannot run hystviz-animate (it is built next to hystviz)");
    if (!bad && (!a->page || !*a->page || strlen(a->page) >= sizeof s->pages[0].id))
        bad = 400, snprintf(msg, sizeof msg, "page: a stream needs the page's id (at most 39 characters)");
    if (bad) {
        stream_free(st);
        return sv_send_error(c, bad, msg);
    }
    char *end;
    st->s = s, st->c = c;
    st->seq = a->seq ? strtoul(a->seq, &end, 10) : 0;
    snprintf(st->page, sizeof st->page, "%s", a->page);
    snprintf(st->rq.op, sizeof st->rq.op, "frames");
    struct MHD_Response *r = MHD_create_response_from_callback(MHD_SIZE_UNKNOWN, 1 << 16, stream_read, st, stream_free);
    if (!r) {
        stream_free(st);
        return MHD_NO;
    }
    sv_add_headers(r, "application/octet-stream");
    enum MHD_Result ret = MHD_queue_response(c, 200, r);
    MHD_destroy_response(r);
    return ret;
}
