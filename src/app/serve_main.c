/* SPDX-License-Identifier: MIT */
/* serve_main.c: the hystviz-serve program, which `hystviz serve` runs.
 * serve lives in its own executable so that only it loads libmicrohttpd and
 * what that links (gnutls, p11-kit, nettle, gmp, idn2, ...: 12 of the 35
 * libraries hystviz loaded); `hystviz render` starts without them
 * (docs/ARCHITECTURE.md, "hystviz serve and watch").  Built without
 * libmicrohttpd it still exists and says what is missing (exit 3).  argv as
 * after "hystviz". */
#include <gsl/gsl_errno.h>
#include <signal.h>

#include "cli_util.h"
#include "cmd_serve.h"
#include "serve_malloc.h"

int main(int argc, char **argv)
{
    sigset_t stop;
    cli_signals_block(&stop); /* first: serve takes SIGINT/SIGTERM itself (sigwait) */
    gsl_set_error_handler_off();
    sv_malloc_tune(); /* freed render memory is reused, not faulted in again */
    static char name[] = "serve";
    return cli_program_run(name, hy_cmd_serve, argc, argv);
}
