/* hy_status.c: error message formatting (see hy_status.h). */
#include "hy_status.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

int hy_error_set(hy_error *e, int code, const char *fmt, ...)
{
    if (e) {
        /* formatted apart first: an argument may be e->msg itself */
        char msg[sizeof e->msg];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(msg, sizeof msg, fmt, ap);
        va_end(ap);
        e->code = code;
        memcpy(e->msg, msg, sizeof msg);
    }
    return code;
}

void hy_error_prefix(hy_error *e, const char *fmt, ...)
{
    if (!e)
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
}
