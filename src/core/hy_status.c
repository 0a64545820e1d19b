/* SPDX-License-Identifier: MIT */
/* hy_status.c: error message formatting (see hy_status.h). */
#include "hy_status.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* Length of the UTF-8 character at p that a terminal shows as text (not a
 * C1 control, not overlong, not a surrogate), or 0. */
static size_t text_char(const unsigned char *p)
{
    if (*p >= 0x20 && *p < 0x7f)
        return 1;
    size_t n = *p >= 0xc2 && *p <= 0xdf ? 2 : *p >= 0xe0 && *p <= 0xef ? 3 : *p >= 0xf0 && *p <= 0xf4 ? 4 : 0;
    for (size_t k = 1; k < n; k++)
        if ((p[k] & 0xc0) != 0x80)
            return 0;
    if ((n == 2 && *p == 0xc2 && p[1] < 0xa0) || (n == 3 && *p == 0xe0 && p[1] < 0xa0) ||
        (n == 3 && *p == 0xed && p[1] >= 0xa0) || (n == 4 && *p == 0xf0 && p[1] < 0x90) ||
        (n == 4 && *p == 0xf4 && p[1] >= 0x90))
        return 0;
    return n;
}

long hy_text_check(const char *s)
{
    if (!s)
        return -1;
    const unsigned char *p = (const unsigned char *)s;
    while (*p) {
        size_t n = *p == '\t' ? 1 : text_char(p);
        if (!n)
            return (long)(p - (const unsigned char *)s);
        p += n;
    }
    return -1;
}

void hy_text_shown(const char *src, char *dst, size_t size)
{
    const unsigned char *p = (const unsigned char *)src;
    size_t o = 0;
    if (!size || !dst)
        return;
    if (!p)
        p = (const unsigned char *)"";
    while (*p) {
        size_t n = text_char(p);
        if (n) {
            if (o + n >= size)
                break;
            memcpy(dst + o, p, n);
            o += n, p += n;
        } else {
            if (o + 4 >= size)
                break;
            snprintf(dst + o, size - o, "\\x%02x", *p++);
            o += 4;
        }
    }
    dst[o] = '\0';
}

int hy_error_set(hy_error *e, int code, const char *fmt, ...)
{
    if (e && !fmt) {
        e->code = code;
        snprintf(e->msg, sizeof e->msg, "(no message)");
    } else if (e) {
        /* formatted apart first: an argument may be e->msg itself */
        char msg[sizeof e->msg];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(msg, sizeof msg, fmt, ap);
        va_end(ap);
        e->code = code;
        hy_text_shown(msg, e->msg, sizeof e->msg);
    }
    return code;
}

void hy_error_prefix(hy_error *e, const char *fmt, ...)
{
    if (!e || !fmt)
        return;
    char pre[256], old[sizeof e->msg];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(pre, sizeof pre, fmt, ap);
    va_end(ap);
    memcpy(old, e->msg, sizeof old);
    size_t n = strlen(pre);
    if (n > sizeof e->msg - 3)
        n = sizeof e->msg - 3;
    memcpy(e->msg, pre, n);
    e->msg[n] = ':';
    e->msg[n + 1] = ' ';
    size_t room = sizeof e->msg - n - 2;
    size_t m = strlen(old);
    if (m >= room)
        m = room - 1;
    memcpy(e->msg + n + 2, old, m);
    e->msg[n + 2 + m] = '\0';
    hy_text_shown(e->msg, old, sizeof old); /* the prefix is text as well */
    memcpy(e->msg, old, sizeof old);
}
