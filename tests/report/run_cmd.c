/* run_cmd.c: test driver running `report` or `check` in-process (argv[1] is
 * the command name), so the tests do not depend on main.c's wiring. */
#include <stdio.h>
#include <string.h>

#include "cmd_check.h"
#include "cmd_report.h"

int main(int argc, char **argv)
{
    if (argc >= 2 && !strcmp(argv[1], "report"))
        return hy_cmd_report(argc - 1, argv + 1);
    if (argc >= 2 && !strcmp(argv[1], "check"))
        return hy_cmd_check(argc - 1, argv + 1);
    fputs("usage: run_cmd report|check [OPTIONS]\n", stderr);
    return 2;
}
