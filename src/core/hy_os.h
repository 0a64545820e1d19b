/* SPDX-License-Identifier: MIT */
/* hy_os.h: the few operating-system services every floor shares, each written
 * once: a monotonic clock in seconds, joining or splitting a path, and a
 * whole file read with its failure as an hy_error.  Not an installed header
 * (nothing here is libhystviz's API).
 *
 *     double t0 = hy_now();
 *     char *p = hy_path_join(dir, "index.html");   // dir/index.html, or NULL
 *     ... free(p); printf("%.3f s\n", hy_now() - t0);
 */
#ifndef HY_OS_H
#define HY_OS_H

#include <stddef.h>

#include "hy_status.h"

/* Seconds on CLOCK_MONOTONIC: only differences mean anything. */
double hy_now(void);

/* dir "/" file, malloc'ed (the caller frees it); NULL when out of memory. */
char *hy_path_join(const char *dir, const char *file);

/* The directory part of path as written, malloc'ed: "." when path has no
 * slash, "/" for a file at the root.  NULL when out of memory. */
char *hy_path_dir(const char *path);

/* Room for element n of the array p of *cap elements of size bytes: p
 * itself while n < *cap, else p reallocated to twice *cap elements (first
 * when *cap is 0) and *cap updated.  NULL when out of memory (p is then
 * unchanged and still the caller's). */
void *hy_grow(void *p, size_t n, size_t *cap, size_t size, size_t first);

/* The status of a file that hy_file_read refused with the error number e:
 * HY_EIO when it is missing, unreadable or the read failed, else HY_EINVAL
 * (not a regular file, too large, ...). */
int hy_file_status(int e);

/* hy_file_read(path, max, buf, len, NULL, ...) with its failure in err as
 * "PATH: WHAT: why" (what: "cannot open input file", ...), with
 * hy_file_status's code.  Returns HY_OK or that code. */
int hy_file_load(const char *path, size_t max, char **buf, size_t *len, const char *what, hy_error *err);

#endif
