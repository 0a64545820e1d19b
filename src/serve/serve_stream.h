/* SPDX-License-Identifier: MIT */
/* serve_stream.h: an animation's frames from the warm workers
 * (serve_frames.h): GET /api/frame?scene=S&frame=I (one PNG, paused or
 * scrubbing) and GET /api/frames?scene=S&from=A&to=B&page=P&seq=N (a stream
 * of records for playback, anim_worker.h). */
#ifndef SERVE_STREAM_H
#define SERVE_STREAM_H

#include "serve_types.h"

sv_handler sv_api_frame, sv_api_frames;

#endif
