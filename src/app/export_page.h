/* SPDX-License-Identifier: MIT */
/* export_page.h: the one-file page of `hystviz export` (issue 21 item 6):
 * every grid point's SVG, shared parts stored once, compressed, in one
 * self-contained HTML file that shows them with a slider per grid key.
 *
 *     exp_page pg;
 *     exp_page_init(&pg);
 *     for (i = 0; i < npoints; i++)           (in point order)
 *         ok ? exp_page_add(&pg, svg, len, &err) : exp_page_refused(&pg, message, &err);
 *     exp_page_write(&pg, meta_json, hy_out_file(&out), &err);
 *     exp_page_free(&pg);
 *
 * The page is the template src/app/export/page.html with the study's
 * description (meta_json, a JSON object: see cmd_export.c) and the payload
 * put in.  The payload is gzip (level 9), base64 in the page, of the JSON
 *
 *     {"format":"hystviz-export 1","chunks":[C0,C1,...],"points":[P0,P1,...]}
 *
 * Pi is an array of chunk indices (the SVG of point i is the concatenation
 * of those chunks, byte for byte) or a string (the scene refused the point:
 * the message).  Each SVG is cut into lines ('\n' kept); every distinct line
 * is one chunk, stored once.  A chunk is the line as a string, or, for a path
 * line whose data cairo wrote as k/256 numbers, a coded path
 *
 *     {"h":"<path ... d=\"","c":"MLLC...","x":[...],"s":1,"e":"\"/>\n"}
 *
 * h and e: the text before and after the path data; c: the commands (M, L:
 * 2 numbers, C: 6, Z: none), written "M x y L x y ..." with single spaces
 * (s: 1 if a space ends the data); x: for the j-th number k_j/256 of the data,
 * the second difference of k along its parity (x_j = k_j - 2 k_{j-2} +
 * k_{j-4}, k before the start 0), i.e. along the x and y coordinates.  A
 * number prints as cairo prints it: k/256 to 6 decimals, ties to even, trailing
 * zeros and a bare '.' dropped, '-' before negatives.  A line is coded only if
 * decoding gives it back exactly (checked here); else it is a string chunk.
 * Sharing lines takes the fonts, axes and legend out of all but one SVG; the
 * path coding makes the curves, which differ everywhere, ~10x smaller.
 */
#ifndef HY_EXPORT_PAGE_H
#define HY_EXPORT_PAGE_H

#include <stddef.h>
#include <stdio.h>

#include "hy_out.h"
#include "hy_status.h"

typedef struct exp_page exp_page;

/* An empty page; NULL when out of memory. */
exp_page *exp_page_new(void);

/* Appends the next point: its SVG (len bytes, UTF-8).  HY_ENOMEM, or
 * HY_EINVAL if svg is not valid UTF-8 (a page could not give it back). */
int exp_page_add(exp_page *pg, const char *svg, size_t len, hy_error *err);

/* Appends the next point as refused by the scene, with its message. */
int exp_page_refused(exp_page *pg, const char *message, hy_error *err);

/* Points added so far, and how many of them were refused. */
size_t exp_page_points(const exp_page *pg, size_t *nrefused);

/* Writes the page: the template with meta_json (a JSON object) and the
 * compressed payload.  HY_EIO/HY_ENOMEM on failure (f's own write errors
 * show when the caller closes it). */
int exp_page_write(exp_page *pg, const char *meta_json, FILE *f, hy_error *err);

void exp_page_free(exp_page *pg);

/* Writes s as a JSON string (quoted) safe inside an HTML <script>: '"',
 * '\\', controls, '<', '>' and '&' escaped; UTF-8 passed through. */
void exp_json_str(FILE *f, const char *s, size_t len);

/* gzip of n bytes at level 9 into *out (malloc'd, *outlen bytes). */
int exp_gzip(const void *data, size_t n, unsigned char **out, size_t *outlen, hy_error *err);

/* Writes n bytes as base64, in lines of 76 characters. */
void exp_base64(FILE *f, const unsigned char *s, size_t n);

/* Ends an export's output: aborts it when rc (what writing it returned) is
 * not 0, else commits it.  Returns rc, or 1 when the commit fails (its
 * message printed as "hystviz export: ..."). */
int exp_out_finish(hy_out *out, int rc);

#endif
