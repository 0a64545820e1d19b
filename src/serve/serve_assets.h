/* SPDX-License-Identifier: MIT */
/* serve_assets.h: the page (src/serve/page/: index.html, app.js, app.css,
 * embedded at build time by page/embed.c, so serve works offline): GET /
 * and /index.html (with this run's save token), /app.js, /app.css. */
#ifndef SERVE_ASSETS_H
#define SERVE_ASSETS_H

#include "serve_types.h"

sv_handler sv_page_html, sv_page_js, sv_page_css;

/* s->page: index.html with s->token in place of @TOKEN@ (none without
 * --allow-save: the page then shows no save button); -1 if out of memory. */
int sv_page_make(sv_server *s);

#endif
