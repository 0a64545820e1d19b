/* SPDX-License-Identifier: MIT */
/* export_page.c: the page of `hystviz export`: a dictionary of distinct SVG
 * lines, cairo's path data coded as second differences of k/256 (see
 * export_page.h), gzip and base64 into src/app/export/page.html. */
#include "export_page.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

extern const char hy_export_html[];
extern const size_t hy_export_html_len;

typedef struct slot {
    char *text;     /* a distinct line (owned), NULL: empty slot */
    size_t len;
    size_t index;   /* its chunk index */
} slot;

struct exp_page {
    slot *tab;      /* open addressing, power-of-two size */
    size_t cap, nchunks;
    char *chunks;   /* the chunks array's JSON, items comma-separated */
    size_t chunks_len;
    FILE *cj;
    char *points;   /* the points array's JSON */
    size_t points_len;
    FILE *pj;
    size_t npoints, nrefused;
    char *tok;      /* scratch for coding a path */
    size_t tok_cap;
};

exp_page *exp_page_new(void)
{
    exp_page *pg = calloc(1, sizeof *pg);
    if (!pg)
        return NULL;
    pg->cap = 1024;
    pg->tab = calloc(pg->cap, sizeof *pg->tab);
    pg->cj = open_memstream(&pg->chunks, &pg->chunks_len);
    pg->pj = open_memstream(&pg->points, &pg->points_len);
    if (!pg->tab || !pg->cj || !pg->pj) {
        exp_page_free(pg);
        return NULL;
    }
    return pg;
}

void exp_page_free(exp_page *pg)
{
    if (!pg)
        return;
    for (size_t i = 0; pg->tab && i < pg->cap; i++)
        free(pg->tab[i].text);
    free(pg->tab);
    if (pg->cj)
        fclose(pg->cj);
    if (pg->pj)
        fclose(pg->pj);
    free(pg->chunks);
    free(pg->points);
    free(pg->tok);
    free(pg);
}

size_t exp_page_points(const exp_page *pg, size_t *nrefused)
{
    if (nrefused)
        *nrefused = pg->nrefused;
    return pg->npoints;
}

/* ---- JSON ------------------------------------------------------------- */

void exp_json_str(FILE *f, const char *s, size_t len)
{
    fputc('"', f);
    for (size_t i = 0; i < len; i++) {
        unsigned char c = (unsigned char)s[i];
        if (c == '"' || c == '\\')
            fprintf(f, "\\%c", c);
        else if (c == '\n')
            fputs("\\n", f);
        else if (c < 0x20 || c == '<' || c == '>' || c == '&')
            fprintf(f, "\\u%04x", c);
        else
            fputc(c, f);
    }
    fputc('"', f);
}

/* Whether s holds valid UTF-8 (no overlongs, surrogates or code points past
 * U+10FFFF). */
static int utf8_valid(const unsigned char *s, size_t n)
{
    for (size_t i = 0; i < n;) {
        unsigned c = s[i];
        size_t k = c < 0x80 ? 0 : (c & 0xE0) == 0xC0 ? 1 : (c & 0xF0) == 0xE0 ? 2 : (c & 0xF8) == 0xF0 ? 3 : 9;
        if (k == 9 || (k && i + k >= n))
            return 0;
        uint32_t cp = k == 0 ? c : c & (0x3Fu >> k);
        for (size_t j = 1; j <= k; j++) {
            if ((s[i + j] & 0xC0) != 0x80)
                return 0;
            cp = cp << 6 | (s[i + j] & 0x3Fu);
        }
        if ((k == 1 && cp < 0x80) || (k == 2 && cp < 0x800) || (k == 3 && cp < 0x10000) || cp > 0x10FFFF ||
            (cp >= 0xD800 && cp <= 0xDFFF))
            return 0;
        i += k + 1;
    }
    return 1;
}

/* ---- path coding ------------------------------------------------------ */

/* k/256 as cairo prints it (module comment); returns the length. */
static int fmt256(int64_t k, char *buf)
{
    int neg = k < 0;
    uint64_t m = (uint64_t)(neg ? -k : k) * 15625u; /* k/256 in units of 1e-6, times 4 */
    uint64_t q = m / 4, r = m % 4;
    if (r == 3 || (r == 2 && (q & 1)))
        q++;
    uint64_t ip = q / 1000000, fp = q % 1000000;
    int n = sprintf(buf, "%s%llu", neg ? "-" : "", (unsigned long long)ip);
    if (fp) {
        n += sprintf(buf + n, ".%06llu", (unsigned long long)fp);
        while (buf[n - 1] == '0')
            n--;
        buf[n] = '\0';
    }
    return n;
}

static int cmd_numbers(char c)
{
    return c == 'M' || c == 'L' ? 2 : c == 'C' ? 6 : c == 'Z' ? 0 : -1;
}

/* Codes the path data d[0..n) (module comment) and checks that decoding
 * gives it back; 0 with *cmds (ncmds) and *ks (nks) malloc'd, else -1. */
static int code_path(const char *d, size_t n, char **cmds, size_t *ncmds, int64_t **ks, size_t *nks)
{
    size_t cap = n / 2 + 8;
    *cmds = malloc(cap);
    *ks = malloc(cap * sizeof **ks);
    *ncmds = *nks = 0;
    if (!*cmds || !*ks)
        goto fail;
    const char *p = d, *end = d + n;
    while (p < end) {
        int want = cmd_numbers(*p);
        if (want < 0 || p + 1 >= end || p[1] != ' ')
            goto fail;
        (*cmds)[(*ncmds)++] = *p;
        p += 2;
        for (int j = 0; j < want; j++) {
            char tok[40], *e;
            size_t len = 0;
            while (p + len < end && p[len] != ' ')
                len++;
            if (len == 0 || len >= sizeof tok || p + len >= end)
                goto fail;
            memcpy(tok, p, len);
            tok[len] = '\0';
            double v = strtod(tok, &e);
            if (*e || !(fabs(v) < 1e9))
                goto fail;
            int64_t k = (int64_t)llround(v * 256);
            char back[48];
            if ((size_t)fmt256(k, back) != len || memcmp(back, tok, len))
                goto fail;
            (*ks)[(*nks)++] = k;
            p += len + 1;
        }
    }
    if (p != end || *ncmds == 0) /* every token ended by a space: the last one too */
        goto fail;
    return 0;
fail:
    free(*cmds);
    free(*ks);
    *cmds = NULL;
    *ks = NULL;
    return -1;
}

/* Writes the chunk for a line: a coded path if the line is one (module
 * comment), else the line as a string. */
static void write_chunk(FILE *f, const char *line, size_t len)
{
    const char *d = NULL;
    for (const char *q = line; len > 1000 && q + 3 < line + len; q++)
        if (q[0] == ' ' && q[1] == 'd' && q[2] == '=' && q[3] == '"') {
            d = q + 4;
            break;
        }
    const char *dend = d ? memchr(d, '"', len - (size_t)(d - line)) : NULL;
    char *cmds = NULL;
    int64_t *ks = NULL;
    size_t ncmds, nks;
    if (!dend || dend - d < 2 || dend[-1] != ' ' || code_path(d, (size_t)(dend - d), &cmds, &ncmds, &ks, &nks)) {
        exp_json_str(f, line, len);
        return;
    }
    fputs("{\"h\":", f);
    exp_json_str(f, line, (size_t)(d - line));
    fputs(",\"c\":\"", f);
    fwrite(cmds, 1, ncmds, f);
    fputs("\",\"x\":[", f);
    int64_t prev[2] = {0, 0}, prevd[2] = {0, 0};
    for (size_t j = 0; j < nks; j++) {
        int par = (int)(j & 1);
        int64_t dk = ks[j] - prev[par];
        fprintf(f, "%s%lld", j ? "," : "", (long long)(dk - prevd[par]));
        prev[par] = ks[j];
        prevd[par] = dk;
    }
    fputs("],\"s\":1,\"e\":", f);
    exp_json_str(f, dend, len - (size_t)(dend - line));
    fputc('}', f);
    free(cmds);
    free(ks);
}

/* ---- the dictionary --------------------------------------------------- */

static uint64_t hash(const char *s, size_t n)
{
    uint64_t h = 14695981039346656037ULL;
    for (size_t i = 0; i < n; i++)
        h = (h ^ (unsigned char)s[i]) * 1099511628211ULL;
    return h;
}

static int grow(exp_page *pg)
{
    size_t cap = pg->cap * 2;
    slot *t = calloc(cap, sizeof *t);
    if (!t)
        return -1;
    for (size_t i = 0; i < pg->cap; i++)
        if (pg->tab[i].text) {
            size_t j = hash(pg->tab[i].text, pg->tab[i].len) & (cap - 1);
            while (t[j].text)
                j = (j + 1) & (cap - 1);
            t[j] = pg->tab[i];
        }
    free(pg->tab);
    pg->tab = t;
    pg->cap = cap;
    return 0;
}

/* The chunk index of a line, adding it if new; -1 when out of memory. */
static long chunk_of(exp_page *pg, const char *line, size_t len)
{
    if (2 * (pg->nchunks + 1) > pg->cap && grow(pg))
        return -1;
    size_t j = hash(line, len) & (pg->cap - 1);
    for (; pg->tab[j].text; j = (j + 1) & (pg->cap - 1))
        if (pg->tab[j].len == len && !memcmp(pg->tab[j].text, line, len))
            return (long)pg->tab[j].index;
    char *copy = malloc(len + 1);
    if (!copy)
        return -1;
    memcpy(copy, line, len);
    copy[len] = '\0';
    pg->tab[j] = (slot){copy, len, pg->nchunks};
    if (pg->nchunks)
        fputc(',', pg->cj);
    write_chunk(pg->cj, line, len);
    return (long)pg->nchunks++;
}

int exp_page_add(exp_page *pg, const char *svg, size_t len, hy_error *err)
{
    if (!utf8_valid((const unsigned char *)svg, len))
        return hy_error_set(err, HY_EINVAL, "the SVG of point %zu is not valid UTF-8", pg->npoints);
    fputs(pg->npoints ? ",[" : "[", pg->pj);
    for (size_t at = 0, k = 0; at < len; k++) {
        const char *nl = memchr(svg + at, '\n', len - at);
        size_t n = nl ? (size_t)(nl - (svg + at)) + 1 : len - at;
        long c = chunk_of(pg, svg + at, n);
        if (c < 0)
            return hy_error_set(err, HY_ENOMEM, "out of memory building the page");
        fprintf(pg->pj, "%s%ld", k ? "," : "", c);
        at += n;
    }
    fputc(']', pg->pj);
    pg->npoints++;
    return HY_OK;
}

int exp_page_refused(exp_page *pg, const char *message, hy_error *err)
{
    (void)err;
    if (pg->npoints)
        fputc(',', pg->pj);
    exp_json_str(pg->pj, message, strlen(message));
    pg->npoints++;
    pg->nrefused++;
    return HY_OK;
}

/* ---- gzip, base64, the page ------------------------------------------- */

int exp_gzip(const void *data, size_t n, unsigned char **out, size_t *outlen, hy_error *err)
{
    z_stream z;
    memset(&z, 0, sizeof z);
    *out = NULL;
    if (deflateInit2(&z, 9, Z_DEFLATED, 15 + 16, 9, Z_DEFAULT_STRATEGY) != Z_OK)
        return hy_error_set(err, HY_ENOMEM, "cannot start zlib");
    size_t cap = deflateBound(&z, (uLong)n) + 64;
    if (!(*out = malloc(cap))) {
        deflateEnd(&z);
        return hy_error_set(err, HY_ENOMEM, "out of memory compressing the page");
    }
    z.next_in = (Bytef *)(uintptr_t)data;
    z.avail_in = (uInt)n;
    z.next_out = *out;
    z.avail_out = (uInt)cap;
    int zr = deflate(&z, Z_FINISH);
    *outlen = z.total_out;
    deflateEnd(&z);
    if (zr != Z_STREAM_END) {
        free(*out);
        *out = NULL;
        return hy_error_set(err, HY_ENOMEM, "zlib could not compress the page (%d)", zr);
    }
    return HY_OK;
}

void exp_base64(FILE *f, const unsigned char *s, size_t n)
{
    static const char b64[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (size_t i = 0; i < n; i += 3) {
        uint32_t v = (uint32_t)s[i] << 16 | (i + 1 < n ? (uint32_t)s[i + 1] << 8 : 0) | (i + 2 < n ? s[i + 2] : 0);
        char q[4] = {b64[v >> 18 & 63], b64[v >> 12 & 63], i + 1 < n ? b64[v >> 6 & 63] : '=',
                     i + 2 < n ? b64[v & 63] : '='};
        fwrite(q, 1, 4, f);
        if (i % 57 == 54) /* lines of 76 characters */
            fputc('\n', f);
    }
}

int exp_page_write(exp_page *pg, const char *meta_json, FILE *f, hy_error *err)
{
    if (fflush(pg->cj) || fflush(pg->pj))
        return hy_error_set(err, HY_ENOMEM, "out of memory building the page");
    char *json = NULL;
    size_t jlen = 0;
    FILE *j = open_memstream(&json, &jlen);
    if (!j)
        return hy_error_set(err, HY_ENOMEM, "out of memory building the page");
    fputs("{\"format\":\"hystviz-export 1\",\"chunks\":[", j);
    fwrite(pg->chunks, 1, pg->chunks_len, j);
    fputs("],\"points\":[", j);
    fwrite(pg->points, 1, pg->points_len, j);
    fputs("]}", j);
    if (fclose(j)) {
        free(json);
        return hy_error_set(err, HY_ENOMEM, "out of memory building the page");
    }
    unsigned char *gz;
    size_t gzlen;
    int rc = exp_gzip(json, jlen, &gz, &gzlen, err);
    free(json);
    if (rc)
        return rc;
    const char *t = hy_export_html, *meta = strstr(t, "@META@"), *pay = meta ? strstr(meta, "@PAYLOAD@") : NULL;
    if (!pay) {
        free(gz);
        return hy_error_set(err, HY_EIO, "the page template lacks its @META@ and @PAYLOAD@ marks");
    }
    fwrite(t, 1, (size_t)(meta - t), f);
    fputs(meta_json, f);
    fwrite(meta + 6, 1, (size_t)(pay - meta - 6), f);
    exp_base64(f, gz, gzlen);
    fwrite(pay + 9, 1, hy_export_html_len - (size_t)(pay + 9 - t), f);
    free(gz);
    return HY_OK;
}

int exp_out_finish(hy_out *out, int rc)
{
    hy_error err = {0};
    if (rc)
        hy_out_abort(out);
    else if (hy_out_commit(out, &err)) {
        fprintf(stderr, "hystviz export: %s\n", err.msg);
        rc = 1;
    }
    return rc;
}
