/* SPDX-License-Identifier: MIT */
/* scene_test.h: the scene tests' checks (tests/hy_test.h under their names)
 * and parse, override and temp-dir helpers. */
#ifndef SCENE_TEST_H
#define SCENE_TEST_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <sys/stat.h>

#include "../hy_test.h"
#include "hy_scene.h"

/* the scene tests' names for tests/hy_test.h's counter and checks */
#define st_failures hy_test_fail

#define CHECK(cond) HY_CHECK(cond, "check failed: %s", #cond)

#define CHECK_NEAR(a, b, tol) HY_CHECK_CLOSE(a, b, tol, #a)

#define CHECK_STR(a, b)                                                          \
    do {                                                                         \
        const char *a_ = (a), *b_ = (b);                                         \
        HY_CHECK(a_ && strcmp(a_, b_) == 0, "%s = \"%s\"\n    expected \"%s\"", #a, \
                 a_ ? a_ : "(null)", b_);                                        \
    } while (0)

/* The test's exit status (0 or 1) after its summary (hy_test_finish). */
static inline int st_done(const char *test)
{
    return hy_test_finish(test);
}

/* Parses text named name; returns the scene or NULL, printing an unexpected error. */
static inline hy_scene *st_parse_ok(const char *name, const char *text, int line)
{
    hy_scene *s = NULL;
    hy_error err = {0, ""};
    if (hy_scene_parse_buffer(name, text, strlen(text), &s, &err)) {
        fprintf(stderr, "line %d: unexpected error: %s\n", line, err.msg);
        st_failures++;
        return NULL;
    }
    return s;
}
#define PARSE_OK(name, text) st_parse_ok(name, text, __LINE__)

/* Parses text expecting failure with exactly the message want. */
static inline void st_parse_fails(const char *name, const char *text, const char *want, int line)
{
    hy_scene *s = NULL;
    hy_error err = {0, ""};
    int rc = hy_scene_parse_buffer(name, text, strlen(text), &s, &err);
    if (rc == 0 || s != NULL) {
        fprintf(stderr, "line %d: parse succeeded, expected: %s\n", line, want);
        st_failures++;
        hy_scene_free(s);
        return;
    }
    if (strcmp(err.msg, want) != 0) {
        fprintf(stderr, "line %d: message\n    \"%s\"\n expected\n    \"%s\"\n", line, err.msg, want);
        st_failures++;
    }
}
#define PARSE_FAILS(text, want) st_parse_fails("t.scene", text, want, __LINE__)

/* Applies the override a expecting failure with exactly the message want. */
static inline void st_set_fails(hy_scene *s, const char *a, const char *want, int line)
{
    hy_error err = {0, ""};
    if (hy_scene_set(s, a, &err) == 0) {
        fprintf(stderr, "line %d: --set %s succeeded, expected: %s\n", line, a, want);
        st_failures++;
    } else if (strcmp(err.msg, want) != 0) {
        fprintf(stderr, "line %d: message\n    \"%s\"\n expected\n    \"%s\"\n", line, err.msg, want);
        st_failures++;
    }
}
#define SET_FAILS(s, a, want) st_set_fails(s, a, want, __LINE__)

/* Creates a fresh directory below the test's own (tests/tmpdir.h: removed
 * with all in it when the test exits, also after failed checks); path in buf. */
static inline void st_tempdir(char *buf, size_t n)
{
    if (!mkdtemp(test_tmppath(buf, n, "hyscene.XXXXXX"))) {
        perror("mkdtemp");
        exit(1);
    }
}

/* Writes text to dir/name. */
static inline void st_write(const char *dir, const char *name, const char *text)
{
    char p[1024];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    FILE *f = fopen(p, "wb");
    if (!f || fputs(text, f) < 0 || fclose(f) != 0) {
        perror(p);
        exit(1);
    }
}

/* Removes dir/name for each name, then dir. */
static inline void st_cleanup(const char *dir, const char *const *names)
{
    char p[1024];
    for (; *names; names++) {
        snprintf(p, sizeof p, "%s/%s", dir, *names);
        unlink(p);
    }
    rmdir(dir);
}

static inline int st_result(const char *what)
{
    if (st_failures)
        fprintf(stderr, "%s: %d check(s) failed\n", what, st_failures);
    return st_failures ? 1 : 0;
}

#endif
