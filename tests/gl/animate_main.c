/* SPDX-License-Identifier: MIT */
/* animate_main.c: a stand-alone driver for `hystviz animate` (tests and
 * benchmarks run it before main.c wires the subcommand): argv as after "hystviz". */
#include "cmd_animate.h"

int main(int argc, char **argv) { return hy_cmd_animate(argc - 1, argv + 1); }
