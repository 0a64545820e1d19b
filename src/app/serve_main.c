/* SPDX-License-Identifier: MIT */
/* serve_main.c: the hystviz-serve program, which `hystviz serve` runs.
 * serve lives in its own executable so that only it loads libmicrohttpd and
 * what that links (gnutls, p11-kit, nettle, gmp, idn2, ...: 12 of the 35
 * libraries hystviz loaded); `hystviz render` starts without them
 * (docs/ARCHITECTURE.md, "hystviz serve and watch").  Built without
 * libmicrohttpd it still exists and says what is missing (exit 3).  argv as
 * after "hystviz". */
#include <gsl/gsl_errno.h>
#include <malloc.h>
#include <signal.h>

#include "cli_util.h"
#include "cmd_serve.h"

int main(int argc, char **argv)
{
    sigset_t stop;
    cli_signals_block(&stop); /* first: serve takes SIGINT/SIGTERM itself (sigwait) */
    gsl_set_error_handler_off();
    /* a render's big arrays (Newmark, decimation, the raster, the answer)
       come from the heap and go back to it, not to the kernel: the next
       render reuses pages instead of faulting fresh ones in (issue 23 item 4) */
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 256 << 20);
    if (argc < 2) {
        static char name[] = "serve", *args[] = {name, NULL};
        return cli_stdout_status("serve", hy_cmd_serve(1, args));
    }
    return cli_stdout_status("serve", hy_cmd_serve(argc - 1, argv + 1));
}
