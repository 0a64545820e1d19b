/* SPDX-License-Identifier: MIT */
/* serve_scenes.h: the endpoints that describe scenes: GET /api/scenes (the
 * catalogue), GET /api/scene?scene=S (a scene's text, caption, controls,
 * presets and animation), GET /scenes/NAME (a scene file's text). */
#ifndef SERVE_SCENES_H
#define SERVE_SCENES_H

#include "hy_scene.h"
#include "hy_scene_decl.h"
#include "serve_types.h"

sv_handler sv_api_scenes, sv_api_scene, sv_api_text;

/* Appends the [figure] caption of d (sc decoded) with its placeholders
 * filled in from sc, as JSON; 0 (nothing appended) when it has none. */
int sv_figure_caption(sv_buf *b, const hy_scene *sc, const hy_scene_doc *d);

#endif
