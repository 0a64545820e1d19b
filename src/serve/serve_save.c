/* SPDX-License-Identifier: MIT */
/* serve_save.c: save as new scene (serve_save.h). */
#include "serve_save.h"

#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "hy_scene.h"
#include "serve_answer.h"
#include "serve_request.h"

#define SAVE_MAX 100        /* saves per run (--allow-save) ... */
#define SAVE_EVERY_S 1.0    /* ... at most one a second */

/* Removes every '#' that starts a line or follows a space, to the end of its line. */
static void strip_comments(char *w)
{
    if (!w)
        return;
    char *o = w;
    for (char *p = w; *p;) {
        if (*p == '#' && (p == w || p[-1] == ' ' || p[-1] == '\n')) {
            while (o > w && o[-1] == ' ')
                o--;
            while (*p && *p != '\n')
                p++;
            continue;
        }
        *o++ = *p++;
    }
    *o = '\0';
}

/* Saving is opt-in (--allow-save) and limited: SAVE_MAX files a run, one
 * every SAVE_EVERY_S.  Returns 1 after answering 429 (with Retry-After) when
 * over a limit, 0 when the save may go on: it is counted now (so two at once
 * cannot both pass) and *prev receives the time to restore if writing fails. */
static int save_refused(sv_server *s, struct MHD_Connection *c, double *prev)
{
    pthread_mutex_lock(&s->mu);
    double t = sv_now();
    int full = s->nsaved >= SAVE_MAX, soon = !full && s->nsaved && t - s->last_save < SAVE_EVERY_S;
    if (!full && !soon) {
        *prev = s->last_save;
        s->nsaved++;
        s->last_save = t;
    }
    pthread_mutex_unlock(&s->mu);
    if (!full && !soon)
        return 0;
    sv_buf b = {0};
    sv_puts(&b, full ? "{\"error\":\"this server has saved its limit of scenes; restart it to save more\"}"
                     : "{\"error\":\"one save a second: try again\"}");
    struct MHD_Response *r = b.oom ? NULL : MHD_create_response_from_buffer(b.len, b.s, MHD_RESPMEM_MUST_FREE);
    if (!r) {
        free(b.s);
        return 1;
    }
    MHD_add_response_header(r, "Content-Type", "application/json");
    if (soon)
        MHD_add_response_header(r, "Retry-After", "1");
    MHD_queue_response(c, 429, r);
    MHD_destroy_response(r);
    return 1;
}

/* Whether the scenes want and got, written back without origins and
 * comments, agree (the same effective values); HY_EINVAL if not. */
static int save_same(const hy_scene *want, const hy_scene *got, hy_error *err)
{
    int rc = HY_OK;
    char *w1 = NULL, *w2 = NULL;
    size_t l1 = 0, l2 = 0;
    FILE *f1 = open_memstream(&w1, &l1), *f2 = open_memstream(&w2, &l2);
    if (f1 && f2) {
        hy_scene_write(want, f1, 1);
        hy_scene_write(got, f2, 1);
    }
    if (f1)
        fclose(f1);
    if (f2)
        fclose(f2);
    /* drop the comments (origins, the header) before comparing */
    strip_comments(w1);
    strip_comments(w2);
    if (!w1 || !w2 || strcmp(w1, w2))
        rc = hy_error_set(err, HY_EINVAL, "the new scene would not reproduce the figure; nothing was written");
    free(w1);
    free(w2);
    return rc;
}

/* Whether newtext, saved as dest, renders what the page shows: want (the
 * original scene, freed here) with the page's overrides and the new output
 * name nm gives the same scene as newtext parsed. */
static int save_reproduces(sv_server *s, const sv_args *a, hy_scene *want, const char *dest, const char *newtext,
                           const char *nm, hy_error *err)
{
    const char *sets[MAX_ARGS + 1];
    char outset[200];
    snprintf(outset, sizeof outset, "output.name=%s", nm);
    for (size_t i = 0; i < a->nsets; i++)
        sets[i] = a->sets[i];
    sets[a->nsets] = outset;
    hy_scene *got = NULL;
    int rc = HY_OK;
    for (size_t i = 0; !rc && i <= a->nsets; i++)
        rc = hy_scene_set(want, sets[i], err);
    if (!rc)
        rc = hy_scene_parse_buffer_policy(dest, newtext, strlen(newtext), &s->pol, &got, err);
    if (!rc) /* same effective values: the scenes written back without origins agree */
        rc = save_same(want, got, err);
    hy_scene_free(want);
    hy_scene_free(got);
    return rc;
}

/* A new scene's name: 1 to 100 letters, digits, '_' or '-', not starting with '.' or '-'. */
static int save_name_ok(const char *nm)
{
    size_t nl = nm ? strlen(nm) : 0;
    return nm && nl && nl <= 100 && nm[0] != '.' && nm[0] != '-' &&
           strspn(nm, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") == nl;
}

/* Writes newtext as dest (file in the directory) unless it exists or the
 * rate limit refuses it (*answered: 429 was sent); a write that fails is
 * not counted. */
static int save_write(sv_server *s, struct MHD_Connection *c, const char *file, const char *dest, const char *newtext,
                      int *answered, hy_error *err)
{
    struct stat st;
    if (!fstatat(s->dirfd, file, &st, AT_SYMLINK_NOFOLLOW)) /* link(2) below decides; this names it early */
        return hy_error_set(err, HY_EINVAL, "%s exists already: choose another name", dest);
    double prev = 0;
    if ((*answered = save_refused(s, c, &prev))) /* answered 429 */
        return HY_OK;
    int rc = sv_write_new(dest, newtext, strlen(newtext), err);
    if (rc) { /* nothing written: not counted */
        pthread_mutex_lock(&s->mu);
        s->nsaved--;
        s->last_save = prev;
        pthread_mutex_unlock(&s->mu);
    }
    return rc;
}

/* The new scene's text from the original's with the page's overrides, or
 * NULL with err (the scene does not parse, or an override does not apply);
 * *want is the original parsed again, for save_reproduces. */
static char *save_text(sv_server *s, const sv_args *a, const char *path, const char *text, size_t tl, const char *nm,
                       hy_scene **want, hy_error *err)
{
    hy_scene *orig = NULL;
    *want = NULL;
    if (hy_scene_parse_buffer_policy(path, text, tl, &s->pol, &orig, err) ||
        hy_scene_parse_buffer_policy(path, text, tl, &s->pol, want, err)) {
        hy_scene_free(orig);
        return NULL;
    }
    /* the new scene must render what the page shows: the original with the
       overrides (and the new output name) */
    char *newtext = sv_scene_with_sets(orig, path, text, (char *const *)a->sets, a->nsets, nm, err);
    hy_scene_free(orig);
    if (!newtext) {
        hy_scene_free(*want);
        *want = NULL;
    }
    return newtext;
}

/* Save as new scene: NAME.scene with the page's overrides written in, after
 * checking that it renders what the page shows; the rate limit is applied
 * just before writing, so a refused request (400, 409, 422) does not count. */
enum MHD_Result sv_api_save(sv_server *s, struct MHD_Connection *c, const sv_args *a, const char *rest)
{
    (void)rest;
    char path[PATH_MAX + 300];
    size_t tl;
    char *text = sv_scene_read(s, a->scene, path, sizeof path, &tl);
    if (!text)
        return sv_send_error(c, 404, "no such scene");
    const char *nm = a->name;
    if (!save_name_ok(nm)) {
        free(text);
        return sv_send_error(c, 400, "name: 1 to 100 letters, digits, '_' or '-' (the new scene is NAME.scene)");
    }
    hy_error err = {0};
    for (size_t i = 0; i < a->nsets; i++)
        if (sv_set_ok(a->sets[i], &err)) {
            free(text);
            return sv_send_error(c, 400, err.msg);
        }
    char dest[PATH_MAX + 300], file[200];
    snprintf(dest, sizeof dest, "%s/%s.scene", s->dir_arg, nm);
    snprintf(file, sizeof file, "%s.scene", nm);
    hy_scene *want;
    char *newtext = save_text(s, a, path, text, tl, nm, &want, &err);
    free(text);
    if (!newtext)
        return sv_send_error(c, 422, err.msg);
    int answered = 0, rc = save_reproduces(s, a, want, dest, newtext, nm, &err);
    if (!rc)
        rc = save_write(s, c, file, dest, newtext, &answered, &err);
    free(newtext);
    if (answered)
        return MHD_YES;
    if (rc)
        return sv_send_error(c, rc == HY_EINVAL ? 409 : 500, err.msg);
    sv_buf b = {0};
    sv_puts(&b, "{\"file\":");
    sv_json(&b, file);
    sv_puts(&b, ",\"path\":");
    sv_json(&b, dest);
    sv_puts(&b, "}");
    return sv_send_json(c, 201, &b);
}
