/* SPDX-License-Identifier: MIT */
/* hy_gl_pick.h: which GL backend hy_gl_create uses (hy_gl_pick.c), below
 * the GL canvas: hy_gl.h includes this header and hy_gl.c asks the pick for
 * the backend; the pick calls nothing of hy_gl.c (no circle between files,
 * tools/include_graph.py).
 *
 *     if (hy_gl_select("egl", &err)) ...   // before any context is made
 *     printf("%s\n", hy_gl_backend_name(&err));
 */
#ifndef HY_GL_PICK_H
#define HY_GL_PICK_H

#include "hy_status.h"

/* The backends built, as "osmesa egl" ("" for none). */
const char *hy_gl_backends(void);
/* Picks the backend of the contexts created from now on: "osmesa" or "egl";
 * NULL goes back to $HYSTVIZ_GL, else OSMesa where built, else EGL.
 * HY_EINVAL for an unknown name, HY_EUNSUP for one not built (the choice is
 * then unchanged).  Call it before any thread creates contexts. */
int hy_gl_select(const char *name, hy_error *err);
/* The name of the backend hy_gl_create would use now; NULL (and err:
 * HY_EINVAL, HY_EUNSUP as hy_gl_select) when $HYSTVIZ_GL names a bad one. */
const char *hy_gl_backend_name(hy_error *err);
/* Checks, without making a context, that the backend hy_gl_create would use
 * can be used (a valid $HYSTVIZ_GL; EGL: a device, a valid
 * HYSTVIZ_EGL_DEVICE): HY_OK, HY_EINVAL (a bad choice) or HY_EUNSUP. */
int hy_gl_check(hy_error *err);

#endif
