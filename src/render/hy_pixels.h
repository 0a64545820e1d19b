/* SPDX-License-Identifier: MIT */
/* hy_pixels.h: the byte layout of a frame's pixels, at the bottom of
 * src/render: the frame writer (hy_frame.c), its PNG encoder (hy_zfast.c),
 * the GL backends and the ffmpeg pipe include it, and it includes none of
 * them (tools/include_graph.py: no circle between files).
 *
 *     if (hy_little_endian()) ...   // a cairo RGB24 pixel is B, G, R, x
 */
#ifndef HY_PIXELS_H
#define HY_PIXELS_H

#include <stdint.h>
#include <string.h>

/* Whether the host stores a uint32 low byte first: a cairo RGB24 pixel is
 * then the bytes B, G, R, x (else x, R, G, B).  Frames are kept in that
 * layout from OpenGL (hy_gl_finish) through libpng and ffmpeg. */
static inline int hy_little_endian(void)
{
    const uint32_t probe = 1;
    unsigned char first;
    memcpy(&first, &probe, 1);
    return first;
}

#endif
