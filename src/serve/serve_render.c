/* SPDX-License-Identifier: MIT */
/* serve_render.c: a figure over the pipeline (serve_render.h):
 * hy_scene_run_load_text, _compute, then _render or _csv, in a render slot
 * and a page slot, cancelled when its client goes; one answer per format. */
#include "serve_render.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hy_formats.h"
#include "scene_run.h"
#include "serve_answer.h"
#include "serve_request.h"
#include "serve_scenes.h"
#include "serve_slots.h"

#define SERVE_OUTPUT_MAX (32u << 20) /* bytes of one answer (SVG, PDF, PNG, CSV, JSON) */
#define FMT_CSV (-2)                 /* the points, as `hystviz data` writes them */
#define REQUEUE_MAX 2                /* times a preempted render queues again before it answers 503 */

/* A render request from its arguments to its answer. */
typedef struct render_job {
    sv_server *s;
    struct MHD_Connection *c;
    const sv_args *a;
    const char *fmt;        /* as asked: svg, pdf, png, csv or json */
    int format;             /* HY_FORMAT_* (json: HY_FORMAT_SVG), or FMT_CSV */
    int anon;               /* no page id: at most half of the render slots */
    char path[PATH_MAX + 300];
    sv_render_watch watch;
    hy_scene_run run;
    int loaded;             /* run holds a loaded scene (freed by whoever ends it) */
    unsigned char *bytes;   /* the figure ... */
    char *csv;              /* ... or the points */
    size_t len;
    hy_panel_map map;
    double seconds, cpu;    /* the render's wall and thread CPU time */
    unsigned stop_st;       /* stopped: 409 superseded, 503 preempted, 0 client gone */
    const char *stop_msg;
    hy_error err;
} render_job;

static void command_line(sv_buf *b, const char *path, const sv_args *a, const char *fmt)
{
    sv_puts(b, !strcmp(fmt, "csv") ? "hystviz data " : "hystviz render ");
    sv_shell(b, path);
    for (size_t i = 0; i < a->nsets; i++) {
        sv_puts(b, " --set ");
        sv_shell(b, a->sets[i]);
    }
    if (strcmp(fmt, "csv"))
        sv_printf(b, " --format %s", fmt);
}


/* One coordinate array of a series as JSON: null where the point is not
 * finite in x or y (a break between pieces). */
static void json_coords(sv_buf *b, const hy_run_series *se, const double *v)
{
    sv_puts(b, "[");
    for (size_t j = 0; j < se->n; j++) {
        if (j)
            sv_puts(b, ",");
        if (isfinite(se->x[j]) && isfinite(se->y[j]))
            sv_printf(b, "%.9g", v[j]);
        else
            sv_puts(b, "null");
    }
    sv_puts(b, "]");
}

static void json_series(sv_buf *b, const hy_scene_run *r)
{
    sv_puts(b, "[");
    for (size_t i = 0; i < r->nseries; i++) {
        const hy_run_series *se = &r->series[i];
        sv_puts(b, i ? ",{\"name\":" : "{\"name\":");
        sv_json(b, se->name);
        sv_puts(b, ",\"x\":");
        json_coords(b, se, se->x);
        sv_puts(b, ",\"y\":");
        json_coords(b, se, se->y);
        if (se->has_mark)
            sv_printf(b, ",\"mark\":[%.9g,%.9g]", se->mark_x, se->mark_y);
        sv_puts(b, "}");
    }
    sv_puts(b, "]");
}

/* The format of fmt (default svg), or -1. */
static int render_format(const char *fmt)
{
    static const char *const ext[] = {HY_FIGURE_FORMATS(HY_FORMAT_EXT) NULL};
    int format = !strcmp(fmt, "json") ? HY_FORMAT_SVG : !strcmp(fmt, "csv") ? FMT_CSV : -1; /* json: an SVG with its numbers */
    for (int k = 0; format == -1 && ext[k]; k++)
        if (!strcmp(fmt, ext[k]))
            format = k;
    return format;
}

static int hover(const sv_args *a)
{
    return a->hover && !strcmp(a->hover, "1");
}

/* The bytes of the PNG surface j's figure draws on (4 a pixel; 0 for the
 * vector formats), as hy_figure_check sizes it. */
static double raster_bytes(const render_job *j)
{
    if (j->format != HY_FORMAT_PNG)
        return 0;
    const hy_decl_figure *f = &j->run.doc.figure;
    double w = f->size[0] > 0 ? f->size[0] : 8.0 / 2.54 * 72.0, h = f->size[1] > 0 ? f->size[1] : 6.0 / 2.54 * 72.0;
    double dpi = f->dpi > 0 ? (double)f->dpi : 150.0;
    return 4.0 * ceil(w * dpi / 72.0) * ceil(h * dpi / 72.0);
}

/* Refuses a raster over SV_RASTER_MAX before anything is computed (422),
 * else reserves its bytes of serve's total (waiting for them); HY_OK, or a
 * status with j->err (HY_ECANCEL: the client went while waiting). */
static int raster_reserve(render_job *j)
{
    double b = raster_bytes(j);
    if (b > (double)SV_RASTER_MAX) {
        const hy_decl_figure *f = &j->run.doc.figure;
        return hy_error_set(&j->err, HY_EINVAL, "%s: a PNG of %.0f MB (%g dpi) is over serve's memory cap of %zu MB "
                            "for one raster: lower figure.dpi or figure.size (hystviz render writes it)",
                            j->path, b / (1 << 20), f->dpi > 0 ? (double)f->dpi : 150.0, SV_RASTER_MAX >> 20);
    }
    if (b > 0 && sv_mem_take(&j->watch, (size_t)b) != SV_SLOT_OK)
        return hy_error_set(&j->err, HY_ECANCEL, "%s: stopped while waiting for memory", j->path);
    return HY_OK;
}

/* Loads text (the caller's) with the page's overrides under serve's policy,
 * computes it and draws or lists it in j's format, timed; HY_OK, or a
 * status with j->err (HY_ECANCEL: the client went).  j->loaded says whether
 * j->run is still to be freed. */
static int render_run(render_job *j, char *text, size_t tl)
{
    double t0 = sv_now(), c0 = sv_thread_cpu();
    const sv_args *a = j->a;
    int rc = hy_scene_run_load_text(&j->run, j->path, text, tl, (char *const *)a->sets, a->nsets, &j->s->pol, &j->err);
    j->loaded = !rc;
    if (!rc && (rc = raster_reserve(j))) {
        hy_scene_run_free(&j->run);
        j->loaded = 0;
    }
    if (!rc) {
        j->run.cancelled = sv_render_unwanted;
        j->run.cancel_ctx = &j->watch;
        /* a figure, not its points (csv, json with hover) */
        j->run.figure_only = j->format != FMT_CSV && !hover(a);
        j->run.formats = j->format == HY_FORMAT_PNG ? "png" : "svg"; /* the work counts a PNG's pixels */
    }
    if (!rc && (rc = hy_scene_run_compute(&j->run, NULL, &j->err))) {
        hy_scene_run_free(&j->run);
        j->loaded = 0;
    }
    if (!rc) {
        if (j->format == FMT_CSV)
            rc = hy_scene_run_csv(&j->run, &j->csv, &j->len, &j->err);
        else
            rc = hy_scene_run_render(&j->run, j->format, &j->bytes, &j->len, &j->map, &j->err);
    }
    j->seconds = sv_now() - t0, j->cpu = sv_thread_cpu() - c0;
    if (!rc && j->len > SERVE_OUTPUT_MAX) {
        rc = hy_error_set(&j->err, HY_EINVAL, "%s: the %s is %.0f MB, over serve's output budget of %u MB per answer "
                          "(hystviz render writes it)", j->path, j->fmt, (double)j->len / (1 << 20), SERVE_OUTPUT_MAX >> 20);
        free(j->bytes);
        free(j->csv);
        j->bytes = NULL, j->csv = NULL;
    }
    return rc;
}

/* The answer to a render that failed with rc: 409 for one superseded by
 * its page, 503 for one preempted, none for a client gone (the connection
 * closes), else 422 with the CLI's message. */
static enum MHD_Result render_failed(render_job *j, int rc)
{
    if (j->loaded)
        hy_scene_run_free(&j->run);
    sv_render_leave(&j->watch, j->anon);
    if (rc == HY_ECANCEL) {
        if (j->stop_st == 409)
            return sv_send_error(j->c, 409, j->stop_msg);
        if (j->stop_st == 503)
            return sv_send_busy(j->c, SV_SLOT_FULL);
        sv_cancelled_count(j->s); /* nobody to answer: close the connection */
        return MHD_NO;
    }
    return sv_send_error(j->c, 422, j->err.msg);
}

/* json: seq, timings, work and budget, the caption with its values, the
 * command line that writes the same figure. */
static void json_head(sv_buf *b, render_job *j)
{
    const char *seq = j->a->seq;
    sv_printf(b, "{\"seq\":%s,\"seconds\":", seq && strspn(seq, "0123456789") == strlen(seq) && *seq ? seq : "0");
    sv_num(b, j->seconds);
    sv_puts(b, ",\"cpu\":");
    sv_num(b, j->cpu);
    /* the work estimate and budget: the page bounds the sliders whose work grows with them */
    sv_puts(b, ",\"work\":");
    sv_num(b, j->run.work);
    sv_puts(b, ",\"budget\":");
    sv_num(b, j->run.budget);
    sv_puts(b, ",\"caption\":"); /* with the values drawn ("σ0 = {model.sigma0}") */
    if (!sv_figure_caption(b, j->run.scene, &j->run.doc))
        sv_puts(b, "null");
    sv_puts(b, ",\"cmd\":");
    sv_buf cmd = {0};
    command_line(&cmd, j->path, j->a, "svg");
    sv_json(b, cmd.s ? cmd.s : "");
    free(cmd.s);
}

/* json: each series' error against its reference. */
static void json_errors(sv_buf *b, const hy_scene_run *run)
{
    sv_puts(b, ",\"errors\":[");
    int first = 1;
    for (size_t i = 0; i < run->nseries; i++)
        if (!isnan(run->series[i].err)) {
            sv_puts(b, first ? "{\"series\":" : ",{\"series\":");
            first = 0;
            sv_json(b, run->series[i].name);
            sv_puts(b, ",\"err\":");
            sv_num(b, run->series[i].err);
            sv_puts(b, ",\"ref\":");
            sv_json(b, run->series[i].err_ref ? run->series[i].err_ref : "");
            sv_puts(b, "}");
        }
    sv_puts(b, "]");
}

/* json: where the panel was drawn, for hover: pixel box and data ranges,
 * and the x quantity's name. */
static void json_map(sv_buf *b, const hy_panel_map *map, int figure_kind)
{
    const struct {
        const char *key;
        double v;
    } mf[] = {{"x0", map->x0},   {"y0", map->y0},   {"w", map->w},     {"h", map->h},
              {"xlo", map->xlo}, {"xhi", map->xhi}, {"ylo", map->ylo}, {"yhi", map->yhi}};
    sv_puts(b, ",\"map\":{");
    for (size_t k = 0; k < sizeof mf / sizeof mf[0]; k++) {
        sv_printf(b, "%s\"%s\":", k ? "," : "", mf[k].key);
        sv_num(b, mf[k].v);
    }
    sv_printf(b, ",\"xlog\":%d,\"ylog\":%d}", map->xlog, map->ylog);
    /* the x quantity by figure kind (timeseries, loop, input, g, psi) */
    static const char *const xname[] = {"t", "u", "t", "v", "\u03f1"};
    sv_printf(b, ",\"xname\":\"%s\"", figure_kind >= 0 && figure_kind < 5 ? xname[figure_kind] : "x");
}

/* fmt=json: the SVG with its numbers (and with hover=1 the drawn series). */
static enum MHD_Result answer_json(render_job *j)
{
    sv_buf b = {0};
    json_head(&b, j);
    json_errors(&b, &j->run);
    json_map(&b, &j->map, j->run.figure_kind);
    if (hover(j->a)) {
        sv_puts(&b, ",\"series\":");
        json_series(&b, &j->run);
    }
    sv_puts(&b, ",\"svg\":");
    unsigned char *bytes = realloc(j->bytes, j->len + 1);
    if (bytes) {
        bytes[j->len] = '\0';
        sv_json(&b, (const char *)bytes);
    } else {
        free(j->bytes);
        b.oom = 1;
    }
    sv_puts(&b, "}");
    free(bytes);
    hy_scene_run_free(&j->run);
    sv_render_leave(&j->watch, j->anon);
    if (b.len > SERVE_OUTPUT_MAX) {
        free(b.s);
        return sv_send_error(j->c, 422, "the figure with its points is over serve's output budget per answer; "
                                        "turn hover off or ask for fewer points");
    }
    return sv_send_json(j->c, 200, &b);
}

/* svg, pdf, png: the bytes render writes, with the render's time. */
static enum MHD_Result answer_figure(render_job *j, const char *disp)
{
    static const char *const types[] = {HY_FIGURE_FORMATS(HY_FORMAT_MIME)};
    char hdr[64];
    snprintf(hdr, sizeof hdr, "%.6f", j->seconds);
    struct MHD_Response *r = MHD_create_response_from_buffer(j->len, j->bytes, MHD_RESPMEM_MUST_FREE);
    if (!r) {
        free(j->bytes);
        return MHD_NO;
    }
    MHD_add_response_header(r, "Content-Type", types[j->format]);
    MHD_add_response_header(r, "Cache-Control", "no-store");
    MHD_add_response_header(r, "X-Content-Type-Options", "nosniff");
    MHD_add_response_header(r, "Content-Security-Policy", "default-src 'none'; style-src 'unsafe-inline'");
    MHD_add_response_header(r, "Content-Disposition", disp);
    MHD_add_response_header(r, "X-Hystviz-Seconds", hdr);
    enum MHD_Result ret = MHD_queue_response(j->c, 200, r);
    MHD_destroy_response(r);
    return ret;
}

/* svg, pdf, png or csv: a file, inline or (name=download) as an attachment. */
static enum MHD_Result answer_file(render_job *j)
{
    char name[256];
    hy_scene_run_name(&j->run, name, sizeof name);
    sv_render_leave(&j->watch, j->anon);
    char disp[400];
    snprintf(disp, sizeof disp, "%s; filename=\"%s.%s\"",
             j->a->name && !strcmp(j->a->name, "download") ? "attachment" : "inline", name, j->fmt);
    hy_scene_run_free(&j->run);
    if (j->format == FMT_CSV)
        return sv_send_buf(j->c, 200, "text/csv; charset=utf-8", j->csv, j->len, 1, disp);
    return answer_figure(j, disp);
}

/* The checks before any work: the format, the overrides' allow-list, the
 * scene; 0, else the HTTP status with the message in msg. */
static unsigned render_check(render_job *j, char **text, size_t *tl, char *msg, size_t size)
{
    if ((j->format = render_format(j->fmt)) == -1)
        return snprintf(msg, size, "fmt: %s, csv or json", HY_FORMAT_NAMES), 400;
    for (size_t i = 0; i < j->a->nsets; i++)
        if (sv_set_ok(j->a->sets[i], &j->err))
            return snprintf(msg, size, "%s", j->err.msg), 400;
    if (!(*text = sv_scene_read(j->s, j->a->scene, j->path, sizeof j->path, tl)))
        return snprintf(msg, size, "no such scene"), 404;
    return 0;
}

enum MHD_Result sv_api_render(sv_server *s, struct MHD_Connection *c, const sv_args *a, const char *rest)
{
    (void)rest;
    render_job j = {.s = s, .c = c, .a = a, .fmt = a->fmt ? a->fmt : "svg", .anon = !a->page,
                    .watch = {.s = s, .c = c, .page = a->page, .client = -1}};
    char *text = NULL, msg[sizeof j.err.msg + 96];
    size_t tl = 0;
    unsigned bad = render_check(&j, &text, &tl, msg, sizeof msg);
    if (bad)
        return sv_send_error(c, bad, msg);
    sv_page_slot *slot;
    const char *why;
    if ((bad = sv_page_watch(s, a, &j.watch, &slot, &why))) {
        free(text);
        return sv_send_error(c, bad, why);
    }
    int got, rc = HY_OK;
    for (int requeued = 0;; requeued++) {
        if ((got = sv_render_enter(&j.watch, j.anon)) != SV_SLOT_OK)
            break;
        rc = render_run(&j, text, tl);
        /* preempted for another client's turn: its work is lost, it waits
           for a slot again (a page's render of 0.3 s on a loaded machine is
           not an error), a few times before it answers 503 */
        if (rc != HY_ECANCEL || requeued == REQUEUE_MAX || !sv_render_requeue(&j.watch))
            break;
        if (j.loaded)
            hy_scene_run_free(&j.run);
        j.loaded = 0;
        sv_render_leave(&j.watch, j.anon);
    }
    free(text);
    if (got != SV_SLOT_OK) {
        if (slot)
            sv_page_leave(s, slot);
        return sv_send_busy(c, got);
    }
    if (rc == HY_ECANCEL) /* why, while the page's slot is still this page's */
        j.stop_st = sv_render_stopped(&j.watch, &j.stop_msg);
    if (slot)
        sv_page_leave(s, slot);
    if (rc)
        return render_failed(&j, rc);
    return !strcmp(j.fmt, "json") ? answer_json(&j) : answer_file(&j);
}
