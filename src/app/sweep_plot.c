/* SPDX-License-Identifier: MIT */
/* sweep_plot.c: the summary figure of `hystviz sweep --plot COLUMN`, drawn
 * from the streamed table (so the merge of shards draws the same bytes). */
#include "sweep_plot.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hy_plot.h"

/* Splits one CSV line in place into at most max fields (quotes removed,
 * doubled quotes kept once); returns the number of fields. */
static size_t csv_split(char *line, char **f, size_t max)
{
    size_t n = 0;
    char *r = line, *w = line;
    line[strcspn(line, "\r\n")] = '\0';
    while (n < max) {
        f[n++] = w;
        if (*r == '"') {
            for (r++; *r; r++) {
                if (*r == '"' && r[1] == '"')
                    *w++ = *r++;
                else if (*r == '"') {
                    r++;
                    break;
                } else
                    *w++ = *r;
            }
        }
        while (*r && *r != ',')
            *w++ = *r++;
        int more = *r == ',';
        *w++ = '\0';
        if (!more)
            break;
        r++;
    }
    return n;
}

static double number(const char *s)
{
    char *end;
    double v = strtod(s, &end);
    return *s && !*end && isfinite(v) ? v : NAN;
}

typedef struct table {
    double *x, *y;
    size_t *group, n;          /* rows, each in a curve (second key's value) */
    char **groups;             /* the second key's value per curve */
    size_t ngroups;
    char xkey[256], gkey[256];
} table;

static void table_free(table *t)
{
    free(t->x);
    free(t->y);
    free(t->group);
    for (size_t g = 0; g < t->ngroups; g++)
        free(t->groups[g]);
    free(t->groups);
}

/* The row's curve: the index of its second-key value (added if new). */
static int group_of(table *t, const char *v, size_t *g)
{
    for (*g = 0; *g < t->ngroups; (*g)++)
        if (!strcmp(t->groups[*g], v))
            return 0;
    char **ng = realloc(t->groups, (t->ngroups + 1) * sizeof *ng);
    if (!ng)
        return -1;
    t->groups = ng;
    if (!(ng[t->ngroups] = strdup(v)))
        return -1;
    *g = t->ngroups++;
    return 0;
}

static int read_table(const char *path, const char *column, table *t, hy_error *err)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return hy_error_set(err, HY_EIO, "--plot: cannot read '%s'", path);
    char *line = NULL, *fl[512];
    size_t cap = 0, nf = 0, ycol = 0, nkeys = 0, rcap = 0;
    int rc = HY_OK;
    if (getline(&line, &cap, f) < 0 || (nf = csv_split(line, fl, 512)) < 4)
        rc = hy_error_set(err, HY_EINVAL, "--plot: '%s' is not a sweep table", path);
    for (size_t c = 3; !rc && c < nf && strcmp(fl[c], "compute_s") && strcmp(fl[c], "ysteady_min"); c++)
        nkeys++;
    for (size_t c = 0; !rc && c < nf && !ycol; c++)
        if (!strcmp(fl[c], column) && c >= 3 + nkeys)
            ycol = c;
    if (!rc && (!nkeys || !ycol))
        rc = hy_error_set(err, HY_EINVAL, "--plot %s: %s", column, !nkeys ? "the sweep has no grid key to plot against"
                          : "no such result column in sweep.csv (see its header: ysteady_min, minor1_area, energy, ...)");
    if (!rc) {
        snprintf(t->xkey, sizeof t->xkey, "%s", fl[3]);
        snprintf(t->gkey, sizeof t->gkey, "%s", nkeys > 1 ? fl[4] : "");
    }
    while (!rc && getline(&line, &cap, f) > 0) {
        if (csv_split(line, fl, 512) <= ycol)
            continue;
        if (t->n == rcap) {
            rcap = rcap ? 2 * rcap : 256;
            double *nx = realloc(t->x, rcap * sizeof *nx), *ny = nx ? realloc(t->y, rcap * sizeof *ny) : NULL;
            size_t *ngr = ny ? realloc(t->group, rcap * sizeof *ngr) : NULL;
            if (nx)
                t->x = nx;
            if (ny)
                t->y = ny;
            if (!ngr) {
                rc = hy_error_set(err, HY_ENOMEM, "out of memory");
                break;
            }
            t->group = ngr;
        }
        t->x[t->n] = number(fl[3]);
        t->y[t->n] = number(fl[ycol]);
        if (isnan(t->x[t->n]))
            rc = hy_error_set(err, HY_EINVAL, "--plot: the first grid key %s has a value that is not a number ('%s')",
                              t->xkey, fl[3]);
        else if (group_of(t, nkeys > 1 ? fl[4] : "", &t->group[t->n]))
            rc = hy_error_set(err, HY_ENOMEM, "out of memory");
        t->n++;
    }
    free(line);
    fclose(f);
    return rc;
}

/* text with the markup's special characters escaped (\_ \^ \{ \} \\ \$), and
 * set upright: a column or key name is not maths. */
static void plain(const char *text, char *out, size_t size)
{
    size_t o = 0;
    const char *pre = "\\text{";
    for (const char *c = pre; *c && o + 1 < size; c++)
        out[o++] = *c;
    for (; *text && o + 3 < size; text++) {
        if (strchr("_^{}\\$", *text))
            out[o++] = '\\';
        out[o++] = *text;
    }
    out[o++] = '}';
    out[o] = '\0';
}

/* The curves' points in table order (row-major: x increases along a curve). */
static int draw(const char *dir, const char *column, const table *t, hy_error *err)
{
    size_t ng = t->ngroups ? t->ngroups : 1;
    hy_series *se = calloc(ng, sizeof *se);
    double *xs = malloc((t->n ? t->n : 1) * sizeof *xs), *ys = malloc((t->n ? t->n : 1) * sizeof *ys);
    char (*labels)[300] = calloc(ng, sizeof *labels);
    if (!se || !xs || !ys || !labels) {
        free(se), free(xs), free(ys), free(labels);
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    }
    const char *gshort = strrchr(t->gkey, '.') ? strrchr(t->gkey, '.') + 1 : t->gkey;
    const char *xshort = strrchr(t->xkey, '.') ? strrchr(t->xkey, '.') + 1 : t->xkey;
    size_t off = 0;
    double lo = INFINITY, hi = 0;
    for (size_t g = 0; g < ng; g++) {
        se[g].x = xs + off;
        se[g].y = ys + off;
        for (size_t i = 0; i < t->n; i++)
            if (t->group[i] == g) {
                xs[off] = t->x[i];
                ys[off++] = t->y[i];
                lo = fmin(lo, t->x[i]);
                hi = fmax(hi, t->x[i]);
            }
        se[g].n = (size_t)(xs + off - se[g].x);
        se[g].colour.palette = (int)(g % HY_PALETTE_SIZE);
        se[g].width = 1.2;
        se[g].marker = HY_MARKER_CIRCLE;
        se[g].marker_size = 3;
        se[g].marker_filled = 1;
        if (t->gkey[0] && ng <= 8) {
            char raw[300];
            snprintf(raw, sizeof raw, "%s = %s", gshort, t->groups[g]);
            plain(raw, labels[g], sizeof labels[g]);
            se[g].label = labels[g];
        }
    }
    char raw[600], title[1300], xlabel[600], ylabel[600];
    snprintf(raw, sizeof raw, "%s%s%s", column, t->gkey[0] ? ", one curve per value of " : "", gshort);
    plain(raw, title, sizeof title);
    plain(xshort, xlabel, sizeof xlabel);
    plain(column, ylabel, sizeof ylabel);
    hy_axes ax = {.series = se, .nseries = ng, .xlabel = xlabel, .ylabel = ylabel, .title = title,
                  .legend = t->gkey[0] && ng <= 8 ? HY_LEGEND_BEST : HY_LEGEND_NONE, .grid = 1};
    ax.x.log = lo > 0 && hi >= 100 * lo;
    hy_figure fig = {.width = hy_cm(12), .height = hy_cm(8), .dpi = 150, .axes = &ax};
    int rc = HY_OK;
    const char *ext[] = {"svg", "png"};
    int fmt[] = {HY_FORMAT_SVG, HY_FORMAT_PNG};
    for (int k = 0; k < 2 && !rc; k++) {
        char path[4400];
        snprintf(path, sizeof path, "%s/sweep_", dir);
        size_t len = strlen(path);
        for (const char *c = column; *c && len + 8 < sizeof path; c++) /* a file-name-safe column */
            path[len++] = (*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') ||
                          *c == '.' || *c == '-' ? *c : '_';
        snprintf(path + len, sizeof path - len, ".%s", ext[k]);
        rc = hy_figure_write(&fig, path, fmt[k], err);
    }
    free(se), free(xs), free(ys), free(labels);
    return rc;
}

int hy_sweep_plot(const char *dir, const char *column, hy_error *err)
{
    char path[4400];
    snprintf(path, sizeof path, "%s/sweep.csv", dir);
    table t;
    memset(&t, 0, sizeof t);
    int rc = read_table(path, column, &t, err);
    if (!rc)
        rc = draw(dir, column, &t, err);
    table_free(&t);
    return rc;
}
