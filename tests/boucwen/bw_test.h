/* bw_test.h: tiny check macros and the location of the benchmark's data for
 * the Bouc-Wen tests.  A test that needs the data and cannot find it exits 77
 * (meson's SKIP) after saying where it looked. */
#ifndef BW_TEST_H
#define BW_TEST_H

#include "hy_config.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static int bw_failures;

#define CHECK(cond, ...)                                                      \
    do {                                                                      \
        if (!(cond)) {                                                        \
            fprintf(stderr, "%s:%d: check failed: %s: ", __FILE__, __LINE__,  \
                    #cond);                                                   \
            fprintf(stderr, __VA_ARGS__);                                     \
            fputc('\n', stderr);                                              \
            bw_failures++;                                                    \
        }                                                                     \
    } while (0)

/* The folder holding uval_multisine.txt: $HY_BOUCWEN_DATA, else the shared
 * data next to the source tree (main checkout: HY_SOURCE_DIR/../shared, a
 * worktree under wt/: HY_SOURCE_DIR/../../shared).  Exits 77 if none. */
static inline const char *bw_data_dir(void)
{
    static const char *cand[] = {
        NULL,
        HY_SOURCE_DIR "/../shared/data/boucwen",
        HY_SOURCE_DIR "/../../shared/data/boucwen",
    };
    cand[0] = getenv("HY_BOUCWEN_DATA");
    for (size_t i = 0; i < sizeof cand / sizeof cand[0]; i++) {
        char path[4096];
        struct stat st;
        if (!cand[i])
            continue;
        snprintf(path, sizeof path, "%s/uval_multisine.txt", cand[i]);
        if (stat(path, &st) == 0)
            return cand[i];
    }
    fprintf(stderr, "SKIP: Bouc-Wen validation data not found (set "
            "HY_BOUCWEN_DATA, or provide %s)\n", cand[1]);
    exit(77);
}

#endif
