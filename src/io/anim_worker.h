/* SPDX-License-Identifier: MIT */
/* anim_worker.h: the frame protocol between `hystviz serve` (src/serve) and
 * `hystviz-animate --worker` (docs/ARCHITECTURE.md, "Animation frames").
 *
 * A worker keeps one GL context and answers requests read from its
 * standard input, one after another, on its standard output.  Everything is
 * length-prefixed; a request is a header line and its fields:
 *
 *     hvw1 OP FIRST LAST WIDTH HEIGHT NFIELDS\n       OP: frames | info
 *     TAG LEN\n<LEN bytes>          (NFIELDS times)   TAG: name | text | set
 *
 * name is a built-in animation's name, or the path of a scene whose TEXT
 * follows (the path only names it in messages and is where its includes are
 * looked up: the worker never opens it); each set is an override
 * "section.key=value" as `--set` takes it.  WIDTH and HEIGHT 0 keep the
 * animation's frame size.  The answer is records of the same shape,
 *
 *     TAG NUM LEN\n<LEN bytes>
 *
 * "frame I" (the PNG of frame I, byte for byte the file `hystviz animate
 * NAME --frames I:I+1 --set ...` writes) for each frame of [FIRST, LAST),
 * or one "info 0" (the line `--info` prints), then "end COUNT 0"; or, at
 * the first failure, "error STATUS" (the message, STATUS the exit status
 * the command line would give) instead of the rest.
 *
 *     aw_request rq;
 *     while (aw_request_read(stdin, &rq, &err) == 0) { ...; aw_request_free(&rq); }
 *     (AW_END: the input ended; another status: a malformed request)
 */
#ifndef ANIM_WORKER_H
#define ANIM_WORKER_H

#include <stddef.h>
#include <stdio.h>

#include "hy_status.h"

#define AW_MAX_SETS 64              /* overrides of one request */
#define AW_MAX_FIELD (4u << 20)     /* bytes of one field (a scene's text at most) */
#define AW_MAX_NAME 4096            /* bytes of a name or an override */

typedef struct aw_request {
    char op[8];               /* "frames" or "info" */
    long first, last;         /* frames [first, last) */
    int width, height;        /* 0: the animation's */
    char *name;               /* built-in animation, or the scene's (virtual) path */
    char *text;               /* the scene's text, NUL-terminated; NULL for a built-in */
    size_t len;
    char *sets[AW_MAX_SETS];
    size_t nsets;
} aw_request;

#define AW_END (-1)               /* aw_request_read: the input ended between requests */

/* Reads one request.  Returns 0, AW_END at the end of input before a request,
 * or HY_EINVAL / HY_ENOMEM (err says what was wrong: the stream is then out
 * of step, and the worker stops).  rq is to be freed after 0 only. */
int aw_request_read(FILE *in, aw_request *rq, hy_error *err);

/* The request's bytes (malloc'd, *len of them); NULL when out of memory. */
char *aw_request_encode(const aw_request *rq, size_t *len);

void aw_request_free(aw_request *rq);

/* Writes one answer record and flushes; 0, or -1 if out could not take it. */
int aw_record_write(FILE *out, const char *tag, long num, const void *data, size_t len);

/* Parses a record's header line "TAG NUM LEN" (without its newline) into
 * tag (8 bytes), num and len; 0, or -1 if it is not one. */
int aw_record_head(const char *line, char tag[8], long *num, size_t *len);

#endif
