/* SPDX-License-Identifier: MIT */
/* serve_util.c: see serve_util.h. */
#include "serve_util.h"
#include "hy_scene_decl.h"
#include "scene_fit.h"
#include "scene_model.h"

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#if defined(__linux__) && __has_include(<linux/openat2.h>)
#include <linux/openat2.h>
#define SV_HAVE_OPENAT2 1
#endif


/* ---- text buffer ---------------------------------------------------- */

void sv_add(sv_buf *b, const char *s, size_t n)
{
    if (b->oom)
        return;
    if (b->len + n + 1 > b->cap) {
        size_t cap = b->cap ? b->cap : 1024;
        while (cap < b->len + n + 1)
            cap *= 2;
        char *ns = realloc(b->s, cap);
        if (!ns) {
            b->oom = 1;
            return;
        }
        b->s = ns;
        b->cap = cap;
    }
    memcpy(b->s + b->len, s, n);
    b->len += n;
    b->s[b->len] = '\0';
}

void sv_puts(sv_buf *b, const char *s) { sv_add(b, s, strlen(s)); }

void sv_printf(sv_buf *b, const char *fmt, ...)
{
    char tmp[512];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(tmp, sizeof tmp, fmt, ap);
    va_end(ap);
    if (n < 0) {
        b->oom = 1;
        return;
    }
    if ((size_t)n < sizeof tmp) {
        sv_add(b, tmp, (size_t)n);
        return;
    }
    char *big = malloc((size_t)n + 1);
    if (!big) {
        b->oom = 1;
        return;
    }
    va_start(ap, fmt);
    vsnprintf(big, (size_t)n + 1, fmt, ap);
    va_end(ap);
    sv_add(b, big, (size_t)n);
    free(big);
}

void sv_json(sv_buf *b, const char *s)
{
    sv_add(b, "\"", 1);
    const char *run = s;
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c >= 0x20 && c != '"' && c != '\\' && c != '<' && c != '>' && c != '&')
            continue;
        sv_add(b, run, (size_t)(s - run));
        run = s + 1;
        switch (c) {
        case '"': sv_add(b, "\\\"", 2); break;
        case '\\': sv_add(b, "\\\\", 2); break;
        case '\n': sv_add(b, "\\n", 2); break;
        case '\t': sv_add(b, "\\t", 2); break;
        case '\r': sv_add(b, "\\r", 2); break;
        default: sv_printf(b, "\\u%04x", c); break; /* controls, and < > & (safe inside HTML) */
        }
    }
    sv_add(b, run, (size_t)(s - run));
    sv_add(b, "\"", 1);
}

void sv_shell(sv_buf *b, const char *s)
{
    int plain = *s != '\0';
    for (const char *p = s; *p; p++)
        if (!strchr("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.,/:=+@%", *p))
            plain = 0;
    if (plain) {
        sv_puts(b, s);
        return;
    }
    sv_add(b, "'", 1);
    for (const char *p = s; *p; p++)
        if (*p == '\'')
            sv_puts(b, "'\\''");
        else
            sv_add(b, p, 1);
    sv_add(b, "'", 1);
}

void sv_num(sv_buf *b, double v)
{
    if (!isfinite(v)) {
        sv_puts(b, "null");
        return;
    }
    char tmp[40];
    /* at least as many digits as the integer part has, so 30 is "30", not "3e+01" */
    int p0 = fabs(v) >= 1 ? (int)floor(log10(fabs(v))) + 1 : 1;
    for (int p = p0 < 17 ? p0 : 17; p <= 17; p++) {
        snprintf(tmp, sizeof tmp, "%.*g", p, v);
        if (strtod(tmp, NULL) == v)
            break;
    }
    sv_puts(b, tmp);
}

/* ---- names and overrides -------------------------------------------- */

int sv_scene_name_ok(const char *name)
{
    size_t n = strlen(name);
    if (n <= 6 || n > 200 || name[0] == '.' || strcmp(name + n - 6, ".scene"))
        return 0;
    for (size_t i = 0; i < n; i++) {
        char c = name[i];
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
              c == '.'))
            return 0;
    }
    return !strstr(name, "..");
}

/* What a page may set: by section, the kinds of key (an allow-list: a key
 * of any other section or kind, a PATH above all, is refused).  The README
 * ("hystviz serve") and serve --help describe this table. */
#define K(kind) (1u << (kind))
#define PAGE_VALUES                                                                                              \
    (K(HY_KIND_NUMBER) | K(HY_KIND_INTEGER) | K(HY_KIND_BOOL) | K(HY_KIND_ENUM) | K(HY_KIND_LENGTH) |            \
     K(HY_KIND_LENGTH_PAIR) | K(HY_KIND_COLOR) | K(HY_KIND_PAIR) | K(HY_KIND_LIMITS) | K(HY_KIND_NUMBER_LIST) | \
     K(HY_KIND_INTEGER_LIST))
static const struct {
    const char *section;
    unsigned kinds;
} page_settable[] = {
    {"model", PAGE_VALUES},  {"input", PAGE_VALUES},  {"compute", PAGE_VALUES},
    {"series", PAGE_VALUES}, {"figure", PAGE_VALUES}, {"annotation", PAGE_VALUES},
    {"param", PAGE_VALUES},  {"forc", PAGE_VALUES},
};

const char *sv_settable_sections(void) { return "model, input, compute, series, figure, annotation, param and forc"; }

int sv_set_ok(const char *set, hy_error *err)
{
    if (strlen(set) > 300)
        return hy_error_set(err, HY_EINVAL, "--set: an override longer than 300 bytes is refused here");
    char *sec, *name, *key;
    const char *value;
    /* the parser hy_scene_set applies: what is checked here is what is set */
    int rc = hy_scene_set_split(set, &sec, &name, &key, &value, err);
    unsigned kinds = 0;
    for (size_t i = 0; !rc && i < sizeof page_settable / sizeof page_settable[0]; i++)
        if (!strcmp(sec, page_settable[i].section))
            kinds = page_settable[i].kinds;
    int si = rc ? -1 : hy_scene_schema_section(sec);
    int ki = si < 0 ? -1 : hy_scene_schema_key(si, key);
    size_t n;
    const hy_scene_section_spec *spec = hy_scene_schema(&n);
    if (!rc && !kinds)
        rc = hy_error_set(err, HY_EINVAL, "--set %s: a page may set keys of [%s] only", set,
                          sv_settable_sections());
    else if (!rc && ki >= 0 && !(kinds & K(spec[si].keys[ki].kind)))
        rc = hy_error_set(err, HY_EINVAL, "--set %s: %s is a %s; a page may set numbers, switches, choices, lengths "
                          "and colours, never a file path or text", set, key,
                          spec[si].keys[ki].kind == HY_KIND_PATH ? "file path" : "text key");
    free(sec);
    free(name);
    free(key);
    return rc; /* an unknown key is left to hy_scene_set, with the CLI's message */
}
#undef K

/* ---- controls ------------------------------------------------------- */

/* The parameters a model kind or input kind has (shown with their defaults
 * when the scene leaves them unset). */
static int wanted(const char *sec, const char *kind, const char *key)
{
    static const char *const bimodal[] = {"umin1", "umin2", "umax1", "umax2", NULL};
    const char *const *l = NULL;
    if (!strcmp(sec, "model")) { /* the model's own keys, from the model table */
        const hy_scene_model *mt = hy_scene_model_find(kind);
        return mt && strcmp(key, "kind") && hy_scene_model_has_key(mt, key);
    }
    if (!strcmp(sec, "input") && !strcmp(kind, "bimodal"))
        l = bimodal;
    for (size_t i = 0; l && l[i]; i++)
        if (!strcmp(l[i], key))
            return 1;
    return 0;
}

/* Whether the computation reads key k of section sec (reads: hy_scene_reads'
 * bits): the model only when a series needs its dynamics, or the keys of its
 * g(v) (rows flagged HY_SPEC_G) for data = g; the input unless only g is drawn. */
static int is_read(const char *sec, const hy_scene_key_spec *k, unsigned reads)
{
    if (!strcmp(sec, "input"))
        return (reads & HY_READS_INPUT) != 0;
    if (strcmp(sec, "model") || (reads & HY_READS_MODEL))
        return 1;
    return (reads & HY_READS_G) && (k->flags & HY_SPEC_G);
}

/* One control of value v: of key k of [sec label], or with param (the name
 * of a [param NAME] that the key reads, and others with it) of that
 * parameter, with k's symbol, unit and range. */
static void control(sv_buf *b, int *first, double v, const hy_scene_key_spec *k, const char *sec, const char *label,
                    int set, const char *model, const char *input, int main, const char *param)
{
    double lo, hi;
    int lg;
    hy_scene_key_range(k, v, &lo, &hi, &lg); /* the fitter's bounds too */
    /* the key's domain given the others (its schema row; a parameter's: none) */
    const hy_scene_model *mt = hy_scene_model_find(model);
    const hy_scene_domain *dm = param ? NULL : &k->dom;
    if (dm && dm->takers && !(mt && (mt->inputs & dm->takers)))
        dm = NULL;
    int order = dm && (!dm->kind || !strcmp(dm->kind, input));
    if (dm && dm->lo < dm->hi && dm->lo <= v && v <= dm->hi) {
        lo = lo > dm->lo ? lo : dm->lo;
        hi = hi < dm->hi ? hi : dm->hi;
        lg = lo > 0 && hi / lo >= 50;
    }
    char range[64];
    hy_scene_range_text(k, range, sizeof range);
    sv_puts(b, *first ? "{\"key\":" : ",{\"key\":");
    *first = 0;
    char full[160];
    if (param)
        snprintf(full, sizeof full, "param.%s.value", param);
    else if (label)
        snprintf(full, sizeof full, "%s.%s.%s", sec, label, k->name);
    else
        snprintf(full, sizeof full, "%s.%s", sec, k->name);
    sv_json(b, full);
    sv_puts(b, ",\"value\":\"");
    sv_num(b, v);
    sv_printf(b, "\",\"set\":%s,\"int\":%s,\"lo\":", set ? "true" : "false", k->kind == HY_KIND_INTEGER ? "true" : "false");
    sv_num(b, lo);
    sv_puts(b, ",\"hi\":");
    sv_num(b, hi);
    sv_printf(b, ",\"log\":%s,\"range\":", lg ? "true" : "false");
    sv_json(b, range);
    sv_puts(b, ",\"doc\":");
    if (param) {
        char doc[300];
        snprintf(doc, sizeof doc, "$%s, read by every key written '= $%s' (%s: %s)", param, param, k->name,
                 k->doc ? k->doc : "");
        sv_json(b, doc);
    } else
        sv_json(b, k->doc ? k->doc : "");
    sv_puts(b, ",\"sym\":");
    sv_json(b, k->symbol ? k->symbol : "");
    sv_puts(b, ",\"unit\":");
    sv_json(b, k->unit ? k->unit : "");
    sv_printf(b, ",\"main\":%d", main);
    if (order) {
        const char *const part[3][2] = {{"above", dm->above}, {"below", dm->below}, {"per", dm->per}};
        for (int j = 0; j < 3; j++)
            if (part[j][1]) {
                sv_printf(b, ",\"%s\":", part[j][0]);
                sv_json(b, part[j][1]);
            }
    }
    if (dm && dm->work)
        sv_puts(b, ",\"work\":true");
    sv_puts(b, "}");
}

/* The place (1-9) of section.[label.]key in the [controls] main keys, 0 if none. */
static int main_place(char (*mains)[HY_SCENE_KEY_MAX], size_t nmain, const char *full)
{
    for (size_t m = 0; m < nmain; m++)
        if (!strcmp(mains[m], full))
            return (int)m + 1;
    return 0;
}

void sv_controls_json(sv_buf *b, const hy_scene *s, const hy_scene_doc *d, unsigned reads)
{
    static const char *const secs[] = {"model", "input", "compute", "series", "forc"};
    size_t nsec;
    const hy_scene_section_spec *spec = hy_scene_schema(&nsec);
    char mains[9][HY_SCENE_KEY_MAX];
    size_t nmain = 0;
    hy_error err = {0};
    if (hy_scene_main_keys(s, mains, 9, &nmain, &err))
        nmain = 0; /* the render says what is wrong */
    const char *model = hy_decl_enum_text(&d->model.h, offsetof(hy_decl_model, kind), d->model.kind);
    const char *input = hy_decl_enum_text(&d->input.h, offsetof(hy_decl_input, kind), d->input.kind);
    int first = 1;
    const char *fed[64]; /* the parameters shown so far */
    size_t nfed = 0;
    sv_puts(b, "[");
    for (size_t i = 0; i < sizeof secs / sizeof secs[0]; i++) {
        int si = hy_scene_schema_section(secs[i]);
        if (si < 0)
            continue;
        const hy_scene_section_spec *ss = &spec[si];
        const char *kind = !strcmp(secs[i], "model") ? model : !strcmp(secs[i], "input") ? input : "";
        const hy_decl_head *h;
        for (size_t l = 0; (h = hy_scene_doc_at(d, secs[i], l)) != NULL; l++) {
            const char *label = ss->takes_name ? h->name : NULL;
            for (size_t j = 0; j < ss->nkeys && j < HY_SCENE_KEYS_MAX; j++) {
                const hy_scene_key_spec *k = &ss->keys[j];
                if ((k->kind != HY_KIND_NUMBER && k->kind != HY_KIND_INTEGER) || !is_read(secs[i], k, reads))
                    continue;
                double v = 0;
                int got = hy_decl_num(h, k->name, &v);
                char full[HY_SCENE_KEY_MAX + 64];
                snprintf(full, sizeof full, "%s.%s%s%s", secs[i], label ? label : "", label ? "." : "", k->name);
                int main = main_place(mains, nmain, full);
                const char *ref = h->at[j].ref;
                if (ref) { /* one control for the parameter, at its first reader */
                    size_t p = 0;
                    while (p < nfed && strcmp(fed[p], ref))
                        p++;
                    const hy_decl_head *ph = hy_scene_doc_find(d, "param", ref);
                    if (p < nfed || nfed == sizeof fed / sizeof fed[0] || !ph || hy_decl_num(ph, "value", &v) != HY_SCENE_SET)
                        continue;
                    fed[nfed++] = ref;
                    snprintf(full, sizeof full, "param.%s.value", ref);
                    control(b, &first, v, k, secs[i], label, 1, model, input, main_place(mains, nmain, full), ref);
                } else if (got == HY_SCENE_SET || (got == HY_SCENE_DEFAULT && (main || wanted(secs[i], kind, k->name))))
                    control(b, &first, v, k, secs[i], label, got == HY_SCENE_SET, model, input, main, NULL);
            }
        }
    }
    sv_puts(b, "]");
}

void sv_presets_json(sv_buf *b, const hy_scene *s, const hy_scene_doc *d)
{
    sv_puts(b, "[");
    char (*sets)[HY_SCENE_SET_MAX] = malloc(HY_SCENE_PRESET_MAX * sizeof *sets);
    for (size_t i = 0, first = 1; sets && i < d->npreset; i++) {
        const hy_decl_preset *p = &d->preset[i];
        const char *name = p->h.name;
        size_t n;
        hy_error err = {0};
        /* the set text split and checked against the schema as --set is (the
           scene's function, which names a bad value's place) */
        if (hy_scene_preset_sets(s, name, sets, HY_SCENE_PRESET_MAX, &n, &err))
            continue; /* the render says what is wrong (hy_scene_run_validate) */
        sv_puts(b, first ? "{\"name\":" : ",{\"name\":");
        first = 0;
        sv_json(b, name);
        sv_puts(b, ",\"label\":");
        sv_json(b, hy_decl_got(&p->h, offsetof(hy_decl_preset, label)) == HY_SCENE_SET ? p->label : name);
        sv_puts(b, ",\"sets\":[");
        for (size_t j = 0; j < n; j++) {
            if (j)
                sv_puts(b, ",");
            sv_json(b, sets[j]);
        }
        sv_puts(b, "]}");
    }
    free(sets);
    sv_puts(b, "]");
}

/* ---- save as new scene ---------------------------------------------- */

char *sv_read_file(const char *path, size_t max, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *buf = malloc(max + 1);
    size_t n = buf ? fread(buf, 1, max + 1, f) : 0;
    int bad = !buf || ferror(f) || n > max;
    fclose(f);
    if (bad) {
        free(buf);
        errno = buf ? EFBIG : ENOMEM;
        return NULL;
    }
    buf[n] = '\0';
    *len = n;
    return buf;
}

/* Opens name below dirfd once: openat2 with RESOLVE_BENEATH (links that stay
 * inside are followed) where the kernel has it, else openat with O_NOFOLLOW
 * (name is one component, so no link at all). */
static int open_beneath(int dirfd, const char *name)
{
    int flags = O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK;
#ifdef SV_HAVE_OPENAT2
    struct open_how how;
    memset(&how, 0, sizeof how);
    how.flags = (unsigned long long)flags;
    how.resolve = RESOLVE_BENEATH | RESOLVE_NO_MAGICLINKS;
    long fd = syscall(SYS_openat2, dirfd, name, &how, sizeof how);
    if (fd >= 0 || (errno != ENOSYS && errno != EPERM))
        return (int)fd;
#endif
    return openat(dirfd, name, flags | O_NOFOLLOW);
}

char *sv_read_beneath(int dirfd, const char *name, size_t max, size_t *len)
{
    if (!sv_scene_name_ok(name)) {
        errno = ENOENT;
        return NULL;
    }
    int fd = open_beneath(dirfd, name);
    if (fd < 0)
        return NULL;
    struct stat st;
    char *buf = NULL;
    int e = 0;
    if (fstat(fd, &st))
        e = errno;
    else if (!S_ISREG(st.st_mode))
        e = EINVAL; /* a FIFO, a device, a directory: never read */
    else if (st.st_size < 0 || (size_t)st.st_size > max)
        e = EFBIG;
    else if (!(buf = malloc((size_t)st.st_size + 1)))
        e = ENOMEM;
    size_t n = 0;
    while (!e) { /* through the descriptor checked above; a file that grew is refused */
        ssize_t r = read(fd, buf + n, (size_t)st.st_size + 1 - n);
        if (r < 0 && errno == EINTR)
            continue;
        if (r < 0)
            e = errno;
        else if (r == 0)
            break;
        else if ((n += (size_t)r) > (size_t)st.st_size)
            e = EFBIG;
    }
    close(fd);
    if (e) {
        free(buf);
        errno = e;
        return NULL;
    }
    buf[n] = '\0';
    *len = n;
    return buf;
}

typedef struct line_edit {
    int after;      /* insert after this line (1-based); 0: append at the end */
    int replace;    /* replace this line instead (1-based), or 0 */
    char text[400];
} line_edit;

static int same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    return !strcmp(a, b) || (!stat(a, &sa) && !stat(b, &sb) && sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino);
}

/* The override a ("section[.label].key=value") as an edit of the file at
 * path (d: where the file writes each key and section header), appended to
 * ed[*ned]: a line replaced, a line after a section header, or a new
 * section at the end (one for all the keys of a section the file lacks).
 * HY_OK, or HY_EINVAL with err. */
static int edit_of(line_edit *ed, size_t *ned, const hy_scene_doc *d, const char *path, const char *a, hy_error *err)
{
    const char *eq = strchr(a, '=');
    const char *d1 = eq ? memchr(a, '.', (size_t)(eq - a)) : NULL;
    const char *d2 = eq;
    while (d2 && d2 > a && d2[-1] != '.')
        d2--;
    if (!eq || !d1 || d2 - 1 < d1)
        return hy_error_set(err, HY_EINVAL, "--set %s: expected section.key=value", a);
    char sec[64], label[128] = "", key[64];
    snprintf(sec, sizeof sec, "%.*s", (int)(d1 - a), a);
    snprintf(key, sizeof key, "%.*s", (int)(eq - d2), d2);
    if (d2 - 1 > d1)
        snprintf(label, sizeof label, "%.*s", (int)(d2 - 1 - d1 - 1), d1 + 1);
    const char *lb = label[0] ? label : NULL;
    line_edit *e = &ed[(*ned)++];
    const hy_decl_head *h = hy_scene_doc_find(d, sec, lb);
    hy_scene_loc kl = h ? hy_decl_loc(h, hy_decl_offset(h, key)) : (hy_scene_loc){path, 0, 0};
    snprintf(e->text, sizeof e->text, "%s = %s", key, eq + 1);
    if (kl.line > 0 && same_file(kl.file, path))
        e->replace = kl.line;
    else if (h && h->loc.line > 0 && same_file(h->loc.file, path))
        e->after = h->loc.line;
    else if (lb) /* a named section from an include: hy_scene_set refused it already */
        return hy_error_set(err, HY_EINVAL, "--set %s: [%s %s] is not in %s", a, sec, lb, path);
    else {
        /* a section the file lacks: one new section for all its keys */
        char head[80];
        snprintf(head, sizeof head, "\n[%s]\n", sec);
        line_edit *prev = NULL;
        for (size_t j = 0; j + 1 < *ned; j++)
            if (!ed[j].after && !ed[j].replace && !strncmp(ed[j].text, head, strlen(head)))
                prev = &ed[j];
        if (prev) {
            size_t l = strlen(prev->text);
            snprintf(prev->text + l, sizeof prev->text - l, "\n%s = %s", key, eq + 1);
            (*ned)--;
        } else
            snprintf(e->text, sizeof e->text, "%s%s = %s", head, key, eq + 1);
    }
    return HY_OK;
}

/* Appends text with the edits applied: each line replaced or followed as
 * an edit says, then the new sections. */
static void apply_edits(sv_buf *b, const char *text, const line_edit *ed, size_t ned)
{
    int line = 1;
    const char *p = text;
    while (*p) {
        const char *nl = strchr(p, '\n');
        size_t n = nl ? (size_t)(nl - p) : strlen(p);
        int replaced = 0;
        for (size_t i = 0; i < ned; i++)
            if (ed[i].replace == line && !replaced) {
                sv_puts(b, ed[i].text);
                replaced = 1;
            }
        if (!replaced)
            sv_add(b, p, n);
        sv_puts(b, "\n");
        for (size_t i = 0; i < ned; i++)
            if (ed[i].after == line) {
                sv_puts(b, ed[i].text);
                sv_puts(b, "\n");
            }
        p += n + (nl ? 1 : 0);
        line++;
    }
    for (size_t i = 0; i < ned; i++)
        if (!ed[i].after && !ed[i].replace) {
            sv_puts(b, ed[i].text);
            sv_puts(b, "\n");
        }
}

char *sv_scene_with_sets(const hy_scene *s, const char *path, const char *text, char *const *sets, size_t nsets,
                         const char *out_name, hy_error *err)
{
    line_edit *ed = calloc(nsets + 1, sizeof *ed);
    hy_scene_doc d = {0}; /* where the file writes each key and section header */
    if (!ed || hy_scene_decode_fill(s, &d, err)) {
        free(ed);
        hy_scene_doc_free(&d);
        return hy_error_set(err, HY_ENOMEM, "out of memory"), NULL;
    }
    size_t ned = 0;
    char outset[300];
    snprintf(outset, sizeof outset, "output.name=%s", out_name);
    int rc = HY_OK;
    for (size_t i = 0; !rc && i <= nsets; i++)
        rc = edit_of(ed, &ned, &d, path, i < nsets ? sets[i] : outset, err);
    sv_buf b = {0};
    if (!rc) {
        sv_printf(&b, "# saved by hystviz serve from %s", path);
        for (size_t i = 0; i < nsets; i++)
            sv_printf(&b, " --set %s", sets[i]);
        sv_puts(&b, "\n");
        apply_edits(&b, text, ed, ned);
    }
    free(ed);
    hy_scene_doc_free(&d);
    if (rc)
        return NULL;
    if (b.oom) {
        free(b.s);
        return hy_error_set(err, HY_ENOMEM, "out of memory"), NULL;
    }
    return b.s;
}

int sv_write_new(const char *path, const char *text, size_t len, hy_error *err)
{
    const char *slash = strrchr(path, '/');
    char tmp[4200];
    if (slash)
        snprintf(tmp, sizeof tmp, "%.*s/.%s.hystviz-tmp.XXXXXX", (int)(slash - path), path, slash + 1);
    else
        snprintf(tmp, sizeof tmp, ".%s.hystviz-tmp.XXXXXX", path); /* hy_out's temporary names */
    int fd = mkstemp(tmp);
    if (fd < 0)
        return hy_error_set(err, HY_EIO, "cannot write next to %s: %s", path, strerror(errno));
    fchmod(fd, 0644);
    size_t done = 0;
    int e = 0;
    while (done < len && !e) {
        ssize_t w = write(fd, text + done, len - done);
        if (w < 0 && errno != EINTR)
            e = errno;
        else if (w > 0)
            done += (size_t)w;
    }
    if (!e && fsync(fd))
        e = errno;
    if (close(fd) && !e)
        e = errno;
    int rc = HY_OK;
    if (e)
        rc = hy_error_set(err, HY_EIO, "cannot write %s: %s", path, strerror(e));
    else if (link(tmp, path)) /* never replaces: EEXIST if the name is taken */
        rc = errno == EEXIST ? hy_error_set(err, HY_EINVAL, "%s exists already: choose another name", path)
                             : hy_error_set(err, HY_EIO, "cannot write %s: %s", path, strerror(errno));
    unlink(tmp);
    return rc;
}
