/* SPDX-License-Identifier: MIT */
/* hy_gl_pick.c: which GL backend a context is made with, in one place:
 * hy_gl_select's name (animate --gl), else $HYSTVIZ_GL, else OSMesa where it
 * is built (the stated default), else EGL. */
#include "hy_gl_pick.h"

#include <stdlib.h>
#include <string.h>

#include "hy_gl_backend.h"

static const hy_gl_backend *const built[] = {
#if HY_HAVE_OSMESA
    &hy_gl_osmesa_backend,
#endif
#if HY_HAVE_EGL
    &hy_gl_egl_backend,
#endif
    NULL,
};

static const char *const known[] = {"osmesa", "egl"};
static const char *chosen;            /* hy_gl_select's name; NULL: the environment's or the default */

const char *hy_gl_backends(void)
{
    static const char list[] = ""
#if HY_HAVE_OSMESA
                               " osmesa"
#endif
#if HY_HAVE_EGL
                               " egl"
#endif
        ;
    return list[0] ? list + 1 : list;
}

static const hy_gl_backend *by_name(const char *name, const char *origin, hy_error *err)
{
    for (int i = 0; built[i]; i++)
        if (!strcmp(built[i]->name, name))
            return built[i];
    for (size_t i = 0; i < sizeof known / sizeof known[0]; i++)
        if (!strcmp(known[i], name)) {
            hy_error_set(err, HY_EUNSUP, "%s '%s': this hystviz was built without the %s backend (built: %s)",
                         origin, name, name, built[0] ? hy_gl_backends() : "none");
            return NULL;
        }
    hy_error_set(err, HY_EINVAL, "%s '%s' is not a GL backend (osmesa or egl)", origin, name);
    return NULL;
}

const hy_gl_backend *hy_gl_backend_current(hy_error *err)
{
    if (chosen)
        return by_name(chosen, "--gl", err);
    const char *env = getenv("HYSTVIZ_GL");
    if (env && *env)
        return by_name(env, "HYSTVIZ_GL", err);
    if (!built[0])
        hy_error_set(err, HY_EUNSUP, "this hystviz was built without a GL backend (neither OSMesa nor EGL)");
    return built[0];
}

int hy_gl_select(const char *name, hy_error *err)
{
    const char *prev = chosen;
    chosen = name;
    if (!hy_gl_backend_current(err)) {
        int st = err->code;
        chosen = prev;
        return st;
    }
    return HY_OK;
}

const char *hy_gl_backend_name(hy_error *err)
{
    const hy_gl_backend *b = hy_gl_backend_current(err);
    return b ? b->name : NULL;
}

int hy_gl_check(hy_error *err)
{
    const hy_gl_backend *b = hy_gl_backend_current(err);
    return b ? b->check(err) : err->code;
}

const char *hy_gl_backend_origin(void)
{
    return chosen ? "--gl" : getenv("HYSTVIZ_GL") && *getenv("HYSTVIZ_GL") ? "HYSTVIZ_GL" : "default";
}

const char *hy_gl_fns_load(hy_gl_fns *f, hy_gl_lookup lookup)
{
#define HY_GL_FN_LOAD(name) \
    if (!(f->name = (__typeof__(gl##name) *)lookup("gl" #name))) \
        return "gl" #name;
    HY_GL_FUNCS(HY_GL_FN_LOAD)
#undef HY_GL_FN_LOAD
    return NULL;
}
