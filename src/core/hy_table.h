/* SPDX-License-Identifier: MIT */
/* hy_table.h: measured samples from text (CSV or whitespace-separated columns),
 * an untrusted input read with caps; and the area of a measured loop.
 *
 * A pure function: text in, columns out, or one message "name:line:col: what"
 * (docs/SCENES.md, "[data NAME]").  The columns u, y (and t, and the column
 * that splits the rows into records) are chosen by a header name or a 1-based
 * index written as text, "H_A_per_m" or "2":
 *
 *     hy_table_spec sp = {{"H_A_per_m", "B_T", NULL, "loop"}, {1, 1, 1}};
 *     hy_table tb;
 *     if (hy_table_parse(text, len, "loops.csv", &sp, 1, &tb, &err)) puts(err.msg);
 *     for (size_t j = 0; j < tb.nrec; j++)   // record j: rows rec[j] .. rec[j+1]-1
 *         printf("%g\n", hy_table_area(tb.u + tb.rec[j], tb.y + tb.rec[j], tb.rec[j + 1] - tb.rec[j]));
 *     hy_table_free(&tb);
 */
#ifndef HY_TABLE_H
#define HY_TABLE_H

#include <stddef.h>

#include "hy_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Caps (docs/SCENES.md states them). */
#define HY_TABLE_MAX_BYTES ((size_t)64 << 20) /* a measured data file: 64 MiB          */
#define HY_TABLE_MAX_ROWS ((size_t)1 << 22)   /* data rows: 4,194,304                  */
#define HY_TABLE_MAX_COLS 64                  /* fields in a row                       */
#define HY_TABLE_MAX_LINE 4095                /* bytes in a line, its end excluded     */

/* The columns a table is read into. */
enum { HY_TABLE_U, HY_TABLE_Y, HY_TABLE_T, HY_TABLE_SPLIT, HY_TABLE_NCOL };

/* col[i]: a header name or a 1-based index ("3"); col[HY_TABLE_T] and
 * col[HY_TABLE_SPLIT] may be NULL (no t, one record).  scale[i] multiplies
 * column i (u, y, t) as read (a unit: 1e-3 for mT to T). */
typedef struct hy_table_spec {
    const char *col[HY_TABLE_NCOL];
    double scale[3];
} hy_table_spec;

/* n rows of u, y (and t, else NULL), scaled, in file order; nrec records,
 * record j the rows rec[j] .. rec[j+1]-1 (a run of rows with one value of
 * the split column; a single record without one) and line[j] the file line
 * of its first row. */
typedef struct hy_table {
    size_t n;
    double *u, *y, *t;
    size_t nrec;
    size_t *rec;
    size_t *line;
} hy_table;

/* Reads text[0..len) named name in messages.  Lines end in LF (CRLF taken);
 * blank lines and lines starting with '#' are skipped; a row's fields are
 * separated by commas when it holds one, else by blanks.  The header, if
 * any, is the first row that is not all numbers, or else the last comment
 * line before the first row when it has as many fields as the rows.  Every
 * field of every row must be a finite decimal number.  Errors (HY_EINVAL,
 * HY_ENOMEM) write "name:line:col: what"; quote 0 (a file a scene named)
 * keeps the file's bytes out of the message, 1 may name its header's
 * columns.  On error out holds nothing.
 * Pointers: text may be NULL only when len is 0; name may be NULL ("data
 * file"); spec, each spec->col[HY_TABLE_U] and spec->col[HY_TABLE_Y], and out
 * must not be NULL (HY_EINVAL, nothing read; out, when not NULL, zeroed). */
int hy_table_parse(const char *text, size_t len, const char *name, const hy_table_spec *spec, int quote,
                   hy_table *out, hy_error *err);

/* Frees t's columns and records and zeroes it (t may be NULL: nothing done;
 * a second call is harmless). */
void hy_table_free(hy_table *t);

/* The signed area of the closed polygon (u[i], y[i]), i < n, the last point
 * joined to the first: (1/2) sum (u_i y_{i+1} - u_{i+1} y_i) = ∮ u dy = -∮ y du,
 * positive for a counter-clockwise loop in the (u, y) plane (a B(H) loop).
 * Coordinates are taken relative to the first point (no cancellation in the
 * sum); 0 for n < 3.  u and y may be NULL only when n < 3 (else NaN). */
double hy_table_area(const double *u, const double *y, size_t n);

#ifdef __cplusplus
}
#endif

#endif
