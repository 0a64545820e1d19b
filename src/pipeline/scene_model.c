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
    return mt ? mt : hy_scene_model_find(HY_MODEL_DEFAULT);
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

int hy_scene_model_read(const hy_scene_model *mt, const hy_scene *s, const hy_decl_model *m, void *par,
                        hy_error *err)
{
    if (mt->read)
        return mt->read(s, m, par, err);
    memcpy(par, m->par, mt->ri_par_size);
    return HY_OK;
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

/* names[0..n) as "a, b or c" in out. */
static void join_or(char *out, size_t size, const char *const *names, size_t n)
{
    out[0] = '\0';
    for (size_t i = 0, len = 0; i < n && len < size; i++, len = strlen(out))
        snprintf(out + len, size - len, "%s%s", i == 0 ? "" : i + 1 == n ? " or " : ", ", names[i]);
}

/* The refusal of value what (of the kind of thing noun names) at off of h:
 * naming the models that accept it (by[0..nby)) or the values model mt
 * accepts (own[0..nown)), whichever is the shorter list. */
static int not_accepted(const hy_decl_head *h, size_t off, const hy_scene_model *mt, const char *noun,
                        const char *verb, const char *what, const char *const *by, size_t nby,
                        const char *const *own, size_t nown, hy_error *err)
{
    char list[256];
    if (nby && nby <= nown) {
        join_or(list, sizeof list, by, nby);
        return hy_decl_error(h, off, err, HY_EINVAL, "%s = %s needs [model] kind = %s (this model is %s)", noun,
                             what, list, mt->name);
    }
    join_or(list, sizeof list, own, nown);
    return hy_decl_error(h, off, err, HY_EINVAL, "a %s model %s %s = %s, not %s", mt->name, verb, noun, list, what);
}

#define NMODELS (sizeof hy_scene_models / sizeof *hy_scene_models)

/* An [input] kind the model does not take. */
static int foreign_input(const hy_scene_run *r, hy_error *err)
{
#define INPUT_NAME(id, name, takers) name,
    static const char *const names[] = {HY_INPUT_KINDS(INPUT_NAME)};
#undef INPUT_NAME
    const hy_scene_model *mt = r->mtype;
    const hy_decl_input *in = &r->doc.input;
    int kind = in->kind;
    if (hy_decl_got(&in->h, offsetof(hy_decl_input, kind)) != HY_SCENE_SET || kind < 0 ||
        kind >= HY_INPUT_KIND_COUNT || (hy_input_kind_takers(kind) & (int)mt->inputs))
        return HY_OK;
    const char *own[HY_INPUT_KIND_COUNT], *by[NMODELS];
    size_t nown = 0, nby = 0;
    for (int k = 0; k < HY_INPUT_KIND_COUNT; k++)
        if (hy_input_kind_takers(k) & (int)mt->inputs)
            own[nown++] = names[k];
    for (size_t j = 0; hy_scene_models[j]; j++)
        if (hy_input_kind_takers(kind) & (int)hy_scene_models[j]->inputs)
            by[nby++] = hy_scene_models[j]->name;
    return not_accepted(&in->h, offsetof(hy_decl_input, kind), mt, "[input] kind", "takes", names[kind], by, nby,
                        own, nown, err);
}

/* A series data the model does not draw. */
static int foreign_data(const hy_scene_run *r, hy_error *err)
{
    const hy_scene_model *mt = r->mtype;
    for (size_t i = 0; i < r->doc.nseries; i++) {
        const hy_decl_series *ds = &r->doc.series[i];
        int d;
        if (hy_scene_series_data(ds, &d) || (mt->data & 1u << d))
            continue;
        const char *own[32], *by[NMODELS];
        size_t nown = 0, nby = 0;
        for (int k = 0; k < 32; k++)
            if (mt->data & 1u << k)
                own[nown++] = hy_scene_data_name(k);
        for (size_t j = 0; hy_scene_models[j]; j++)
            if (hy_scene_models[j]->data & 1u << d)
                by[nby++] = hy_scene_models[j]->name;
        return not_accepted(&ds->h, offsetof(hy_decl_series, data), mt, "data", "draws", hy_scene_data_name(d), by,
                            nby, own, nown, err);
    }
    return HY_OK;
}

/* A [model] key written that the model does not read. */
static int foreign_keys(const hy_scene_run *r, hy_error *err)
{
    const hy_scene_section_spec *ms = hy_scene_schema(NULL) + hy_scene_schema_section("model");
    const hy_decl_head *h = &r->doc.model.h;
    for (size_t j = 0; j < ms->nkeys && j < HY_SCENE_KEYS_MAX; j++) {
        const char *key = ms->keys[j].name;
        if (h->at[j].set && !hy_scene_model_has_key(r->mtype, key)) {
            char list[256] = "";
            const char *p;
            for (size_t i = 0; (p = hy_scene_model_param(r->mtype, i)); i++)
                snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i ? ", " : "", p);
            return hy_decl_error_row(h, j, err, HY_EINVAL, "'%s' is not a parameter of a %s model (its keys: %s)",
                                     key, r->mtype->name, list);
        }
    }
    return HY_OK;
}

int hy_scene_model_accepts(const hy_scene_run *r, hy_error *err)
{
    int rc = foreign_input(r, err);
    if (!rc)
        rc = foreign_data(r, err);
    if (!rc)
        rc = foreign_keys(r, err);
    return rc;
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
