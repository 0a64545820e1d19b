/* SPDX-License-Identifier: MIT */
/* hy_scene_param.c: named parameters: [param NAME] value, read by keys written `key = $NAME`
 * (docs/SCENES.md "Named parameters"), so that keys that belong together move together.
 * The `$NAME` reference itself is read by hy_scene_ref.c, below both the parser and
 * hy_scene.c's overrides, so that they do not call into this file. */
#include "hy_scene_internal.h"
#include "hy_scene.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int param_value(const hy_scene *s, const char *name, double *x)
{
    int sec = hy_scene_schema_section("param");
    const hy__section *p = hy__scene_find(s, sec, name);
    if (!p)
        return -1;
    const hy__slot *v = &p->slots[hy_scene_schema_key(sec, "value")];
    if (!v->set)
        return -2;
    *x = v->v.num;
    return 0;
}

/* The value x as the slot's key (secs[si].slots[k]) would take it, checked
 * like a scene line: *out on success, else a message. */
static int ref_value(const hy_scene *s, size_t si, size_t k, double x, hy__value *out, char *msg,
                     size_t msgsz)
{
    const hy__section *x_sec = &s->secs[si];
    const hy_scene_section_spec *ss = hy_scene_schema(NULL) + x_sec->spec;
    char where[160], text[40];
    if (x_sec->name)
        snprintf(where, sizeof where, "[%s %s]", ss->name, x_sec->name);
    else
        snprintf(where, sizeof where, "[%s]", ss->name);
    for (int d = 15; d <= 17; d++) { /* the shortest text that reads back as x */
        snprintf(text, sizeof text, "%.*g", d, x);
        if (strtod(text, NULL) == x)
            break;
    }
    int col = 0;
    return hy__value_parse(&ss->keys[k], where, NULL, text, strlen(text), 1, out, &col, msg, msgsz);
}

/* The names of the scene's [param] sections closest to name (a typo), or NULL. */
static const char *param_suggest(const hy_scene *s, const char *name)
{
    const char *cand[64];
    size_t n = 0;
    for (size_t i = 0; n < 64 && hy_scene_name_at(s, "param", i); i++)
        cand[n++] = hy_scene_name_at(s, "param", i);
    return hy__suggest(name, cand, n);
}

static int check_caption(const hy_scene *s, hy_error *err);

int hy__scene_resolve(hy_scene *s, hy_error *err)
{
    const hy_scene_section_spec *spec = hy_scene_schema(NULL);
    for (size_t i = 0; i < s->nsecs; i++) {
        hy__section *x = &s->secs[i];
        for (size_t k = 0; k < spec[x->spec].nkeys; k++) {
            hy__slot *slot = &x->slots[k];
            if (!slot->set || !slot->ref)
                continue;
            const char *name = s->refs[slot->ref - 1];
            char msg[400];
            double v;
            int got = param_value(s, name, &v);
            hy__value out;
            const char *sug = got == -1 ? param_suggest(s, name) : NULL;
            /* names as messages quote a scene's text (cut, "..."): a name of
             * any length leaves the message's own words whole */
            char nm[2][HY_SCENE_SHOWN_MAX * 4 + 4];
            const char *sn = hy_file_shown(name, strlen(name), HY_SCENE_SHOWN_MAX, nm[0], sizeof nm[0]);
            if (got == -1 && sug)
                snprintf(msg, sizeof msg, "unknown parameter $%s; did you mean $%s?", sn,
                         hy_file_shown(sug, strlen(sug), HY_SCENE_SHOWN_MAX, nm[1], sizeof nm[1]));
            else if (got == -1)
                snprintf(msg, sizeof msg, "unknown parameter $%s: the scene has no [param %s]", sn, sn);
            else if (got == -2)
                snprintf(msg, sizeof msg, "parameter $%s: [param %s] sets no value", sn, sn);
            else if (ref_value(s, i, k, v, &out, msg, sizeof msg) == HY_OK) {
                hy__value_clear(&slot->v);
                slot->v = out;
                continue;
            }
            if (got == 0) /* the key's own message, said of the parameter */
                hy_error_set(err, HY_EINVAL, "$%s = %.15g: %s", sn, v, msg);
            else
                hy_error_set(err, HY_EINVAL, "%s", msg);
            if (slot->loc.line)
                hy_error_prefix(err, "%s:%d:%d", slot->loc.file, slot->loc.line, slot->refcol);
            else
                hy_error_prefix(err, "%s", slot->loc.file);
            return HY_EINVAL;
        }
    }
    return check_caption(s, err);
}

int hy__param_propagate(hy_scene *s, const char *name, double x, const char *a, int record,
                        hy_error *err)
{
    const hy_scene_section_spec *spec = hy_scene_schema(NULL);
    size_t r = 0;
    for (size_t i = 0; i < s->nrefs && !r; i++)
        if (!strcmp(s->refs[i], name))
            r = i + 1;
    if (!r)
        return HY_OK; /* nothing reads it */
    for (int pass = 0; pass < 2; pass++) /* check all, then change all */
        for (size_t i = 0; i < s->nsecs; i++) {
            hy__section *sx = &s->secs[i];
            for (size_t k = 0; k < spec[sx->spec].nkeys; k++) {
                hy__slot *slot = &sx->slots[k];
                if (!slot->set || slot->ref != r)
                    continue;
                char msg[400];
                hy__value out;
                if (ref_value(s, i, k, x, &out, msg, sizeof msg))
                    return hy_error_set(err, HY_EINVAL, "--set %s: %s (it reads $%s at %s:%d)", a, msg, name,
                                        slot->loc.file, slot->loc.line);
                if (!pass) {
                    hy__value_clear(&out);
                    continue;
                }
                if (record && hy__undo_push(s, i, k, slot)) {
                    hy__value_clear(&out);
                    return hy_error_set(err, HY_ENOMEM, "--set %s: out of memory", a);
                }
                if (!record)
                    hy__value_clear(&slot->v);
                slot->v = out;
            }
        }
    return HY_OK;
}

const char *hy_scene_get_ref(const hy_scene *s, const char *section, const char *name, const char *key)
{
    int sec = hy_scene_schema_section(section), k = hy_scene_schema_key(sec, key);
    const hy__section *x = k < 0 ? NULL : hy__scene_find(s, sec, name);
    if (!x || !x->slots[k].set || !x->slots[k].ref)
        return NULL;
    return s->refs[x->slots[k].ref - 1];
}

/* ---- placeholders: {section.key} in a caption -------------------------- */

/* If p (before end) opens a placeholder "{section.key}" or
 * "{section.NAME.key}" (a schema section, then letters, digits, _ - .),
 * its length with the braces; else 0 (the text is literal). */
static size_t placeholder_len(const char *p)
{
    if (*p != '{')
        return 0;
    size_t n = 1;
    while (p[n] >= 'a' && p[n] <= 'z')
        n++;
    if (n == 1 || p[n] != '.' || n - 1 >= 32)
        return 0;
    char sec[32];
    memcpy(sec, p + 1, n - 1);
    sec[n - 1] = '\0';
    if (hy_scene_schema_section(sec) < 0)
        return 0;
    size_t k = n + 1;
    while (hy__name_char((unsigned char)p[k]))
        k++;
    return k > n + 1 && p[k] == '}' && p[k - 1] != '.' ? k + 1 : 0;
}

/* Writes the value of the key that placeholder ph[0..n) names, as scene
 * text would show it, into val; HY_EINVAL with a reason in why otherwise. */
static int placeholder_value(const hy_scene *s, const char *ph, size_t n, char *val, size_t valsz, char *why,
                             size_t whysz)
{
    char set[200], *sec = NULL, *name = NULL, *key = NULL;
    const char *v;
    hy_error err = {0};
    snprintf(set, sizeof set, "%.*s=", (int)(n - 2), ph + 1);
    int rc = hy_scene_set_split(set, &sec, &name, &key, &v, &err);
    int si = rc ? -1 : hy_scene_schema_section(sec), ki = si < 0 ? -1 : hy_scene_schema_key(si, key);
    const hy_scene_key_spec *k = ki < 0 ? NULL : &hy_scene_schema(NULL)[si].keys[ki];
    double x;
    long l;
    const char *t = NULL;
    int got = -1;
    why[0] = '\0';
    if (!k)
        snprintf(why, whysz, "'%.*s' names no key of the scene format (write {section.key} or {section.NAME.key})",
                 (int)n, ph);
    else if (k->kind == HY_KIND_NUMBER && (got = hy_scene_get_num(s, sec, name, key, &x)) >= 0)
        snprintf(val, valsz, "%.15g", x);
    else if (k->kind == HY_KIND_INTEGER && (got = hy_scene_get_int(s, sec, name, key, &l)) >= 0)
        snprintf(val, valsz, "%ld", l);
    else if (k->kind == HY_KIND_ENUM && (got = hy_scene_get_enum(s, sec, name, key, NULL, &t)) >= 0)
        snprintf(val, valsz, "%s", t);
    else if (k->kind == HY_KIND_NAME && (got = hy_scene_get_str(s, sec, name, key, &t)) >= 0)
        snprintf(val, valsz, "%s", t);
    else if (k->kind != HY_KIND_NUMBER && k->kind != HY_KIND_INTEGER && k->kind != HY_KIND_ENUM && k->kind != HY_KIND_NAME)
        snprintf(why, whysz, "'%.*s' (%s) cannot be shown: a placeholder shows a number, an identifier or a name", (int)n, ph,
                 hy_scene_kind_name(k->kind));
    if (k && got < 0 && !why[0])
        snprintf(why, whysz, "'%.*s' has no value in this scene%s", (int)n, ph,
                 name ? " (is the section's name right?)" : "");
    rc = why[0] ? HY_EINVAL : HY_OK;
    free(sec);
    free(name);
    free(key);
    return rc;
}

int hy_scene_expand(const hy_scene *s, const char *text, char **out, hy_error *err)
{
    size_t cap = strlen(text) + 64, len = 0;
    char *o = malloc(cap);
    *out = NULL;
    if (!o)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    for (const char *p = text; *p;) {
        size_t n = placeholder_len(p);
        char val[200], why[300];
        const char *piece = p;
        size_t pl = 1;
        if (n) {
            if (placeholder_value(s, p, n, val, sizeof val, why, sizeof why)) {
                free(o);
                return hy_error_set(err, HY_EINVAL, "%s", why);
            }
            piece = val;
            pl = strlen(val);
        }
        if (len + pl + 1 > cap) {
            char *g = realloc(o, cap = 2 * (len + pl + 1));
            if (!g) {
                free(o);
                return hy_error_set(err, HY_ENOMEM, "out of memory");
            }
            o = g;
        }
        memcpy(o + len, piece, pl);
        len += pl;
        p += n ? n : 1;
    }
    o[len] = '\0';
    *out = o;
    return HY_OK;
}

/* The placeholders of the [figure] caption and of each [series] label name
 * keys with values (else an error at the key's line). */
static int check_caption(const hy_scene *s, hy_error *err)
{
    for (size_t i = 0; i <= hy_scene_count(s, "series"); i++) {
        const char *sec = i ? "series" : "figure", *name = i ? hy_scene_name_at(s, "series", i - 1) : NULL;
        const char *key = i ? "label" : "caption", *text = NULL;
        char *out = NULL;
        if (hy_scene_get_str(s, sec, name, key, &text) != HY_SCENE_SET || !strchr(text, '{'))
            continue;
        hy_error e = {0};
        int rc = hy_scene_expand(s, text, &out, &e);
        free(out);
        if (rc)
            return hy_scene_error_at(s, sec, name, key, err, rc, "%s: %s", key, e.msg);
    }
    return HY_OK;
}
