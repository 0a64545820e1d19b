/* gallery_main.c: a stand-in `hystviz` for the gallery tests and benchmark:
 * `gallery_main gallery ARGS...` runs hy_cmd_gallery exactly as the real
 * command's main() dispatches it (argv[0] = "gallery"). */
#include <stdio.h>
#include <string.h>

#include "cmd_gallery.h"

int main(int argc, char **argv)
{
    if (argc < 2 || strcmp(argv[1], "gallery")) {
        fputs("usage: gallery_main gallery [OPTIONS] (see hystviz gallery --help)\n", stderr);
        return 2;
    }
    return hy_cmd_gallery(argc - 1, argv + 1);
}
