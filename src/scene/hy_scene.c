/* SPDX-License-Identifier: MIT */
/* hy_scene.c: the scene object: schema defaults, typed getters, --set overrides, content hash. */
#include "hy_scene_internal.h"
#include "hy_os.h"
#include "hy_scene.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FNV_OFFSET 0xcbf29ce484222325ULL
#define FNV_PRIME 0x100000001b3ULL

/* Parses every schema default once per scene so getters can return them. */
static int prepare_defaults(hy_scene *s, hy_error *err)
{
    size_t nsec, total = 0;
    const hy_scene_section_spec *sec = hy_scene_schema(&nsec);
    s->defoff = malloc(nsec * sizeof *s->defoff);
    if (!s->defoff)
        return hy_error_set(err, HY_ENOMEM, "out of memory preparing scene defaults");
    for (size_t i = 0; i < nsec; i++) {
        s->defoff[i] = total;
        total += sec[i].nkeys;
    }
    s->defaults = calloc(total, sizeof *s->defaults);
    if (!s->defaults)
        return hy_error_set(err, HY_ENOMEM, "out of memory preparing scene defaults");
    for (size_t i = 0; i < nsec; i++) {
        /* "[name]" once a section, by hand: this runs for every scene made
           (hy_steady_loop's every call), and printf is slow where a printf
           hook is registered (libquadmath, loaded with NumPy) */
        char where[64];
        size_t l = 0;
        while (sec[i].name[l] && l < sizeof where - 3)
            l++;
        where[0] = '[';
        memcpy(where + 1, sec[i].name, l);
        memcpy(where + 1 + l, "]", 2);
        for (size_t j = 0; j < sec[i].nkeys; j++) {
            const hy_scene_key_spec *k = &sec[i].keys[j];
            char msg[256];
            int col = 0;
            if (!k->def)
                continue;
            if (hy__value_parse(k, where, NULL, k->def, strlen(k->def), 1,
                                &s->defaults[s->defoff[i] + j], &col, msg, sizeof msg))
                return hy_error_set(err, HY_EINVAL, "schema default of %s.%s is invalid: %s",
                                    sec[i].name, k->name, msg);
        }
    }
    return HY_OK;
}

hy_scene *hy__scene_new(hy_error *err)
{
    hy_scene *s = calloc(1, sizeof *s);
    if (!s) {
        hy_error_set(err, HY_ENOMEM, "out of memory allocating a scene");
        return NULL;
    }
    s->hash = FNV_OFFSET;
    size_t nsec;
    hy_scene_schema(&nsec);
    s->kinds = calloc(nsec, sizeof *s->kinds);
    if (!s->kinds) {
        hy_error_set(err, HY_ENOMEM, "out of memory allocating a scene");
        free(s);
        return NULL;
    }
    if (prepare_defaults(s, err)) {
        hy_scene_free(s);
        return NULL;
    }
    return s;
}

void hy_scene_free(hy_scene *s)
{
    if (!s)
        return;
    size_t nsec;
    const hy_scene_section_spec *spec = hy_scene_schema(&nsec);
    for (size_t i = 0; i < s->nsecs; i++) {
        hy__section *sec = &s->secs[i];
        for (size_t j = 0; j < spec[sec->spec].nkeys; j++)
            hy__value_clear(&sec->slots[j].v);
        free(sec->slots);
        free(sec->name);
    }
    free(s->secs);
    free(s->table);
    for (size_t i = 0; s->kinds && i < nsec; i++)
        free(s->kinds[i].idx);
    free(s->kinds);
    free(s->root);
    for (size_t i = 0; i < s->nincdirs; i++)
        free(s->incdirs[i]);
    free(s->incdirs);
    for (size_t i = 0; i < s->nundo; i++)
        hy__value_clear(&s->undo[i].old.v);
    free(s->undo);
    for (size_t i = 0; i < s->nrefs; i++)
        free(s->refs[i]);
    free(s->refs);
    if (s->defaults && s->defoff) {
        for (size_t i = 0; i < nsec; i++)
            for (size_t j = 0; j < spec[i].nkeys; j++)
                hy__value_clear(&s->defaults[s->defoff[i] + j]);
    }
    free(s->defaults);
    free(s->defoff);
    for (size_t i = 0; i < s->nfiles; i++)
        free(s->files[i]);
    free(s->files);
    free(s);
}

int hy__scene_add_file(hy_scene *s, const char *name)
{
    if (s->nfiles == s->capfiles) {
        size_t cap = s->capfiles ? 2 * s->capfiles : 8;
        char **f = realloc(s->files, cap * sizeof *f);
        if (!f)
            return -1;
        s->files = f;
        s->capfiles = cap;
    }
    char *d = strdup(name);
    if (!d)
        return -1;
    s->files[s->nfiles] = d;
    return (int)s->nfiles++;
}

/* FNV-1a of a section's kind and name (NULL for unnamed kinds). */
static size_t section_hash(int sec, const char *name)
{
    uint64_t h = FNV_OFFSET ^ (uint64_t)(unsigned)sec;
    h *= FNV_PRIME;
    for (const char *c = name ? name : ""; *c; c++) {
        h ^= (unsigned char)*c;
        h *= FNV_PRIME;
    }
    return (size_t)(h ^ (h >> 29));
}

static int same_section(const hy__section *x, int sec, const char *name)
{
    return x->spec == sec && ((!name && !x->name) || (name && x->name && strcmp(name, x->name) == 0));
}

/* The slot of (sec, name) in the table: where it is, or the empty slot where it would go. */
static size_t table_slot(const hy_scene *s, int sec, const char *name)
{
    size_t mask = s->captable - 1, i = section_hash(sec, name) & mask;
    while (s->table[i] && !same_section(&s->secs[s->table[i] - 1], sec, name))
        i = (i + 1) & mask;
    return i;
}

/* Doubles the table (or makes the first one); 0 or -1 on allocation failure. */
static int table_grow(hy_scene *s)
{
    size_t cap = s->captable ? 2 * s->captable : 64;
    size_t *t = calloc(cap, sizeof *t);
    if (!t)
        return -1;
    free(s->table);
    s->table = t;
    s->captable = cap;
    for (size_t i = 0; i < s->nsecs; i++)
        s->table[table_slot(s, s->secs[i].spec, s->secs[i].name)] = i + 1;
    return 0;
}

hy__section *hy__scene_find(const hy_scene *s, int sec, const char *name)
{
    if (!s->captable)
        return NULL;
    size_t i = s->table[table_slot(s, sec, name)];
    return i ? &s->secs[i - 1] : NULL;
}

/* Appends section index i to the list of its kind; 0 or -1. */
static int kind_push(hy_scene *s, int sec, size_t i)
{
    hy__kind_list *k = &s->kinds[sec];
    size_t *idx = hy_grow(k->idx, k->n, &k->cap, sizeof *idx, 8);
    if (!idx)
        return -1;
    k->idx = idx;
    k->idx[k->n++] = i;
    return 0;
}

hy__section *hy__scene_touch(hy_scene *s, int sec, const char *name, hy_scene_loc loc)
{
    hy__section *x = hy__scene_find(s, sec, name);
    if (x)
        return x;
    if (2 * (s->nsecs + 1) > s->captable && table_grow(s))
        return NULL;
    hy__section *secs = hy_grow(s->secs, s->nsecs, &s->capsecs, sizeof *secs, 8);
    if (!secs)
        return NULL;
    s->secs = secs;
    const hy_scene_section_spec *spec = hy_scene_schema(NULL);
    x = &s->secs[s->nsecs];
    memset(x, 0, sizeof *x);
    x->spec = sec;
    x->loc = loc;
    x->slots = calloc(spec[sec].nkeys, sizeof *x->slots);
    x->name = name ? strdup(name) : NULL;
    if (!x->slots || (name && !x->name) || kind_push(s, sec, s->nsecs)) {
        free(x->slots);
        free(x->name);
        return NULL;
    }
    s->table[table_slot(s, sec, name)] = ++s->nsecs;
    return x;
}

void hy__scene_hash_bytes(hy_scene *s, const void *p, size_t n)
{
    const unsigned char *b = p;
    uint64_t h = s->hash;
    for (size_t i = 0; i < n; i++) {
        h ^= b[i];
        h *= FNV_PRIME;
    }
    s->hash = h;
}

uint64_t hy_scene_hash(const hy_scene *s)
{
    return s->hash;
}

const char *hy_scene_source(const hy_scene *s)
{
    return s->nfiles ? s->files[0] : "";
}

/* ---- getters ---- */

/* Finds the value of section/name/key if its kind is one of kinds (bitmask of
 * 1u << kind); returns SET, DEFAULT, ABSENT or BADKEY. */
static int lookup(const hy_scene *s, const char *section, const char *name, const char *key,
                  unsigned kinds, const hy__value **v, const hy__slot **slot, const hy_scene_key_spec **ks)
{
    int sec = hy_scene_schema_section(section);
    int k = hy_scene_schema_key(sec, key);
    if (k < 0)
        return HY_SCENE_BADKEY;
    const hy_scene_section_spec *spec = hy_scene_schema(NULL) + sec;
    if (ks)
        *ks = &spec->keys[k];
    if (!(kinds & (1u << spec->keys[k].kind)) || (spec->takes_name != (name != NULL)))
        return HY_SCENE_BADKEY;
    const hy__section *x = hy__scene_find(s, sec, name);
    if (x && x->slots[k].set) {
        *v = &x->slots[k].v;
        if (slot)
            *slot = &x->slots[k];
        return HY_SCENE_SET;
    }
    if (!spec->keys[k].def)
        return HY_SCENE_ABSENT;
    *v = &s->defaults[s->defoff[sec] + (size_t)k];
    return HY_SCENE_DEFAULT;
}

#define BIT(k) (1u << (k))

int hy_scene_get_num(const hy_scene *s, const char *section, const char *name,
                     const char *key, double *out)
{
    const hy__value *v;
    int rc = lookup(s, section, name, key, BIT(HY_KIND_NUMBER) | BIT(HY_KIND_INTEGER), &v, NULL, NULL);
    if (rc >= 0)
        *out = v->num;
    return rc;
}

int hy_scene_get_int(const hy_scene *s, const char *section, const char *name,
                     const char *key, long *out)
{
    const hy__value *v;
    int rc = lookup(s, section, name, key, BIT(HY_KIND_INTEGER), &v, NULL, NULL);
    if (rc >= 0)
        *out = v->ival;
    return rc;
}

int hy_scene_get_bool(const hy_scene *s, const char *section, const char *name,
                      const char *key, int *out)
{
    const hy__value *v;
    int rc = lookup(s, section, name, key, BIT(HY_KIND_BOOL), &v, NULL, NULL);
    if (rc >= 0)
        *out = (int)v->ival;
    return rc;
}

int hy_scene_get_enum(const hy_scene *s, const char *section, const char *name,
                      const char *key, int *index, const char **text)
{
    const hy__value *v;
    const hy_scene_key_spec *k;
    int rc = lookup(s, section, name, key, BIT(HY_KIND_ENUM), &v, NULL, &k);
    if (rc >= 0) {
        if (index)
            *index = (int)v->ival;
        if (text)
            *text = k->enums[v->ival];
    }
    return rc;
}

int hy_scene_get_str(const hy_scene *s, const char *section, const char *name,
                     const char *key, const char **out)
{
    const hy__value *v;
    int rc = lookup(s, section, name, key,
                    BIT(HY_KIND_STRING) | BIT(HY_KIND_NAME) | BIT(HY_KIND_PATH), &v, NULL, NULL);
    if (rc >= 0)
        *out = v->str;
    return rc;
}

int hy_scene_get_list(const hy_scene *s, const char *section, const char *name,
                      const char *key, const double **vals, size_t *n)
{
    const hy__value *v;
    int rc = lookup(s, section, name, key,
                    BIT(HY_KIND_NUMBER_LIST) | BIT(HY_KIND_INTEGER_LIST) | BIT(HY_KIND_ENUM_LIST), &v, NULL, NULL);
    if (rc >= 0) {
        *vals = v->list;
        *n = v->n;
    }
    return rc;
}

int hy_scene_get_enum_at(const hy_scene *s, const char *section, const char *name,
                         const char *key, size_t i, const char **text, size_t *n)
{
    const hy__value *v;
    const hy_scene_key_spec *k;
    int rc = lookup(s, section, name, key, BIT(HY_KIND_ENUM_LIST), &v, NULL, &k);
    if (rc < 0)
        return rc;
    if (i >= v->n)
        return HY_SCENE_BADKEY;
    if (text)
        *text = k->enums[(size_t)v->list[i]];
    if (n)
        *n = v->n;
    return rc;
}

static double to_pt(const hy_scene *s, double x, int unit)
{
    switch (unit) {
    case HY__UNIT_CM: return x * 72.0 / 2.54;
    case HY__UNIT_MM: return x * 72.0 / 25.4;
    case HY__UNIT_IN: return x * 72.0;
    case HY__UNIT_PX: {
        long dpi = 300;
        hy_scene_get_int(s, "figure", NULL, "dpi", &dpi);
        return x * 72.0 / (double)dpi;
    }
    default: return x;
    }
}

int hy_scene_get_length_pt(const hy_scene *s, const char *section, const char *name,
                           const char *key, double *out)
{
    const hy__value *v;
    int rc = lookup(s, section, name, key, BIT(HY_KIND_LENGTH), &v, NULL, NULL);
    if (rc >= 0)
        *out = to_pt(s, v->a[0], v->unit[0]);
    return rc;
}

int hy_scene_get_length_pair_pt(const hy_scene *s, const char *section, const char *name,
                                const char *key, double out[2])
{
    const hy__value *v;
    int rc = lookup(s, section, name, key, BIT(HY_KIND_LENGTH_PAIR), &v, NULL, NULL);
    if (rc >= 0) {
        out[0] = to_pt(s, v->a[0], v->unit[0]);
        out[1] = to_pt(s, v->a[1], v->unit[1]);
    }
    return rc;
}

int hy_scene_get_pair(const hy_scene *s, const char *section, const char *name,
                      const char *key, double out[2], int *is_auto)
{
    const hy__value *v;
    int rc = lookup(s, section, name, key, BIT(HY_KIND_PAIR) | BIT(HY_KIND_LIMITS), &v, NULL, NULL);
    if (rc >= 0) {
        if (is_auto)
            *is_auto = v->is_auto;
        if (!v->is_auto) {
            out[0] = v->a[0];
            out[1] = v->a[1];
        }
    }
    return rc;
}

int hy_scene_get_color(const hy_scene *s, const char *section, const char *name,
                       const char *key, hy_scene_color *out)
{
    const hy__value *v;
    int rc = lookup(s, section, name, key, BIT(HY_KIND_COLOR), &v, NULL, NULL);
    if (rc >= 0)
        *out = v->color;
    return rc;
}

size_t hy_scene_count(const hy_scene *s, const char *section)
{
    int sec = hy_scene_schema_section(section);
    return sec < 0 ? 0 : s->kinds[sec].n;
}

const char *hy_scene_name_at(const hy_scene *s, const char *section, size_t i)
{
    int sec = hy_scene_schema_section(section);
    if (sec < 0 || i >= s->kinds[sec].n)
        return NULL;
    return s->secs[s->kinds[sec].idx[i]].name;
}

int hy_scene_get_loc(const hy_scene *s, const char *section, const char *name,
                     const char *key, hy_scene_loc *loc)
{
    int sec = hy_scene_schema_section(section);
    const hy__section *x = sec < 0 ? NULL : hy__scene_find(s, sec, name);
    if (!x)
        return 0;
    if (!key) {
        *loc = x->loc;
        return 1;
    }
    int k = hy_scene_schema_key(sec, key);
    if (k < 0 || !x->slots[k].set)
        return 0;
    *loc = x->slots[k].loc;
    return 1;
}

int hy_scene_error_at(const hy_scene *s, const char *section, const char *name,
                      const char *key, hy_error *err, int code, const char *fmt, ...)
{
    if (!err)
        return code;
    hy_scene_loc loc = {hy_scene_source(s), 0, 0};
    if (!hy_scene_get_loc(s, section, name, key, &loc))
        hy_scene_get_loc(s, section, name, NULL, &loc);
    va_list ap;
    va_start(ap, fmt);
    hy__error_vat(loc, err, code, fmt, ap);
    va_end(ap);
    return code;
}

void hy__error_vat(hy_scene_loc loc, hy_error *err, int code, const char *fmt, va_list ap)
{
    char msg[sizeof err->msg]; /* an argument may be err->msg itself */
    vsnprintf(msg, sizeof msg, fmt, ap);
    err->code = code;
    memcpy(err->msg, msg, sizeof msg);
    if (loc.line > 0)
        hy_error_prefix(err, "%s:%d:%d", loc.file, loc.line, loc.col);
    else
        hy_error_prefix(err, "%s", loc.file);
}

/* ---- overrides ---- */

int hy_scene_set_split(const char *a, char **sec, char **name, char **key, const char **value,
                       hy_error *err)
{
    *sec = *name = *key = NULL;
    *value = NULL;
    const char *eq = strchr(a, '=');
    if (!eq)
        return hy_error_set(err, HY_EINVAL, "--set %s: expected section.key=value", a);
    const char *b = a, *e = eq;
    while (b < e && (*b == ' ' || *b == '\t'))
        b++;
    while (e > b && (e[-1] == ' ' || e[-1] == '\t'))
        e--;
    const char *d1 = memchr(b, '.', (size_t)(e - b));
    const char *d2 = e;
    while (d2 > b && d2[-1] != '.')
        d2--;
    if (!d1 || d1 == b || d2 == e || d2 - 1 < d1)
        return hy_error_set(err, HY_EINVAL,
                            "--set %s: expected section.key=value or section.NAME.key=value", a);
    *sec = strndup(b, (size_t)(d1 - b));
    *key = strndup(d2, (size_t)(e - d2));
    *name = (d2 - 1 > d1) ? strndup(d1 + 1, (size_t)(d2 - 1 - d1 - 1)) : NULL;
    *value = eq + 1;
    if (!*sec || !*key || (d2 - 1 > d1 && !*name))
        return hy_error_set(err, HY_ENOMEM, "--set %s: out of memory", a);
    if (*name && !**name)
        return hy_error_set(err, HY_EINVAL, "--set %s: empty section name", a);
    return HY_OK;
}

/* Checks section, name and key of an override against the schema and scene. */
static int check_target(const hy_scene *s, const char *a, const char *secname, const char *name,
                        const char *key, int *sec, int *k, hy_error *err)
{
    size_t nsec;
    const hy_scene_section_spec *spec = hy_scene_schema(&nsec);
    *sec = hy_scene_schema_section(secname);
    if (*sec < 0) {
        const char *c[16];
        for (size_t i = 0; i < nsec && i < 16; i++)
            c[i] = spec[i].name;
        const char *sug = hy__suggest(secname, c, nsec < 16 ? nsec : 16);
        return hy_error_set(err, HY_EINVAL, "--set %s: unknown section [%s]%s%s%s", a, secname,
                            sug ? "; did you mean '" : "", sug ? sug : "", sug ? "'?" : "");
    }
    const hy_scene_section_spec *ss = &spec[*sec];
    if (ss->takes_name && !name)
        return hy_error_set(err, HY_EINVAL, "--set %s: [%s] sections are named: write %s.NAME.%s=...",
                            a, secname, secname, key);
    if (!ss->takes_name && name)
        return hy_error_set(err, HY_EINVAL, "--set %s: [%s] takes no name: write %s.%s=...", a,
                            secname, secname, key);
    if (name && !hy__scene_find(s, *sec, name))
        return hy_error_set(err, HY_EINVAL, "--set %s: the scene has no section [%s %s]", a,
                            secname, name);
    *k = hy_scene_schema_key(*sec, key);
    if (*k < 0) {
        const char *c[64];
        size_t n = ss->nkeys < 64 ? ss->nkeys : 64;
        for (size_t i = 0; i < n; i++)
            c[i] = ss->keys[i].name;
        const char *sug = hy__suggest(key, c, n);
        if (sug)
            return hy_error_set(err, HY_EINVAL, "--set %s: unknown key '%s' in [%s]; did you mean '%s'?",
                                a, key, secname, sug);
        char list[300];
        size_t used = 0;
        for (size_t i = 0; i < n && used < sizeof list; i++)
            used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "", c[i]);
        return hy_error_set(err, HY_EINVAL, "--set %s: unknown key '%s' in [%s]; valid keys are %s",
                            a, key, secname, list);
    }
    return HY_OK;
}

/* Keeps the slot's old value (moved: the slot's is then the log's) for
 * hy_scene_restore; -1 on allocation failure, the slot untouched. */
int hy__undo_push(hy_scene *s, size_t sec, size_t key, const hy__slot *slot)
{
    if (s->nundo == s->capundo) {
        size_t cap = s->capundo ? 2 * s->capundo : 16;
        hy__undo *u = realloc(s->undo, cap * sizeof *u);
        if (!u)
            return -1;
        s->undo = u;
        s->capundo = cap;
    }
    s->undo[s->nundo++] = (hy__undo){sec, key, *slot};
    return 0;
}

int hy_scene_mark(hy_scene *s)
{
    for (size_t i = 0; i < s->nundo; i++) /* the old values of the last mark's overrides */
        hy__value_clear(&s->undo[i].old.v);
    s->nundo = 0;
    s->marked = 1;
    s->mark_files = s->nfiles;
    s->mark_secs = s->nsecs;
    s->mark_hash = s->hash;
    return HY_OK;
}

void hy_scene_restore(hy_scene *s)
{
    if (!s->marked)
        return;
    const hy_scene_section_spec *spec = hy_scene_schema(NULL);
    while (s->nundo) { /* newest first: a key set twice ends at its first old value */
        hy__undo *u = &s->undo[--s->nundo];
        hy__slot *slot = &s->secs[u->sec].slots[u->key];
        hy__value_clear(&slot->v);
        *slot = u->old;
    }
    if (s->nsecs > s->mark_secs) { /* sections the overrides created: gone, the table rebuilt */
        for (size_t i = s->mark_secs; i < s->nsecs; i++) {
            hy__section *x = &s->secs[i];
            for (size_t j = 0; j < spec[x->spec].nkeys; j++)
                hy__value_clear(&x->slots[j].v);
            free(x->slots);
            free(x->name);
            hy__kind_list *k = &s->kinds[x->spec];
            while (k->n && k->idx[k->n - 1] >= s->mark_secs)
                k->n--;
        }
        s->nsecs = s->mark_secs;
        memset(s->table, 0, s->captable * sizeof *s->table);
        for (size_t i = 0; i < s->nsecs; i++)
            s->table[table_slot(s, s->secs[i].spec, s->secs[i].name)] = i + 1;
    }
    while (s->nfiles > s->mark_files)
        free(s->files[--s->nfiles]);
    s->hash = s->mark_hash;
}

static int apply_override(hy_scene *s, const char *a, int sec, const char *name, int k,
                          const char *value, hy_error *err)
{
    const hy_scene_section_spec *ss = hy_scene_schema(NULL) + sec;
    char where[160], msg[400];
    int col = 0;
    hy__value v;
    if (name)
        snprintf(where, sizeof where, "[%s %s]", ss->name, name);
    else
        snprintf(where, sizeof where, "[%s]", ss->name);
    size_t ref = 0;
    int rc = hy__ref_parse(s, &ss->keys[k], where, value, strlen(value), 1, &ref, &col, msg, sizeof msg);
    if (rc > 0)
        return hy_error_set(err, rc, "--set %s: %s", a, msg);
    if (rc == 0) { /* $NAME: the parameter's value now */
        const char *pn = s->refs[ref - 1];
        int ps = hy_scene_schema_section("param");
        const hy__section *px = hy__scene_find(s, ps, pn);
        const hy__slot *pv = px ? &px->slots[hy_scene_schema_key(ps, "value")] : NULL;
        if (!pv || !pv->set) {
            char nm[HY_SCENE_SHOWN_MAX * 4 + 4]; /* a name of any length leaves the words whole */
            hy_file_shown(pn, strlen(pn), HY_SCENE_SHOWN_MAX, nm, sizeof nm);
            return hy_error_set(err, HY_EINVAL, "--set %s: unknown parameter $%s: the scene has no [param %s] with a value",
                                a, nm, nm);
        }
        char text[40];
        snprintf(text, sizeof text, "%.17g", pv->v.num);
        rc = hy__value_parse(&ss->keys[k], where, NULL, text, strlen(text), 1, &v, &col, msg, sizeof msg);
    } else
        rc = hy__value_parse(&ss->keys[k], where, NULL, value, strlen(value), 1, &v, &col, msg, sizeof msg);
    if (rc)
        return hy_error_set(err, rc, "--set %s: %s", a, msg);
    if (name && !strcmp(ss->name, "param") && !strcmp(ss->keys[k].name, "value") &&
        (rc = s->propagate(s, name, v.num, a, s->marked, err))) {
        hy__value_clear(&v);
        return rc;
    }
    char label[400];
    snprintf(label, sizeof label, "--set %s", a);
    int inst = hy__scene_add_file(s, label);
    hy_scene_loc loc = {inst < 0 ? NULL : s->files[inst], 0, 0};
    hy__section *x = inst < 0 ? NULL : hy__scene_touch(s, sec, name, loc);
    if (!x) {
        hy__value_clear(&v);
        return hy_error_set(err, HY_ENOMEM, "--set %s: out of memory", a);
    }
    hy__slot *slot = &x->slots[k];
    if (s->marked && hy__undo_push(s, (size_t)(x - s->secs), (size_t)k, slot)) {
        hy__value_clear(&v);
        return hy_error_set(err, HY_ENOMEM, "--set %s: out of memory", a);
    }
    if (!s->marked)
        hy__value_clear(&slot->v);
    slot->v = v;
    slot->set = 1;
    slot->inst = inst;
    slot->loc = loc;
    slot->ref = ref;
    slot->refcol = 0;
    hy__scene_hash_bytes(s, "\n--set ", 7);
    hy__scene_hash_bytes(s, a, strlen(a));
    return HY_OK;
}

int hy_scene_set(hy_scene *s, const char *assignment, hy_error *err)
{
    char *secname = NULL, *name = NULL, *key = NULL;
    const char *value = NULL;
    int sec = -1, k = -1;
    int rc = hy_scene_set_split(assignment, &secname, &name, &key, &value, err);
    if (!rc)
        rc = check_target(s, assignment, secname, name, key, &sec, &k, err);
    if (!rc)
        rc = apply_override(s, assignment, sec, name, k, value, err);
    free(secname);
    free(name);
    free(key);
    return rc;
}

/* The sections whose keys serve shows as controls (src/serve/serve_util.c). */
static int main_section(const char *sec)
{
    static const char *const secs[] = {"model", "input", "compute", "series", "param"};
    for (size_t i = 0; i < sizeof secs / sizeof secs[0]; i++)
        if (!strcmp(sec, secs[i]))
            return 1;
    return 0;
}

int hy_scene_main_keys(const hy_scene *s, char (*keys)[HY_SCENE_KEY_MAX], size_t max, size_t *n, hy_error *err)
{
    const char *list = NULL;
    *n = 0;
    if (hy_scene_get_str(s, "controls", NULL, "main", &list) != HY_SCENE_SET || !list)
        return HY_OK;
    size_t nsec;
    const hy_scene_section_spec *spec = hy_scene_schema(&nsec);
    for (const char *p = list + strspn(list, " ,"); *p; p += strspn(p, " ,")) {
        size_t len = strcspn(p, " ,");
        if (len >= HY_SCENE_KEY_MAX)
            return hy_scene_error_at(s, "controls", NULL, "main", err, HY_EINVAL, "main: '%.40s...' is too long for a key", p);
        if (*n == max)
            return hy_scene_error_at(s, "controls", NULL, "main", err, HY_EINVAL, "main: at most %zu keys", max);
        char set[HY_SCENE_KEY_MAX + 2], *sec, *name, *key;
        const char *value;
        snprintf(set, sizeof set, "%.*s=", (int)len, p);
        int rc = hy_scene_set_split(set, &sec, &name, &key, &value, err);
        int si = rc ? -1 : hy_scene_schema_section(sec), ki = si < 0 ? -1 : hy_scene_schema_key(si, key);
        double v;
        if (!rc && (ki < 0 || (spec[si].keys[ki].kind != HY_KIND_NUMBER && spec[si].keys[ki].kind != HY_KIND_INTEGER) ||
                    !spec[si].takes_name != !name || !main_section(sec)))
            rc = hy_scene_error_at(s, "controls", NULL, "main", err, HY_EINVAL,
                                   "main: '%.*s' is not a numeric key of [model], [input], [compute] or a [series NAME], "
                                   "written as for --set (model.sigma0, series.NAME.gamma)", (int)len, p);
        else if (!rc && hy_scene_get_num(s, sec, name, key, &v) < 0)
            rc = hy_scene_error_at(s, "controls", NULL, "main", err, HY_EINVAL,
                                   "main: the scene has no value for '%.*s'%s", (int)len, p,
                                   name ? " (is the section's name right?)" : "");
        else if (rc)
            rc = hy_scene_error_at(s, "controls", NULL, "main", err, HY_EINVAL,
                                   "main: '%.*s' is not written as SECTION.key or SECTION.NAME.key", (int)len, p);
        free(sec);
        free(name);
        free(key);
        if (rc)
            return rc;
        snprintf(keys[(*n)++], HY_SCENE_KEY_MAX, "%.*s", (int)len, p);
        p += len;
    }
    return HY_OK;
}

int hy_scene_preset_sets(const hy_scene *s, const char *name, char (*sets)[HY_SCENE_SET_MAX], size_t max, size_t *n,
                         hy_error *err)
{
    const char *list = "";
    *n = 0;
    hy_scene_get_str(s, "preset", name, "set", &list);
    for (const char *p = list; *p;) {
        p += strspn(p, " \t;");
        size_t len = strcspn(p, ";");
        while (len && (p[len - 1] == ' ' || p[len - 1] == '\t'))
            len--;
        if (!len)
            break;
        if (len >= HY_SCENE_SET_MAX)
            return hy_scene_error_at(s, "preset", name, "set", err, HY_EINVAL, "set: '%.40s...' is longer than %d bytes",
                                     p, HY_SCENE_SET_MAX - 1);
        if (*n == max)
            return hy_scene_error_at(s, "preset", name, "set", err, HY_EINVAL, "set: at most %zu values", max);
        char *sec, *nm, *key;
        const char *value;
        snprintf(sets[*n], HY_SCENE_SET_MAX, "%.*s", (int)len, p);
        int rc = hy_scene_set_split(sets[*n], &sec, &nm, &key, &value, err);
        int si = rc ? -1 : hy_scene_schema_section(sec);
        if (rc || si < 0 || hy_scene_schema_key(si, key) < 0 || !*value)
            rc = hy_scene_error_at(s, "preset", name, "set", err, HY_EINVAL,
                                   "set: '%s' is not SECTION.key=VALUE or SECTION.NAME.key=VALUE of a key the scene "
                                   "format knows (values are separated by ';')", sets[*n]);
        free(sec);
        free(nm);
        free(key);
        if (rc)
            return rc;
        (*n)++;
        p += len;
        p += strcspn(p, ";");
    }
    return HY_OK;
}
