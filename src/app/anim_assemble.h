/* SPDX-License-Identifier: MIT */
/* anim_assemble.h: `hystviz animate NAME --assemble FMT`: the video of an
 * animation whose PNG frames were rendered in pieces (--frames A:B or
 * --shard K/N, on one machine or several), encoded by ffmpeg from
 * outdir/name/frame_00000.png ... once every frame is there (issue 13). */
#ifndef HY_ANIM_ASSEMBLE_H
#define HY_ANIM_ASSEMBLE_H

#include "hy_anim.h"

/* The frames [*first, *last) of piece k of n: contiguous, sizes differing by
 * at most one, together every frame once. */
void hy_anim_shard_range(long nframes, long k, long n, long *first, long *last);

/* Encodes the hy_anim_nframes(p) frames outdir/name/frame_%05d.png into
 * outdir/name.FMT (mp4, webm or gif) at p->fps through the output writer
 * (whole or absent).  HY_EINVAL for an unknown format or missing frames (the
 * message lists them as --frames ranges), HY_EUNSUP without ffmpeg on PATH,
 * HY_EIO if ffmpeg fails. */
int hy_anim_assemble(const hy_anim_params *p, const char *fmt, hy_error *err);

#endif
