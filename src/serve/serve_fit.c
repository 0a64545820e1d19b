/* SPDX-License-Identifier: MIT */
/* serve_fit.c: a fit on the page (serve_fit.h; issue 32 item 6): the least
 * squares of scene_fit.c (GSL multifit_nlinear) run in a render slot, with
 * serve's work budget as its budget of model evaluations and the render's
 * cancellation (sv_render_unwanted) as its hook, answered as JSON. */
#include "serve_fit.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene_fit.h"
#include "serve_answer.h"
#include "serve_request.h"
#include "serve_scenes.h"
#include "serve_slots.h"

#define FIT_KEYS 16   /* free keys of one fit (hy_scene_fit_run's limit) */
#define FIT_CORR 0.95 /* pairs flagged above this |r| (hy_fit_report's) */

/* The free keys of "a,b,c" into keys (copied into buf); their count, or 0
 * with msg on a list that is empty, too long or has an empty name. */
static size_t free_keys(const char *list, char *buf, size_t size, const char **keys, const char **msg)
{
    if (!list || !*list)
        return *msg = "free: name the [model] keys to fit (free=KEY,KEY,...)", 0;
    if (strlen(list) >= size)
        return *msg = "free: too long", 0;
    memcpy(buf, list, strlen(list) + 1);
    size_t n = 0;
    for (char *p = buf, *e; p; p = e) {
        if ((e = strchr(p, ',')))
            *e++ = '\0';
        if (!*p || n == FIT_KEYS)
            return *msg = !*p ? "free: an empty key name" : "free: at most 16 keys", 0;
        keys[n++] = p;
    }
    return n;
}

/* The JSON answer of a fit f that took sec seconds in all. */
static void fit_json(sv_buf *b, const hy_scene_fit *f, const sv_args *a, double sec)
{
    const hy_fit_result *r = &f->res;
    const char *seq = a->seq;
    sv_printf(b, "{\"seq\":%s,\"params\":[", seq && *seq && strspn(seq, "0123456789") == strlen(seq) ? seq : "0");
    for (size_t j = 0; j < f->pb.p; j++) {
        char key[96];
        snprintf(key, sizeof key, "model.%s", f->prm[j].name);
        sv_puts(b, j ? ",{\"key\":" : "{\"key\":");
        sv_json(b, key);
        const struct {
            const char *k;
            double v;
        } num[] = {{"start", f->x0[j]}, {"estimate", r->theta[j]}, {"se", r->se[j]}, {"ci_lo", r->ci_lo[j]},
                   {"ci_hi", r->ci_hi[j]}, {"lo", f->prm[j].lo}, {"hi", f->prm[j].hi}};
        for (size_t k = 0; k < sizeof num / sizeof num[0]; k++) {
            sv_printf(b, ",\"%s\":", num[k].k);
            sv_num(b, num[k].v);
        }
        sv_printf(b, ",\"log\":%s,\"unidentifiable\":%s}", f->prm[j].scale == HY_FIT_LOG ? "true" : "false",
                  r->unident[j] ? "true" : "false");
    }
    sv_puts(b, "],\"correlated\":["); /* the pairs |r| > FIT_CORR */
    int first = 1;
    for (size_t i = 0; i < f->pb.p; i++)
        for (size_t j = i + 1; j < f->pb.p; j++) {
            double c = r->corr[i * f->pb.p + j];
            if (!(fabs(c) > FIT_CORR))
                continue;
            sv_printf(b, "%s[\"model.%s\",\"model.%s\",", first ? "" : ",", f->prm[i].name, f->prm[j].name);
            sv_num(b, c);
            sv_puts(b, "]");
            first = 0;
        }
    const struct {
        const char *k;
        double v;
    } stat[] = {{"rms", r->rms},        {"nrms", r->nrms},       {"max_error", r->max_abs},
                {"fit_index", r->fit_index}, {"cond", r->cond},  {"iterations", (double)r->iter},
                {"evaluations", (double)r->nevals}, {"points", (double)f->pb.n},
                {"fit_seconds", r->seconds}, {"seconds", sec}};
    sv_puts(b, "]");
    for (size_t k = 0; k < sizeof stat / sizeof stat[0]; k++) {
        sv_printf(b, ",\"%s\":", stat[k].k);
        sv_num(b, stat[k].v);
    }
    sv_puts(b, ",\"data\":[");
    for (size_t d = 0; d < f->ndata; d++) {
        sv_puts(b, d ? "," : "");
        sv_json(b, f->dname[d]);
    }
    sv_puts(b, "]}");
}

/* The checks before any work: the overrides' allow-list, the free keys, the
 * scene; 0, else the HTTP status with its message in msg. */
static unsigned fit_check(sv_server *s, const sv_args *a, hy_scene_fit_opts *o, const char **keys, char *kbuf,
                          size_t ksize, char *path, size_t psize, char **text, char *msg, size_t size)
{
    hy_error err = {0};
    for (size_t i = 0; i < a->nsets; i++)
        if (sv_set_ok(a->sets[i], &err))
            return snprintf(msg, size, "%s", err.msg), 400;
    const char *why = NULL;
    if (!(o->nfree = free_keys(a->free, kbuf, ksize, keys, &why)))
        return snprintf(msg, size, "%s", why), 400;
    if (!(*text = sv_scene_read(s, a->scene, path, psize, &o->text_len)))
        return snprintf(msg, size, "no such scene"), 404;
    return 0;
}

enum MHD_Result sv_api_fit(sv_server *s, struct MHD_Connection *c, const sv_args *a, const char *rest)
{
    (void)rest;
    double t0 = sv_now();
    hy_scene_fit_opts o;
    hy_scene_fit_opts_default(&o);
    const char *keys[FIT_KEYS];
    char kbuf[1024], path[PATH_MAX + 300], msg[sizeof ((hy_error *)0)->msg + 96], *text = NULL;
    unsigned bad = fit_check(s, a, &o, keys, kbuf, sizeof kbuf, path, sizeof path, &text, msg, sizeof msg);
    if (bad)
        return sv_send_error(c, bad, msg);
    int anon = !a->page;
    sv_render_watch w = {.s = s, .c = c, .page = a->page, .client = -1};
    sv_page_slot *slot;
    const char *why;
    if ((bad = sv_page_watch(s, a, &w, &slot, &why))) {
        free(text);
        return sv_send_error(c, bad, why);
    }
    int got = sv_render_enter(&w, anon), rc = HY_OK;
    hy_scene_fit f = {0};
    hy_error err = {0};
    if (got == SV_SLOT_OK) {
        hy_cancel hook = {sv_render_unwanted, &w};
        o.free_keys = keys;
        o.text = text;
        o.sets = (char *const *)a->sets, o.nsets = a->nsets;
        o.pol = &s->pol;
        o.max_work = s->max_work; /* one fit: the work of one render, in measured points */
        o.fit.jobs = 1;           /* one slot, one thread; from the page's values only */
        o.fit.cancel = &hook;
        rc = hy_scene_fit_run(path, &o, &f, &err);
    }
    free(text);
    unsigned stop = 0;
    const char *stop_msg = NULL;
    if (got == SV_SLOT_OK && rc == HY_ECANCEL)
        stop = sv_render_stopped(&w, &stop_msg);
    if (got == SV_SLOT_OK)
        sv_render_leave(&w, anon);
    if (slot)
        sv_page_leave(s, slot);
    if (got != SV_SLOT_OK)
        return sv_send_busy(c, got);
    if (rc == HY_ECANCEL) {
        if (stop == 409)
            return sv_send_error(c, 409, stop_msg);
        if (stop == 503)
            return sv_send_busy(c, SV_SLOT_FULL);
        sv_cancelled_count(s); /* nobody to answer: close the connection */
        return MHD_NO;
    }
    if (rc)
        return sv_send_error(c, rc == HY_ENOMEM ? 500 : 422, err.msg);
    sv_buf b = {0};
    fit_json(&b, &f, a, sv_now() - t0);
    hy_scene_fit_free(&f);
    return sv_send_json(c, 200, &b);
}
