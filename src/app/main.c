/* main.c: the hystviz command; wires subcommands, owns no numerics. */
#include "hy_config.h"
#include <stdio.h>
#include <string.h>

int main(int argc, char **argv)
{
    if (argc > 1 && strcmp(argv[1], "--version") == 0) {
        printf("hystviz %s\n", HY_VERSION);
        return 0;
    }
    fprintf(stderr, "hystviz: no command given (try --help)\n");
    return 2;
}
