/* SPDX-License-Identifier: MIT */
/* zfast_replay.c: zfast_replay DIR...: every file of the directories through
 * zfast_fuzz_one (hy_zfast's stream against zlib and the strict inflater),
 * the seed corpus of fuzz_zfast and its reproducers; exit 0 only when all
 * pass and there was at least one. */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "zfast_harness.h"

static int run_file(const char *path, int *n)
{
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return printf("FAIL %s: cannot open\n", path), 1;
    static uint8_t buf[1 << 20];
    size_t len = fread(buf, 1, sizeof buf, fp);
    fclose(fp);
    char why[300];
    ++*n;
    if (zfast_fuzz_one(buf, len, why, sizeof why))
        return printf("FAIL %s: %s\n", path, why), 1;
    return 0;
}

int main(int argc, char **argv)
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
                bad += run_file(path, &n);
            }
            free(ents[j]);
        }
        free(ents);
    }
    printf("zfast_replay: %d inputs, %d passed, %d failed\n", n, n - bad, bad);
    return bad || !n;
}
