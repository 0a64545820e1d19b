/* SPDX-License-Identifier: MIT */
/* test_image.c: reference-image tests (cairo test-suite style): PNG output vs tests/reference/render_*.png.
 *
 * Passes when the images are identical or no channel of any pixel differs by
 * more than TOLERANCE (out of 255).  On failure the output and a diff image
 * (differing pixels in red, scaled by the difference) are left in the build
 * directory.  HY_UPDATE_REFERENCE=1 rewrites the references from the output. */
#include <cairo.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "figures.h"
#include "hy_config.h"

#define TOLERANCE 8

static int copy_file(const char *from, const char *to)
{
    FILE *in = fopen(from, "rb"), *out = in ? fopen(to, "wb") : NULL;
    char buf[65536];
    size_t n;
    int ok = in && out;
    while (ok && (n = fread(buf, 1, sizeof buf, in)) > 0)
        ok = fwrite(buf, 1, n, out) == n;
    if (in)
        fclose(in);
    if (out && fclose(out) != 0)
        ok = 0;
    return ok;
}

static unsigned pixel(cairo_surface_t *s, int x, int y)
{
    const unsigned char *d = cairo_image_surface_get_data(s);
    return ((const unsigned *)(const void *)(d + (size_t)y * cairo_image_surface_get_stride(s)))[x];
}

/* Compares out with ref; writes diff_path on failure.  Returns 0 on a pass. */
static int compare(const char *out, const char *ref, const char *diff_path)
{
    cairo_surface_t *a = cairo_image_surface_create_from_png(out);
    cairo_surface_t *b = cairo_image_surface_create_from_png(ref);
    int rc = 1;
    if (cairo_surface_status(a) || cairo_surface_status(b)) {
        printf("FAIL cannot read %s or %s (%s); to create references run with HY_UPDATE_REFERENCE=1\n",
               out, ref, cairo_status_to_string(cairo_surface_status(b)));
        goto done;
    }
    int w = cairo_image_surface_get_width(a), h = cairo_image_surface_get_height(a);
    if (w != cairo_image_surface_get_width(b) || h != cairo_image_surface_get_height(b)) {
        printf("FAIL %s is %dx%d, reference %s is %dx%d\n", out, w, h, ref,
               cairo_image_surface_get_width(b), cairo_image_surface_get_height(b));
        goto done;
    }
    cairo_surface_t *diff = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
    unsigned char *dd = cairo_image_surface_get_data(diff);
    int dstride = cairo_image_surface_get_stride(diff), maxd = 0;
    long changed = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            unsigned pa = pixel(a, x, y), pb = pixel(b, x, y);
            int m = 0;
            for (int sh = 0; sh < 24; sh += 8) {
                int d = abs((int)((pa >> sh) & 255) - (int)((pb >> sh) & 255));
                m = d > m ? d : m;
            }
            changed += m > 0;
            maxd = m > maxd ? m : maxd;
            unsigned v = m ? 0xFF0000u | (unsigned)(255 - (m * 4 > 255 ? 255 : m * 4)) * 0x101u
                           : 0xFFFFFFu;
            ((unsigned *)(void *)(dd + (size_t)y * dstride))[x] = v;
        }
    cairo_surface_mark_dirty(diff);
    rc = maxd > TOLERANCE;
    if (rc) {
        cairo_surface_write_to_png(diff, diff_path);
        printf("FAIL %s: %ld pixels differ, max channel difference %d > %d\n  output: %s\n  diff:   %s\n",
               ref, changed, maxd, TOLERANCE, out, diff_path);
    } else {
        printf("ok   %s (%ld pixels differ, max channel difference %d <= %d)\n", ref, changed, maxd,
               TOLERANCE);
    }
    cairo_surface_destroy(diff);
done:
    cairo_surface_destroy(a);
    cairo_surface_destroy(b);
    return rc;
}

/* DejaVu Sans digits advance 1303/2048 em; another font means fontconfig substituted. */
static int have_dejavu(void)
{
    cairo_surface_t *img = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 4, 4);
    cairo_t *cr = cairo_create(img);
    cairo_text_extents_t te;
    cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, 100.0);
    cairo_text_extents(cr, "0123456789", &te);
    cairo_destroy(cr);
    cairo_surface_destroy(img);
    double want = 1000.0 * 1303.0 / 2048.0;
    return te.x_advance > 0.99 * want && te.x_advance < 1.01 * want;
}

int main(void)
{
    if (!have_dejavu())
        printf("warning: the font \"DejaVu Sans\" is not installed (Debian: fonts-dejavu-core); "
               "text will differ from the references\n");
    const char *upd = getenv("HY_UPDATE_REFERENCE");
    int update = upd && !strcmp(upd, "1"), fails = 0;
    for (int i = 0; i < FIG_COUNT; i++) {
        hy_figure fig;
        hy_error err;
        const char *name = fig_build(i, &fig);
        char out[512], ref[1024], diff[512];
        snprintf(out, sizeof out, "render_%s.png", name);
        snprintf(diff, sizeof diff, "render_%s.diff.png", name);
        snprintf(ref, sizeof ref, "%s/tests/reference/render_%s.png", HY_SOURCE_DIR, name);
        if (hy_figure_write(&fig, out, HY_FORMAT_PNG, &err)) {
            printf("FAIL %s\n", err.msg);
            fails++;
            continue;
        }
        if (update) {
            if (!copy_file(out, ref)) {
                printf("FAIL cannot update %s\n", ref);
                fails++;
            } else {
                printf("updated %s\n", ref);
            }
            continue;
        }
        fails += compare(out, ref, diff);
    }
    cairo_debug_reset_static_data();   /* drop font caches so leak checkers see only real leaks */
    return fails ? 1 : 0;
}
