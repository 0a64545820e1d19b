/* SPDX-License-Identifier: MIT */
/* serve_malloc.h: hystviz-serve's allocator settings (issue 23 item 4), in
 * one place for the server and the benchmark that times it as it runs.
 *
 * A render's big arrays (Newmark, decimation, the raster, the answer) come
 * from the heap and go back to it, not to the kernel: the next render reuses
 * those pages instead of faulting fresh ones in (bw_fig1a: 2900 page faults a
 * render before, about 20 after). */
#ifndef SERVE_MALLOC_H
#define SERVE_MALLOC_H

#include <malloc.h>

static inline void sv_malloc_tune(void)
{
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 256 << 20);
}

#endif
