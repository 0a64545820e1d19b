/* SPDX-License-Identifier: MIT */
/* scene_model.c: the model table (one line per kind in HY_MODEL_KINDS,
 * generated from src/pipeline/meson.build's table) and what the model files share. */
#include "scene_model.h"

#include <string.h>

#define MODEL_PTR(id, name) &hy_scene_model_##id,
const hy_scene_model *const hy_scene_models[] = {HY_MODEL_KINDS(MODEL_PTR) NULL};

const char *hy_scene_cap_name(unsigned cap)
{
    switch (cap) {
    case HY_CAP_STEADY: return "steady";
    case HY_CAP_YSTAR: return "ystar";
    case HY_CAP_CLOSED_MINOR: return "closed-form-minor-loops";
    case HY_CAP_ENERGY: return "energy";
    case HY_CAP_RETURN_POINT: return "return-point-memory";
    case HY_CAP_RATE_INDEPENDENT: return "rate-independent";
    case HY_CAP_EXACT_STEP: return "exact";
    case HY_CAP_GSL: return "gsl";
    default: return NULL;
    }
}

const hy_scene_model *hy_scene_model_find(const char *kind)
{
    for (size_t i = 0; kind && hy_scene_models[i]; i++)
        if (!strcmp(hy_scene_models[i]->name, kind))
            return hy_scene_models[i];
    return NULL;
}

const hy_scene_model *hy_scene_model_of(const hy_decl_model *m)
{
    const hy_scene_model *mt = hy_scene_model_find(hy_decl_enum_text(&m->h, offsetof(hy_decl_model, kind), m->kind));
    return mt ? mt : hy_scene_model_find("lugre");
}

const char *hy_scene_model_param(const hy_scene_model *mt, size_t i)
{
    if (mt->params) {
        for (size_t j = 0; j < i; j++)
            if (!mt->params[j])
                return NULL;
        return mt->params[i];
    }
    const hy_scene_section_spec *ms = hy_scene_schema(NULL) + hy_scene_schema_section("model");
    for (size_t j = 0; j < ms->nkeys; j++)
        if (ms->keys[j].model && !strcmp(ms->keys[j].model, mt->name) && i-- == 0)
            return ms->keys[j].name;
    return NULL;
}

int hy_scene_model_has_key(const hy_scene_model *mt, const char *key)
{
    if (!strcmp(key, "kind"))
        return 1;
    const char *p;
    for (size_t i = 0; (p = hy_scene_model_param(mt, i)); i++)
        if (!strcmp(p, key))
            return 1;
    return 0;
}

void hy_scene_model_read_numbers(const hy_decl_model *m, const char *const *keys, const size_t *offsets, void *par)
{
    for (size_t i = 0; keys[i]; i++) {
        size_t off = hy_decl_offset(&m->h, keys[i]);
        if (hy_decl_got(&m->h, off) >= 0) /* a number key of the table: a double in m */
            memcpy((char *)par + offsets[i], (const char *)m + off, sizeof(double));
    }
}

int hy_scene_model_area_sign(const hy_scene_model *mt)
{
    return mt && mt->ri && !(mt->ri->caps & HY_RI_AREA_YDU) ? -1 : 1;
}

int hy_scene_model_relocate(const hy_decl_model *m, const hy_scene_model *mt, int rc, hy_error *err)
{
    if (!rc)
        return rc;
    char msg[sizeof err->msg];
    memcpy(msg, err->msg, sizeof msg);
    for (size_t i = 0; mt->core_names && mt->core_names[i]; i++)
        if (strstr(msg, mt->core_names[i])) {
            const char *key = hy_scene_model_param(mt, i);
            return hy_decl_error(&m->h, hy_decl_offset(&m->h, key), err, rc, "%s: %s", key, msg);
        }
    return hy_decl_error(&m->h, HY_DECL_HEAD, err, rc, "%s", msg);
}

void hy_scene_model_par_free(const hy_scene_model *mt, void *par)
{
    if (mt && mt->par_free && par)
        mt->par_free(par);
}
