/* SPDX-License-Identifier: MIT */
/* test_preisach_plane.c: the built-in animation preisach-plane (issue 22
 * item 5), rendered by `hystviz animate` in-process at 640x360:
 *  - the memory a frame draws equals the core's extrema stack, built here
 *    independently (hy_preisach_mem fed Fig. 2's extrema in order, then the
 *    input at that time), and the staircase's vertices are those extrema:
 *    horizontal steps at the maxima, vertical ones at the minima, ending at
 *    (u, u);
 *  - in the PNG, the relays just below/left of every step are up and those
 *    just above/right are down;
 *  - the output is the plane's integral: sum over the pixels of the
 *    triangle of sign(colour) mu(alpha, beta) dA equals the model's y within
 *    a bound made of what pixels cannot resolve: the density's mass the
 *    panel's pixels miss (ys minus the sum of mu dA over every triangle pixel,
 *    measured), plus mu dA of every pixel whose colour is neither up nor down
 *    (the staircase, the diagonal, the marker) or whose centre lies within
 *    1.5 px of a step (the midpoint rule misjudges at most those);
 *  - frames are byte-identical across runs with -j 1 and -j 2. */
#include "hy_config.h"

#include <cairo.h>
#include <math.h>
#include <string.h>

#include "anim_preisach.h"
#include "animtest.h"
#include "gltest.h"
#include "hy_cairo.h"

#define W 640
#define H 360
#define FPS 30.0
#define DUR 8.0

static const long frames[] = {20, 60, 110, 150, 200, 239};

/* The memory at input time tin, fed here from Fig. 2's extrema (Definition 1:
 * 0 -> 1 -> 0.2 -> 1.5 -> 0 at t = 1, 2.2, 3.2, 5 per period). */
static int own_memory(const hy_preisach *p, const hy_input *in, double tin, hy_preisach_mem *m)
{
    static const double te[4] = {1, 2.2, 3.2, 5}, ue[4] = {1, 0.2, 1.5, 0};
    hy_error err;
    if (hy_preisach_mem_init(m, p, 0.0, &err))
        return -1;
    for (int k = 0; k < 2; k++)
        for (int i = 0; i < 4; i++)
            if (k * 5.0 + te[i] < tin && hy_preisach_mem_apply(m, ue[i], NULL, &err))
                return -1;
    return hy_preisach_mem_apply(m, hy_input_u(in, tin), NULL, &err) ? -1 : 0;
}

static double dens(const hy_preisach *p, double a, double b)
{
    double za = (a - p->ma) / p->sa, zb = (b - p->mb) / p->sb;
    return p->scale * exp(-0.5 * (za * za + zb * zb)) / (2 * M_PI * p->sa * p->sb);
}

/* Colour class of pixel (x, y): +1 up (vermillion), -1 down (blue), 0 neither. */
static int klass(const unsigned char *px, int stride, int x, int y)
{
    uint32_t v;
    memcpy(&v, px + (size_t)y * (size_t)stride + 4 * (size_t)x, 4);
    int r = (int)(v >> 16 & 255), g = (int)(v >> 8 & 255), b = (int)(v & 255);
    if (r > b + 12 && r >= g && r > 150)
        return 1;
    if (b > r + 12 && b >= g && b > 150)
        return -1;
    return 0;
}

static int near_step(const double *sb, const double *sa, size_t ns, double px, double py, const double *rect,
                     const double *lim, double tol)
{
    double kx = rect[2] / (lim[1] - lim[0]), ky = rect[3] / (lim[3] - lim[2]);
    for (size_t i = 0; i + 1 < ns; i++) {
        double x0 = rect[0] + (sb[i] - lim[0]) * kx, x1 = rect[0] + (sb[i + 1] - lim[0]) * kx;
        double y0 = rect[1] + rect[3] - (sa[i] - lim[2]) * ky, y1 = rect[1] + rect[3] - (sa[i + 1] - lim[2]) * ky;
        double xa = fmin(x0, x1) - tol, xb = fmax(x0, x1) + tol, ya = fmin(y0, y1) - tol, yb = fmax(y0, y1) + tol;
        if (px >= xa && px <= xb && py >= ya && py <= yb)
            return 1;
    }
    return 0;
}

int main(void)
{
    hy_gl *probe = gl_or_skip(64, 64);
    hy_gl_free(probe);
    char fr[32];
    snprintf(fr, sizeof fr, "%ld:%ld", frames[0], frames[sizeof frames / sizeof *frames - 1] + 1);
    CHECK(run_cmd("animate", "preisach-plane", "-o", "out_pp1", "--size", "640x360", "--frames", fr, "-j", "1",
                  "--quiet", NULL) == 0, "animate preisach-plane -j 1");
    CHECK(run_cmd("animate", "preisach-plane", "-o", "out_pp2", "--size", "640x360", "--frames", fr, "-j", "2",
                  "--quiet", NULL) == 0, "animate preisach-plane -j 2");
    hy_anim_params prm = hy_anim_defaults();
    prm.width = W, prm.height = H, prm.fps = FPS, prm.duration = DUR;
    void *st = NULL;
    hy_error err;
    CHECK(!pplane_prepare(&st, &prm, &err), "prepare: %s", err.msg);
    if (!st)
        return 1;
    const hy_preisach *p = pplane_model(st);
    hy_input in;
    static const double tb[4] = {1, 2.2, 3.2, 5};
    CHECK(!hy_input_bimodal(&in, 0, 0.2, 1, 1.5, tb, HY_SHAPE_COSINE, &err), "Fig. 2's input");
    /* where the plane panel lies: the layout on a cairo canvas of the frame's size */
    cairo_surface_t *cs = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, W, H);
    cairo_t *cr = cairo_create(cs);
    double k = H / HY_ANIM_POINTS_HIGH;
    cairo_scale(cr, k, k);
    hy_cairo_canvas cc;
    hy_anim_frame f = {0, 240, 0, DUR, 0, W, H, k, NULL, {0}, hy_canvas_cairo(&cc, cr, NULL)};
    double rect[4], lim[4];
    CHECK(!pplane_panel(st, &f, rect, lim, &err), "panel: %s", err.msg);
    cairo_destroy(cr);
    cairo_surface_destroy(cs);
    double dA = (lim[1] - lim[0]) / rect[2] * (lim[3] - lim[2]) / rect[3];
    for (size_t q = 0; q < sizeof frames / sizeof *frames; q++) {
        long i = frames[q];
        double time = i / FPS, tin = pplane_input_time(st, time);
        hy_preisach_mem m, own;
        CHECK(!pplane_memory(st, time, &m, &err), "memory at frame %ld: %s", i, err.msg);
        CHECK(!own_memory(p, &in, tin, &own), "own memory at frame %ld", i);
        int same = m.n == own.n && fabs(m.y - own.y) <= 1e-12;
        for (size_t j = 1; same && j <= m.n; j++)
            same = m.s[j] == own.s[j];
        CHECK(same, "frame %ld: the animation's memory (%zu extrema, y %.15g) == the core's fed here (%zu, %.15g)", i,
              m.n, m.y, own.n, own.y);
        double sb[70], sa[70];
        size_t ns = pplane_staircase(&m, lim[0] - 1, lim[1] + 1, sb, sa, 70);
        int ok = ns == m.n + 1 && sb[ns - 1] == own.s[own.n] && sa[ns - 1] == own.s[own.n];
        for (size_t j = 1; ok && j < ns; j++) { /* step j goes to extremum j+1: at alpha = a max, beta = a min */
            int is_max = own.s[j] > own.s[j - 1];
            ok = is_max ? sa[j - 1] == own.s[j] : sb[j - 1] == own.s[j];
            ok = ok && (sa[j] == sa[j - 1] || sb[j] == sb[j - 1]); /* horizontal or vertical */
        }
        CHECK(ok, "frame %ld: %zu staircase vertices from the extrema, ending at (u, u) = %g", i, ns, own.s[own.n]);
        char a[256], b[256];
        snprintf(a, sizeof a, "out_pp1/preisach-plane/frame_%05ld.png", i);
        snprintf(b, sizeof b, "out_pp2/preisach-plane/frame_%05ld.png", i);
        CHECK(same_file(a, b), "frame %ld byte-identical with -j 1 and -j 2", i);
        cairo_surface_t *img = cairo_image_surface_create_from_png(a);
        if (cairo_surface_status(img)) {
            CHECK(0, "cannot read %s", a);
            continue;
        }
        const unsigned char *px = cairo_image_surface_get_data(img);
        int stride = cairo_image_surface_get_stride(img);
        /* relays beside each step: up below / left, down above / right */
        double kx = rect[2] / (lim[1] - lim[0]), ky = rect[3] / (lim[3] - lim[2]);
        int bad = 0, seen = 0;
        for (size_t j = 0; j + 1 < ns; j++) {
            double mb = 0.5 * (sb[j] + sb[j + 1]), ma = 0.5 * (sa[j] + sa[j + 1]);
            double x = rect[0] + (fmax(lim[0], fmin(lim[1], mb)) - lim[0]) * kx;
            double y = rect[1] + rect[3] - (fmax(lim[2], fmin(lim[3], ma)) - lim[2]) * ky;
            int horiz = sa[j] == sa[j + 1];
            double d = 5;
            int xu = (int)(horiz ? x : x - d), yu = (int)(horiz ? y + d : y);
            int xd = (int)(horiz ? x : x + d), yd = (int)(horiz ? y - d : y);
            /* only where both probes are relays of the triangle, inside the panel */
            double au = lim[3] - (yu + 0.5 - rect[1]) / ky, bu = lim[0] + (xu + 0.5 - rect[0]) / kx;
            double ad = lim[3] - (yd + 0.5 - rect[1]) / ky, bd = lim[0] + (xd + 0.5 - rect[0]) / kx;
            double len = horiz ? (fmin(lim[1], fmax(sb[j], sb[j + 1])) - fmax(lim[0], fmin(sb[j], sb[j + 1]))) * kx
                               : (fmin(lim[3], fmax(sa[j], sa[j + 1])) - fmax(lim[2], fmin(sa[j], sa[j + 1]))) * ky;
            if (au < bu + 0.02 || ad < bd + 0.02 || len < 14 || xu < rect[0] || xd > rect[0] + rect[2] || yd < rect[1] ||
                yu > rect[1] + rect[3])
                continue;
            seen++;
            bad += klass(px, stride, xu, yu) != 1 || klass(px, stride, xd, yd) != -1;
        }
        CHECK(!bad && seen >= 1, "frame %ld: up below/left and down above/right of each step (%d of %d wrong)", i,
              bad, seen);
        /* the output as the plane's integral */
        double Y = 0, mass = 0, amb = 0;
        long nup = 0, ndown = 0;
        for (int yy = (int)ceil(rect[1]); yy < (int)floor(rect[1] + rect[3]); yy++)
            for (int xx = (int)ceil(rect[0]); xx < (int)floor(rect[0] + rect[2]); xx++) {
                double al = lim[3] - (yy + 0.5 - rect[1]) / ky, be = lim[0] + (xx + 0.5 - rect[0]) / kx;
                if (al < be)
                    continue;
                double mu = dens(p, al, be) * dA;
                mass += mu;
                int c = klass(px, stride, xx, yy);
                nup += c > 0, ndown += c < 0;
                if (!c || near_step(sb, sa, ns, xx + 0.5, yy + 0.5, rect, lim, 1.5))
                    amb += mu;
                else
                    Y += c * mu;
            }
        double tol = fabs(p->ys - mass) + amb;
        CHECK(fabs(Y - m.y) <= tol && tol < 0.08,
              "frame %ld: sum of sign mu dA over %ld up and %ld down pixels = %.5f, the model's y = %.5f "
              "(|diff| %.2e <= bound %.2e: mass missed %.1e, unresolved %.1e)", i, nup, ndown, Y, m.y,
              fabs(Y - m.y), tol, fabs(p->ys - mass), amb);
        printf("frame %3ld: u %.3f, %zu extrema, y %+.5f, plane %+.5f (bound %.1e)\n", i, own.s[own.n], m.n, m.y,
               Y, tol);
        cairo_surface_destroy(img);
        hy_preisach_mem_free(&m);
        hy_preisach_mem_free(&own);
    }
    hy_input_free(&in);
    pplane_release(st);
    return hy_test_finish("preisach-plane");
}
