/* SPDX-License-Identifier: MIT */
/* hy_frame.h: animation frames: compositing a cairo overlay over a GL layer,
 * and writing 8-bit RGB PNG frames with libpng at frame-friendly settings.
 *
 * The GL layer comes from hy_gl_read (RGBA, rows bottom-up); the overlay is a
 * cairo ARGB32 image surface of the same size (premultiplied, native-endian
 * 32-bit pixels, rows top-down).  The result is packed RGB, rows top-down:
 *     out = overlay + (1 - overlay_alpha) * gl      (per channel, rounded)
 * Frames go through the output writer (hy_out.h): a temporary file renamed
 * into place, so a crash never leaves a truncated frame under the final name.
 *
 *     hy_frame_composite(w, h, gl_rgba, argb, stride, rgb);
 *     hy_png_opts o = hy_png_frame_defaults();
 *     if (hy_png_write_rgb("out/frame_00000.png", w, h, rgb, &o, &err)) ...
 *
 * No GL needed: this part builds without OSMesa.
 */
#ifndef HY_FRAME_H
#define HY_FRAME_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "hy_pixels.h" /* hy_little_endian */
#include "hy_status.h"

/* Composites the overlay (may be NULL) over the GL layer into rgb (w*h*3). */
void hy_frame_composite(int w, int h, const unsigned char *gl_rgba_bottom_up, const unsigned char *argb,
                        int argb_stride, unsigned char *rgb);

typedef struct hy_png_opts {
    int level;        /* zlib level 0..9, or libdeflate's 0..12 with engine */
    int filter;       /* HY_PNG_FILTER_* (zlib only; libdeflate: none)     */
    int strategy;     /* zlib strategy: 0 default, 1 filtered, 3 RLE */
    int engine;       /* HY_PNG_ZLIB (libpng), or HY_PNG_LIBDEFLATE: the IDAT
                       * stream compressed by libdeflate in one call, the
                       * chunks written here (zlib where not built with it),
                       * or HY_PNG_FAST: hy_zfast.h's encoder (level and
                       * filter unused; packed RGB input goes to the others) */
} hy_png_opts;
enum { HY_PNG_ZLIB = 0, HY_PNG_LIBDEFLATE = 1, HY_PNG_FAST = 2 };
enum { HY_PNG_FILTER_NONE = 0, HY_PNG_FILTER_SUB, HY_PNG_FILTER_UP, HY_PNG_FILTER_PAETH, HY_PNG_FILTER_ALL };

/* The PNG modes of animation frames (`hystviz animate --png MODE`), one
 * table: X(name, level, engine, description); the first is the default.
 * Their cost on a 1920x1080 gamma-sweep frame, as tests/bench/bench_gl
 * prints it for each mode (OSMesa, load 1.3, medians): fast 4.7 ms and
 * 207 kB, small 13.5 ms and 173 kB. */
#define HY_PNG_MODES(X)                                                                            \
    X("fast", 2, HY_PNG_FAST, "hystviz's encoder for plot frames (runs, the row above, pixel pairs)") \
    X("small", 6, HY_PNG_LIBDEFLATE, "libdeflate level 6, else zlib level 6: about 16 % smaller, 3x the time [bench gl]")

/* The frame default: the first PNG mode. */
hy_png_opts hy_png_frame_defaults(void);

/* The options of mode name into *o; HY_EINVAL naming the modes if unknown. */
int hy_png_mode(const char *name, hy_png_opts *o, hy_error *err);

/* Writes rgb (w*h*3, top-down) to path atomically.  HY_EIO names the path;
 * on failure no file is left at path or at the temporary name. */
int hy_png_write_rgb(const char *path, int w, int h, const unsigned char *rgb, const hy_png_opts *o,
                     hy_error *err);

/* The same from cairo RGB24 pixels (one native-endian 0x00RRGGBB word per
 * pixel, rows stride bytes apart, top row first): libpng drops the unused
 * byte and orders the channels while it encodes, so no conversion pass. */
int hy_png_write_xrgb(const char *path, int w, int h, const unsigned char *xrgb, int stride, const hy_png_opts *o,
                      hy_error *err);

/* The same PNG bytes hy_png_write_xrgb writes, onto fp (an open_memstream:
 * a frame kept in memory, hystviz-animate --worker).  HY_EIO when the
 * encoder or the stream fails. */
int hy_png_encode_xrgb(FILE *fp, int w, int h, const unsigned char *xrgb, int stride, const hy_png_opts *o,
                       hy_error *err);

#endif
