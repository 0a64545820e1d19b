/* SPDX-License-Identifier: MIT */
/* test_output.c: SVG structure (balanced tags, path and glyph counts), byte determinism, atomic writes. */
#include <cairo.h>
#include <dirent.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "figures.h"
#include "hy_cairo.h"

#include "../hy_test.h"
#include "rcheck.h"

/* Counts of what an SVG body holds, outside <defs>. */
typedef struct svg_counts {
    int well_formed;
    long paths, uses;
} svg_counts;

/* A tiny XML checker: every start tag closed by the matching end tag, one root. */
static svg_counts svg_check(const char *s)
{
    svg_counts c = {1, 0, 0};
    char stack[64][32];
    int depth = 0, roots = 0, in_defs = 0;
    for (const char *p = s; (p = strchr(p, '<')) != NULL;) {
        if (!strncmp(p, "<?", 2) || !strncmp(p, "<!--", 4)) {
            const char *e = strstr(p, p[1] == '?' ? "?>" : "-->");
            if (!e)
                return c.well_formed = 0, c;
            p = e + 2;
            continue;
        }
        int closing = p[1] == '/';
        const char *q = p + 1 + closing;
        char name[32];
        size_t k = 0;
        while (*q && !strchr(" \t\r\n/>", *q) && k < sizeof name - 1)
            name[k++] = *q++;
        name[k] = '\0';
        char quote = 0;   /* find the tag's end, skipping quoted attribute values */
        for (; *q && (quote || *q != '>'); q++)
            if (*q == '"' || *q == '\'')
                quote = quote == *q ? 0 : quote ? quote : *q;
        if (!*q || !k)
            return c.well_formed = 0, c;
        int self = q[-1] == '/';
        if (closing) {
            if (depth == 0 || strcmp(stack[depth - 1], name))
                return c.well_formed = 0, c;
            if (!strcmp(name, "defs"))
                in_defs = 0;
            depth--;
        } else {
            if (depth == 0)
                roots++;
            if (!in_defs && !strcmp(name, "path"))
                c.paths++;
            if (!in_defs && !strcmp(name, "use"))
                c.uses++;
            if (!self) {
                if (depth == 64)
                    return c.well_formed = 0, c;
                strcpy(stack[depth++], name);
                if (!strcmp(name, "defs"))
                    in_defs = 1;
            }
        }
        p = q + 1;
    }
    c.well_formed = c.well_formed && depth == 0 && roots == 1;
    return c;
}

/* A canvas that forwards to cairo and counts the paths and glyphs it emits. */
typedef struct counter {
    hy_canvas inner;
    long paths, glyphs, filled;   /* filled: markers cairo may split into fill + stroke */
} counter;

static void k_begin(void *c) { ((counter *)c)->inner.ops->begin_path(((counter *)c)->inner.ctx); }
static void k_move(void *c, double x, double y) { ((counter *)c)->inner.ops->move_to(((counter *)c)->inner.ctx, x, y); }
static void k_line(void *c, double x, double y) { ((counter *)c)->inner.ops->line_to(((counter *)c)->inner.ctx, x, y); }
static void k_stroke(void *c, const hy_pen *p)
{
    counter *k = c;
    k->paths++;
    k->inner.ops->stroke(k->inner.ctx, p);
}
static void k_rect(void *c, double x, double y, double w, double h, hy_rgb col, double a)
{
    counter *k = c;
    k->paths++;
    k->inner.ops->fill_rect(k->inner.ctx, x, y, w, h, col, a);
}
static void k_marker(void *c, int s, double x, double y, double sz, const hy_pen *p, const hy_rgb *f)
{
    counter *k = c;
    k->paths++;
    k->filled += f != NULL;
    k->inner.ops->marker(k->inner.ctx, s, x, y, sz, p, f);
}
static void k_text(void *c, double x, double y, const char *s, double sz, int it, int v, hy_rgb col)
{
    counter *k = c;
    for (const char *p = s; *p; p++)
        k->glyphs += ((unsigned char)*p & 0xC0) != 0x80;
    k->inner.ops->text(k->inner.ctx, x, y, s, sz, it, v, col);
}
static void k_measure(void *c, const char *s, double sz, int it, hy_text_extents *e)
{
    ((counter *)c)->inner.ops->measure(((counter *)c)->inner.ctx, s, sz, it, e);
}
static void k_clip(void *c, double x, double y, double w, double h)
{
    ((counter *)c)->inner.ops->clip(((counter *)c)->inner.ctx, x, y, w, h);
}
static void k_unclip(void *c) { ((counter *)c)->inner.ops->unclip(((counter *)c)->inner.ctx); }
static const hy_canvas_ops counting_ops = {"counter", k_begin, k_move, k_line, k_stroke, k_rect,
                                           k_marker, k_text, k_measure, k_clip, k_unclip};

static void test_svg_structure(int i)
{
    hy_figure fig;
    hy_error err;
    const char *name = fig_build(i, &fig);
    char path[256];
    snprintf(path, sizeof path, "out_%s.svg", name);
    CHECK(hy_figure_write(&fig, path, HY_FORMAT_SVG, &err) == 0, "%s", err.msg);
    size_t len;
    char *svg = hy_test_slurp(path, &len);
    CHECK(svg != NULL, "cannot read %s", path);
    if (!svg)
        return;
    svg_counts c = svg_check(svg);
    CHECK(c.well_formed, "%s is not well-formed XML", path);
    CHECK(strstr(svg, "<svg") && strstr(svg, "pt\""), "%s lacks an <svg> root sized in points", path);

    cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 10, 10);
    cairo_t *cr = cairo_create(img);
    hy_cairo_canvas cc;
    counter k = {hy_canvas_cairo(&cc, cr, "DejaVu Sans"), 0, 0, 0};
    hy_canvas cv = {&counting_ops, &k};
    CHECK(hy_figure_draw(&fig, &cv, &err) == 0, "%s", err.msg);
    cairo_destroy(cr);
    cairo_surface_destroy(img);
    /* One <path> per stroke, fill or marker; a clipped filled marker may become two. */
    CHECK(c.paths >= k.paths && c.paths <= k.paths + k.filled,
          "%s: %ld <path> elements, the canvas stroked/filled %ld (%ld filled markers)", path, c.paths,
          k.paths, k.filled);
    CHECK(c.uses == k.glyphs, "%s: %ld glyph <use>s, the canvas drew %ld characters", path, c.uses, k.glyphs);
    printf("ok   %s: well-formed, %ld paths, %ld glyphs\n", path, c.paths, c.uses);
    free(svg);
}

static void test_checker(void)
{
    CHECK(svg_check("<?xml v?><svg a=\"x>y\"><g><path/></g></svg>").well_formed, "checker rejects good XML");
    CHECK(!svg_check("<svg><g></svg>").well_formed, "checker accepts unbalanced tags");
    CHECK(!svg_check("<svg></svg><svg></svg>").well_formed, "checker accepts two roots");
}

static void test_determinism(int i)
{
    static const char *ext[3] = {"svg", "pdf", "png"};
    hy_figure fig;
    hy_error err;
    const char *name = fig_build(i, &fig);
    for (int f = 0; f < 3; f++) {
        char a[256], b[256];
        size_t la = 0, lb = 0;
        snprintf(a, sizeof a, "det_%s_a.%s", name, ext[f]);
        snprintf(b, sizeof b, "det_%s_b.%s", name, ext[f]);
        CHECK(!hy_figure_write(&fig, a, f, &err) && !hy_figure_write(&fig, b, f, &err), "%s", err.msg);
        char *da = hy_test_slurp(a, &la), *db = hy_test_slurp(b, &lb);
        CHECK(da && db && la == lb && la > 0 && !memcmp(da, db, la), "%s and %s differ", a, b);
        free(da);
        free(db);
    }
}

/* Files in dir whose name starts with stem, and temporaries of the output
 * writer for such a name (".STEM....hystviz-tmp.XXXXXX"). */
static int leftovers(const char *dir, const char *stem)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    int n = 0;
    while (d && (e = readdir(d)) != NULL)
        n += !strncmp(e->d_name, stem, strlen(stem)) ||
             (e->d_name[0] == '.' && !strncmp(e->d_name + 1, stem, strlen(stem)) && strstr(e->d_name, ".hystviz-tmp."));
    if (d)
        closedir(d);
    return n;
}

static void test_atomic(void)
{
    hy_figure fig;
    hy_error err = {0, ""};
    fig_build(1, &fig);
    const char *p1 = "no_such_dir/sub/fig.png";
    CHECK(hy_figure_write(&fig, p1, HY_FORMAT_PNG, &err) == HY_EIO, "write into a missing directory succeeded");
    CHECK(strstr(err.msg, p1) != NULL, "message \"%s\" does not name the path", err.msg);
    struct stat st;
    CHECK(stat("no_such_dir", &st) != 0, "a directory was created");

    /* Read-only directory (meaningless as root, who may write anyway). */
    mkdir("ro_dir", 0755);
    chmod("ro_dir", 0555);
    if (geteuid() != 0) {
        err.msg[0] = '\0';
        CHECK(hy_figure_write(&fig, "ro_dir/fig.svg", HY_FORMAT_SVG, &err) == HY_EIO, "read-only dir accepted");
        CHECK(strstr(err.msg, "ro_dir/fig.svg") != NULL, "message \"%s\" does not name the path", err.msg);
        CHECK(leftovers("ro_dir", "fig") == 0, "files left in ro_dir");
    } else {
        printf("note: running as root, read-only directory case skipped\n");
    }
    chmod("ro_dir", 0755);

    /* A directory component that is a regular file: unwritable for root too. */
    FILE *plain = fopen("plain_file", "w");
    if (plain)
        fclose(plain);
    err.msg[0] = '\0';
    CHECK(hy_figure_write(&fig, "plain_file/fig.svg", HY_FORMAT_SVG, &err) == HY_EIO, "write under a file succeeded");
    CHECK(strstr(err.msg, "plain_file/fig.svg") != NULL, "message \"%s\" does not name the path", err.msg);

    /* The target is a directory: rename fails after a complete write; the temp file goes. */
    mkdir("atomic_dir", 0755);
    mkdir("atomic_dir/fig.pdf", 0755);
    CHECK(hy_figure_write(&fig, "atomic_dir/fig.pdf", HY_FORMAT_PDF, &err) == HY_EIO, "rename onto a directory succeeded");
    CHECK(strstr(err.msg, "atomic_dir/fig.pdf") != NULL, "message \"%s\" does not name the path", err.msg);
    CHECK(leftovers("atomic_dir", "fig.pdf.") == 0, "temporary file left in atomic_dir");
    rmdir("atomic_dir/fig.pdf");

    /* A write failure part-way (file size limit, as ENOSPC would): the old file survives. */
    size_t lold = 0, lnow = 0;
    CHECK(hy_figure_write(&fig, "atomic_dir/keep.svg", HY_FORMAT_SVG, &err) == 0, "%s", err.msg);
    char *old = hy_test_slurp("atomic_dir/keep.svg", &lold);
    struct rlimit saved, small;
    getrlimit(RLIMIT_FSIZE, &saved);
    small = saved;
    small.rlim_cur = 4096;
    signal(SIGXFSZ, SIG_IGN);
    setrlimit(RLIMIT_FSIZE, &small);
    static const int fmts[3] = {HY_FORMAT_SVG, HY_FORMAT_PDF, HY_FORMAT_PNG};
    static const char *paths[3] = {"atomic_dir/keep.svg", "atomic_dir/big.pdf", "atomic_dir/big.png"};
    int rcs[3];
    hy_error errs[3];
    for (int f = 0; f < 3; f++)
        rcs[f] = hy_figure_write(&fig, paths[f], fmts[f], &errs[f]);
    setrlimit(RLIMIT_FSIZE, &saved);
    for (int f = 0; f < 3; f++) {
        CHECK(rcs[f] == HY_EIO, "write of %s past the size limit returned %d", paths[f], rcs[f]);
        CHECK(rcs[f] == 0 || strstr(errs[f].msg, paths[f]), "message \"%s\" does not name the path", errs[f].msg);
        if (rcs[f])
            printf("ok   expected failure: %s\n", errs[f].msg);
    }
    char *now = hy_test_slurp("atomic_dir/keep.svg", &lnow);
    CHECK(old && now && lold == lnow && !memcmp(old, now, lold), "a failed write damaged the existing file");
    CHECK(leftovers("atomic_dir", "big") == 0, "partial files left after write failures");
    CHECK(leftovers("atomic_dir", "keep.svg.") == 0, "temporary file left after a write failure");
    free(old);
    free(now);
}

int main(void)
{
    test_checker();
    for (int i = 0; i < FIG_COUNT; i++) {
        test_svg_structure(i);
        test_determinism(i);
    }
    test_atomic();
    CHECK(hy_format_from_path("a/b.svg") == HY_FORMAT_SVG && hy_format_from_path("x.png") == HY_FORMAT_PNG &&
          hy_format_from_path("x.pdf") == HY_FORMAT_PDF && hy_format_from_path("x.jpg") == -1,
          "hy_format_from_path");
    /* an absurd raster is refused before anything is drawn or written */
    hy_figure big;
    hy_error berr = {0, ""};
    fig_build(1, &big);
    big.width = hy_in(40), big.height = hy_in(40), big.dpi = 2400;
    CHECK(hy_figure_check(&big, HY_FORMAT_PNG, &berr) == HY_EINVAL && strstr(berr.msg, "96000 x 96000 pixels"),
          "40 x 40 in at 2400 dpi: %s", berr.msg);
    CHECK(hy_figure_write(&big, "big.png", HY_FORMAT_PNG, &berr) == HY_EINVAL && leftovers(".", "big.png") == 0,
          "the absurd PNG was written or left a file");
    CHECK(hy_figure_check(&big, HY_FORMAT_SVG, &berr) == HY_OK, "a vector figure of 40 x 40 in is fine");
    big.width = hy_in(10), big.height = hy_in(10), big.dpi = 2400; /* 24000 px a side: 576 Mpx > 2^28 */
    CHECK(hy_figure_check(&big, HY_FORMAT_PNG, &berr) == HY_EINVAL, "576 million pixels accepted");
    big.width = hy_in(5);                                          /* 12000 x 24000 = 288 Mpx > 2^28 */
    CHECK(hy_figure_check(&big, HY_FORMAT_PNG, &berr) == HY_EINVAL, "288 million pixels accepted");
    big.width = hy_in(4);                                          /* 9600 x 24000 = 230 Mpx: allowed */
    CHECK(hy_figure_check(&big, HY_FORMAT_PNG, &berr) == HY_OK, "230 million pixels refused: %s", berr.msg);
    hy_figure empty = {0};
    hy_error err;
    CHECK(hy_figure_write(&empty, "empty.svg", HY_FORMAT_SVG, &err) == HY_EINVAL, "a figure without panels was written");
    CHECK(leftovers(".", "empty.svg") == 0, "a failed figure left a file");
    cairo_debug_reset_static_data();   /* drop font caches so leak checkers see only real leaks */
    return hy_test_finish("output");
}
