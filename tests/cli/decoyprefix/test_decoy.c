/* SPDX-License-Identifier: MIT */
/* test_decoy.c: prints where hy_file_installed (hy_file.c, compiled with
 * this directory's decoy prefix) finds the scenes, the Bouc-Wen data and
 * hystviz-animate, one "what path" line each ("-" when not found), after the
 * configured prefix's data directory (tests/cli/test_decoy.sh). */
#include <stdio.h>

#include "hy_config.h"
#include "hy_file.h"

int main(void)
{
    static const struct {
        int what;
        const char *sub;
    } ask[] = {{HY_INSTALLED_DATA, "scenes"}, {HY_INSTALLED_DATA, "boucwen"}, {HY_INSTALLED_LIBEXEC, "hystviz-animate"}};
    char buf[4200];
    printf("configured %s\n", HY_DATA_DIR);
    for (size_t i = 0; i < sizeof ask / sizeof ask[0]; i++)
        printf("%s %s\n", ask[i].sub, hy_file_installed(ask[i].what, ask[i].sub, buf, sizeof buf) ? "-" : buf);
    return 0;
}
