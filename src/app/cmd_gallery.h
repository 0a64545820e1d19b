/* SPDX-License-Identifier: MIT */
/* cmd_gallery.h: `hystviz gallery`: every scene of a directory rendered, in
 * parallel, into one directory with a static index.html; scenes whose text
 * (with includes) did not change since the last run are skipped.
 *
 *     hystviz gallery [-j N] [--scenes DIR] [-o DIR] [--force] [--quiet]
 */
#ifndef HY_CMD_GALLERY_H
#define HY_CMD_GALLERY_H

/* Runs the gallery command (argv[0] = "gallery").  Returns 0 when every figure
 * is up to date, 1 when a scene failed (the others are still rendered and its
 * previous outputs kept), 2 on a usage error or when the index cannot be written. */
int hy_cmd_gallery(int argc, char **argv);

#endif
