/* SPDX-License-Identifier: MIT */
/* bw_test.h: the check (tests/hy_test.h) and the location of the benchmark's data for
 * the Bouc-Wen tests (tests/data/boucwen, in the tree: a test that cannot find
 * it fails after saying where it looked). */
#ifndef BW_TEST_H
#define BW_TEST_H

#include "hy_config.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "../hy_test.h"

/* the Bouc-Wen tests' name for tests/hy_test.h's check: CHECK(cond, fmt, ...)
 * counts and says what failed; a test ends with return hy_test_finish(name) */
#define CHECK HY_CHECK

/* The folder holding uval_multisine.txt: $HY_BOUCWEN_DATA, else the copy in
 * the source tree (tests/data/boucwen).  The data belongs to the project, so a
 * missing file is a failure (exit 1), not a reason to skip. */
static inline const char *bw_data_dir(void)
{
    static const char *cand[] = {NULL, HY_SOURCE_DIR "/tests/data/boucwen"};
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
    fprintf(stderr, "FAIL: Bouc-Wen validation data not found in %s (or $HY_BOUCWEN_DATA)\n", cand[1]);
    exit(1);
}

#endif
