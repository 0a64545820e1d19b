/* SPDX-License-Identifier: MIT */
/* hy_gl_backend.h (private to hy_gl*.c): what differs between the off-screen
 * GL backends (context creation, the framebuffer a frame lands in, reading
 * the frame back); shaders, drawing and the cairo overlay are shared
 * (hy_gl.c).  hy_gl_osmesa.c: OSMesa (Mesa < 25.1).  hy_gl_egl.c: EGL on the
 * device platform (EGL_EXT_platform_device; the software rasteriser or a GPU),
 * drawing into a framebuffer object.  hy_gl_pick.c holds the choice. */
#ifndef HY_GL_BACKEND_H
#define HY_GL_BACKEND_H

#include <stdio.h>

#include "hy_config.h"
#include "hy_gl_fn.h"
#include "hy_status.h"

typedef struct hy_gl_surface hy_gl_surface;   /* a context and its frame, defined per backend */

typedef struct hy_gl_backend {
    const char *name;                          /* "osmesa", "egl" */
    /* 1: every context's GL calls are serialised by hy_gl.c's process-wide
     * lock (OSMesa); 0: contexts draw concurrently, one per thread (EGL). */
    int serialise;
    /* 1: every surface draws with the same context (OSMesa): the GL objects
     * (programs, buffers) are made once for all, a surface is bound by
     * make_current, and each frame's GL work, from its first call to its
     * frame or read, runs under the lock as one piece. */
    int one_context;
    /* Creates a w x h OpenGL 3.3 core context with an RGBA8 colour target
     * and no depth (the 2-D strokes need none; a 3-D frame draws into a
     * multisampled framebuffer with its own, hy_gl.c msaa_target: the depth
     * buffer had cost its allocation and a clear at every frame), and makes
     * it current on this thread.  *fns: its entry
     * points; *fbo: the framebuffer that is the frame (0: the default one).
     * HY_EUNSUP when the library cannot, HY_EINVAL for a bad device choice. */
    int (*open)(hy_gl_surface **out, int w, int h, const hy_gl_fns **fns, unsigned *fbo, hy_error *err);
    /* Makes s current on this thread again (after another context was); 0 ok. */
    int (*make_current)(hy_gl_surface *s);
    /* After drawing (the frame's framebuffer bound): the frame as a cairo
     * RGB24 image (native 0x??RRGGBB words, top row first, stride 4 w),
     * owned by s and valid until the next drawing. */
    const unsigned char *(*frame)(hy_gl_surface *s);
    /* Destroys s; current: it is the context current on this thread. */
    void (*close)(hy_gl_surface *s, int current);
    /* Writes what this backend would use (devices, the chosen one) to f. */
    void (*info)(FILE *f);
    /* Cheap check, no context made, that open can find what it needs (EGL: a
     * device, a valid HYSTVIZ_EGL_DEVICE): HY_OK, HY_EUNSUP or HY_EINVAL. */
    int (*check)(hy_error *err);
} hy_gl_backend;

#if HY_HAVE_OSMESA
extern const hy_gl_backend hy_gl_osmesa_backend;
#endif
#if HY_HAVE_EGL
extern const hy_gl_backend hy_gl_egl_backend;
#endif

/* The backend that hy_gl_create uses now (hy_gl_select's choice, else
 * HYSTVIZ_GL, else OSMesa where built, else EGL); NULL and err if the choice is bad. */
const hy_gl_backend *hy_gl_backend_current(hy_error *err);
/* Where the current choice comes from: "--gl" (hy_gl_select), "HYSTVIZ_GL"
 * or "default". */
const char *hy_gl_backend_origin(void);

#endif
