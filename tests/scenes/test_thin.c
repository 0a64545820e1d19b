/* SPDX-License-Identifier: MIT */
/* test_thin.c: drawn-only series (scene_run.c, hy_scene_run.figure_only)
 * against the same scene computed with every point (as `hystviz data`):
 *  - a series below HY_THIN_MIN, or one not thinned, is the same, bit for bit;
 *  - a series drawn only as its mark holds no points, its mark is the full
 *    run's and its error is measured at that point (<= 1e-14 g(0));
 *  - a thinned loop's points are points of the full grid, in order, with the
 *    same gaps; the full grid's x and y extremes are among them; and every
 *    full-grid point lies within HY_THIN_TOL of the narrowest y window
 *    (y's range, zoom_y) of the chord between the kept points around it,
 *    measured vertically: the bound the thinning claims (docs/ARCHITECTURE.md).
 * The tolerance check can fail: a kept point moved off the curve by 1e-3 of
 * the window is caught. */
#include <gsl/gsl_errno.h>
#include <stdlib.h>
#include <string.h>

#include "../core/tutil.h"
#include "scene_run.h"

static const char *SRC;

static int load(const char *scene, char **sets, size_t nsets, int figure_only, hy_scene_run *r)
{
    char path[1024];
    hy_error err;
    snprintf(path, sizeof path, "%s/scenes/%s.scene", SRC, scene);
    int rc = hy_scene_run_load(r, path, sets, nsets, &err);
    if (!rc) {
        r->figure_only = figure_only;
        if ((rc = hy_scene_run_compute(r, NULL, &err)))
            hy_scene_run_free(r);
    }
    CHECK(rc == 0, "%s: %s", scene, err.msg);
    return rc;
}

/* The narrowest y window: the full loops' y range, zoom_y where set. */
static double window(const hy_scene_run *f)
{
    double lo = INFINITY, hi = -INFINITY, v[2];
    for (size_t i = 0; i < f->nseries; i++)
        for (size_t j = 0; j < f->series[i].n; j++)
            if (!isnan(f->series[i].y[j]))
                lo = fmin(lo, f->series[i].y[j]), hi = fmax(hi, f->series[i].y[j]);
    double w = hi - lo;
    int is_auto = 1;
    if (hy_scene_get_pair(f->scene, "figure", NULL, "zoom_y", v, &is_auto) == HY_SCENE_SET && !is_auto)
        w = fmin(w, v[1] - v[0]);
    return w;
}

/* Largest vertical distance of a full-grid point from the thinned polyline,
 * or INFINITY when a thinned point is not the next full-grid point in order
 * or the extremes differ. */
static double deviation(const hy_run_series *F, const hy_run_series *T)
{
    double dev = 0, e[2][4] = {{INFINITY, -INFINITY, INFINITY, -INFINITY}, {INFINITY, -INFINITY, INFINITY, -INFINITY}};
    size_t j = 0, prev = 0;
    for (size_t k = 0; k < T->n; k++) {
        while (j < F->n && !(F->x[j] == T->x[k] && F->y[j] == T->y[k]) && !(isnan(F->x[j]) && isnan(T->x[k]))) {
            if (isnan(F->x[j]) || k == 0 || isnan(T->x[k - 1]))
                return INFINITY; /* a gap or a first point not kept */
            double xa = F->x[prev], ya = F->y[prev], xb = T->x[k], yb = T->y[k];
            double yc = xb != xa ? ya + (yb - ya) * (F->x[j] - xa) / (xb - xa) : ya;
            dev = fmax(dev, fabs(F->y[j] - yc));
            j++;
        }
        if (j == F->n)
            return INFINITY;
        prev = j++;
    }
    for (size_t i = 0; i < F->n + T->n; i++) { /* extremes of both */
        const hy_run_series *S = i < F->n ? F : T;
        size_t m = i < F->n ? i : i - F->n;
        double (*x)[4] = &e[S == T];
        if (!isnan(S->x[m]))
            (*x)[0] = fmin((*x)[0], S->x[m]), (*x)[1] = fmax((*x)[1], S->x[m]), (*x)[2] = fmin((*x)[2], S->y[m]),
            (*x)[3] = fmax((*x)[3], S->y[m]);
    }
    return j == F->n && !memcmp(e[0], e[1], sizeof e[0]) ? dev : INFINITY;
}

static void compare(const char *scene, char **sets, size_t nsets, int want_thin)
{
    hy_scene_run F, T;
    if (load(scene, sets, nsets, 0, &F))
        return;
    if (load(scene, sets, nsets, 1, &T)) {
        hy_scene_run_free(&F);
        return;
    }
    double tol = HY_THIN_TOL * window(&F), g0 = hy_model_g0(&F.model);
    int thinned = 0;
    for (size_t i = 0; i < F.nseries; i++) {
        const hy_run_series *f = &F.series[i], *t = &T.series[i];
        CHECK(f->grid_n == 0, "%s/%s: thinned without figure_only", scene, f->name);
        if (!t->grid_n) {
            CHECK(t->n == f->n && !memcmp(t->x, f->x, f->n * sizeof *f->x) && !memcmp(t->y, f->y, f->n * sizeof *f->y),
                  "%s/%s: not thinned, yet not the full series", scene, f->name);
            continue;
        }
        thinned++;
        CHECK(t->grid_n == f->n, "%s/%s: grid of %zu points, the full series has %zu", scene, f->name, t->grid_n, f->n);
        if (!t->n) {
            CHECK(t->has_mark && f->has_mark && t->mark_x == f->mark_x && t->mark_y == f->mark_y,
                  "%s/%s: mark (%.17g, %.17g), full run's (%.17g, %.17g)", scene, f->name, t->mark_x, t->mark_y,
                  f->mark_x, f->mark_y);
            CHECK(isfinite(t->err) && t->err <= 1e-14 * g0 && t->err_ref && strstr(t->err_ref, "all 1 points"),
                  "%s/%s: mark's error %.3g (%s)", scene, f->name, t->err, t->err_ref ? t->err_ref : "NULL");
            continue;
        }
        double dev = deviation(f, t);
        printf("%-34s %-6s %8zu of %8zu points, deviation %.3g (bound %.3g)\n", scene, f->name, t->n, f->n, dev, tol);
        CHECK(t->n < f->n / 2, "%s/%s: %zu of %zu points kept", scene, f->name, t->n, f->n);
        CHECK(dev <= tol * (1 + 1e-6) + 1e-15 * g0, "%s/%s: a full-grid point %.3g from the drawn chord (bound %.3g)",
              scene, f->name, dev, tol);
        CHECK(t->err == f->err, "%s/%s: error %.3g, full run's %.3g", scene, f->name, t->err, f->err);
        /* the check can fail: a kept point inside the loop moved by 1e-3 of the window */
        size_t m = t->n / 3;
        while (m + 1 < t->n && (isnan(t->y[m]) || isnan(t->y[m + 1])))
            m++;
        double keep = t->y[m];
        t->y[m] += 1e-3 * window(&F);
        CHECK(!(deviation(f, t) <= tol), "%s/%s: a moved point was not noticed", scene, f->name);
        t->y[m] = keep;
    }
    CHECK(!want_thin || thinned, "%s: nothing thinned", scene);
    CHECK(want_thin || !thinned, "%s: thinned below HY_THIN_MIN", scene);
    hy_scene_run_free(&F);
    hy_scene_run_free(&T);
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: test_thin SOURCE_DIR\n");
        return 2;
    }
    SRC = argv[1];
    gsl_set_error_handler_off();
    char *many[] = {"compute.points=200000"};
    compare("fig15_minor_loop_ex4", many, 1, 1);
    compare("fig16_minor_loop_ex4_sigma1", many, 1, 1); /* its inset's zoom_y */
    compare("multimodal_three_minor_loops", many, 1, 1);
    compare("fig15_minor_loop_ex4", NULL, 0, 0);         /* the gallery's size: untouched */
    return tu_finish("thin");
}
