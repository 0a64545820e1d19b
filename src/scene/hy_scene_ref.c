/* SPDX-License-Identifier: MIT */
/* hy_scene_ref.c: a value written `key = $NAME` (docs/SCENES.md "Named
 * parameters"): the reference read and interned, for the parser and for
 * hy_scene_set's overrides; hy_scene_param.c resolves it to [param NAME]'s
 * value.  It calls nothing of hy_scene.c or hy_scene_param.c. */
#include "hy_scene_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* 1 + the index of name[0..n) in s->refs, added if new; 0 on allocation failure. */
static size_t ref_intern(hy_scene *s, const char *name, size_t n)
{
    for (size_t i = 0; i < s->nrefs; i++)
        if (strlen(s->refs[i]) == n && !memcmp(s->refs[i], name, n))
            return i + 1;
    if (s->nrefs == s->caprefs) {
        size_t cap = s->caprefs ? 2 * s->caprefs : 8;
        char **r = realloc(s->refs, cap * sizeof *r);
        if (!r)
            return 0;
        s->refs = r;
        s->caprefs = cap;
    }
    char *d = malloc(n + 1);
    if (!d)
        return 0;
    memcpy(d, name, n);
    d[n] = '\0';
    s->refs[s->nrefs++] = d;
    return s->nrefs;
}

int hy__ref_parse(hy_scene *s, const hy_scene_key_spec *spec, const char *where, const char *text,
                  size_t len, int col0, size_t *ref, int *errcol, char *msg, size_t msgsz)
{
    const char *p = text, *end = text + len;
    while (p < end && (*p == ' ' || *p == '\t'))
        p++;
    if (p == end || *p != '$')
        return -1;
    *errcol = col0 + (int)(p - text);
    int ps = hy_scene_schema_section("param");
    if (spec == &hy_scene_schema(NULL)[ps].keys[hy_scene_schema_key(ps, "value")]) {
        snprintf(msg, msgsz, "'value' in %s is a number: a parameter cannot read another ($NAME)", where);
        return HY_EINVAL;
    }
    if (spec->kind != HY_KIND_NUMBER && spec->kind != HY_KIND_INTEGER) {
        snprintf(msg, msgsz, "'%s' in %s cannot read a parameter ($NAME): only number and integer keys can",
                 spec->name, where);
        return HY_EINVAL;
    }
    const char *n0 = ++p;
    while (p < end && hy__name_char((unsigned char)*p))
        p++;
    if (p == n0) {
        snprintf(msg, msgsz, "expected a parameter name after '$' (a [param NAME] of the scene)");
        return HY_EINVAL;
    }
    const char *q = p;
    while (q < end && (*q == ' ' || *q == '\t'))
        q++;
    if (q < end && !hy__is_comment(q, end)) {
        char ch[8];
        *errcol = col0 + (int)(q - text);
        snprintf(msg, msgsz, "unexpected '%s' after the parameter $%.*s", hy__char_text(*q, ch),
                 (int)(p - n0), n0);
        return HY_EINVAL;
    }
    *ref = ref_intern(s, n0, (size_t)(p - n0));
    if (!*ref) {
        snprintf(msg, msgsz, "out of memory");
        return HY_ENOMEM;
    }
    return HY_OK;
}

/* The value of [param name]: 0 and *x, -1 without such a section, -2 when it
 * has no value. */
