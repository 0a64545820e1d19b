/* SPDX-License-Identifier: MIT */
/* render_demo.c: writes the fixed test figures as SVG, PDF and PNG into a directory (demo, not installed). */
#include <stdio.h>

#include "figures.h"

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : ".";
    static const char *ext[3] = {"svg", "pdf", "png"};
    int bad = 0;
    for (int i = 0; i < FIG_COUNT; i++) {
        hy_figure fig;
        const char *name = fig_build(i, &fig);
        for (int f = 0; f < 3; f++) {
            char path[1024];
            hy_error err;
            snprintf(path, sizeof path, "%s/render_%s.%s", dir, name, ext[f]);
            if (hy_figure_write(&fig, path, f, &err)) {
                fprintf(stderr, "render_demo: %s\n", err.msg);
                bad = 1;
            } else {
                printf("%s\n", path);
            }
        }
    }
    return bad;
}
