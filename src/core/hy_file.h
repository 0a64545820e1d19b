/* SPDX-License-Identifier: MIT */
/* hy_file.h: reading a whole input file safely: regular files only, a size cap,
 * never blocking on a FIFO or a device; and short printable excerpts of text.
 *
 *     char *buf, why[160]; size_t n;
 *     if (hy_file_read(path, 1 << 20, &buf, &n, NULL, why, sizeof why))
 *         printf("%s: %s\n", path, why);     // "is a directory", ...
 */
#ifndef HY_FILE_H
#define HY_FILE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Reads the regular file at path, at most max bytes, into *buf (malloc'ed,
 * NUL-terminated; len excludes the NUL).  If real is not NULL it receives the
 * malloc'ed real path of the file actually opened (symlinks resolved).
 * Returns 0, or an errno-like code (EISDIR, EINVAL not regular, EFBIG too
 * large, ...) with the reason, without the path, in why.  path, buf and len
 * must not be NULL (EINVAL, "... must not be NULL" in why, *buf and *len
 * cleared when given); real may be NULL; why may be NULL (no reason). */
int hy_file_read(const char *path, size_t max, char **buf, size_t *len, char **real, char *why,
                 size_t whysz);

/* At most 20 bytes of p[0..n) up to the first line end, each non-printable
 * byte as \xNN, "..." appended if cut: text safe to show in a message.
 * p and buf may be NULL as for hy_file_shown. */
const char *hy_file_excerpt(const char *p, size_t n, char *buf, size_t size);

/* At most max bytes of p[0..n), each non-printable byte (line ends too) as
 * \xNN, "..." appended if cut: a name or text safe to quote in a message.
 * Returns buf.  p NULL with n > 0 is shown as empty text; buf NULL (size 0
 * or not) writes nothing and returns NULL. */
const char *hy_file_shown(const char *p, size_t n, size_t max, char *buf, size_t size);

/* what hy_file_installed looks for: a data directory, a helper program */
enum { HY_INSTALLED_DATA = 0, HY_INSTALLED_LIBEXEC = 1 };

/* Where an installed hystviz keeps what it ships: *buf receives
 * PREFIX/share/hystviz/sub (sub "scenes", "boucwen") when that directory
 * exists, PREFIX taken first from the running program's location (an
 * install moved or made with DESTDIR still finds its files: bin/hystviz ->
 * share/hystviz), then the prefix it was configured with.  what ==
 * HY_INSTALLED_LIBEXEC looks for the program sub in the running program's
 * own directory (the build tree), then PREFIX/libexec.  A program run from
 * its build tree (the file hystviz-source-root at the top of the build
 * directory) never looks in an install: it finds only a helper next to
 * itself, as where nothing is installed.  Returns 0 if found, -1 if not (buf
 * then empty).  sub NULL: -1; buf may be NULL only when size is 0 (-1). */
int hy_file_installed(int what, const char *sub, char *buf, size_t size);

#ifdef __cplusplus
}
#endif

#endif
