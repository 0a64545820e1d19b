/* SPDX-License-Identifier: MIT */
/* test_typeset.c: every gallery figure (scenes/NAME.scene with series or
 * panels) as a referee reads it (issue 38 item 5):
 *  - units upright: every text the figure sets (title, axis labels, legend
 *    entries, annotations with their placeholders filled in) is parsed by the
 *    markup, and a known unit standing as a unit (a compound one such as
 *    A/m or J/m³ anywhere, a lone one such as T or N after a number or alone
 *    in parentheses) must come out upright; this detector is written apart
 *    from the markup's rule, from the units the gallery prints;
 *  - an integral sign is followed by a thin space, and a differential "d"
 *    after it is upright with its variable italic (∮ H dB, not decibels);
 *  - annotations off the curves: each placed annotation's box covers no
 *    curve, mark, legend or other annotation and stays inside its frame
 *    (hy_figure_text_hits, the layout's own collision measure);
 *  - colour-blind safe: the drawn series of every panel, through the
 *    protanopia, deuteranopia and tritanopia simulations of Machado,
 *    Oliveira and Fernandes (IEEE TVCG 15(6) 1291-1298, 2009; severity 1,
 *    applied to linear sRGB) and without, are at least DE_MIN apart in
 *    CIELAB (CIE76 ΔE*ab, D65), or differ in a second cue (dash pattern or
 *    marker).  DE_MIN = 20: a ΔE*ab of about 2.3 tells large patches apart,
 *    but thin lines need several times more (Szafir, IEEE TVCG 24(1) 2018:
 *    the difference needed grows as the mark shrinks); 20 sits above the
 *    closest pair of Fig. 8 (bluish green and blue, 17.0 under tritanopia)
 *    and below the Okabe-Ito pairs that stay distinct under every
 *    simulation (sky blue and blue, 24.8).  Series drawn exactly alike
 *    (one family in pieces, as Fig. 4's unlabelled loops) are not pairs;
 *  - every SVG carries a <title> (the root's first child) and a <desc>
 *    naming the axes and holding every number the annotations print. */
#include <cairo.h>
#include <dirent.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../core/tutil.h"
#include "hy_cairo.h"
#include "hy_markup.h"
#include "hy_plot.h"
#include "scene_run.h"

#define DE_MIN 20.0

static const char *SRC;

/* ---- units ---------------------------------------------------------------- */

/* Units the gallery prints, as a reader names them (not the markup's list). */
static const char *const lone_units[] = {"T", "N", "s", "A", "J", "m", "mm", "Hz", "dB", "kA", NULL};
static const char *const compound_units[] = {"A/m", "J/m³", "kA/m", "J/m^3", NULL};

typedef struct flat {
    char text[1024];
    char italic[1024];   /* per byte */
    size_t n;
} flat;

/* The label's base-line and script text, in order, with each byte's style. */
static int flatten(const char *src, flat *f)
{
    hy_mrun runs[HY_MARKUP_MAX];
    size_t n = 0;
    hy_error err;
    f->n = 0;
    if (hy_markup_parse(src, runs, HY_MARKUP_MAX, &n, &err))
        return -1;
    for (size_t i = 0; i < n; i++)
        for (const char *c = runs[i].text; *c && f->n < sizeof f->text - 1; c++)
            f->italic[f->n] = (char)runs[i].italic, f->text[f->n++] = *c;
    f->text[f->n] = '\0';
    return 0;
}

static int letter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }

/* Whether byte i of f is preceded (spaces skipped, at least one) by a digit, or by '('. */
static int after_number(const flat *f, size_t i, size_t len)
{
    if (i > 0 && f->text[i - 1] == '(' && f->text[i + len] == ')')
        return 1;
    size_t j = i;
    while (j > 0 && f->text[j - 1] == ' ')
        j--;
    /* a digit, a superscript's digit ("10^{-4} T" flattens to "10−4 T") */
    return j < i && j > 0 && f->text[j - 1] >= '0' && f->text[j - 1] <= '9';
}

static void check_units(const char *where, const char *label)
{
    flat f;
    if (!label || flatten(label, &f))
        return;
    for (size_t i = 0; i < f.n; i++) {
        if (i > 0 && letter(f.text[i - 1]))
            continue;
        for (int k = 0; compound_units[k]; k++) {
            size_t len = strlen(compound_units[k]);
            if (!strncmp(f.text + i, compound_units[k], len) && !letter(f.text[i + len]))
                for (size_t b = i; b < i + len; b++)
                    CHECK(!f.italic[b], "%s: \"%s\": the unit %s is set in italic", where, label, compound_units[k]);
        }
        for (int k = 0; lone_units[k]; k++) {
            size_t len = strlen(lone_units[k]);
            if (!strncmp(f.text + i, lone_units[k], len) && !letter(f.text[i + len]) && f.text[i + len] != '/' &&
                after_number(&f, i, len))
                CHECK(!f.italic[i], "%s: \"%s\": the unit %s is set in italic", where, label, lone_units[k]);
        }
    }
    /* ∮ / ∫: a thin space after; "d" + letter after a thin space: d upright, the letter italic */
    const char *thin = "\xE2\x80\x89";
    int integral = 0;
    for (size_t i = 0; i + 2 < f.n; i++) {
        if ((unsigned char)f.text[i] == 0xE2 && (unsigned char)f.text[i + 1] == 0x88 &&
            ((unsigned char)f.text[i + 2] == 0xAB || (unsigned char)f.text[i + 2] == 0xAE)) {
            integral = 1;
            CHECK(i + 3 < f.n && !strncmp(f.text + i + 3, thin, 3), "%s: \"%s\": no thin space after the integral sign",
                  where, label);
        }
        if (integral && !strncmp(f.text + i, thin, 3) && f.text[i + 3] == 'd' && letter(f.text[i + 4]) &&
            !letter(f.text[i + 5]))
            CHECK(!f.italic[i + 3] && f.italic[i + 4], "%s: \"%s\": the differential d%c is not d upright, %c italic",
                  where, label, f.text[i + 4], f.text[i + 4]);
    }
    if (integral)
        CHECK(strstr(f.text, "dB") == NULL || strstr(f.text, "\xE2\x80\x89" "dB"),
              "%s: \"%s\": \"dB\" after an integral not set as a differential", where, label);
}

/* ---- colour ---------------------------------------------------------------- */

static const double machado[3][9] = {
    {0.152286, 1.052583, -0.204868, 0.114503, 0.786281, 0.099216, -0.003882, -0.048116, 1.051998},   /* protanopia */
    {0.367322, 0.860646, -0.227968, 0.280085, 0.672501, 0.047413, -0.011820, 0.042940, 0.968881},    /* deuteranopia */
    {1.255528, -0.076749, -0.178779, -0.078411, 0.930809, 0.147602, 0.004733, 0.691367, 0.303900},   /* tritanopia */
};
static const char *const cvd_names[4] = {"protanopia", "deuteranopia", "tritanopia", "normal vision"};

static double lin(double c) { return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4); }
static double flab(double t) { return t > 216.0 / 24389.0 ? cbrt(t) : (24389.0 / 27.0 * t + 16.0) / 116.0; }

/* CIELAB (D65) of an sRGB colour seen with deficiency k (3: none). */
static void to_lab(hy_rgb c, int k, double lab[3])
{
    double l[3] = {lin(c.r), lin(c.g), lin(c.b)}, s[3];
    for (int i = 0; i < 3; i++) {
        s[i] = k < 3 ? machado[k][3 * i] * l[0] + machado[k][3 * i + 1] * l[1] + machado[k][3 * i + 2] * l[2] : l[i];
        s[i] = s[i] < 0 ? 0 : s[i] > 1 ? 1 : s[i];
    }
    double X = 0.4124 * s[0] + 0.3576 * s[1] + 0.1805 * s[2];
    double Y = 0.2126 * s[0] + 0.7152 * s[1] + 0.0722 * s[2];
    double Z = 0.0193 * s[0] + 0.1192 * s[1] + 0.9505 * s[2];
    double fx = flab(X / 0.95047), fy = flab(Y), fz = flab(Z / 1.08883);
    lab[0] = 116 * fy - 16, lab[1] = 500 * (fx - fy), lab[2] = 200 * (fy - fz);
}

static hy_rgb rgb_of(hy_colour c)
{
    if (c.palette == HY_RGB_EXPLICIT)
        return c.rgb;
    return hy_palette[(c.palette < 0 ? -c.palette : c.palette) % HY_PALETTE_SIZE];
}

static int drawn(const hy_series *s)
{
    return s->n > 0 && (s->style != HY_LINE_NONE || s->marker != HY_MARKER_NONE);
}

static void check_colours(const char *where, const hy_axes *ax)
{
    for (size_t a = 0; a < ax->nseries; a++)
        for (size_t b = a + 1; b < ax->nseries; b++) {
            const hy_series *s = &ax->series[a], *t = &ax->series[b];
            if (!drawn(s) || !drawn(t))
                continue;
            /* one series drawn in pieces (same label, colour and line) is one curve */
            if (s->label && t->label && !strcmp(s->label, t->label))
                continue;
            if (s->style != t->style || s->marker != t->marker)
                continue;   /* a second cue: the dash pattern or the marker */
            hy_rgb u = rgb_of(s->colour), v = rgb_of(t->colour);
            if (u.r == v.r && u.g == v.g && u.b == v.b)
                continue;   /* drawn alike: the figure does not tell them apart (one family, as Fig. 4's loops) */
            for (int k = 0; k < 4; k++) {
                double p[3], q[3];
                to_lab(rgb_of(s->colour), k, p);
                to_lab(rgb_of(t->colour), k, q);
                double de = sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
                CHECK(de >= DE_MIN, "%s: series \"%s\" and \"%s\" differ by colour alone, ΔE*ab %.1f < %.0f under %s",
                      where, s->label ? s->label : "?", t->label ? t->label : "?", de, DE_MIN, cvd_names[k]);
            }
        }
}

/* ---- one figure ------------------------------------------------------------ */

static void check_axes(const char *name, int panel, const hy_axes *ax)
{
    char where[300];
    snprintf(where, sizeof where, "%s panel %d", name, panel + 1);
    check_units(where, ax->title);
    check_units(where, ax->xlabel);
    check_units(where, ax->ylabel);
    for (size_t i = 0; i < ax->nseries; i++)
        check_units(where, ax->series[i].label);
    for (size_t i = 0; i < ax->ntexts; i++)
        check_units(where, ax->texts[i].text);
    check_colours(where, ax);
}

static void check_hits(const char *name, const hy_figure *fig)
{
    cairo_surface_t *sf = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 4, 4);
    cairo_t *cr = cairo_create(sf);
    hy_cairo_canvas cc;
    hy_canvas cv = hy_canvas_cairo(&cc, cr, fig->font ? fig->font : "DejaVu Sans");
    int n = (fig->nrows > 0 ? fig->nrows : 1) * (fig->ncols > 0 ? fig->ncols : 1);
    for (int i = 0; i < n; i++) {
        const hy_axes *ax = &fig->axes[i];
        double hits[64];
        size_t nt = ax->ntexts < 64 ? ax->ntexts : 64;
        hy_error err;
        if (!nt)
            continue;
        CHECK(hy_figure_text_hits(fig, &cv, i, hits, nt, &err) == 0, "%s: %s", name, err.msg);
        for (size_t t = 0; t < nt; t++)
            /* exact: the layout calls a spot free only at 0, and every annotation of the gallery has one */
            CHECK(isnan(hits[t]) || hits[t] == 0.0, "%s panel %d: the annotation \"%s\" covers %g pt of %s", name,
                  i + 1, ax->texts[t].text, hits[t], isinf(hits[t]) ? "the frame's edge" : "drawn data or text");
    }
    cairo_destroy(cr);
    cairo_surface_destroy(sf);
}

/* The SVG as written: a <title> and a <desc> first in the root element,
 * non-empty, the desc naming every panel's axes and every printed note. */
static void check_svg(const char *name, const hy_scene_run *r, const hy_scene_fig *st)
{
    unsigned char *buf = NULL;
    size_t len = 0;
    hy_error err;
    int rc = hy_scene_run_render(r, HY_FORMAT_SVG, &buf, &len, NULL, &err);
    CHECK(rc == 0, "%s: SVG: %s", name, err.msg);
    if (rc)
        return;
    char *text = malloc(len + 1);
    memcpy(text, buf, len);
    text[len] = '\0';
    free(buf);
    const char *root = strstr(text, "<svg"), *t = strstr(text, "<title>"), *d = strstr(text, "<desc>");
    const char *first = root ? strchr(root, '<' ) : NULL;
    first = first ? strchr(first + 1, '<') : NULL;   /* the root's first child */
    CHECK(t && first == t && strstr(t, "</title>") > t + 7, "%s.svg: no <title> as the root's first child", name);
    CHECK(d && strstr(d, "</desc>") > d + 6, "%s.svg: no <desc>", name);
    if (d) {
        int n = (st->fig.nrows > 0 ? st->fig.nrows : 1) * (st->fig.ncols > 0 ? st->fig.ncols : 1);
        char *end = strstr(d, "</desc>");
        if (end)
            *end = '\0';
        for (int i = 0; i < n; i++) {
            const hy_axes *ax = &st->fig.axes[i];
            CHECK(strstr(d, "x axis") && strstr(d, "y axis"), "%s.svg: the desc names no axes", name);
            for (size_t k = 0; k < ax->ntexts; k++) {
                flat f;   /* the note's numbers as the figure prints them: its first digits */
                if (flatten(ax->texts[k].text, &f))
                    continue;
                const char *dig = strpbrk(f.text, "0123456789");
                char num[8] = "";
                if (dig)
                    snprintf(num, sizeof num, "%.*s", (int)strspn(dig, "0123456789."), dig);
                CHECK(!*num || strstr(d, num), "%s.svg: the desc lacks the number %s of \"%s\"", name, num,
                      ax->texts[k].text);
            }
        }
    }
    free(text);
}

/* What the one annotation of a one-panel figure covers. */
static void check_hits_one(const hy_figure *fig, double *hit)
{
    cairo_surface_t *sf = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 4, 4);
    cairo_t *cr = cairo_create(sf);
    hy_cairo_canvas cc;
    hy_canvas cv = hy_canvas_cairo(&cc, cr, NULL);
    hy_error err;
    CHECK(hy_figure_text_hits(fig, &cv, 0, hit, 1, &err) == 0, "self-test: %s", err.msg);
    cairo_destroy(cr);
    cairo_surface_destroy(sf);
}

static int is_figure_scene(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return 0;
    char buf[65536];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    return strstr(buf, "[series") || strstr(buf, "[panel");
}

static void one_scene(const char *file)
{
    char path[2048];
    snprintf(path, sizeof path, "%s/scenes/%s", SRC, file);
    if (!is_figure_scene(path))
        return;
    hy_scene_run r;
    hy_scene_fig st;
    hy_error err;
    memset(&st, 0, sizeof st);
    /* at the scene's own dpi: the curves are thinned to the output's pixels, as drawn */
    if (hy_scene_run_load(&r, path, NULL, 0, &err)) {
        CHECK(0, "%s: %s", file, err.msg);
        return;
    }
    int rc = hy_scene_run_compute(&r, NULL, &err);
    if (!rc)
        rc = hy_scene_run_figure(&r, &st, &err);
    CHECK(rc == 0, "%s: %s", file, err.msg);
    if (!rc) {
        int n = (st.fig.nrows > 0 ? st.fig.nrows : 1) * (st.fig.ncols > 0 ? st.fig.ncols : 1);
        for (int i = 0; i < n; i++)
            check_axes(file, i, &st.fig.axes[i]);
        check_hits(file, &st.fig);
    }
    if (!rc)
        check_svg(file, &r, &st);
    hy_scene_fig_free(&st);
    hy_scene_run_free(&r);
}

static void check_hits_one(const hy_figure *fig, double *hit);

/* The detector itself on labels known to be wrong and right. */
static void self_test(void)
{
    flat f;
    CHECK(flatten("B (T)", &f) == 0 && !f.italic[3] && f.italic[0], "\"B (T)\": B italic, T upright");
    CHECK(flatten("H (A/m)", &f) == 0 && !f.italic[3] && !f.italic[5], "\"H (A/m)\": A/m upright");
    CHECK(flatten("q = 816.9 J/m³", &f) == 0 && !f.italic[10], "J/m³ upright");
    CHECK(flatten("T = 3", &f) == 0 && f.italic[0], "a variable T stays italic");
    CHECK(flatten("\\mathit", &f) != 0, "an unknown command is refused");
    /* the colour check on a pair it must refuse: bluish green and blue, both dashed */
    hy_series s[2] = {{.n = 2, .style = HY_LINE_DASHED, .colour = {3, {0, 0, 0}}, .label = "a"},
                      {.n = 2, .style = HY_LINE_DASHED, .colour = {5, {0, 0, 0}}, .label = "b"}};
    double p[3], q[3];
    to_lab(hy_palette[3], 2, p);
    to_lab(hy_palette[5], 2, q);
    double de = sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
    CHECK(de < DE_MIN, "bluish green and blue under tritanopia: ΔE %.1f, want below %.0f", de, DE_MIN);
    s[1].style = HY_LINE_DOTTED;
    hy_axes ax = {.series = s, .nseries = 2};
    check_colours("self-test", &ax);   /* a second cue: passes */

    /* the collision measure: a dense zig-zag fills the frame, so a note finds
     * no free spot and must be reported; one over empty axes is free */
    enum { NZ = 64 };
    double zx[NZ], zy[NZ];
    for (int i = 0; i < NZ; i++)
        zx[i] = i / (NZ - 1.0), zy[i] = i % 2;
    hy_series z = {.x = zx, .y = zy, .n = NZ, .style = HY_LINE_SOLID, .width = 1};
    hy_text note = {.x = 0.1, .y = 0.5, .text = "a note with nowhere to go"};
    hy_axes za = {.series = &z, .nseries = 1, .texts = &note, .ntexts = 1, .x = {0, 1, 0, 0}, .y = {0, 1, 0, 0}};
    hy_figure zf = {.width = 200, .height = 150, .axes = &za, .nrows = 1, .ncols = 1};
    double hit = -1;
    check_hits_one(&zf, &hit);
    CHECK(hit > 0, "a note over a frame full of curve: covers %g pt, want > 0", hit);
    za.nseries = 0;
    check_hits_one(&zf, &hit);
    CHECK(hit == 0.0, "a note over empty axes: covers %g pt, want 0", hit);
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: test_typeset SOURCE_ROOT\n");
        return 2;
    }
    SRC = argv[1];
    self_test();
    char dir[2048];
    snprintf(dir, sizeof dir, "%s/scenes", SRC);
    DIR *d = opendir(dir);
    CHECK(d != NULL, "cannot open %s", dir);
    struct dirent *e;
    int count = 0;
    while (d && (e = readdir(d))) {
        size_t len = strlen(e->d_name);
        if (len < 7 || strcmp(e->d_name + len - 6, ".scene"))
            continue;
        one_scene(e->d_name);
        count++;
    }
    if (d)
        closedir(d);
    CHECK(count >= 20, "only %d scenes found in %s", count, dir);
    return tu_finish("test_typeset");
}
