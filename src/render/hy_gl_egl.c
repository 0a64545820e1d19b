/* SPDX-License-Identifier: MIT */
/* hy_gl_egl.c: the EGL backend (hy_gl_backend.h).  One EGL display on the
 * device platform (EGL_EXT_platform_device) for the process, initialised by
 * the first context; each context is surfaceless
 * (EGL_KHR_surfaceless_context) and draws into its own framebuffer object
 * (RGBA8 colour, 24-bit depth renderbuffers), read back with glReadPixels.
 *
 * The device is chosen once, by the first context.
 *
 * Devices: eglQueryDevicesEXT lists GPUs (EGL_EXT_device_drm, NVIDIA's
 * EGL_NV_device_cuda) and Mesa's software rasteriser (EGL_MESA_device_software,
 * llvmpipe).  The default is the first device that is not the software one,
 * else the software one; HYSTVIZ_EGL_DEVICE=N picks device N. */
#include "hy_gl_backend.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <errno.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

#define MAX_DEVICES 32

struct hy_gl_surface {
    EGLContext ctx;
    GLuint fbo, rb[1];
    int w, h;
    unsigned char *fb, *row;          /* the frame read back (top row first); one row for the flip */
};

/* The display, made by the first context and kept for the process (EGL
 * holds it in its own list, so it stays reachable, not leaked): Mesa 22.3's
 * eglTerminate leaves objects of the driver that it then unloads, which a
 * leak checker could only report as from "<unknown module>". */
static pthread_mutex_t mu = PTHREAD_MUTEX_INITIALIZER;   /* guards dpy and config */
static EGLDisplay dpy = EGL_NO_DISPLAY;
static EGLConfig config;              /* EGL_NO_CONFIG_KHR where the display allows it */

static hy_gl_fns fns;
static const char *fns_missing;
static pthread_once_t fns_once = PTHREAD_ONCE_INIT;

static hy_gl_proc lookup(const char *name) { return (hy_gl_proc)eglGetProcAddress(name); }
static void load_fns(void) { fns_missing = hy_gl_fns_load(&fns, lookup); }

static int has_ext(const char *list, const char *name)
{
    size_t n = strlen(name);
    for (const char *p = list; p && (p = strstr(p, name)); p += n)
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0'))
            return 1;
    return 0;
}

typedef struct devices {
    PFNEGLQUERYDEVICESTRINGEXTPROC string;
    EGLDeviceEXT dev[MAX_DEVICES];
    EGLint n;
} devices;

/* The devices EGL lists; HY_EUNSUP when it has no device platform or none. */
static int list_devices(devices *d, hy_error *err)
{
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!client || !has_ext(client, "EGL_EXT_platform_device") ||
        !(has_ext(client, "EGL_EXT_device_enumeration") || has_ext(client, "EGL_EXT_device_base")))
        return hy_error_set(err, HY_EUNSUP, "EGL found no device: no EGL driver offers the device platform "
                            "(EGL_EXT_platform_device; install libegl-mesa0 for Mesa's software rasteriser, "
                            "or the GPU's EGL driver)");
    PFNEGLQUERYDEVICESEXTPROC query = (PFNEGLQUERYDEVICESEXTPROC)eglGetProcAddress("eglQueryDevicesEXT");
    d->string = (PFNEGLQUERYDEVICESTRINGEXTPROC)eglGetProcAddress("eglQueryDeviceStringEXT");
    d->n = 0;
    if (!query || !d->string || !query(MAX_DEVICES, d->dev, &d->n) || d->n <= 0)
        return hy_error_set(err, HY_EUNSUP, "EGL lists no device: neither a GPU driver nor Mesa's software "
                            "rasteriser (install libegl-mesa0, or the GPU's EGL driver)");
    return HY_OK;
}

static int is_software(const devices *d, int i)
{
    return has_ext(d->string(d->dev[i], EGL_EXTENSIONS), "EGL_MESA_device_software");
}

/* HYSTVIZ_EGL_DEVICE, else the first hardware device, else device 0. */
static int choose_device(const devices *d, int *pick, hy_error *err)
{
    const char *env = getenv("HYSTVIZ_EGL_DEVICE");
    if (env && *env) {
        char *end;
        errno = 0;
        long v = strtol(env, &end, 10);
        if (errno || *end || end == env || v < 0 || v >= d->n)
            return hy_error_set(err, HY_EINVAL, "HYSTVIZ_EGL_DEVICE='%s' is not a device number 0..%d (hystviz "
                                "animate --gl-info lists the EGL devices)", env, (int)d->n - 1);
        *pick = (int)v;
        return HY_OK;
    }
    *pick = 0;
    for (int i = 0; i < d->n; i++)
        if (!is_software(d, i)) {
            *pick = i;
            break;
        }
    return HY_OK;
}

/* Under mu: the display of the chosen device, initialised. */
static int display_get(hy_error *err)
{
    if (dpy != EGL_NO_DISPLAY)
        return HY_OK;
    devices d;
    int pick, st = list_devices(&d, err);
    if (st || (st = choose_device(&d, &pick, err)))
        return st;
    PFNEGLGETPLATFORMDISPLAYEXTPROC get =
        (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
    dpy = get ? get(EGL_PLATFORM_DEVICE_EXT, d.dev[pick], NULL) : EGL_NO_DISPLAY;
    EGLint major, minor;
    if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, &major, &minor)) {
        dpy = EGL_NO_DISPLAY;
        return hy_error_set(err, HY_EUNSUP, "EGL could not open device %d (error 0x%04x)", pick, eglGetError());
    }
    const char *ext = eglQueryString(dpy, EGL_EXTENSIONS);
    EGLint n = 0;
    const EGLint want[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    if (!has_ext(ext, "EGL_KHR_surfaceless_context"))
        st = hy_error_set(err, HY_EUNSUP, "EGL device %d cannot make a context current without a surface "
                          "(EGL_KHR_surfaceless_context)", pick);
    else if (has_ext(ext, "EGL_KHR_no_config_context"))
        config = EGL_NO_CONFIG_KHR;
    else if (!eglChooseConfig(dpy, want, &config, 1, &n) || n < 1)
        st = hy_error_set(err, HY_EUNSUP, "EGL device %d has no OpenGL configuration", pick);
    if (st) {
        eglTerminate(dpy);
        dpy = EGL_NO_DISPLAY;
        return st;
    }
    return HY_OK;
}


static void egl_close(hy_gl_surface *s, int current)
{
    if (!s)
        return;
    if (s->ctx != EGL_NO_CONTEXT) {
        pthread_mutex_lock(&mu);
        if (current)
            eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(dpy, s->ctx);   /* its framebuffer object and renderbuffers with it */
        pthread_mutex_unlock(&mu);
        if (current)
            eglReleaseThread();
    }
    free(s->fb);
    free(s->row);
    free(s);
}

/* The framebuffer object of the frame, bound; 0 if incomplete. */
static int make_fbo(hy_gl_surface *s)
{
    fns.GenFramebuffers(1, &s->fbo);
    fns.BindFramebuffer(GL_FRAMEBUFFER, s->fbo);
    fns.GenRenderbuffers(1, s->rb);   /* colour only: 3-D frames have their own (hy_gl.c msaa_target) */
    fns.BindRenderbuffer(GL_RENDERBUFFER, s->rb[0]);
    fns.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, s->w, s->h);
    fns.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, s->rb[0]);
    return fns.CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
}

static int egl_open(hy_gl_surface **out, int w, int h, const hy_gl_fns **f, unsigned *fbo, hy_error *err)
{
    hy_gl_surface *s = calloc(1, sizeof *s);
    if (!s || !(s->fb = malloc((size_t)w * (size_t)h * 4)) || !(s->row = malloc((size_t)w * 4))) {
        if (s)
            free(s->fb);
        free(s);
        return hy_error_set(err, HY_ENOMEM, "out of memory for a %d x %d GL frame", w, h);
    }
    s->w = w, s->h = h, s->ctx = EGL_NO_CONTEXT;
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    pthread_mutex_lock(&mu);
    int st = display_get(err);
    if (!st) {
        if (eglBindAPI(EGL_OPENGL_API))   /* per thread */
            s->ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, attribs);
        if (s->ctx == EGL_NO_CONTEXT)
            st = hy_error_set(err, HY_EUNSUP, "EGL could not create an OpenGL 3.3 core-profile context "
                              "(error 0x%04x)", eglGetError());
        else if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, s->ctx))
            st = hy_error_set(err, HY_EUNSUP, "EGL could not make a context current without a surface "
                              "(error 0x%04x)", eglGetError());
        if (st && s->ctx != EGL_NO_CONTEXT)
            eglDestroyContext(dpy, s->ctx), s->ctx = EGL_NO_CONTEXT;
    }
    pthread_mutex_unlock(&mu);
    if (st) {
        egl_close(s, 0);
        return st;
    }
    pthread_once(&fns_once, load_fns);
    if (fns_missing) {
        egl_close(s, 1);
        return hy_error_set(err, HY_EUNSUP, "EGL has no entry point %s", fns_missing);
    }
    if (!make_fbo(s)) {
        egl_close(s, 1);
        return hy_error_set(err, HY_EUNSUP, "the %d x %d framebuffer object is incomplete", w, h);
    }
    *f = &fns, *fbo = s->fbo, *out = s;
    return HY_OK;
}

/* Called only when another context was used on this thread since, maybe an
 * OSMesa one: EGL still believes s current and would skip the bind, leaving
 * Mesa's dispatch on the OSMesa context (GL_INVALID_OPERATION on our FBO,
 * test_backends), so it is released first. */
static int egl_make_current(hy_gl_surface *s)
{
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    return eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, s->ctx) ? 0 : -1;
}

/* BGRA as 8_8_8_8_REV is a native 0xAARRGGBB word per pixel on any host:
 * cairo's RGB24.  GL's rows are bottom-up: flipped here. */
static const unsigned char *egl_frame(hy_gl_surface *s)
{
    size_t stride = (size_t)s->w * 4;
    fns.BindFramebuffer(GL_FRAMEBUFFER, s->fbo);
    fns.PixelStorei(GL_PACK_ALIGNMENT, 4);
    fns.ReadPixels(0, 0, s->w, s->h, GL_BGRA, GL_UNSIGNED_INT_8_8_8_8_REV, s->fb);
    for (int y = 0; y < s->h / 2; y++) {
        unsigned char *a = s->fb + (size_t)y * stride, *b = s->fb + (size_t)(s->h - 1 - y) * stride;
        memcpy(s->row, a, stride);
        memcpy(a, b, stride);
        memcpy(b, s->row, stride);
    }
    return s->fb;
}

static void egl_info(FILE *f)
{
    hy_error err = {0};
    devices d;
    int pick = -1;
    if (list_devices(&d, &err)) {
        fprintf(f, "egl: %s\n", err.msg);
        return;
    }
    int st = choose_device(&d, &pick, &err);
    for (int i = 0; i < d.n; i++) {
        const char *node = has_ext(d.string(d.dev[i], EGL_EXTENSIONS), "EGL_EXT_device_drm")
                               ? d.string(d.dev[i], EGL_DRM_DEVICE_FILE_EXT) : NULL;
        fprintf(f, "egl device %d: %s%s%s%s\n", i, is_software(&d, i) ? "software rasteriser" : "hardware",
                node ? " " : "", node ? node : "", !st && i == pick ? " (used)" : "");
    }
    if (st)
        fprintf(f, "egl: %s\n", err.msg);
}

static int egl_check(hy_error *err)
{
    devices d;
    int pick, st = list_devices(&d, err);
    return st ? st : choose_device(&d, &pick, err);
}

const hy_gl_backend hy_gl_egl_backend = {"egl",     0,        0,        egl_open, egl_make_current,
                                         egl_frame, egl_close, egl_info, egl_check};
