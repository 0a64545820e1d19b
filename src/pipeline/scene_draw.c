/* SPDX-License-Identifier: MIT */
/* scene_draw.c: computed scene series → hy_figure (styles, markers, labels,
 * annotations with loop-area placeholders) → SVG/PDF/PNG files and CSV data. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <cairo.h>

#include "hy_cairo.h"
#include "hy_out.h"
#include "hy_plot.h"
#include "hy_markup.h"
#include "scene_model.h"
#include "scene_forc.h"
#include "scene_run.h"

static const char *const default_xlabel[] = {"t", "u", "t", "\\nu", "\\varrho", "H_c"};
static const char *const default_ylabel[] = {"y", "y", "u(t)", "g(\\nu)", "\\psi_u(\\varrho)", "H_u"};

int hy_scene_catalogue_part(const char *file)
{
    if (!strncmp(file, "fig", 3) && file[3] >= '0' && file[3] <= '9')
        return 0;
    if (!strncmp(file, "bw_fig", 6))
        return 1;
    if (!strncmp(file, "anim_", 5))
        return 3;
    return 2;
}

void hy_scene_figure_label(const char *file, char *buf, size_t size)
{
    int part = hy_scene_catalogue_part(file);
    if (size)
        buf[0] = '\0';
    if (part > 1 || !size)
        return;
    const char *p = file + (part == 1 ? 6 : 3);
    int num = atoi(p);
    while (*p >= '0' && *p <= '9')
        p++;
    if (*p >= 'a' && *p <= 'z' && p[1] == '_')
        snprintf(buf, size, "Fig. %d%c", num, *p);
    else
        snprintf(buf, size, "Fig. %d", num);
}

/* [output] name if set, else path's file name without .scene. */
static void output_name(const hy_decl_output *o, const char *path, char *buf, size_t size)
{
    if (o->name && o->name[0]) {
        snprintf(buf, size, "%s", o->name);
        return;
    }
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    snprintf(buf, size, "%s", base);
    char *dot = strrchr(buf, '.');
    if (dot && !strcmp(dot, ".scene"))
        *dot = '\0';
}

void hy_scene_run_name(const hy_scene_run *r, char *buf, size_t size)
{
    output_name(&r->doc.output, r->path, buf, size);
}

void hy_scene_probe_name(const hy_scene *s, const char *path, char *buf, size_t size)
{
    hy_decl_output o;
    memset(&o, 0, sizeof o);
    hy_scene_decode_section(s, "output", NULL, &o.h);
    output_name(&o, path, buf, size);
}

/* Replaces {major.area}, {energy}, {minorN.area}, {minorN.own}, {minorN.ystart},
 * {minorN.yclose}, {nminor}, and for a ygamma/transient series NAME {NAME.gamma},
 * and {NAME.dist} (max |y_γ - y*_u| over its points), and {SECTION.key} (a numeric
 * key, set or by default, e.g. {model.sigma0}) in text by their values (4 significant
 * digits, hy_markup_number); {minorN.turn} is the loop's orientation in the (u, y) plane as an arrow, ↻
 * clockwise, ↺ counter-clockwise: the sign of ∮ y du, i.e. of minorN.area times the model's area sign. */
static int expand_text(const hy_scene_run *r, const char *text, const hy_decl_head *h, size_t off, int series_only,
                       char *out, size_t size, hy_error *err);

static int expand(const hy_scene_run *r, const hy_decl_annotation *a, char *out, size_t size, hy_error *err)
{
    return expand_text(r, a->text ? a->text : "", &a->h, offsetof(hy_decl_annotation, text), 0, out, size, err);
}

/* The value of placeholder key in r (NaN: none such); *turn is set for
 * minorN.turn, whose value is the loop's area (shown as its orientation). */
static double placeholder_value(const hy_scene_run *r, const char *key, int *turn)
{
    double v = NAN;
    unsigned idx;
    char field[16];
    const char *dot;
    const hy_loops *L = &r->loops;
    if (!strcmp(key, "major.area") || !strcmp(key, "energy"))
        v = L->area_period;
    else if (!strcmp(key, "major.own"))
        v = L->major.own_area;
    else if (!strcmp(key, "nminor"))
        v = (double)L->nminor;
    else if (sscanf(key, "minor%u.%15s", &idx, field) == 2 && idx >= 1 && idx <= L->nminor) {
        const hy_loop *m = &L->minor[idx - 1];
        *turn = !strcmp(field, "turn");
        v = !strcmp(field, "area") || *turn ? m->area : !strcmp(field, "own") ? m->own_area : !strcmp(field, "ystart") ? m->y_start
            : !strcmp(field, "yclose") ? m->y_close : !strcmp(field, "gap") ? m->y_close - m->y_start : NAN;
    } else if ((dot = strrchr(key, '.')) != NULL) { /* SERIES.gamma, SERIES.dist */
        for (size_t i = 0; i < r->nseries; i++) {
            const hy_run_series *se = &r->series[i];
            if (strlen(se->name) != (size_t)(dot - key) || strncmp(se->name, key, (size_t)(dot - key)))
                continue;
            int yg = se->data == HY_DATA_YGAMMA || se->data == HY_DATA_TRANSIENT;
            v = !yg ? hy_scene_data_value(r, se, dot + 1) /* data = measured, modelled: area, rms */
                    : !strcmp(dot + 1, "gamma") ? se->gamma : !strcmp(dot + 1, "dist") ? se->dist : NAN;
        }
        if (isnan(v) && dot - key < 16) { /* SECTION.key: a numeric key, set or default */
            char sect[16];
            snprintf(sect, sizeof sect, "%.*s", (int)(dot - key), key);
            double x;
            if (!hy_scene_doc_num(&r->doc, sect, dot + 1, &x))
                v = x;
        }
    }
    return v;
}

/* expand's work on text (errors at field off of h).  series_only (a legend
 * label): only the SERIES.* placeholders are filled, every other brace kept
 * as written for hy_scene_expand's {section.key}. */
static int expand_text(const hy_scene_run *r, const char *text, const hy_decl_head *h, size_t off, int series_only,
                       char *out, size_t size, hy_error *err)
{
    size_t o = 0;
    for (const char *c = text; *c && o + 1 < size;) {
        if (*c != '{') {
            out[o++] = *c++;
            continue;
        }
        const char *e = strchr(c, '}');
        if (!e)
            return hy_decl_error(h, off, err, HY_EINVAL,
                                 "unterminated '{' in annotation text (no '}' after it)");
        char key[48];
        size_t klen = (size_t)(e - c - 1);
        snprintf(key, sizeof key, "%.*s", (int)(klen < sizeof key ? klen : sizeof key - 1), c + 1);
        /* a group of any length is markup; a placeholder name is short */
        int ph = klen < sizeof key ? hy_scene_is_placeholder(key) : memchr(c + 1, '.', klen) != NULL;
        if (ph && klen >= sizeof key)
            return hy_decl_error(h, off, err, HY_EINVAL,
                                 "unknown placeholder {%.40s...}: longer than any placeholder name", key);
        if (ph && series_only) { /* a legend label: SERIES.* here, the rest by hy_scene_expand */
            const char *dt = strrchr(key, '.');
            int found = 0;
            for (size_t i = 0; dt && i < r->nseries; i++)
                found |= strlen(r->series[i].name) == (size_t)(dt - key) &&
                         !strncmp(r->series[i].name, key, (size_t)(dt - key));
            ph = found;
        }
        if (!ph) { /* a markup group such as u_{min,2}: kept */
            size_t n = (size_t)(e - c + 1);
            if (o + n >= size)
                break;
            memcpy(out + o, c, n);
            o += n;
            c = e + 1;
            continue;
        }
        int turn = 0; /* minorN.turn: the loop's net orientation in words */
        double v = placeholder_value(r, key, &turn);
        const hy_loops *L = &r->loops;
        if (isnan(v))
            return hy_decl_error(h, off, err, HY_EINVAL,
                                 "unknown placeholder {%s} (major.area, major.own, energy, nminor, minorN.area, minorN.turn, minorN.own, minorN.ystart, minorN.yclose, minorN.gap; this input has %zu minor loops; SERIES.gamma, SERIES.dist of a ygamma or transient series; SERIES.area of a measured or modelled series of one record, SERIES.rms of a modelled one; SECTION.key of a numeric key)",
                                     key, L->nminor);
        char num[64];
        if (turn)
            snprintf(num, sizeof num, "%s", v * hy_scene_model_area_sign(r->mtype) > 0 ? "\xE2\x86\xBB"
                                            : v * hy_scene_model_area_sign(r->mtype) < 0 ? "\xE2\x86\xBA" : ""); /* ↻ ↺ */
        else
            hy_markup_number(num, sizeof num, v, 4);
        int w = snprintf(out + o, size - o, "%s", num);
        o += (size_t)(w > 0 ? w : 0);
        c = e + 1;
    }
    out[o < size ? o : size - 1] = '\0';
    return HY_OK;
}

typedef hy_scene_fig fig_store;

/* The figure's [figure] size and dpi (all a format check needs). */
static void figure_size(const hy_decl_figure *d, hy_figure *f)
{
    f->full_resolution = d->full_resolution;
    f->width = d->size[0];
    f->height = d->size[1];
    f->dpi = (double)d->dpi;
}

void hy_scene_fig_free(hy_scene_fig *st)
{
    for (size_t i = 0; st->panels && i < st->npanels; i++)
        hy_scene_fig_free(&st->panels[i]);
    free(st->panels);
    free(st->axes);
    free(st->series);
    free(st->marks);
    free(st->texts);
    free(st->textbuf);
    free(st->labelbuf);
    free(st->title);
    free(st->desc);
}

/* Whether key names a placeholder this scene could fill, before computing
 * (the minor loop count is known only after it; expand checks it then). */
static int placeholder_known(const hy_scene_doc *d, const char *key)
{
    static const char *const whole[] = {"major.area", "major.own", "energy", "nminor"};
    static const char *const minor[] = {"area", "turn", "own", "ystart", "yclose", "gap"};
    for (size_t i = 0; i < sizeof whole / sizeof whole[0]; i++)
        if (!strcmp(key, whole[i]))
            return 1;
    unsigned idx;
    char field[16];
    if (sscanf(key, "minor%u.%15s", &idx, field) == 2 && idx >= 1) {
        for (size_t i = 0; i < sizeof minor / sizeof minor[0]; i++)
            if (!strcmp(field, minor[i]))
                return 1;
        return 0;
    }
    const char *dot = strrchr(key, '.');
    if (!dot)
        return 0;
    char sect[48];
    snprintf(sect, sizeof sect, "%.*s", (int)(dot - key), key);
    const hy_decl_series *se = hy_scene_doc_series(d, sect);
    if (se && hy_decl_got(&se->h, offsetof(hy_decl_series, data)) >= 0 &&
        (se->data == HY_DATA_YGAMMA || se->data == HY_DATA_TRANSIENT) && (!strcmp(dot + 1, "gamma") || !strcmp(dot + 1, "dist")))
        return 1;
    if (se && hy_decl_got(&se->h, offsetof(hy_decl_series, data)) >= 0 &&
        ((se->data == HY_DATA_MEASURED && !strcmp(dot + 1, "area")) ||
         (se->data == HY_DATA_MODELLED && (!strcmp(dot + 1, "area") || !strcmp(dot + 1, "rms")))))
        return 1;
    double x;
    return dot - key < 16 && !hy_scene_doc_num(d, sect, dot + 1, &x);
}

/* The window of an inset that follows the minor loop: the bounding box of
 * every drawn minor-loop point, widened by 12 % of its span on each side
 * (on a log axis, of the decades it spans); 0 when no minor loop is drawn. */
static int minor_window(const hy_scene_run *r, const hy_axes *ax, double zx[2], double zy[2])
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    int lg[2] = {ax->x.log, ax->y.log};
    for (size_t i = 0; i < r->nseries; i++) {
        const hy_run_series *rs = &r->series[i];
        for (size_t j = 0; rs->data == HY_DATA_MINOR && j < rs->n; j++) {
            double v[2] = {rs->x[j], rs->y[j]};
            int ok = 1;
            for (int k = 0; k < 2; k++)
                ok &= isfinite(v[k]) && (!lg[k] || v[k] > 0.0);
            for (int k = 0; ok && k < 2; k++) {
                double w = lg[k] ? log10(v[k]) : v[k];
                lo[k] = fmin(lo[k], w), hi[k] = fmax(hi[k], w);
            }
        }
    }
    if (!(lo[0] <= hi[0]))
        return 0;
    double *z[2] = {zx, zy};
    for (int k = 0; k < 2; k++) {
        double span = hi[k] - lo[k], pad = 0.12 * span;
        if (!(pad > 1e-9 * fmax(fabs(lo[k]), fabs(hi[k])))) /* a loop flat in this direction */
            pad = fmax(1e-3 * fmax(fabs(lo[k]), fabs(hi[k])), 1e-12);
        z[k][0] = lo[k] - pad, z[k][1] = hi[k] + pad;
        if (lg[k])
            z[k][0] = pow(10.0, z[k][0]), z[k][1] = pow(10.0, z[k][1]);
    }
    return 1;
}

int hy_scene_run_validate(const hy_scene_run *r, hy_error *err)
{
    const hy_scene_doc *d = &r->doc;
    if (!d->nseries && !d->nannotation && !d->npanel && r->figure_kind != FIG_FORC)
        return hy_error_set(err, HY_EINVAL, "%s:1:1: the scene draws nothing: it has no [series NAME] (or [annotation NAME]) section; "
                                 "a file of shared settings is included by scenes, not rendered", d->source);
    for (size_t i = 0; i < d->nannotation; i++) {
        const hy_decl_annotation *a = &d->annotation[i];
        const char *text = a->text ? a->text : "";
        for (const char *c = strchr(text, '{'); c; c = strchr(c + 1, '{')) {
            const char *e = strchr(c, '}');
            if (!e)
                return hy_decl_error(&a->h, offsetof(hy_decl_annotation, text), err, HY_EINVAL,
                                     "unterminated '{' in annotation text (no '}' after it)");
            char key[48];
            size_t n = (size_t)(e - c - 1);
            snprintf(key, sizeof key, "%.*s", (int)(n < sizeof key ? n : sizeof key - 1), c + 1);
            int ph = n < sizeof key ? hy_scene_is_placeholder(key) : memchr(c + 1, '.', n) != NULL;
            if (ph && (n >= sizeof key || !placeholder_known(d, key)))
                return hy_decl_error(&a->h, offsetof(hy_decl_annotation, text), err, HY_EINVAL,
                                     "unknown placeholder {%s%s} (major.area, major.own, energy, nminor, "
                                     "minorN.area, minorN.turn, minorN.own, minorN.ystart, minorN.yclose, minorN.gap; "
                                     "SERIES.gamma, SERIES.dist of a ygamma or transient series; SERIES.area of a "
                                     "measured or modelled series, SERIES.rms of a modelled one; SECTION.key "
                                     "of a numeric key)", key, n >= sizeof key ? "..." : "");
        }
    }
    return HY_OK;
}

/* A [panel] figure: each panel scene's axes in a grid of [figure] columns
 * per row, in the size and fonts of this scene. */
static int panel_figure(const hy_scene_run *r, hy_scene_fig *st, hy_error *err)
{
    long cols = hy_decl_got(&r->doc.figure.h, offsetof(hy_decl_figure, columns)) >= 0 ? r->doc.figure.columns
                                                                                       : (long)r->npanels;
    st->panels = calloc(r->npanels, sizeof *st->panels);
    st->axes = calloc(r->npanels, sizeof *st->axes);
    if (!st->panels || !st->axes)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    st->npanels = r->npanels;
    for (size_t i = 0; i < r->npanels; i++) {
        int rc = hy_scene_run_figure(&r->panels[i], &st->panels[i], err);
        if (rc)
            return rc;
        st->axes[i] = st->panels[i].ax;
    }
    st->fig.axes = st->axes;
    st->fig.ncols = (int)cols;
    st->fig.nrows = (int)(r->npanels / (size_t)cols);
    return HY_OK;
}

/* The curves of the figure: style, colour, width, label and marker of each series. */
static size_t figure_series(const hy_scene_run *r, hy_scene_fig *st)
{
    size_t nm = 0;
    for (size_t i = 0; i < r->nseries; i++) {
        const hy_run_series *rs = &r->series[i];
        const hy_decl_series *d = hy_scene_doc_series(&r->doc, rs->name);
        hy_series *se = &st->series[i];
        se->x = rs->x;
        se->y = rs->y;
        se->n = rs->n;
        se->style = d->style;
        if (hy_decl_got(&d->h, offsetof(hy_decl_series, color)) == HY_SCENE_SET)
            se->colour = (hy_colour){HY_RGB_EXPLICIT, {d->color.r, d->color.g, d->color.b}};
        else
            se->colour = (hy_colour){(int)(i % HY_PALETTE_SIZE), {0, 0, 0}};
        se->width = d->width;
        char *lab = NULL, own[256];
        hy_error e = {0};
        /* {SERIES.rms} and the other run values as in annotations (expand_text),
           then {section.key} ("\\gamma = {param.g20.value}") */
        if (d->label && strchr(d->label, '{') &&
            !expand_text(r, d->label, &d->h, offsetof(hy_decl_series, label), 1, own, sizeof own, &e) &&
            !hy_scene_expand(r->scene, own, &lab, &e)) {
            snprintf(st->labelbuf[i], sizeof st->labelbuf[i], "%s", lab);
            se->label = st->labelbuf[i];
        } else if (d->label && d->label[0])
            se->label = d->label;
        free(lab);
        int mk = d->marker;
        if (mk && rs->data == HY_DATA_MEASURED) /* a marker at every measured point: smaller than one mark */
            se->marker_size = 3;
        if (mk && rs->has_mark) {
            hy_mark *m = &st->marks[nm++];
            m->x = rs->mark_x;
            m->y = rs->mark_y;
            m->marker = mk;
            m->size = 6;
            m->filled = 0;
            m->colour = se->colour;
        } else if (mk)
            se->marker = mk;
    }
    return nm;
}

/* The inset: zoom_follow = minor (the minor loop's box, or a note that there
 * is none), else zoom_x and zoom_y as written (hy_scene_decode checked them). */
static void figure_zoom(const hy_scene_run *r, hy_scene_fig *st)
{
    const hy_decl_figure *f = &r->doc.figure;
    hy_axes *ax = &st->ax;
    double zx[2], zy[2];
    int hzx = 0;
    if (!strcmp(hy_decl_enum_text(&f->h, offsetof(hy_decl_figure, zoom_follow), f->zoom_follow), "minor")) {
        if (!(hzx = minor_window(r, ax, zx, zy)))
            snprintf(st->note, sizeof st->note, "note: no inset: zoom_follow = minor and no minor loop at these values\n");
    } else if (hy_decl_got(&f->h, offsetof(hy_decl_figure, zoom_x)) == HY_SCENE_SET) {
        hzx = 1;
        memcpy(zx, f->zoom_x.v, sizeof zx);
        memcpy(zy, f->zoom_y.v, sizeof zy);
    }
    if (hzx) {
        ax->zoom_x = (hy_range){zx[0], zx[1], ax->x.log, 0};
        ax->zoom_y = (hy_range){zy[0], zy[1], ax->y.log, 0};
        if (!hy_axes_zoom_shows_data(ax))
            snprintf(st->note, sizeof st->note,
                     "note: no inset: its window x %g..%g, y %g..%g holds no drawn data at these values\n", zx[0],
                     zx[1], zy[0], zy[1]);
    }
}

/* ---- the figure's text description (issue 38 item 6) --------------------- */

typedef struct dbuf {
    char *b;
    size_t len, cap;
} dbuf;

/* Appends text (at most cap - 1 bytes in all; the rest is cut). */
static void dput(dbuf *d, const char *text)
{
    size_t n = strlen(text);
    if (d->len + n >= d->cap)
        n = d->cap - 1 - d->len;
    memcpy(d->b + d->len, text, n);
    d->len += n;
    d->b[d->len] = '\0';
}

/* A label's markup as plain text a screen reader can speak: scripts as
 * "_x" and "^x" (braced when longer), the symbols as their characters. */
static void dput_markup(dbuf *d, const char *src)
{
    hy_mrun runs[HY_MARKUP_MAX];
    size_t n = 0;
    if (hy_markup_parse(src, runs, HY_MARKUP_MAX, &n, NULL)) {
        dput(d, src);
        return;
    }
    for (size_t i = 0; i < n; i++) {
        const hy_mrun *m = &runs[i];
        int longer = strlen(m->text) > 1 && (unsigned char)m->text[0] < 0x80;
        if (m->script != HY_SCRIPT_BASE)
            dput(d, m->script == HY_SCRIPT_SUP ? (longer ? "^(" : "^") : (longer ? "_(" : "_"));
        dput(d, !strcmp(m->text, "\xE2\x80\x89") ? " " : m->text);
        if (m->script != HY_SCRIPT_BASE && longer)
            dput(d, ")");
    }
}

/* One panel: its title, axes, series and the notes it prints (their numbers filled in). */
static void describe_axes(dbuf *d, const hy_axes *ax)
{
    if (ax->title) {
        dput_markup(d, ax->title);
        dput(d, ": ");
    }
    dput(d, "x axis ");
    dput_markup(d, ax->xlabel ? ax->xlabel : "x");
    dput(d, ", y axis ");
    dput_markup(d, ax->ylabel ? ax->ylabel : "y");
    int any = 0;
    for (size_t i = 0; i < ax->nseries; i++)
        if (ax->series[i].label && ax->series[i].n) {
            dput(d, any++ ? ", " : "; curves: ");
            dput_markup(d, ax->series[i].label);
        }
    for (size_t i = 0; i < ax->ntexts; i++) {
        dput(d, i ? "; " : "; printed: ");
        dput_markup(d, ax->texts[i].text);
    }
    dput(d, ". ");
}

/* st->title (the caption's first clause, else the [figure] title, else the
 * output name) and st->desc (the caption, then each panel), for the SVG. */
static int describe(const hy_scene_run *r, hy_scene_fig *st, hy_error *err)
{
    const hy_decl_figure *df = &r->doc.figure;
    const char *cap = df->caption && df->caption[0] ? df->caption : NULL;
    char *capx = NULL; /* the caption with its {section.key} filled in, as the gallery's index shows it */
    hy_error e = {0};
    if (cap && strchr(cap, '{') && !hy_scene_expand(r->scene, cap, &capx, &e))
        cap = capx;
    st->title = calloc(1, 256);
    dbuf d = {calloc(1, 8192), 0, 8192};
    if (!st->title || !d.b) {
        free(d.b);
        free(capx);
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    }
    st->desc = d.b;
    if (cap) {
        size_t n = strcspn(cap, ";(");   /* the first clause, "Fig. 1: B-H loop of a magnetic system" */
        while (n > 0 && (cap[n - 1] == ' ' || cap[n - 1] == ',' || cap[n - 1] == ':'))
            n--;
        snprintf(st->title, 256, "%.*s", (int)(n < 255 ? n : 255), cap);
        dput(&d, cap);
        dput(&d, " ");
        free(capx);
    } else if (df->title && df->title[0]) {
        dbuf t = {st->title, 0, 256};
        dput_markup(&t, df->title);
    } else {
        hy_scene_run_name(r, st->title, 256);
    }
    if (st->npanels)
        for (size_t i = 0; i < st->npanels; i++) {
            char head[40];
            snprintf(head, sizeof head, "Panel %zu: ", i + 1);
            dput(&d, head);
            describe_axes(&d, &st->axes[i]);
        }
    else
        describe_axes(&d, &st->ax);
    while (d.len && d.b[d.len - 1] == ' ')
        d.b[--d.len] = '\0';
    st->fig.svg_title = st->title;
    st->fig.svg_desc = st->desc;
    return HY_OK;
}

int hy_scene_run_figure(const hy_scene_run *r, hy_scene_fig *st, hy_error *err)
{
    const hy_scene_doc *d = &r->doc;
    const hy_decl_figure *df = &d->figure;
    size_t na = d->nannotation;
    memset(st, 0, sizeof *st);
    st->series = calloc(r->nseries + 1, sizeof *st->series);
    st->marks = calloc(r->nseries + 1, sizeof *st->marks);
    st->texts = calloc(na + 1, sizeof *st->texts);
    st->textbuf = calloc(na + 1, sizeof *st->textbuf);
    st->labelbuf = calloc(r->nseries + 1, sizeof *st->labelbuf);
    if (!st->series || !st->marks || !st->texts || !st->textbuf || !st->labelbuf)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    size_t nm = figure_series(r, st);
    for (size_t i = 0; i < na; i++) {
        const hy_decl_annotation *a = &d->annotation[i];
        int rc = expand(r, a, st->textbuf[i], sizeof st->textbuf[i], err);
        if (rc)
            return rc;
        st->texts[i] = (hy_text){a->x, a->y, st->textbuf[i], HY_ANCHOR_LEFT, 0, 0, {0, {0, 0, 0}}, 0, 0, 0};
        if (hy_decl_got(&a->h, offsetof(hy_decl_annotation, point_x)) >= 0)
            st->texts[i].has_point = 1, st->texts[i].px = a->point_x, st->texts[i].py = a->point_y;
    }
    hy_axes *ax = &st->ax;
    ax->series = st->series;
    ax->nseries = r->nseries;
    ax->marks = st->marks;
    ax->nmarks = nm;
    ax->texts = st->texts;
    ax->ntexts = na;
    ax->xlabel = df->xlabel ? df->xlabel : default_xlabel[r->figure_kind];
    ax->ylabel = df->ylabel ? df->ylabel : default_ylabel[r->figure_kind];
    ax->title = df->title && df->title[0] ? df->title : NULL;
    ax->x = hy_scene_axis_range(&df->xlim, df->xlog);
    ax->y = hy_scene_axis_range(&df->ylim, df->ylog);
    ax->legend = df->legend;
    ax->grid = df->grid;
    if (hy_decl_got(&df->h, offsetof(hy_decl_figure, shade)) == HY_SCENE_SET) {
        ax->band = 1;
        ax->band_lo = df->shade.v[0];
        ax->band_hi = df->shade.v[1];
    }
    figure_zoom(r, st);
    hy_figure *f = &st->fig;
    figure_size(df, f);
    f->font = df->font;
    f->font_size = df->fontsize;
    f->theme = df->theme;
    f->axes = ax;
    f->nrows = f->ncols = 1;
    int rc = r->npanels ? panel_figure(r, st, err) : HY_OK;
    return rc ? rc : describe(r, st, err);
}

static int mkdir_p(const char *dir, hy_error *err)
{
    char buf[4096];
    snprintf(buf, sizeof buf, "%s", dir);
    for (char *p = buf + 1; *p; p++) {
        if (*p != '/')
            continue;
        *p = '\0';
        if (mkdir(buf, 0755) && errno != EEXIST)
            return hy_error_set(err, HY_EIO, "%s: cannot create directory: %s", buf, strerror(errno));
        *p = '/';
    }
    if (mkdir(buf, 0755) && errno != EEXIST)
        return hy_error_set(err, HY_EIO, "%s: cannot create directory: %s", buf, strerror(errno));
    return HY_OK;
}

static const char *const format_ext[] = {HY_FIGURE_FORMATS(HY_FORMAT_EXT) NULL};

int hy_scene_formats_parse(const char *list, int fmt[HY_FORMAT_COUNT], size_t *n, hy_error *err)
{
    *n = 0;
    for (const char *c = list; c && *c;) {
        size_t len = strcspn(c, ",");
        int f = -1;
        for (int k = 0; format_ext[k]; k++)
            if (len == strlen(format_ext[k]) && !strncmp(c, format_ext[k], len))
                f = k;
        if (f < 0 && len)
            return hy_error_set(err, HY_EINVAL, "--format: unknown format '%.*s' (%s)", (int)(len > 40 ? 40 : len), c,
                                HY_FORMAT_NAMES);
        int dup = f < 0;
        for (size_t i = 0; i < *n && !dup; i++)
            dup = fmt[i] == HY_FORMAT_SVG + f;
        if (!dup)
            fmt[(*n)++] = HY_FORMAT_SVG + f;
        c += len + (c[len] == ',');
    }
    if (!*n)
        return hy_error_set(err, HY_EINVAL, "--format: no format given (%s)", HY_FORMAT_NAMES);
    return HY_OK;
}

/* The formats to write: the override list, else the scene's [output] formats. */
static int run_formats(const hy_scene_doc *d, const char *formats, int fmt[HY_FORMAT_COUNT], size_t *nf, hy_error *err)
{
    if (formats)
        return hy_scene_formats_parse(formats, fmt, nf, err);
    const hy_scene_list *l = &d->output.formats;
    *nf = 0;
    for (size_t i = 0; i < l->n && *nf < HY_FORMAT_COUNT; i++) {
        const char *t = hy_decl_enum_text(&d->output.h, offsetof(hy_decl_output, formats), (int)l->v[i]);
        for (int k = 0; format_ext[k]; k++)
            if (!strcmp(t, format_ext[k]))
                fmt[(*nf)++] = HY_FORMAT_SVG + k;
    }
    return HY_OK;
}

int hy_scene_run_check_output(const hy_scene_run *r, const char *formats, hy_error *err)
{
    int fmt[HY_FORMAT_COUNT];
    size_t nf;
    hy_figure f;
    memset(&f, 0, sizeof f);
    figure_size(&r->doc.figure, &f);
    int rc = run_formats(&r->doc, formats, fmt, &nf, err);
    for (size_t i = 0; i < nf && !rc; i++)
        if ((rc = hy_figure_check(&f, fmt[i], err)))
            hy_error_prefix(err, "%s", r->path);
    return rc;
}

double hy_scene_run_png_pixels(const hy_scene_run *r)
{
    int fmt[HY_FORMAT_COUNT];
    size_t nf;
    hy_error err = {0};
    hy_figure f;
    memset(&f, 0, sizeof f);
    figure_size(&r->doc.figure, &f);
    if (run_formats(&r->doc, r->formats, fmt, &nf, &err))
        return 0; /* refused by hy_scene_run_check_output */
    for (size_t i = 0; i < nf; i++)
        if (fmt[i] == HY_FORMAT_PNG)
            return hy_figure_png_pixels(&f);
    return 0;
}

/* Writes every format to a temporary, then renames them all: all or none. */
static int write_all(const hy_figure *fig, char paths[][4400], const int *fmt, size_t nf, hy_error *err)
{
    hy_out out[HY_FORMAT_COUNT];
    size_t opened = 0;
    int rc = HY_OK;
    for (size_t i = 0; i < nf && !rc; i++)
        if (!(rc = hy_figure_check(fig, fmt[i], err)) && !(rc = hy_out_open(&out[i], paths[i], HY_OUT_HOLD, err))) {
            opened++;
            rc = hy_figure_write_out(fig, &out[i], fmt[i], err); /* aborts out[i] on failure */
        }
    for (size_t i = 0; i < opened; i++) {
        if (rc)
            hy_out_abort(&out[i]); /* no-op for the one that failed */
        else if ((rc = hy_out_publish(&out[i], err)) && i)
            hy_error_prefix(err, "only %zu of the %zu files were replaced", i, nf);
    }
    return rc;
}

/* A note line for each annotation the layout found no free spot for (it
 * then sits where it covers the least: over a curve, or at the frame's
 * edge), appended to out; what `render -v` prints, as for a left-out inset. */
static void note_covering(const hy_figure *f, char *out, size_t size)
{
    cairo_surface_t *sf = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 1, 1);
    cairo_t *cr = cairo_create(sf);
    hy_cairo_canvas cc;
    hy_canvas cv = hy_canvas_cairo(&cc, cr, f->font && f->font[0] ? f->font : NULL); /* as hy_figure_write */
    int n = (f->nrows > 0 ? f->nrows : 1) * (f->ncols > 0 ? f->ncols : 1);
    for (int i = 0; i < n; i++) {
        double hits[32];
        size_t nt = f->axes[i].ntexts < 32 ? f->axes[i].ntexts : 32;
        if (!nt || hy_figure_text_hits(f, &cv, i, hits, nt, NULL))
            continue;
        for (size_t t = 0; t < nt; t++)
            if (hits[t] > 0) {
                size_t len = strlen(out);
                snprintf(out + len, size - len, "note: panel %d: the annotation \"%s\" found no free spot: it covers %s "
                         "(move its x, y or widen the axes)\n", i + 1, f->axes[i].texts[t].text,
                         isinf(hits[t]) ? "the frame's edge" : "drawn data");
            }
    }
    cairo_destroy(cr);
    cairo_surface_destroy(sf);
}

int hy_scene_run_write(const hy_scene_run *r, const char *dir, const char *formats, char *written, size_t written_size,
                       hy_error *err)
{
    const hy_scene *s = r->scene;
    char name[256];
    hy_scene_run_name(r, name, sizeof name);
    int fmt[HY_FORMAT_COUNT];
    size_t nf = 0;
    int rc = run_formats(&r->doc, formats, fmt, &nf, err);
    if (rc)
        return rc;
    char *odir = NULL; /* -o, or [output] dir below the scene's directory (hy_scene_policy.h) */
    const char *cli_dir = dir;
    if ((rc = hy_scene_output_dir(s, cli_dir, &odir, err)))
        return rc;
    dir = odir;
    char paths[HY_FORMAT_COUNT][4400];
    for (size_t i = 0; i < nf; i++)
        snprintf(paths[i], sizeof paths[i], "%s/%s.%s", dir, name, format_ext[fmt[i] - HY_FORMAT_SVG]);
    if (r->figure_kind == FIG_FORC) { /* the heat map: scene_forc.c */
        if (!(rc = mkdir_p(dir, err)) && !(rc = hy_scene_output_dir_check(s, cli_dir, dir, err)))
            rc = hy_scene_forc_write_all(r, paths, fmt, nf, err);
        for (size_t i = 0; i < nf && !rc && written; i++) {
            size_t len = strlen(written);
            snprintf(written + len, written_size - len, "%s\n", paths[i]);
        }
        free(odir);
        return rc;
    }
    fig_store st;
    rc = hy_scene_run_figure(r, &st, err);
    if (!rc)
        rc = mkdir_p(dir, err);
    if (!rc)
        rc = hy_scene_output_dir_check(s, cli_dir, dir, err);
    if (!rc)
        rc = write_all(&st.fig, paths, fmt, nf, err);
    if (!rc && written) {
        size_t len = strlen(written);
        snprintf(written + len, written_size - len, "%s", st.note);
        note_covering(&st.fig, written, written_size);
    }
    for (size_t i = 0; i < nf && !rc && written; i++) {
        size_t len = strlen(written);
        snprintf(written + len, written_size - len, "%s\n", paths[i]);
    }
    hy_scene_fig_free(&st);
    free(odir);
    return rc;
}

/* The rows of r's series, names prefixed with "panel/" when panel is set. */
static void data_rows(const hy_scene_run *r, const char *panel, FILE *out)
{
    for (size_t i = 0; i < r->nseries; i++) {
        const hy_run_series *se = &r->series[i];
        for (size_t j = 0; j < se->n; j++)
            if (!isnan(se->x[j]))
                fprintf(out, "%s%s%s,%.17g,%.17g\n", panel ? panel : "", panel ? "/" : "", se->name, se->x[j], se->y[j]);
        /* data = modelled: the measured y and the residual (model - measured) at the same x */
        for (int k = 0; se->ymeas && k < 2; k++)
            for (size_t j = 0; j < se->n; j++)
                if (!isnan(se->x[j]))
                    fprintf(out, "%s%s%s@%s,%.17g,%.17g\n", panel ? panel : "", panel ? "/" : "", se->name,
                            k ? "residual" : "measured", se->x[j], k ? se->y[j] - se->ymeas[j] : se->ymeas[j]);
        if (se->has_mark)
            fprintf(out, "%s%s%s@marker,%.17g,%.17g\n", panel ? panel : "", panel ? "/" : "", se->name, se->mark_x,
                    se->mark_y);
    }
}

int hy_scene_run_data(const hy_scene_run *r, FILE *out, hy_error *err)
{
    if (r->figure_kind == FIG_FORC && r->forc)
        hy_scene_forc_data(r, out);
    else
        fprintf(out, "series,x,y\n");
    data_rows(r, NULL, out);
    for (size_t p = 0; p < r->npanels; p++) /* a [panel] figure: PANEL/SERIES */
        data_rows(&r->panels[p], r->doc.panel[p].h.name, out);
    if (ferror(out))
        return hy_error_set(err, HY_EIO, "error writing the data: %s", strerror(errno));
    return HY_OK;
}

int hy_scene_run_render(const hy_scene_run *r, int format, unsigned char **buf, size_t *len, hy_panel_map *map,
                        hy_error *err)
{
    *buf = NULL;
    *len = 0;
    fig_store st;
    int rc = hy_scene_run_check_cancel(r, err);
    if (rc)
        return rc;
    if (r->figure_kind == FIG_FORC) {
        if (map)
            memset(map, 0, sizeof *map);
        return hy_scene_forc_render(r, format, buf, len, err);
    }
    rc = hy_scene_run_figure(r, &st, err);
    hy_cancel hook = {r->cancelled, r->cancel_ctx}; /* placing the annotations, one at a time */
    st.fig.cancel = r->cancelled ? &hook : NULL;
    if (!rc && !(rc = hy_scene_run_check_cancel(r, err)))
        rc = hy_figure_render_mem_mapped(&st.fig, format, buf, len, map, map ? 1 : 0, err);
    hy_scene_fig_free(&st);
    return rc;
}

int hy_scene_run_csv(const hy_scene_run *r, char **buf, size_t *len, hy_error *err)
{
    *buf = NULL;
    *len = 0;
    FILE *f = open_memstream(buf, len);
    if (!f)
        return hy_error_set(err, HY_ENOMEM, "out of memory for the data");
    int rc = hy_scene_run_data(r, f, err);
    if (fclose(f) && !rc)
        rc = hy_error_set(err, HY_ENOMEM, "out of memory for the data");
    if (rc) {
        free(*buf);
        *buf = NULL;
        *len = 0;
    }
    return rc;
}
