/* SPDX-License-Identifier: MIT */
/* hy_scene_parse.c: the scene file parser: lines, [section] headers, keys, includes and their precedence. */
#include "hy_scene_internal.h"
#include "hy_scene.h"

#include "hy_file.h"
#include "hy_os.h"
#include "hy_scene_policy.h"

#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define HY_SCENE_MAX_DEPTH 16

/* A key or section header already written in the file being read. */
typedef struct seen {
    size_t sec; /* index in scene->secs, + 1 (0: an empty slot of the table) */
    int key;    /* -1 for a section header */
    int line;
} seen;

/* One file on the include stack. */
typedef struct frame {
    int inst;    /* index in scene->files */
    char *canon; /* realpath, for cycle detection */
    char *dir;   /* directory that relative includes and paths start from */
} frame;

typedef struct pctx {
    hy_scene *s;
    hy_error *err;
    frame stack[HY_SCENE_MAX_DEPTH + 1];
    int depth;
} pctx;

/* State of one file while its lines are read. */
typedef struct fstate {
    seen *seen;           /* open addressing over (sec, key): O(1) duplicate checks */
    size_t nseen, capseen; /* capseen a power of two, at least twice nseen          */
    long cur; /* current section (index in scene->secs), -1 before any header */
    int line;
} fstate;

static const char *cur_file(const pctx *c)
{
    return c->s->files[c->stack[c->depth - 1].inst];
}

static int perr(pctx *c, int line, int col, int code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;

static int perr(pctx *c, int line, int col, int code, const char *fmt, ...)
{
    if (!c->err)
        return code;
    va_list ap;
    va_start(ap, fmt);
    c->err->code = code;
    vsnprintf(c->err->msg, sizeof c->err->msg, fmt, ap);
    va_end(ap);
    hy_error_prefix(c->err, "%s:%d:%d", cur_file(c), line, col);
    return code;
}

static size_t seen_hash(size_t sec, int key)
{
    uint64_t h = (uint64_t)sec * 0x9e3779b97f4a7c15ULL ^ (uint64_t)(unsigned)(key + 1) * 0xc2b2ae3d27d4eb4fULL;
    return (size_t)(h ^ (h >> 31));
}

/* The slot of (sec, key) in the table: where it is or where it would go. */
static size_t seen_slot(const fstate *fs, size_t sec, int key)
{
    size_t mask = fs->capseen - 1, i = seen_hash(sec, key) & mask;
    while (fs->seen[i].sec && !(fs->seen[i].sec == sec + 1 && fs->seen[i].key == key))
        i = (i + 1) & mask;
    return i;
}

static int push_seen(fstate *fs, size_t sec, int key, int line)
{
    if (2 * (fs->nseen + 1) > fs->capseen) {
        size_t cap = fs->capseen ? 2 * fs->capseen : 64;
        seen *old = fs->seen;
        size_t oldcap = fs->capseen;
        fs->seen = calloc(cap, sizeof *fs->seen);
        if (!fs->seen) {
            fs->seen = old;
            return HY_ENOMEM;
        }
        fs->capseen = cap;
        for (size_t i = 0; i < oldcap; i++)
            if (old[i].sec)
                fs->seen[seen_slot(fs, old[i].sec - 1, old[i].key)] = old[i];
        free(old);
    }
    fs->seen[seen_slot(fs, sec, key)] = (seen){sec + 1, key, line};
    fs->nseen++;
    return HY_OK;
}

static const seen *find_seen(const fstate *fs, size_t sec, int key)
{
    if (!fs->capseen)
        return NULL;
    const seen *x = &fs->seen[seen_slot(fs, sec, key)];
    return x->sec ? x : NULL;
}

/* "[section]" or "[section NAME]" into buf (n >= 2 bytes, cut to fit, the
 * ']' kept).  By hand, not snprintf: it runs for every key of every scene
 * (each hy_steady_loop call), and printf is slow in a process where a printf
 * hook is registered (libquadmath, which NumPy loads). */
static void section_label(const hy_scene *s, size_t si, char *buf, size_t n)
{
    const hy__section *x = &s->secs[si];
    const char *parts[4] = {"[", hy_scene_schema(NULL)[x->spec].name, x->name ? " " : "", x->name ? x->name : ""};
    size_t k = 0;
    for (int i = 0; i < 4; i++)
        for (const char *p = parts[i]; *p && k + 2 < n; p++)
            buf[k++] = *p;
    buf[k++] = ']';
    buf[k] = '\0';
}

static int is_ident(int ch)
{
    return isalnum(ch) || ch == '_' || ch == '-';
}

static int is_label(int ch)
{
    return isalnum(ch) || ch == '_' || ch == '-' || ch == '.';
}

static const char *skip_ws(const char *p, const char *end)
{
    while (p < end && (*p == ' ' || *p == '\t'))
        p++;
    return p;
}

/* Resolves a section header to its spec and checks its name; returns the spec index or -1. */
static int header_spec(pctx *c, fstate *fs, const char *w, size_t wl, const char *nm, size_t nl,
                       int col, int ncol)
{
    size_t nsec;
    const hy_scene_section_spec *spec = hy_scene_schema(&nsec);
    char word[64];
    if (wl >= sizeof word) {
        perr(c, fs->line, col, HY_EINVAL, "section name too long");
        return -1;
    }
    memcpy(word, w, wl);
    word[wl] = '\0';
    int sec = hy_scene_schema_section(word);
    if (sec < 0) {
        const char *cand[32];
        for (size_t i = 0; i < nsec && i < 32; i++)
            cand[i] = spec[i].name;
        const char *sug = hy__suggest(word, cand, nsec < 32 ? nsec : 32);
        perr(c, fs->line, col, HY_EINVAL, "unknown section [%s]%s%s%s", word,
             sug ? "; did you mean '" : "", sug ? sug : "", sug ? "'?" : "");
        return -1;
    }
    if (spec[sec].takes_name && !nl) {
        perr(c, fs->line, col, HY_EINVAL, "section [%s] needs a name, as in [%s NAME]", word, word);
        return -1;
    }
    if (!spec[sec].takes_name && nl) {
        perr(c, fs->line, ncol, HY_EINVAL, "section [%s] takes no name, got '%.*s'", word,
             (int)nl, nm);
        return -1;
    }
    return sec;
}

/* "[section]" or "[section NAME]", then only a comment. */
static int parse_header(pctx *c, fstate *fs, const char *ls, const char *p, const char *end)
{
    const char *w, *nm = NULL;
    size_t wl, nl = 0;
    int ncol = 0, hcol = (int)(p - ls) + 1;
    char ch[8];
    p = skip_ws(p + 1, end);
    w = p;
    while (p < end && is_ident((unsigned char)*p))
        p++;
    wl = (size_t)(p - w);
    if (!wl)
        return perr(c, fs->line, (int)(p - ls) + 1, HY_EINVAL,
                    "bad section header: expected a section name after '['");
    p = skip_ws(p, end);
    if (p < end && *p != ']') {
        nm = p;
        ncol = (int)(p - ls) + 1;
        while (p < end && is_label((unsigned char)*p))
            p++;
        nl = (size_t)(p - nm);
        p = skip_ws(p, end);
    }
    if (p == end || *p != ']' || (nm && !nl))
        return perr(c, fs->line, (int)(p - ls) + 1, HY_EINVAL,
                    "bad section header: expected ']'%s", nm ? " after the section name" : "");
    p = skip_ws(p + 1, end);
    if (p < end && !hy__is_comment(p, end))
        return perr(c, fs->line, (int)(p - ls) + 1, HY_EINVAL,
                    "unexpected '%s' after the section header", hy__char_text(*p, ch));
    int sec = header_spec(c, fs, w, wl, nm, nl, (int)(w - ls) + 1, ncol);
    if (sec < 0)
        return HY_EINVAL;
    char name[128];
    if (nl >= sizeof name)
        return perr(c, fs->line, ncol, HY_EINVAL, "section name too long");
    memcpy(name, nm ? nm : "", nl);
    name[nl] = '\0';
    hy_scene_loc loc = {cur_file(c), fs->line, hcol};
    const hy_scene_section_spec *spec = hy_scene_schema(NULL) + sec;
    if (nl && !spec->repeatable && hy_scene_count(c->s, spec->name) &&
        !hy__scene_find(c->s, sec, name))
        return perr(c, fs->line, ncol, HY_EINVAL, "only one [%s] section is allowed", spec->name);
    hy__section *x = hy__scene_touch(c->s, sec, nl ? name : NULL, loc);
    if (!x)
        return perr(c, fs->line, 1, HY_ENOMEM, "out of memory");
    size_t si = (size_t)(x - c->s->secs);
    const seen *dup = find_seen(fs, si, -1);
    if (dup) {
        char lab[160];
        section_label(c->s, si, lab, sizeof lab);
        return perr(c, fs->line, 1, HY_EINVAL, "duplicate section %s (first at line %d)", lab,
                    dup->line);
    }
    fs->cur = (long)si;
    return push_seen(fs, si, -1, fs->line) ? perr(c, fs->line, 1, HY_ENOMEM, "out of memory")
                                           : HY_OK;
}

/* True if the file instance inst is one of the files including the current one. */
static int is_ancestor(const pctx *c, int inst)
{
    for (int i = 0; i < c->depth - 1; i++)
        if (c->stack[i].inst == inst)
            return 1;
    return 0;
}

static int unknown_key(pctx *c, fstate *fs, const char *key, int col)
{
    const hy__section *x = &c->s->secs[fs->cur];
    const hy_scene_section_spec *spec = hy_scene_schema(NULL) + x->spec;
    const char *cand[64];
    size_t n = spec->nkeys < 64 ? spec->nkeys : 64;
    char lab[160];
    for (size_t i = 0; i < n; i++)
        cand[i] = spec->keys[i].name;
    const char *sug = hy__suggest(key, cand, n);
    section_label(c->s, (size_t)fs->cur, lab, sizeof lab);
    if (sug)
        return perr(c, fs->line, col, HY_EINVAL, "unknown key '%s' in %s; did you mean '%s'?", key,
                    lab, sug);
    char list[300];
    size_t used = 0;
    for (size_t i = 0; i < n && used < sizeof list; i++)
        used += (size_t)snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "", cand[i]);
    return perr(c, fs->line, col, HY_EINVAL, "unknown key '%s' in %s; valid keys are %s", key,
                lab, list);
}

/* Stores a parsed value, applying the include precedence (docs/SCENES.md). */
static int assign(pctx *c, fstate *fs, int k, hy__value *v, int col, const char *key, size_t ref, int refcol)
{
    size_t si = (size_t)fs->cur;
    const seen *dup = find_seen(fs, si, k);
    if (dup) {
        char lab[160];
        hy__value_clear(v);
        section_label(c->s, si, lab, sizeof lab);
        return perr(c, fs->line, col, HY_EINVAL, "duplicate key '%s' in %s (first set at line %d)",
                    key, lab, dup->line);
    }
    if (push_seen(fs, si, k, fs->line)) {
        hy__value_clear(v);
        return perr(c, fs->line, col, HY_ENOMEM, "out of memory");
    }
    hy__slot *slot = &c->s->secs[si].slots[k];
    if (slot->set && is_ancestor(c, slot->inst)) {
        hy__value_clear(v); /* an including file already set it: it wins */
        return HY_OK;
    }
    hy__value_clear(&slot->v);
    slot->v = *v;
    slot->set = 1;
    slot->inst = c->stack[c->depth - 1].inst;
    slot->loc = (hy_scene_loc){cur_file(c), fs->line, col};
    slot->ref = ref;
    slot->refcol = refcol;
    return HY_OK;
}

/* "key = value" inside the current section. */
static int parse_key(pctx *c, fstate *fs, const char *ls, const char *p, const char *end)
{
    const char *k0 = p;
    char key[64];
    int col = (int)(p - ls) + 1;
    while (p < end && (isalnum((unsigned char)*p) || *p == '_'))
        p++;
    size_t kl = (size_t)(p - k0);
    if (!kl) {
        char ch[8];
        return perr(c, fs->line, col, HY_EINVAL,
                    "expected 'key = value', '[section]' or 'include \"file\"', got '%s'",
                    hy__char_text(*p, ch));
    }
    if (kl >= sizeof key)
        return perr(c, fs->line, col, HY_EINVAL, "key name too long");
    memcpy(key, k0, kl);
    key[kl] = '\0';
    p = skip_ws(p, end);
    if (p == end || *p != '=')
        return perr(c, fs->line, (int)(p - ls) + 1, HY_EINVAL, "missing '=' after key '%s'", key);
    if (fs->cur < 0)
        return perr(c, fs->line, col, HY_EINVAL,
                    "key '%s' outside any section (start one with a [section] header)", key);
    int k = hy_scene_schema_key(c->s->secs[fs->cur].spec, key);
    if (k < 0)
        return unknown_key(c, fs, key, col);
    const hy_scene_key_spec *spec = &hy_scene_schema(NULL)[c->s->secs[fs->cur].spec].keys[k];
    char lab[160], msg[400];
    int ecol = 0;
    hy__value v;
    section_label(c->s, (size_t)fs->cur, lab, sizeof lab);
    p++;
    size_t ref = 0;
    int rc = hy__ref_parse(c->s, spec, lab, p, (size_t)(end - p), (int)(p - ls) + 1, &ref, &ecol, msg, sizeof msg);
    if (rc > 0)
        return perr(c, fs->line, ecol, rc, "%s", msg);
    if (rc == 0) { /* the value comes from the parameter once every file is read */
        v = (hy__value){.kind = spec->kind};
        return assign(c, fs, k, &v, col, key, ref, ecol);
    }
    rc = hy__value_parse(spec, lab, c->stack[c->depth - 1].dir, p, (size_t)(end - p),
                             (int)(p - ls) + 1, &v, &ecol, msg, sizeof msg);
    if (rc)
        return perr(c, fs->line, ecol, rc, "%s", msg);
    return assign(c, fs, k, &v, col, key, 0, 0);
}

static int parse_text(pctx *c, const char *text, size_t len);

/* Fails if canon (the real path of an included file) is already on the
 * include stack, naming the chain from its first appearance. */
static int check_cycle(pctx *c, fstate *fs, const char *canon, const char *path, int col)
{
    for (int i = 0; canon && i < c->depth; i++) {
        if (!c->stack[i].canon || strcmp(c->stack[i].canon, canon) != 0)
            continue;
        char chain[400];
        size_t used = 0;
        for (int j = i; j < c->depth && used < sizeof chain; j++)
            used += (size_t)snprintf(chain + used, sizeof chain - used, "%s -> ",
                                     c->s->files[c->stack[j].inst]);
        if (used < sizeof chain)
            snprintf(chain + used, sizeof chain - used, "%s", path);
        return perr(c, fs->line, col, HY_EINVAL, "include cycle: %s", chain);
    }
    return HY_OK;
}

/* Reads, checks (policy, caps, cycle, depth) and parses one included file. */
static int include_file(pctx *c, fstate *fs, const char *rel, int col)
{
    const frame *top = &c->stack[c->depth - 1];
    char *buf = NULL, *canon = NULL, *path = NULL, why[300];
    size_t blen = 0;
    int rc = hy__policy_include(c->s, top->dir, rel, &path, &buf, &blen, &canon, why, sizeof why);
    if (rc)
        return perr(c, fs->line, col, rc, "%s", why);
    rc = check_cycle(c, fs, canon, path, col);
    if (rc)
        goto done;
    if (c->depth >= HY_SCENE_MAX_DEPTH) {
        rc = perr(c, fs->line, col, HY_EINVAL,
                  "includes nested deeper than %d levels at '%s'", HY_SCENE_MAX_DEPTH, rel);
        goto done;
    }
    frame *f = &c->stack[c->depth];
    f->inst = hy__scene_add_file(c->s, path);
    f->dir = hy_path_dir(path);
    f->canon = canon;
    canon = NULL;
    if (f->inst < 0 || !f->dir) {
        free(f->dir);
        free(f->canon);
        rc = perr(c, fs->line, col, HY_ENOMEM, "out of memory");
        goto done;
    }
    c->depth++;
    rc = parse_text(c, buf, blen);
    c->depth--;
    free(f->dir);
    free(f->canon);
done:
    free(canon);
    free(buf);
    free(path);
    return rc;
}

/* `include "file"`. */
static int parse_include(pctx *c, fstate *fs, const char *ls, const char *p, const char *end)
{
    static const hy_scene_key_spec inc = {"include", HY_KIND_STRING, NULL, 0, 0, 0, 0, 0,
                                          NULL, NULL, NULL, NULL, 0, 0, NULL, HY_SCENE_NO_DOMAIN};
    char msg[400];
    int ecol = 0, col;
    hy__value v;
    p = skip_ws(p, end);
    col = (int)(p - ls) + 1;
    if (p == end || hy__is_comment(p, end))
        return perr(c, fs->line, col, HY_EINVAL,
                    "include needs a file name in quotes, as in include \"style.scene\"");
    int rc = hy__value_parse(&inc, "include", NULL, p, (size_t)(end - p), col, &v, &ecol, msg,
                             sizeof msg);
    if (rc)
        return perr(c, fs->line, ecol, rc, "%s", msg);
    if (!v.str[0])
        rc = perr(c, fs->line, col, HY_EINVAL, "include needs a file name");
    else
        rc = include_file(c, fs, v.str, col);
    hy__value_clear(&v);
    return rc;
}

static int parse_line(pctx *c, fstate *fs, const char *ls, const char *end)
{
    const char *p = skip_ws(ls, end);
    if (p == end || hy__is_comment(p, end))
        return HY_OK;
    if (*p == '[')
        return parse_header(c, fs, ls, p, end);
    if ((size_t)(end - p) >= 7 && strncmp(p, "include", 7) == 0 &&
        (end - p == 7 || p[7] == ' ' || p[7] == '\t' || p[7] == '"' || p[7] == '#'))
        return parse_include(c, fs, ls, p + 7, end);
    return parse_key(c, fs, ls, p, end);
}

static int parse_text(pctx *c, const char *text, size_t len)
{
    fstate fs = {NULL, 0, 0, -1, 0};
    const char *p = text, *end = text + len;
    int rc = HY_OK;
    hy__scene_hash_bytes(c->s, text, len);
    hy__scene_hash_bytes(c->s, "\n\377", 2); /* separates files */
    if (len >= 3 && memcmp(p, "\357\273\277", 3) == 0)
        p += 3; /* UTF-8 byte order mark */
    while (p < end && rc == HY_OK) {
        const char *nl = memchr(p, '\n', (size_t)(end - p));
        size_t n = (size_t)((nl ? nl : end) - p);
        fs.line++;
        if (n && p[n - 1] == '\r')
            n--;
        const char *le = p + n;
        if (memchr(p, '\0', n))
            rc = perr(c, fs.line, 1, HY_EINVAL, "NUL byte in scene text");
        else
            rc = parse_line(c, &fs, p, le);
        p = nl ? nl + 1 : end;
    }
    free(fs.seen);
    return rc;
}

/* Parses text as the top file name under pol (NULL: the default). */
static int parse_top(const char *name, const char *text, size_t len, const hy_scene_policy *pol,
                     hy_scene **out, hy_error *err)
{
    *out = NULL;
    hy_scene *s = hy__scene_new(err);
    if (!s)
        return err ? err->code : HY_ENOMEM;
    s->propagate = hy__param_propagate;
    pctx c = {.s = s, .err = err, .depth = 1};
    c.stack[0].inst = hy__scene_add_file(s, name);
    c.stack[0].dir = hy_path_dir(name);
    c.stack[0].canon = realpath(name, NULL);
    int rc;
    if (c.stack[0].inst < 0 || !c.stack[0].dir)
        rc = hy_error_set(err, HY_ENOMEM, "%s: out of memory", name);
    else
        rc = hy__policy_roots(s, c.stack[0].dir, pol, len, err);
    if (!rc)
        rc = parse_text(&c, text, len);
    if (!rc)
        rc = hy__scene_resolve(s, err);
    free(c.stack[0].dir);
    free(c.stack[0].canon);
    if (rc) {
        hy_scene_free(s);
        return rc;
    }
    *out = s;
    return HY_OK;
}

int hy_scene_parse_buffer(const char *name, const char *text, size_t len, hy_scene **out,
                          hy_error *err)
{
    return parse_top(name, text, len, NULL, out, err);
}

int hy_scene_parse_buffer_policy(const char *name, const char *text, size_t len,
                                 const hy_scene_policy *pol, hy_scene **out, hy_error *err)
{
    return parse_top(name, text, len, pol, out, err);
}

int hy_scene_parse_file_policy(const char *path, const hy_scene_policy *pol, hy_scene **out,
                               hy_error *err)
{
    char *buf = NULL;
    size_t len = 0;
    *out = NULL;
    int rc = hy_file_load(path, HY_SCENE_MAX_FILE_BYTES, &buf, &len, "cannot read scene file", err);
    if (rc)
        return rc;
    rc = parse_top(path, buf, len, pol, out, err);
    free(buf);
    return rc;
}

int hy_scene_parse_file(const char *path, hy_scene **out, hy_error *err)
{
    return hy_scene_parse_file_policy(path, NULL, out, err);
}
