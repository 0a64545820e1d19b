/* SPDX-License-Identifier: MIT */
/* replay_dirs.c: one input, or every file of some directories, through a fuzz harness (replay_dirs.h). */
#include "replay_dirs.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int run_file(const char *path, replay_one_fn one, int *n)
{
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return printf("FAIL %s: cannot open\n", path), 1;
    static uint8_t buf[1 << 20];
    size_t len = fread(buf, 1, sizeof buf, fp);
    fclose(fp);
    char why[300];
    ++*n;
    if (one(buf, len, why, sizeof why))
        return printf("FAIL %s: %s\n", path, why), 1;
    return 0;
}

int replay_dirs(int argc, char **argv, const char *prog, replay_one_fn one)
{
    int n = 0, bad = 0;
    for (int i = 1; i < argc; i++) {
        struct dirent **ents;
        int k = scandir(argv[i], &ents, NULL, alphasort);
        if (k < 0) {
            printf("FAIL %s: cannot list\n", argv[i]);
            bad++;
            continue;
        }
        for (int j = 0; j < k; j++) {
            if (ents[j]->d_name[0] != '.') {
                char path[4096];
                snprintf(path, sizeof path, "%s/%s", argv[i], ents[j]->d_name);
                bad += run_file(path, one, &n);
            }
            free(ents[j]);
        }
        free(ents);
    }
    printf("%s: %d inputs, %d passed, %d failed\n", prog, n, n - bad, bad);
    return bad || !n;
}

int fuzz_bytes_one(const char *prog, replay_one_fn one, const uint8_t *data, size_t size)
{
    char why[300];
    if (one(data, size, why, sizeof why)) {
        fprintf(stderr, "%s: %s\n", prog, why);
        abort();
    }
    return 0;
}
