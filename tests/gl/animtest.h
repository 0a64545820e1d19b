/* SPDX-License-Identifier: MIT */
/* animtest.h: helpers of the tests that drive `hystviz animate` in-process
 * (test_anim, test_scene_anim): run the command, count and compare frames. */
#ifndef HY_ANIMTEST_H
#define HY_ANIMTEST_H

#include <dirent.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cmd_animate.h"

#include "../hy_test.h"

/* hystviz animate ARGS... (NULL-terminated); returns its exit status. */
static inline int run_cmd(const char *first, ...)
{
    char *argv[32];
    int argc = 0;
    va_list ap;
    va_start(ap, first);
    for (const char *s = first; s && argc < 31; s = va_arg(ap, const char *))
        argv[argc++] = (char *)s;
    va_end(ap);
    argv[argc] = NULL;
    return hy_cmd_animate(argc, argv);
}

/* Finished frames (frame_*.png, no temporaries) in dir. */
static inline long count_frames(const char *dir)
{
    DIR *d = opendir(dir);
    long n = 0;
    for (struct dirent *e; d && (e = readdir(d));)
        n += !strncmp(e->d_name, "frame_", 6) && strstr(e->d_name, ".png") && !strstr(e->d_name, ".tmp");
    if (d)
        closedir(d);
    return n;
}

/* Temporaries of the output writer (".NAME.hystviz-tmp.XXXXXX") in dir. */
static inline long count_tmps(const char *dir)
{
    DIR *d = opendir(dir);
    long n = 0;
    for (struct dirent *e; d && (e = readdir(d));)
        n += strstr(e->d_name, ".hystviz-tmp.") != NULL;
    if (d)
        closedir(d);
    return n;
}

/* Byte-identical files. */
static inline int same_file(const char *a, const char *b)
{
    size_t la = 0, lb = 0;
    char *x = hy_test_slurp(a, &la), *y = hy_test_slurp(b, &lb);
    int same = x && y && la == lb && !memcmp(x, y, la);
    free(x);
    free(y);
    return same;
}

#endif
