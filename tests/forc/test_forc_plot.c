/* SPDX-License-Identifier: MIT */
/* test_forc_plot: the FORC diagram's pixels (src/render/hy_forc_plot.c).  A
 * grid with ρ = +v on H_u > 0, −v on H_u < 0 and NaN in one corner is drawn
 * as PNG and read back: red above, blue below, white where ρ is NaN, the
 * zero contour grey along H_u = 0, and the colour scale centred at 0 (a
 * value of 0 is white). */
#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hy_forc_plot.h"
#include "hy_plot.h"
#include "../core/tutil.h"

typedef struct reader {
    const unsigned char *p;
    size_t n;
} reader;

static cairo_status_t rd(void *c, unsigned char *data, unsigned int len)
{
    reader *r = c;
    if (len > r->n)
        return CAIRO_STATUS_READ_ERROR;
    memcpy(data, r->p, len);
    r->p += len;
    r->n -= len;
    return CAIRO_STATUS_SUCCESS;
}

/* RGB of the pixel at data (hc, hu) for the default layout (frame at 58 pt
 * from the left, 12 from the top, 78 and 42 pt kept for the bar and axis). */
static void pixel(cairo_surface_t *s, const hy_forc_plot_opts *o, const hy_forc_grid *g, double hc, double hu,
                  int rgb[3])
{
    double k = o->dpi / 72, w = o->width - 58 - 78, h = o->height - 12 - 42;
    double xpt = 58 + (hc - g->hc0) / (g->hc1 - g->hc0) * w, ypt = 12 + h - (hu - g->hu0) / (g->hu1 - g->hu0) * h;
    int x = (int)(xpt * k), y = (int)(ypt * k);
    const unsigned char *px = cairo_image_surface_get_data(s) + (size_t)y * (size_t)cairo_image_surface_get_stride(s);
    unsigned v = ((const unsigned *)(const void *)px)[x];
    rgb[0] = (int)(v >> 16 & 255), rgb[1] = (int)(v >> 8 & 255), rgb[2] = (int)(v & 255);
}

int main(void)
{
    hy_forc_grid g = {.hc0 = 0, .hc1 = 1, .hu0 = -1, .hu1 = 1, .nc = 41, .nu = 41};
    g.rho = malloc(g.nc * g.nu * sizeof *g.rho);
    for (size_t iu = 0; iu < g.nu; iu++)
        for (size_t ic = 0; ic < g.nc; ic++) {
            double hu = g.hu0 + (double)iu * 0.05, hc = (double)ic * 0.025;
            g.rho[iu * g.nc + ic] = hc > 0.8 && hu > 0.8 ? NAN : hu > 0.3 ? 2e-5 : hu < -0.3 ? -2e-5 : 2e-5 * hu / 0.3;
        }
    hy_forc_plot_opts o = hy_forc_plot_defaults();
    o.field_to_mt = 1e3;
    o.rho_unit = "A m²/T²";
    hy_error err = {0};
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    CHECK(f && !hy_forc_plot_write(&g, &o, f, HY_FORMAT_PNG, &err), "write: %s", err.msg);
    fclose(f);
    reader r = {(const unsigned char *)buf, len};
    cairo_surface_t *s = cairo_image_surface_create_from_png_stream(rd, &r);
    CHECK(cairo_surface_status(s) == CAIRO_STATUS_SUCCESS && cairo_image_surface_get_width(s) == 833 &&
              cairo_image_surface_get_height(s) == 667,
          "png %dx%d", cairo_image_surface_get_width(s), cairo_image_surface_get_height(s));
    int c[3];
    pixel(s, &o, &g, 0.4, 0.6, c); /* +vmax: the map's red end (0.70, 0.09, 0.17) */
    CHECK(abs(c[0] - 179) <= 3 && abs(c[1] - 23) <= 3 && abs(c[2] - 43) <= 3, "positive %d %d %d", c[0], c[1], c[2]);
    pixel(s, &o, &g, 0.4, -0.6, c); /* −vmax: blue (0.13, 0.40, 0.67) */
    CHECK(abs(c[0] - 33) <= 3 && abs(c[1] - 102) <= 3 && abs(c[2] - 171) <= 3, "negative %d %d %d", c[0], c[1], c[2]);
    pixel(s, &o, &g, 0.95, 0.95, c); /* NaN: the white page */
    CHECK(c[0] == 255 && c[1] == 255 && c[2] == 255, "NaN %d %d %d", c[0], c[1], c[2]);
    /* ρ = 0.4 vmax at H_u = 0.12 (between the contours at 0.3 and 0.5):
     * tint √0.4 of the way to red; 4 levels for the PNG's bilinear filter */
    pixel(s, &o, &g, 0.4, 0.12, c);
    double t = sqrt(0.4);
    CHECK(abs(c[0] - (int)lround(255 * (1 + t * (0.70 - 1)))) <= 4 &&
              abs(c[1] - (int)lround(255 * (1 + t * (0.09 - 1)))) <= 4,
          "half %d %d %d", c[0], c[1], c[2]);
    /* the zero contour along H_u = 0 is grey over a white map; 3 pt off it white */
    int grey = 0;
    for (int d = -3; d <= 3; d++) {
        pixel(s, &o, &g, 0.4, d * 0.001, c);
        grey |= c[0] < 200 && abs(c[0] - c[1]) < 30 && abs(c[1] - c[2]) < 30;
    }
    CHECK(grey, "no grey zero contour at H_u = 0");
    pixel(s, &o, &g, 0.4, 0.012, c); /* ρ = 0.04 vmax: a light red tint (√0.04 = 0.2), not the line */
    CHECK(c[0] >= 235 && c[0] > c[1] + 8, "just above 0: %d %d %d", c[0], c[1], c[2]);
    cairo_surface_destroy(s);
    free(buf);
    /* refusals */
    for (size_t i = 0; i < g.nc * g.nu; i++)
        g.rho[i] = NAN;
    f = open_memstream(&buf, &len);
    CHECK_MSG(hy_forc_plot_write(&g, &o, f, HY_FORMAT_SVG, &err), err, HY_EINVAL, "no finite nonzero value");
    fclose(f);
    free(buf);
    free(g.rho);
    return tu_finish("test_forc_plot");
}
