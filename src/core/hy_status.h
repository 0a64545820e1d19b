/* SPDX-License-Identifier: MIT */
/* hy_status.h: status codes and error messages shared by every hystviz module.
 *
 * Every fallible function returns an int status (HY_OK = 0 on success) and,
 * when given a non-NULL hy_error *, writes one human-readable sentence into it
 * that names the offending parameter or file.  A failed call leaves its
 * outputs untouched unless its header says otherwise.
 *
 * Pointers (every installed header): an hy_error * may always be NULL (no
 * message).  Each function's comment says which of its other pointer
 * arguments may be NULL and what that means; one it says must not be NULL,
 * or a number outside its domain (a NaN or infinite value where a finite one
 * is wanted, a size out of range), is refused the header's way, never with a
 * crash: an int status function returns HY_EINVAL with "FUNCTION: X must not
 * be NULL" (or the number named) and writes no output, a function returning
 * a double returns NaN, a size returns 0, a pointer NULL, and a void
 * function does nothing.
 *
 *     hy_error err;
 *     if (hy_model_validate(&m, &err)) { fprintf(stderr, "%s\n", err.msg); ... }
 */
#ifndef HY_STATUS_H
#define HY_STATUS_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

enum {
    HY_OK = 0,
    HY_EINVAL = 1,  /* a parameter or input is outside its domain      */
    HY_ENOMEM = 2,  /* an allocation failed                             */
    HY_ENUM = 3,    /* a numerical method failed (step cap, divergence) */
    HY_EIO = 4,     /* a file could not be read or written              */
    HY_EUNSUP = 5,  /* the request is valid but not supported here      */
    HY_ECANCEL = 6  /* the caller stopped the work (its client has gone) */
};

typedef struct hy_error {
    int code;
    char msg[512];
} hy_error;

/* Formats the message into e (if e is not NULL) and returns code (fmt NULL:
 * the message "(no message)").  The
 * arguments may include e->msg itself (the old message is read before the new
 * one is written).  The message is made text a terminal shows as it is
 * (hy_text_shown): a scene's bytes quoted in it cannot retitle or recolour
 * the terminal of whoever reads it (issue 20 item 10). */
int hy_error_set(hy_error *e, int code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Copies src into dst (size bytes, NUL-terminated, cut at a character):
 * printable ASCII and UTF-8 characters other than controls as they are,
 * every other byte (C0 and C1 controls, DEL, invalid UTF-8) as \xNN.
 * src may be NULL (the empty text); dst may be NULL only when size is 0
 * (else nothing is done). */
void hy_text_shown(const char *src, char *dst, size_t size);

/* The offset of the first byte of s that is not such text (a control
 * character other than tab, DEL, a C1 control or invalid UTF-8), or -1.
 * s may be NULL (the empty text: -1). */
long hy_text_check(const char *s);

/* Prefixes an existing message with "prefix: " (used to add file:line); the
 * arguments may include e->msg.  The result is text as with hy_error_set.
 * e may be NULL (nothing done); fmt NULL: the message is left as it is. */
void hy_error_prefix(hy_error *e, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

#ifdef __cplusplus
}
#endif

#endif
