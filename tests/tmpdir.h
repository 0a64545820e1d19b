/* SPDX-License-Identifier: MIT */
/* tests/tmpdir.h: where a C test keeps its files.  test_tmpdir() makes one
 * directory $TMPDIR/hy_test.XXXXXX (/tmp when TMPDIR is unset) at its first
 * call and removes it, with everything in it, when the test exits (also
 * after failed checks; by the process that made it, not by its forked
 * children), so a test leaves nothing behind.
 *
 *     char path[4200];
 *     int fd = mkstemp(test_tmppath(path, sizeof path, "input_XXXXXX"));
 */
#ifndef HY_TEST_TMPDIR_H
#define HY_TEST_TMPDIR_H

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static char test_tmp_dir[4096];
static pid_t test_tmp_owner; /* a forked child's exit leaves the directory alone */

/* Removes path and, for a directory, everything below it. */
static inline void test_tmp_remove(const char *path)
{
    struct stat st;
    if (lstat(path, &st))
        return;
    if (!S_ISDIR(st.st_mode)) {
        unlink(path);
        return;
    }
    DIR *d = opendir(path);
    for (struct dirent *de; d && (de = readdir(d));) {
        char p[4096 + 512];
        if (strcmp(de->d_name, ".") && strcmp(de->d_name, "..") &&
            snprintf(p, sizeof p, "%s/%s", path, de->d_name) < (int)sizeof p)
            test_tmp_remove(p);
    }
    if (d)
        closedir(d);
    rmdir(path);
}

static inline void test_tmp_cleanup(void)
{
    if (test_tmp_dir[0] && getpid() == test_tmp_owner)
        test_tmp_remove(test_tmp_dir);
}

/* The test's directory, made at the first call (exit 1 if it cannot be). */
static inline const char *test_tmpdir(void)
{
    if (!test_tmp_dir[0]) {
        const char *t = getenv("TMPDIR");
        snprintf(test_tmp_dir, sizeof test_tmp_dir, "%s/hy_test.XXXXXX", t && *t ? t : "/tmp");
        if (!mkdtemp(test_tmp_dir)) {
            perror("mkdtemp");
            exit(1);
        }
        test_tmp_owner = getpid();
        atexit(test_tmp_cleanup);
    }
    return test_tmp_dir;
}

/* buf = test_tmpdir()/name (a template's XXXXXX is left to mkstemp or
 * mkdtemp); exit 1 when it does not fit in n bytes. */
static inline char *test_tmppath(char *buf, size_t n, const char *name)
{
    const char *d = test_tmpdir();
    size_t a = strlen(d), b = strlen(name);
    if (a + 1 + b >= n) {
        fprintf(stderr, "test_tmppath: '%s/%s' is longer than %zu bytes (a shorter TMPDIR?)\n", d, name, n - 1);
        exit(1);
    }
    memcpy(buf, d, a);
    buf[a] = '/';
    memcpy(buf + a + 1, name, b + 1);
    return buf;
}

#endif
