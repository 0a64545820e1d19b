/* SPDX-License-Identifier: MIT */
/* serve_fit.h: POST /api/fit?scene=S&free=K,...[&set=K=V]...[&page=P&seq=N]:
 * the scene's [model] keys K fitted to its measured data (scene_fit.h, as
 * `hystviz fit S --free K,... --set ...`) from the page's values, in a render
 * slot and the page's slot, within serve's work budget, stopped when its
 * client goes or its page asks anew; JSON: estimates, standard errors,
 * flags and the fit's statistics (docs/SERVE.md "Fitting on the page"). */
#ifndef SERVE_FIT_H
#define SERVE_FIT_H

#include "serve_types.h"

sv_handler sv_api_fit;

#endif
