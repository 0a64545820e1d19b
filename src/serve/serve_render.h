/* SPDX-License-Identifier: MIT */
/* serve_render.h: GET /api/render?scene=S&fmt=F[&set=K=V]...: the figure
 * as render writes it (svg, pdf, png), its points (csv, as `hystviz
 * data`), or json: the SVG with its numbers (timings, work, caption, the
 * command line, errors, the panel's map, with hover=1 the drawn series). */
#ifndef SERVE_RENDER_H
#define SERVE_RENDER_H

#include "serve_types.h"

sv_handler sv_api_render;

#endif
