/* SPDX-License-Identifier: MIT */
/* test_strokes.c: line styles as drawn in the output files: a dash-dot pattern's
 * zero-length "on" entry survives into the SVG's stroke-dasharray with round
 * caps and is a round dot in the PNG; a sharp turning point is drawn with a
 * round join (no miter spike past the data); a PNG of a size that is not a
 * whole number of pixels has a white last row and column. */
#include <cairo.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "hy_plot.h"

#include "../hy_test.h"
#include "rcheck.h"

/* A single horizontal dash-dot line at y = 0.5 across x = 0..1, no ticks in the way. */
static void dashdot_figure(hy_figure *fig, hy_axes *ax, hy_series *s, double *x, double *y)
{
    x[0] = 0.0, x[1] = 1.0, y[0] = y[1] = 0.5;
    *s = (hy_series){.x = x, .y = y, .n = 2, .style = HY_LINE_DASHDOT, .width = 1.0,
                     .colour = {.palette = 0}};
    *ax = (hy_axes){.series = s, .nseries = 1, .x = {0.0, 1.0, 0, 0}, .y = {0.0, 1.0, 0, 0}};
    *fig = (hy_figure){.width = 240, .height = 120, .dpi = 288, .axes = ax, .nrows = 1, .ncols = 1};
}

/* Every stroke-dasharray of the SVG: at least one, each with a 0 entry, on a
 * path with round caps (the zero-length dash is a dot only with them). */
static void check_svg_dots(const char *svg)
{
    int found = 0;
    for (const char *p = svg; (p = strstr(p, "stroke-dasharray:")) != NULL; p++) {
        const char *tag = p;
        while (tag > svg && *tag != '<')
            tag--;
        const char *end = strchr(p, '"');
        char list[128] = "";
        size_t n = strcspn(p + 17, ";\"");
        snprintf(list, sizeof list, "%.*s", (int)(n < 127 ? n : 127), p + 17);
        int zero = !strncmp(list, "0,", 2) || strstr(list, ",0,") != NULL ||
                   (strlen(list) > 2 && !strcmp(list + strlen(list) - 2, ",0"));
        CHECK(zero, "stroke-dasharray:%s has no 0 entry (the dot was merged into the gaps)", list);
        char style[512];
        snprintf(style, sizeof style, "%.*s", (int)(end && end - tag < 511 ? end - tag : 511), tag);
        CHECK(strstr(style, "stroke-linecap:round") != NULL, "dash-dot path without round caps: %s", style);
        found++;
    }
    CHECK(found == 1, "%d dashed paths in the SVG, want 1", found);
}

/* Runs of dark pixels along row y between x0 and x1: counts of short runs
 * (dots: at most dot_max px) and of long runs (dashes: at least dash_min px). */
static void count_runs(cairo_surface_t *img, int y, int x0, int x1, int dot_max, int dash_min,
                       int *dots, int *dashes)
{
    const unsigned char *d = cairo_image_surface_get_data(img);
    int stride = cairo_image_surface_get_stride(img), run = 0;
    *dots = *dashes = 0;
    for (int x = x0; x <= x1; x++) {
        const uint32_t px = *(const uint32_t *)(const void *)(d + (size_t)y * stride + 4 * (size_t)x);
        int dark = ((px >> 8) & 0xff) < 128;
        if (dark) {
            run++;
            continue;
        }
        if (run > 0 && run <= dot_max)
            (*dots)++;
        else if (run >= dash_min)
            (*dashes)++;
        run = 0;
    }
}

static int dark_at(cairo_surface_t *img, int x, int y, int level)
{
    const unsigned char *d = cairo_image_surface_get_data(img);
    int stride = cairo_image_surface_get_stride(img);
    uint32_t px = *(const uint32_t *)(const void *)(d + (size_t)y * stride + 4 * (size_t)x);
    return (int)((px >> 8) & 0xff) < level;
}

static void test_dashdot(void)
{
    double x[2], y[2];
    hy_series s;
    hy_axes ax;
    hy_figure fig;
    hy_error err;
    dashdot_figure(&fig, &ax, &s, x, y);
    CHECK(hy_figure_write(&fig, "strokes_dashdot.svg", HY_FORMAT_SVG, &err) == 0, "svg: %s", err.msg);
    CHECK(hy_figure_write(&fig, "strokes_dashdot.png", HY_FORMAT_PNG, &err) == 0, "png: %s", err.msg);
    char *svg = hy_test_slurp("strokes_dashdot.svg", NULL);
    CHECK(svg != NULL, "cannot read strokes_dashdot.svg");
    if (svg)
        check_svg_dots(svg);
    free(svg);

    cairo_surface_t *img = cairo_image_surface_create_from_png("strokes_dashdot.png");
    CHECK(cairo_surface_status(img) == CAIRO_STATUS_SUCCESS, "cannot read strokes_dashdot.png");
    int w = cairo_image_surface_get_width(img), h = cairo_image_surface_get_height(img);
    /* The line is at mid-height.  At 288 dpi (4 px/pt) the pattern {5, 2.4, 0,
     * 2.4} pt is 20 px dashes (+4 px of round caps), gaps 9.6 - 4 px and dots
     * of one line width (4 px).  Count both in the middle 60 % of the row, so
     * frame edges stay out: about 0.6 * 240 pt / 9.8 pt = 14.7 periods. */
    int dots = 0, dashes = 0, row = h / 2, most = -1;
    for (int yy = h / 4; yy < 3 * h / 4; yy++) {   /* the line's centre row: the darkest */
        int n = 0;
        for (int xx = w / 5; xx <= 4 * w / 5; xx++)
            n += dark_at(img, xx, yy, 128);
        if (n > most)
            most = n, row = yy;
    }
    count_runs(img, row, w / 5, 4 * w / 5, 7, 16, &dots, &dashes);
    printf("dash-dot row: %d dots, %d dashes\n", dots, dashes);
    CHECK(dashes >= 12 && dashes <= 17, "%d dashes in the crop, want about 14", dashes);
    CHECK(dots >= dashes - 1 && dots <= dashes + 1, "%d dots for %d dashes: the dots are missing", dots, dashes);
    cairo_surface_destroy(img);
    unlink("strokes_dashdot.svg");
    unlink("strokes_dashdot.png");
}

/* A V with a sharp tip at (0.5, 0.9) (ranges 0..1, a nearly square frame):
 * its sides meet at 2 atan(0.1 / 0.8) = 14 degrees, so a miter join passes
 * the vertex by hw / sin(7.1 deg) = 8.1 half-widths (16 px here; within
 * cairo's default miter limit of 10, as the GL path's was); a round join ends
 * one half width (1 pt = 2 px) above it. */
static void test_round_join(void)
{
    double x[3] = {0.4, 0.5, 0.6}, y[3] = {0.1, 0.9, 0.1};
    hy_series s = {.x = x, .y = y, .n = 3, .style = HY_LINE_SOLID, .width = 2.0, .colour = {.palette = 0}};
    hy_axes ax = {.series = &s, .nseries = 1, .x = {0.0, 1.0, 0, 0}, .y = {0.0, 1.0, 0, 0}};
    hy_figure fig = {.width = 200, .height = 200, .dpi = 144, .axes = &ax, .nrows = 1, .ncols = 1};
    hy_error err;
    CHECK(hy_figure_write(&fig, "strokes_join.png", HY_FORMAT_PNG, &err) == 0, "png: %s", err.msg);
    cairo_surface_t *img = cairo_image_surface_create_from_png("strokes_join.png");
    CHECK(cairo_surface_status(img) == CAIRO_STATUS_SUCCESS, "cannot read strokes_join.png");
    int w = cairo_image_surface_get_width(img), h = cairo_image_surface_get_height(img);
    int frame_top = -1, frame_bot = -1, top = -1;
    for (int yy = 0; yy < h; yy++)          /* the frame's top and bottom lines at x = w / 4 */
        if (dark_at(img, w / 4, yy, 128)) {
            if (frame_top < 0)
                frame_top = yy;
            frame_bot = yy;
        }
    for (int yy = frame_top + 6; yy < h && top < 0; yy++)   /* the stroke's highest ink near x = w / 2 */
        for (int xx = w / 2 - 8; xx <= w / 2 + 8; xx++)
            if (dark_at(img, xx, yy, 230)) {
                top = yy;
                break;
            }
    cairo_surface_destroy(img);
    double tip = frame_top + 0.5 + (frame_bot - frame_top) * 0.1;   /* y = 0.9 of 0..1, y down */
    double above = tip - top;
    printf("join: tip at row %.1f, ink from row %d: %.1f px above it (round join: 2 px + AA)\n", tip, top, above);
    CHECK(top > 0 && above <= 3.5, "stroke passes the tip by %.1f px: a miter spike", above);
    unlink("strokes_join.png");
}

/* 12 cm x 9 cm at 200 dpi is 944.9 x 708.7 px: the PNG has whole pixels and
 * its last column and row are pure background. */
static void test_whole_pixels(void)
{
    double x[2] = {0, 1}, y[2] = {0, 1};
    hy_series s = {.x = x, .y = y, .n = 2};
    hy_axes ax = {.series = &s, .nseries = 1};
    hy_figure fig = {.width = hy_cm(12), .height = hy_cm(9), .dpi = 200, .axes = &ax, .nrows = 1, .ncols = 1};
    hy_error err;
    CHECK(hy_figure_write(&fig, "strokes_edge.png", HY_FORMAT_PNG, &err) == 0, "png: %s", err.msg);
    cairo_surface_t *img = cairo_image_surface_create_from_png("strokes_edge.png");
    int w = cairo_image_surface_get_width(img), h = cairo_image_surface_get_height(img);
    int stride = cairo_image_surface_get_stride(img), bad = 0;
    const unsigned char *d = cairo_image_surface_get_data(img);
    CHECK(w == 945 && h == 709, "size %d x %d, want 945 x 709", w, h);
    for (int yy = 0; yy < h; yy++)
        for (int xx = 0; xx < w; xx++) {
            if (xx != w - 1 && yy != h - 1)
                continue;
            uint32_t px = *(const uint32_t *)(const void *)(d + (size_t)yy * stride + 4 * (size_t)xx);
            bad += (px & 0xffffff) != 0xffffff;
        }
    CHECK(bad == 0, "%d pixels of the last row and column are not white", bad);
    cairo_surface_destroy(img);
    unlink("strokes_edge.png");
}

int main(void)
{
    test_dashdot();
    test_round_join();
    test_whole_pixels();
    return hy_test_finish("strokes");
}
