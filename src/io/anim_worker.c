/* SPDX-License-Identifier: MIT */
/* anim_worker.c: the length-prefixed frame protocol of hystviz-animate
 * --worker (anim_worker.h): requests read and encoded, records written and
 * their headers parsed.  No GL here: hystviz serve links it too. */
#include "anim_worker.h"

#include <stdlib.h>
#include <string.h>

/* One header line (at most size - 1 bytes, without its newline) into buf;
 * 0, 1 at the end of input before any byte, -1 for a line too long or cut. */
static int read_line(FILE *in, char *buf, size_t size)
{
    size_t n = 0;
    for (;;) {
        int c = getc(in);
        if (c == EOF)
            return n ? -1 : 1;
        if (c == '\n')
            break;
        if (n + 1 >= size)
            return -1;
        buf[n++] = (char)c;
    }
    buf[n] = '\0';
    return 0;
}

/* One field "TAG LEN\n<bytes>": its tag (16 bytes) and malloc'd, NUL-terminated bytes. */
static int read_field(FILE *in, char tag[16], char **data, size_t *len, hy_error *err)
{
    char line[64], extra;
    unsigned long long n;
    if (read_line(in, line, sizeof line) || sscanf(line, "%15s %llu%c", tag, &n, &extra) != 2 || n > AW_MAX_FIELD)
        return hy_error_set(err, HY_EINVAL, "worker: a field is not 'TAG LEN' with LEN <= %u", AW_MAX_FIELD);
    if (!(*data = malloc((size_t)n + 1)))
        return hy_error_set(err, HY_ENOMEM, "worker: out of memory for a %llu-byte field", n);
    if (fread(*data, 1, (size_t)n, in) != (size_t)n) {
        free(*data);
        *data = NULL;
        return hy_error_set(err, HY_EINVAL, "worker: the input ended inside a field");
    }
    (*data)[n] = '\0';
    *len = (size_t)n;
    return HY_OK;
}

/* Files one field into rq, or refuses it. */
static int take_field(aw_request *rq, const char *tag, char *data, size_t len, hy_error *err)
{
    if (strcmp(tag, "text") && (len > AW_MAX_NAME || strlen(data) != len)) {
        free(data);
        return hy_error_set(err, HY_EINVAL, "worker: a %s field holds a NUL or passes %d bytes", tag, AW_MAX_NAME);
    }
    char **slot = !strcmp(tag, "name") ? &rq->name : !strcmp(tag, "text") ? &rq->text : NULL;
    if (slot && !*slot) {
        *slot = data;
        if (slot == &rq->text)
            rq->len = len;
        return HY_OK;
    }
    if (!strcmp(tag, "set") && rq->nsets < AW_MAX_SETS) {
        rq->sets[rq->nsets++] = data;
        return HY_OK;
    }
    free(data);
    return hy_error_set(err, HY_EINVAL, "worker: unexpected field '%s' (name and text once, set at most %d times)",
                        tag, AW_MAX_SETS);
}

int aw_request_read(FILE *in, aw_request *rq, hy_error *err)
{
    memset(rq, 0, sizeof *rq);
    char line[160], magic[8], extra;
    long first, last;
    int w, h, nfields;
    int r = read_line(in, line, sizeof line);
    if (r == 1)
        return AW_END;
    if (r || sscanf(line, "%7s %7s %ld %ld %d %d %d%c", magic, rq->op, &first, &last, &w, &h, &nfields, &extra) != 7 ||
        strcmp(magic, "hvw1") || (strcmp(rq->op, "frames") && strcmp(rq->op, "info")) || first < 0 || last < first ||
        w < 0 || h < 0 || w > 8192 || h > 8192 || nfields < 1 || nfields > AW_MAX_SETS + 2)
        return hy_error_set(err, HY_EINVAL, "worker: not a request header 'hvw1 frames|info FIRST LAST W H NFIELDS'");
    rq->first = first, rq->last = last, rq->width = w, rq->height = h;
    int st = HY_OK;
    for (int i = 0; i < nfields && !st; i++) {
        char tag[16], *data = NULL;
        size_t len = 0;
        st = read_field(in, tag, &data, &len, err);
        if (!st)
            st = take_field(rq, tag, data, len, err);
    }
    if (!st && !rq->name)
        st = hy_error_set(err, HY_EINVAL, "worker: a request needs a name field");
    if (st)
        aw_request_free(rq);
    return st;
}

/* Appends a field to the growing buffer; -1 when out of memory. */
static int put_field(char **buf, size_t *len, size_t *cap, const char *tag, const char *data, size_t n)
{
    char head[48];
    int h = snprintf(head, sizeof head, "%s %zu\n", tag, n);
    size_t need = *len + (size_t)h + n;
    if (need > *cap) {
        size_t c = need * 2;
        char *g = realloc(*buf, c);
        if (!g)
            return -1;
        *buf = g, *cap = c;
    }
    memcpy(*buf + *len, head, (size_t)h);
    if (n)
        memcpy(*buf + *len + h, data, n);
    *len = need;
    return 0;
}

char *aw_request_encode(const aw_request *rq, size_t *len)
{
    size_t cap = 256 + (rq->text ? rq->len : 0), n = 0;
    char *buf = malloc(cap);
    if (!buf)
        return NULL;
    int nf = 1 + (rq->text != NULL) + (int)rq->nsets;
    n = (size_t)snprintf(buf, cap, "hvw1 %s %ld %ld %d %d %d\n", rq->op, rq->first, rq->last, rq->width, rq->height, nf);
    int bad = put_field(&buf, &n, &cap, "name", rq->name, strlen(rq->name));
    if (rq->text)
        bad = bad || put_field(&buf, &n, &cap, "text", rq->text, rq->len);
    for (size_t i = 0; i < rq->nsets; i++)
        bad = bad || put_field(&buf, &n, &cap, "set", rq->sets[i], strlen(rq->sets[i]));
    if (bad) {
        free(buf);
        return NULL;
    }
    *len = n;
    return buf;
}

void aw_request_free(aw_request *rq)
{
    free(rq->name);
    free(rq->text);
    for (size_t i = 0; i < rq->nsets; i++)
        free(rq->sets[i]);
    memset(rq, 0, sizeof *rq);
}

int aw_record_write(FILE *out, const char *tag, long num, const void *data, size_t len)
{
    if (fprintf(out, "%s %ld %zu\n", tag, num, len) < 0 || (len && fwrite(data, 1, len, out) != len))
        return -1;
    return fflush(out) ? -1 : 0;
}

int aw_record_head(const char *line, char tag[8], long *num, size_t *len)
{
    char extra;
    unsigned long long n;
    if (sscanf(line, "%7s %ld %llu%c", tag, num, &n, &extra) != 3 || n > (64u << 20))
        return -1;
    *len = (size_t)n;
    return 0;
}
