/* SPDX-License-Identifier: MIT */
/* hy_gl_osmesa.c: the OSMesa backend (hy_gl_backend.h).  OSMesa renders into
 * a buffer of ours laid out as a cairo RGB24 image, so reading a frame back
 * is a glFinish.  Every surface of the process draws with one OSMesa context
 * (one_context): a surface is its own frame buffer, bound by making the
 * context current with it.  A second context cost as much as the first
 * (about 0.1 s of CPU at 720p: creation, the first bind's buffers, llvmpipe's
 * compile of every shader variant again) and gained nothing, as hy_gl.c
 * serialises OSMesa's GL calls anyway. */
#include "hy_gl_backend.h"

#include <GL/osmesa.h>
#include <pthread.h>
#include <stdlib.h>

#include "hy_frame.h"

struct hy_gl_surface {
    unsigned char *fb;                /* the colour buffer OSMesa draws into */
    int w, h;
};

/* The process's context, made by the first open (under hy_gl.c's lock) and
 * kept to the end of the process: a thread that had it current keeps a
 * pointer to it (Mesa's current context), and OSMesaMakeCurrent on that
 * thread flushes it first, so destroying it from another thread left a
 * dangling context behind (bench_gl crashed at its next run). */
static OSMesaContext shared_ctx;

static hy_gl_fns fns;                 /* the same for every context: filled once */
static const char *fns_missing;
static pthread_once_t fns_once = PTHREAD_ONCE_INIT;

static hy_gl_proc lookup(const char *name) { return (hy_gl_proc)OSMesaGetProcAddress(name); }
static void load_fns(void) { fns_missing = hy_gl_fns_load(&fns, lookup); }

static void osm_close(hy_gl_surface *s, int current)
{
    (void)current;
    if (!s)
        return;
    free(s->fb);
    free(s);
}

/* Mesa 22.3 keeps each context's framebuffer in a list that nothing frees
 * (tests/gl/lsan.supp).  Under AddressSanitizer OSMesa's allocations here are
 * left out of the leak check (LeakSanitizer's own interface): matching them
 * against the suppression at exit symbolizes libasan's allocator frame, about
 * 0.2 s of CPU in every process that drew a frame. */
#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#define MESA_ALLOC_BEGIN() __lsan_disable()
#define MESA_ALLOC_END() __lsan_enable()
#else
#define MESA_ALLOC_BEGIN() ((void)0)
#define MESA_ALLOC_END() ((void)0)
#endif

static int osm_open(hy_gl_surface **out, int w, int h, const hy_gl_fns **f, unsigned *fbo, hy_error *err)
{
    hy_gl_surface *s = calloc(1, sizeof *s);
    if (!s || !(s->fb = malloc((size_t)w * (size_t)h * 4))) {
        free(s);
        return hy_error_set(err, HY_ENOMEM, "out of memory for a %d x %d GL frame", w, h);
    }
    s->w = w, s->h = h;
    /* Bytes B, G, R, A (little-endian hosts) or A, R, G, B (big-endian), top
     * row first: OSMesa's buffer is then a cairo RGB24 image, and the overlay
     * is drawn straight onto the frame (hy_gl_finish) */
    const int attribs[] = {OSMESA_FORMAT, hy_little_endian() ? OSMESA_BGRA : OSMESA_ARGB, OSMESA_DEPTH_BITS, 0,
                           OSMESA_STENCIL_BITS, 0, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, 3, OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
    MESA_ALLOC_BEGIN();
    if (!shared_ctx)
        shared_ctx = OSMesaCreateContextAttribs(attribs, NULL);
    int current = shared_ctx && OSMesaMakeCurrent(shared_ctx, s->fb, GL_UNSIGNED_BYTE, w, h);
    MESA_ALLOC_END();
    if (!shared_ctx) {
        free(s->fb);
        free(s);
        return hy_error_set(err, HY_EUNSUP, "OSMesa could not create an OpenGL 3.3 core-profile context");
    }
    if (!current) {
        osm_close(s, 0);
        return hy_error_set(err, HY_EUNSUP, "OSMesa could not make a %d x %d context current", w, h);
    }
    OSMesaPixelStore(OSMESA_Y_UP, 0);
    pthread_once(&fns_once, load_fns);
    if (fns_missing) {
        osm_close(s, 1);
        return hy_error_set(err, HY_EUNSUP, "OSMesa has no entry point %s", fns_missing);
    }
    *f = &fns, *fbo = 0, *out = s;
    return HY_OK;
}

static int osm_make_current(hy_gl_surface *s)
{
    MESA_ALLOC_BEGIN();
    int current = OSMesaMakeCurrent(shared_ctx, s->fb, GL_UNSIGNED_BYTE, s->w, s->h);
    MESA_ALLOC_END();
    return current ? 0 : -1;
}

static const unsigned char *osm_frame(hy_gl_surface *s)
{
    fns.Finish();                     /* OSMesa copies the frame into s->fb */
    return s->fb;
}

static void osm_info(FILE *f) { fputs("osmesa: Mesa's off-screen library (libOSMesa), software rasteriser\n", f); }

static int osm_check(hy_error *err)
{
    (void)err;                        /* linked: the library is there */
    return HY_OK;
}

const hy_gl_backend hy_gl_osmesa_backend = {"osmesa",  1,        1,        osm_open, osm_make_current,
                                            osm_frame, osm_close, osm_info, osm_check};
