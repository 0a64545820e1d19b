/* SPDX-License-Identifier: MIT */
/* serve_scenes.c: the catalogue, a scene's description and a scene file's
 * text (serve_scenes.h), each read beneath the directory and parsed under
 * serve's policy. */
#include "serve_scenes.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hy_scene_policy.h"
#include "scene_run.h"
#include "serve_anim.h"
#include "serve_answer.h"
#include "serve_request.h"

/* The header comment of a scene file, without the '#'s. */
static void caption(sv_buf *b, const char *text)
{
    sv_buf c = {0};
    for (const char *p = text; *p == '#';) {
        const char *nl = strchr(p, '\n');
        size_t n = nl ? (size_t)(nl - p) : strlen(p);
        const char *q = p + 1;
        while (q < p + n && *q == ' ')
            q++;
        if (c.len)
            sv_puts(&c, " ");
        sv_add(&c, q, (size_t)(p + n - q));
        if (!nl)
            break;
        p = nl + 1;
    }
    sv_json(b, c.s ? c.s : "");
    free(c.s);
}

/* The gallery's order: by catalogue part, then by file name. */
static int by_name(const void *a, const void *b)
{
    const char *x = *(char *const *)a, *y = *(char *const *)b;
    int d = hy_scene_catalogue_part(x) - hy_scene_catalogue_part(y);
    return d ? d : strcmp(x, y);
}

/* The [figure] caption of d (sc decoded) with its placeholders
 * ({model.sigma0}) replaced by the scene's values (overrides included), as
 * JSON; 0 when it has none.  hy_scene_expand fills them from sc: a
 * placeholder shows a value as the scene text writes it, any key of any
 * section (not only the decoded numbers). */
int sv_figure_caption(sv_buf *b, const hy_scene *sc, const hy_scene_doc *d)
{
    const char *cap = d->figure.caption;
    char *out = NULL;
    hy_error err = {0};
    if (!sc || hy_decl_got(&d->figure.h, offsetof(hy_decl_figure, caption)) != HY_SCENE_SET || !cap || !*cap)
        return 0;
    sv_json(b, hy_scene_expand(sc, cap, &out, &err) ? cap : out);
    free(out);
    return 1;
}

/* The caption: the scene's [figure] caption (as the gallery), else its header comment. */
static void scene_caption(sv_buf *b, const hy_scene *sc, const hy_scene_doc *d, const char *text)
{
    if (!sv_figure_caption(b, sc, d))
        caption(b, text);
}

static int is_animation(const hy_scene_doc *d)
{
    return d->nkeyframe > 0;
}

/* The catalogue's scene file names (sv_scene_name_ok) in the gallery's
 * order, malloc'd; -1 if the directory cannot be read.  Out of memory ends
 * the list where it came. */
static int scene_names(const sv_server *s, char ***names, size_t *count)
{
    DIR *d = opendir(s->dir);
    if (!d)
        return -1;
    char **v = NULL;
    size_t n = 0, cap = 0;
    for (struct dirent *de; (de = readdir(d));) {
        if (!sv_scene_name_ok(de->d_name))
            continue;
        if (n == cap) {
            char **nv = realloc(v, (cap = cap ? 2 * cap : 64) * sizeof *v);
            if (!nv)
                break;
            v = nv;
        }
        if (!(v[n] = strdup(de->d_name)))
            break;
        n++;
    }
    closedir(d);
    if (n)
        qsort(v, n, sizeof *v, by_name);
    *names = v, *count = n;
    return 0;
}

/* The catalogue entry of file (sc parsed from text at path, NULL if bad;
 * bad: what render would refuse, err why). */
static void entry_json(sv_buf *b, const sv_server *s, const char *file, const char *path, const char *text,
                       hy_scene *sc, int bad, hy_error *err)
{
    char name[256];
    hy_scene_doc d = {0};
    hy_error derr = {0};
    if (sc && hy_scene_decode_fill(sc, &d, &derr)) {
        hy_scene_doc_free(&d); /* out of memory: shown without caption and as a still */
        memset(&d, 0, sizeof d);
    }
    if (sc)
        hy_scene_probe_name(sc, path, name, sizeof name);
    else
        snprintf(name, sizeof name, "%.*s", (int)(strlen(file) - 6), file);
    sv_puts(b, "{\"file\":");
    sv_json(b, file);
    sv_puts(b, ",\"name\":");
    sv_json(b, name);
    sv_puts(b, ",\"caption\":");
    scene_caption(b, sc, &d, text);
    char label[32];
    hy_scene_figure_label(file, label, sizeof label);
    sv_printf(b, ",\"label\":\"%s\",\"part\":%d", label, hy_scene_catalogue_part(file));
    sv_printf(b, ",\"anim\":%s", is_animation(&d) ? "true" : "false");
    if (bad) {
        if (strstr(err->msg, "cannot read included file") && !s->pol.ninclude_dirs)
            hy_error_set(err, err->code, "%.400s (a file of another directory: start serve with --include-dir DIR)",
                         err->msg);
        sv_puts(b, ",\"error\":");
        sv_json(b, err->msg);
    }
    sv_puts(b, "}");
    hy_scene_doc_free(&d);
}

/* Appends the catalogue entry of the scene file (a comma first unless
 * *first); nothing for a file gone meanwhile or one that is not a figure
 * (style.scene and other includes). */
static void scene_entry(sv_buf *b, sv_server *s, const char *file, int *first)
{
    char path[PATH_MAX + 300];
    hy_scene *sc = NULL;
    hy_error err = {0};
    size_t tl;
    char *text = sv_scene_read(s, file, path, sizeof path, &tl);
    if (!text)
        return;
    int bad = hy_scene_parse_buffer_policy(path, text, tl, &s->pol, &sc, &err);
    if (!bad && !hy_scene_is_figure(sc)) {
        hy_scene_free(sc);
        free(text);
        return;
    }
    hy_scene_run chk; /* what render refuses before computing: the catalogue says why */
    if (!bad && (bad = hy_scene_run_load_scene(&chk, sc, path, hy_scene_policy_budget(&s->pol), &err)) == 0)
        hy_scene_run_free(&chk);
    if (!*first)
        sv_puts(b, ",");
    *first = 0;
    entry_json(b, s, file, path, text, sc, bad, &err);
    free(text);
    hy_scene_free(sc);
}

/* Appends the built-in animations' entries (after the scenes). */
static void builtins_json(sv_buf *b, const sv_server *s, int first)
{
    for (int i = 0; i < s->nbuiltin; i++) {
        char at[40];
        snprintf(at, sizeof at, "@%s", s->builtin[i]);
        sv_puts(b, first ? "{\"file\":" : ",{\"file\":");
        first = 0;
        sv_json(b, at);
        sv_puts(b, ",\"builtin\":true,\"anim\":true,\"part\":4,\"label\":\"\",\"name\":");
        sv_json(b, s->builtin[i]);
        sv_puts(b, ",\"caption\":");
        sv_json(b, s->builtin_doc[i]);
        sv_puts(b, "}");
    }
}

/* GET /api/scenes: {"dir","first","scenes":[...]}, each figure of the
 * directory (with why render would refuse it), then the built-ins. */
enum MHD_Result sv_api_scenes(sv_server *s, struct MHD_Connection *c, const sv_args *a, const char *rest)
{
    (void)a;
    (void)rest;
    char **v = NULL;
    size_t n = 0;
    if (scene_names(s, &v, &n))
        return sv_send_error(c, 500, "cannot read the scenes directory");
    sv_buf b = {0};
    sv_puts(&b, "{\"dir\":");
    sv_json(&b, s->dir_arg);
    sv_puts(&b, ",\"first\":");
    sv_json(&b, s->first);
    sv_puts(&b, ",\"scenes\":[");
    int first = 1;
    for (size_t i = 0; i < n; i++) {
        scene_entry(&b, s, v[i], &first);
        free(v[i]);
    }
    free(v);
    builtins_json(&b, s, first);
    sv_puts(&b, "]}");
    return sv_send_json(c, 200, &b);
}

/* GET /api/scene?scene=@NAME: a built-in animation's description. */
static enum MHD_Result builtin_scene(sv_server *s, struct MHD_Connection *c, const sv_args *a, int bi)
{
    sv_buf b = {0};
    sv_puts(&b, "{\"file\":");
    sv_json(&b, a->scene);
    sv_puts(&b, ",\"builtin\":true,\"path\":");
    sv_json(&b, s->builtin[bi]);
    sv_puts(&b, ",\"name\":");
    sv_json(&b, s->builtin[bi]);
    sv_puts(&b, ",\"caption\":");
    sv_json(&b, s->builtin_doc[bi]);
    sv_puts(&b, ",\"text\":\"\",\"controls\":[]");
    sv_json_anim(&b, s, c, sv_name_hash(s->builtin[bi]), s->builtin[bi], NULL, 0);
    sv_puts(&b, "}");
    return sv_send_json(c, 200, &b);
}

/* GET /api/scene?scene=S: the scene's text, caption, name, controls,
 * presets and animation (or why it cannot be rendered). */
enum MHD_Result sv_api_scene(sv_server *s, struct MHD_Connection *c, const sv_args *a, const char *rest)
{
    (void)rest;
    int bi = sv_builtin_index(s, a->scene);
    if (bi >= 0)
        return builtin_scene(s, c, a, bi);
    char path[PATH_MAX + 300];
    size_t tl;
    char *text = sv_scene_read(s, a->scene, path, sizeof path, &tl);
    if (!text)
        return sv_send_error(c, 404, "no such scene");
    hy_scene *sc = NULL;
    hy_error err = {0};
    sv_buf b = {0};
    sv_puts(&b, "{\"file\":");
    sv_json(&b, a->scene);
    sv_puts(&b, ",\"path\":");
    sv_json(&b, path);
    sv_puts(&b, ",\"text\":");
    sv_json(&b, text);
    int bad = hy_scene_parse_buffer_policy(path, text, tl, &s->pol, &sc, &err);
    hy_scene_doc d = {0};
    if (!bad && hy_scene_decode_fill(sc, &d, &err)) {
        hy_scene_doc_free(&d);
        hy_scene_free(sc);
        free(text);
        free(b.s);
        return sv_send_error(c, 500, err.msg);
    }
    sv_puts(&b, ",\"caption\":");
    scene_caption(&b, bad ? NULL : sc, &d, text);
    if (bad) {
        sv_puts(&b, ",\"controls\":[],\"anim\":null,\"error\":");
        sv_json(&b, err.msg);
    } else {
        char name[256];
        hy_scene_probe_name(sc, path, name, sizeof name);
        sv_puts(&b, ",\"name\":");
        sv_json(&b, name);
        sv_puts(&b, ",\"controls\":");
        sv_controls_json(&b, sc, &d, hy_scene_doc_reads(&d));
        sv_puts(&b, ",\"presets\":");
        sv_presets_json(&b, sc, &d);
        sv_puts(&b, ",\"fit\":"); /* the [data] that drives the model: the page offers POST /api/fit */
        if (d.input.data)
            sv_json(&b, d.input.data);
        else
            sv_puts(&b, "null");
        if (is_animation(&d))
            sv_json_anim(&b, s, c, hy_scene_hash(sc), path, text, tl);
        else
            sv_puts(&b, ",\"anim\":null");
        hy_scene_doc_free(&d);
        hy_scene_free(sc);
    }
    free(text);
    sv_puts(&b, "}");
    return sv_send_json(c, 200, &b);
}

/* GET /scenes/NAME: the scene file's text. */
enum MHD_Result sv_api_text(sv_server *s, struct MHD_Connection *c, const sv_args *a, const char *name)
{
    (void)a;
    char path[PATH_MAX + 300];
    size_t n;
    char *text = sv_scene_read(s, name, path, sizeof path, &n);
    if (!text)
        return sv_send_text(c, 404, "not found");
    return sv_send_buf(c, 200, "text/plain; charset=utf-8", text, n, 1, NULL);
}
