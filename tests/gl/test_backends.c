/* SPDX-License-Identifier: MIT */
/* test_backends.c: the 3-D ribbon pass (depth, lighting, 4x multisampling
 * resolved by a blit) with 2-D strokes under and over it gives the same
 * bytes on OSMesa and on EGL, and a thread can hold one context of each,
 * switching between them (hy_gl.c makes the used one current).  The
 * animations cover the 2-D path (backends_equal.sh); no built-in animation
 * draws a ribbon any more, so this one does.  SKIP unless both backends are
 * built. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gltest.h"

enum { W = 320, H = 180, LOOPS = 24, PTS = 60 };

static double pts[LOOPS][PTS * 3];

/* One frame: a dashed diagonal, the ribbon, a thick stroke over it. */
static const unsigned char *draw(hy_gl *g, double azimuth, hy_error *err)
{
    hy_gl_begin(g, (hy_rgb){1, 1, 1});
    hy_canvas c = hy_gl_canvas(g, 1.0);
    static const double dash[2] = {4, 3};
    hy_pen thin = {.width = 1.5, .colour = {0.2, 0.3, 0.8}, .dash = dash, .ndash = 2};
    c.ops->begin_path(c.ctx);
    c.ops->move_to(c.ctx, 10, 170);
    c.ops->line_to(c.ctx, 310, 10);
    c.ops->stroke(c.ctx, &thin);
    hy_gl_ribbon r = {&pts[0][0], LOOPS, PTS, HY_CMAP_VIRIDIS, azimuth, 0.5, 0, 40, 10, 240, 160};
    if (hy_gl_draw_ribbon(g, &r, err))
        return NULL;
    hy_pen thick = {.width = 6, .colour = {0.9, 0.4, 0.1}, .round_caps = 1};
    c.ops->begin_path(c.ctx);
    c.ops->move_to(c.ctx, 20, 90);
    c.ops->line_to(c.ctx, 160, 60);
    c.ops->line_to(c.ctx, 300, 120);
    c.ops->stroke(c.ctx, &thick);
    return hy_gl_finish(g, err);
}

int main(void)
{
    hy_error err;
    if (strcmp(hy_gl_backends(), "osmesa egl")) {
        printf("SKIP: needs both GL backends (built: '%s')\n", hy_gl_backends());
        return 77;
    }
    for (int i = 0; i < LOOPS; i++)          /* loops of a hysteresis-like ribbon */
        for (int j = 0; j < PTS; j++) {
            double t = 2 * M_PI * j / (PTS - 1), s = (double)i / (LOOPS - 1);
            pts[i][3 * j] = 0.8 * sin(t);
            pts[i][3 * j + 1] = (0.3 + 0.5 * s) * sin(t + 0.3 + s);
            pts[i][3 * j + 2] = 2 * s - 1;
        }
    CHECK(hy_gl_select("osmesa", &err) == HY_OK, "select osmesa: %s", err.msg);
    hy_gl *a = gl_or_skip(W, H);
    CHECK(hy_gl_select("egl", &err) == HY_OK, "select egl: %s", err.msg);
    hy_gl *b = gl_or_skip(W, H);
    CHECK(strstr(hy_gl_describe(a), "(osmesa)") && strstr(hy_gl_describe(b), "(egl)"), "backends: %s | %s",
          hy_gl_describe(a), hy_gl_describe(b));
    static unsigned char fa[W * H * 4];
    for (int k = 0; k < 3; k++) {             /* three camera angles, alternating contexts */
        const unsigned char *p = draw(a, 0.4 + k, &err);
        CHECK(p != NULL, "osmesa frame %d: %s", k, err.msg);
        if (!p)
            break;
        memcpy(fa, p, sizeof fa);
        const unsigned char *q = draw(b, 0.4 + k, &err);
        CHECK(q != NULL, "egl frame %d: %s", k, err.msg);
        if (!q)
            break;
        long ndiff = 0, nink = 0;
        int maxd = 0;
        for (size_t i = 0; i < sizeof fa; i++) {
            int d = abs(fa[i] - q[i]);
            ndiff += d > 0, maxd = d > maxd ? d : maxd;
            nink += (i % 4 != 3) && fa[i] < 200;
        }
        printf("frame %d: %ld bytes differ (largest %d), %ld dark channels drawn\n", k, ndiff, maxd, nink);
        CHECK(ndiff == 0, "frame %d: osmesa and egl differ in %ld bytes (largest %d)", k, ndiff, maxd);
        CHECK(nink > 1000, "frame %d: almost nothing drawn (%ld dark channels)", k, nink);
    }
    hy_gl_free(a);
    hy_gl_free(b);
    return hy_test_finish("backends");
}
