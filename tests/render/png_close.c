/* SPDX-License-Identifier: MIT */
/* png_close.c: whether two PNGs show the same pixels within a tolerance.
 *
 * usage: png_close MAXDIFF A.png B.png
 * Decodes both (cairo), prints the number of pixels that differ and the
 * largest difference of any channel (0..255); exit 0 when the sizes agree
 * and no channel differs by more than MAXDIFF, 1 when they do not, 2 when a
 * file cannot be read.  tests/render/test_resolution.sh uses it to hold the
 * curves drawn at the output's resolution to the pixels of every point. */
#include <cairo.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: png_close MAXDIFF A.png B.png\n");
        return 2;
    }
    int tol = atoi(argv[1]);
    cairo_surface_t *a = cairo_image_surface_create_from_png(argv[2]);
    cairo_surface_t *b = cairo_image_surface_create_from_png(argv[3]);
    int rc = 2;
    if (cairo_surface_status(a) || cairo_surface_status(b)) {
        fprintf(stderr, "png_close: cannot read %s or %s\n", argv[2], argv[3]);
        goto done;
    }
    int w = cairo_image_surface_get_width(a), h = cairo_image_surface_get_height(a);
    rc = 1;
    if (w != cairo_image_surface_get_width(b) || h != cairo_image_surface_get_height(b)) {
        printf("%s is %dx%d, %s is %dx%d\n", argv[2], w, h, argv[3], cairo_image_surface_get_width(b),
               cairo_image_surface_get_height(b));
        goto done;
    }
    const unsigned char *da = cairo_image_surface_get_data(a), *db = cairo_image_surface_get_data(b);
    int sa = cairo_image_surface_get_stride(a), sb = cairo_image_surface_get_stride(b), maxd = 0;
    long changed = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < 4 * w; x += 4) {
            int m = 0;
            for (int c = 0; c < 4; c++) {
                int d = abs((int)da[(size_t)y * sa + x + c] - (int)db[(size_t)y * sb + x + c]);
                m = d > m ? d : m;
            }
            changed += m > 0;
            maxd = m > maxd ? m : maxd;
        }
    printf("%ld pixels differ, largest channel difference %d (at most %d): %s\n", changed, maxd, tol,
           maxd <= tol ? "ok" : "FAIL");
    rc = maxd > tol;
done:
    cairo_surface_destroy(a);
    cairo_surface_destroy(b);
    return rc;
}
