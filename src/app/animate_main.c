/* SPDX-License-Identifier: MIT */
/* animate_main.c: the hystviz-animate program, which `hystviz animate` runs.
 * Animations live in their own executable so that only they load OpenGL
 * (OSMesa and LLVM cost ~17 ms at every process start): a cairo figure,
 * `hystviz render`, never initialises GL.  argv as after "hystviz". */
#include <gsl/gsl_errno.h>
#include <pthread.h>
#include <signal.h>

#include "cli_util.h"
#include "cmd_animate.h"

int main(int argc, char **argv)
{
    sigset_t stop;
    cli_signals_block(&stop); /* first: a signal at any moment of start-up is taken (README "Signals") */
    if (cli_signals_end())
        pthread_sigmask(SIG_UNBLOCK, &stop, NULL);
    gsl_set_error_handler_off();
    static char name[] = "animate";
    int rc = cli_program_run(name, hy_cmd_animate, argc, argv);
    cli_leak_check_release(); /* the animation's threads have ended */
    return rc;
}
