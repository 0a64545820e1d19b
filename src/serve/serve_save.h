/* SPDX-License-Identifier: MIT */
/* serve_save.h: POST /api/save?scene=S&name=NEW[&set=K=V]...: "save as new
 * scene" (with --allow-save and the page's token): NEW.scene with the
 * page's overrides written in, checked to render what the page shows,
 * never replacing a file, at most 100 a run and one a second. */
#ifndef SERVE_SAVE_H
#define SERVE_SAVE_H

#include "serve_types.h"

sv_handler sv_api_save;

#endif
