/* SPDX-License-Identifier: MIT */
/* hy_grid.h: the parameter grid of `hystviz sweep` and the shard partition
 * shared by `sweep` and `gallery` (issue 13).
 *
 * A grid is the Cartesian product of axes, one per `--grid KEY=SPEC`:
 *   list     1,2,5           the values as written
 *   linear   0.1:0.5:5       5 values from 0.1 to 0.5, equally spaced
 *   log      1:1e3:log7      7 values from 1 to 1e3, equally spaced in log10
 * Points are numbered 0..P-1 in row-major order: the first --grid is the
 * outermost (slowest) axis, the last varies fastest, as nested loops in the
 * order the options are written.  A computed value is written as the shortest
 * decimal that reads back to the same double (%.15g, %.16g or %.17g), and that
 * text is what the point passes to the scene, so `render --set KEY=TEXT`
 * reproduces the point exactly.
 *
 *     hy_grid g;
 *     if (hy_grid_add(&g, "model.sigma0=1:10:log10", &err)) ...
 *     for (size_t i = 0; i < hy_grid_points(&g); i++)
 *         for (size_t a = 0; a < g.naxes; a++)
 *             printf("%s=%s\n", g.axes[a].key, hy_grid_value(&g, i, a));
 *     hy_grid_free(&g);
 *
 * Shards: item i (a point, a gallery scene) belongs to shard i mod N, so every
 * shard holds floor or ceil of items/N items, items of every part of the grid,
 * the same on every machine.
 */
#ifndef HY_GRID_H
#define HY_GRID_H

#include <stddef.h>

#include "hy_status.h"

/* The most points a sweep may have, and the most values of one axis. */
#define HY_GRID_MAX_POINTS 100000000UL
#define HY_GRID_MAX_VALUES 1000000UL
/* The most shards a study may be split into. */
#define HY_SHARD_MAX 100000L

typedef struct hy_grid_axis {
    char *key;       /* "model.sigma0"                                  */
    char *spec;      /* the SPEC as given                                */
    char **values;   /* nvalues texts, each a valid --set value          */
    size_t nvalues;
} hy_grid_axis;

typedef struct hy_grid {
    hy_grid_axis *axes;
    size_t naxes;
    size_t npoints;  /* product of the axes' value counts (1 with none)  */
} hy_grid;

/* Empties g (no axes, one point). */
void hy_grid_init(hy_grid *g);

/* Adds the axis "KEY=SPEC" (see above).  HY_EINVAL with a message naming
 * the spec for a malformed spec, a count outside 1..HY_GRID_MAX_VALUES, a log
 * range through zero or a negative bound, a key given twice, or a product over
 * HY_GRID_MAX_POINTS; g is unchanged on error. */
int hy_grid_add(hy_grid *g, const char *arg, hy_error *err);

/* The number of points. */
size_t hy_grid_points(const hy_grid *g);

/* The index along axis a of point i. */
size_t hy_grid_coord(const hy_grid *g, size_t i, size_t a);

/* The value text of axis a at point i (owned by g). */
const char *hy_grid_value(const hy_grid *g, size_t i, size_t a);

void hy_grid_free(hy_grid *g);

/* The shortest of %.15g/%.16g/%.17g that reads back to v, into buf. */
void hy_grid_format(double v, char *buf, size_t size);

/* Parses "K/N" (0 <= K < N <= HY_SHARD_MAX); HY_EINVAL with a message. */
int hy_shard_parse(const char *s, long *k, long *n, hy_error *err);

/* How many of n items shard k of nshards holds (items k, k + nshards, ...). */
size_t hy_shard_count(size_t n, long k, long nshards);

/* The shard files of one split in dir, named PREFIX K-of-N SUFFIX
 * ("sweep.shard-" "3-of-8" ".csv"): *nshards gets N and *present (malloc'd,
 * N bytes) which K are there.  HY_EINVAL with a message naming dir when there
 * are none or shards of two splits. */
int hy_shard_find(const char *dir, const char *prefix, const char *suffix, long *nshards, unsigned char **present,
                  hy_error *err);

/* How many of the n shards are not present; buf gets " K/N, K/N" for the
 * first 20 of them (", ..." if more). */
long hy_shard_missing(long n, const unsigned char *present, char *buf, size_t size);

#endif
