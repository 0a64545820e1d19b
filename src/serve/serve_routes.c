/* SPDX-License-Identifier: MIT */
/* serve_routes.c: the route table (serve_routes.h; docs/ARCHITECTURE.md
 * "hystviz serve and watch" shows it). */
#include "serve_routes.h"

#include <string.h>

#include "serve_assets.h"
#include "serve_events.h"
#include "serve_fit.h"
#include "serve_render.h"
#include "serve_request.h"
#include "serve_save.h"
#include "serve_scenes.h"
#include "serve_stream.h"

const sv_route sv_routes[] = {
    {SV_GET, "/", 0, sv_page_html, SV_OPEN, "the page (index.html with the run's token)"},
    {SV_GET, "/index.html", 0, sv_page_html, SV_OPEN, "the page"},
    {SV_GET, "/app.js", 0, sv_page_js, SV_OPEN, "the page's script"},
    {SV_GET, "/app.css", 0, sv_page_css, SV_OPEN, "the page's style"},
    {SV_GET, "/events", 0, sv_api_events, SV_OPEN, "an event stream: 32 in all, 2 a page"},
    {SV_GET, "/api/scenes", 0, sv_api_scenes, SV_OPEN, "parses and loads every scene of the directory"},
    {SV_GET, "/api/scene", 0, sv_api_scene, SV_OPEN, "an animation's --info in a render slot (cached)"},
    {SV_GET, "/api/render", 0, sv_api_render, SV_OPEN, "a render slot and the page's slot; --max-work; 32 MB"},
    {SV_GET, "/api/frame", 0, sv_api_frame, SV_OPEN, "a render slot, the page's slot and a frame worker"},
    {SV_GET, "/api/frames", 0, sv_api_frames, SV_OPEN, "per frame a render slot, the page's slot and a worker"},
    {SV_POST, "/api/fit", 0, sv_api_fit, SV_OPEN, "a render slot and the page's slot; --max-work measured points in all"},
    {SV_POST, "/api/save", 0, sv_api_save, SV_SAVE, "100 new scenes a run, one a second"},
    {SV_GET, "/scenes/", 1, sv_api_text, SV_OPEN, "a scene file's text (HY_SCENE_MAX_FILE_BYTES)"},
    {0, NULL, 0, NULL, 0, NULL},
};

const sv_route *sv_route_find(sv_method m, const char *url, const char **rest)
{
    for (const sv_route *r = sv_routes; r->path; r++) {
        size_t n = strlen(r->path);
        if (r->method == m && (r->prefix ? !strncmp(url, r->path, n) : !strcmp(url, r->path))) {
            *rest = url + (r->prefix ? n : strlen(url));
            return r;
        }
    }
    return NULL;
}

unsigned sv_route_refused(const sv_route *r, const sv_server *s, struct MHD_Connection *c, const char **msg)
{
    if (r->guard != SV_SAVE)
        return 0;
    if (!s->allow_save)
        return *msg = "saving is off: start hystviz serve with --allow-save", 403;
    if (!sv_token_ok(s, c))
        return *msg = "missing or wrong X-Hystviz-Token (reload the page)", 403;
    return 0;
}
