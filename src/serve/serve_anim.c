/* SPDX-License-Identifier: MIT */
/* serve_anim.c: hystviz-animate out of process: --list at start-up, --info
 * through the frame workers, cached (serve_anim.h). */
#include "serve_anim.h"

#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "hy_child.h"
#include "serve_request.h"
#include "serve_slots.h"

#define CHILD_TIMEOUT_S 60  /* hystviz-animate --info / --list: killed after this */

extern char **environ;

/* Runs argv with stdout and stderr into out (NUL-terminated, truncated to
 * size); returns the exit status, -1 if it could not run or was killed
 * after CHILD_TIMEOUT_S, -2 if stop_fd (a signalfd, or -1 for none) became
 * readable first (the child is killed).  The child is reaped before this
 * returns. */
static int run_capture(char *const *argv, char *out, size_t size, int stop_fd)
{
    int fd[2];
    out[0] = '\0';
    if (pipe(fd))
        return -1;
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, fd[1], 1);
    posix_spawn_file_actions_adddup2(&fa, fd[1], 2);
    posix_spawn_file_actions_addclose(&fa, fd[0]);
    pid_t pid;
    int sp = posix_spawn(&pid, argv[0], &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    close(fd[1]);
    size_t n = 0;
    double deadline = sv_now() + CHILD_TIMEOUT_S;
    int killed = 0, stopped = 0;
    for (;;) {
        struct pollfd pf[2] = {{fd[0], POLLIN, 0}, {stop_fd, POLLIN, 0}};
        double left = deadline - sv_now();
        int pr = sp ? 1 : left <= 0 ? 0 : poll(pf, stop_fd >= 0 ? 2 : 1, (int)(left * 1000) + 1);
        if (!sp && stop_fd >= 0 && pr > 0 && (pf[1].revents & POLLIN)) {
            kill(pid, SIGKILL); /* a signal for serve during start-up */
            stopped = 1;
            break;
        }
        if (!sp && pr == 0) {
            kill(pid, SIGKILL); /* hung: its slot and its pipe are freed */
            killed = 1;
            break;
        }
        if (hy_child_read(fd[0], out, size, &n) <= 0)
            break;
    }
    out[n] = '\0';
    close(fd[0]);
    if (sp)
        return -1;
    int status;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR)
            return -1;
    return stopped ? -2 : !killed && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/* The built-in animations (hystviz-animate animate --list); -1 when a
 * signal came meanwhile (stop_fd readable), else 0. */
int sv_list_builtins(sv_server *s, int stop_fd)
{
    char out[8192];
    char *argv[] = {s->animate, "animate", "--list", NULL};
    int rc = s->animate[0] ? run_capture(argv, out, sizeof out, stop_fd) : 1;
    if (rc == -2)
        return -1;
    if (rc != 0)
        return 0; /* no hystviz-animate, or built without OSMesa */
    for (char *line = out; *line && s->nbuiltin < 32;) {
        char *nl = strchr(line, '\n');
        if (nl)
            *nl = '\0';
        if (!*line)
            break; /* the animations end at the first empty line (the GL backend follows) */
        char *sp = strchr(line, ' ');
        if (sp && sp - line < 32 && strspn(line, "abcdefghijklmnopqrstuvwxyz0123456789-") == (size_t)(sp - line)) {
            snprintf(s->builtin[s->nbuiltin], sizeof s->builtin[0], "%.*s", (int)(sp - line), line);
            while (*sp == ' ')
                sp++;
            snprintf(s->builtin_doc[s->nbuiltin], sizeof s->builtin_doc[0], "%s", sp);
            s->nbuiltin++;
        }
        if (!nl)
            break;
        line = nl + 1;
    }
    return 0;
}

/* "@NAME" of a built-in animation: its index, or -1. */
int sv_builtin_index(const sv_server *s, const char *name)
{
    for (int i = 0; name && name[0] == '@' && i < s->nbuiltin; i++)
        if (!strcmp(name + 1, s->builtin[i]))
            return i;
    return -1;
}

/* The frames and fps of an animation (`hystviz animate WHAT --info`, asked
 * of a frame worker with the scene's text, NULL for a built-in); 0 or -1
 * with msg set.  The answer is cached by hash (hy_scene_hash: the scene's
 * text and its includes), so reloading a page asks nothing; a request runs
 * in a render slot. */
static int anim_info(sv_server *s, struct MHD_Connection *c, uint64_t hash, const char *what, const char *text,
                     size_t len, long *frames, double *fps, char *msg, size_t size)
{
    pthread_mutex_lock(&s->mu);
    for (size_t i = 0; i < ANIM_CACHE; i++)
        if (s->anim[i].hash == hash && (s->anim[i].ok || s->anim[i].msg[0])) {
            sv_anim_entry e = s->anim[i];
            pthread_mutex_unlock(&s->mu);
            *frames = e.frames, *fps = e.fps;
            snprintf(msg, size, "%s", e.msg);
            return e.ok ? 0 : -1;
        }
    pthread_mutex_unlock(&s->mu);
    int slot = sv_slot_take(s, c, 0);
    if (slot != SV_SLOT_OK) {
        snprintf(msg, size, "the server is busy: reload the page");
        return -1;
    }
    aw_request rq = {.op = "info", .name = (char *)what, .text = (char *)text, .len = len};
    char *out = NULL, why[2048];
    int rc = s->frames ? sv_frames_run(s->frames, &rq, NULL, NULL, NULL, NULL, &out, why, sizeof why)
                       : (snprintf(why, sizeof why, "no frame worker"), SV_FRAMES_FAILED);
    sv_slot_give(s, c, 0);
    sv_anim_entry e = {.hash = hash};
    if (rc == 0 && out && sscanf(out, "frames %ld fps %lf", &e.frames, &e.fps) == 2)
        e.ok = 1;
    else
        snprintf(e.msg, sizeof e.msg, "%.*s", (int)sizeof e.msg - 1,
                 rc < 0 ? "cannot run hystviz-animate (it is built next to hystviz)" : why);
    free(out);
    if (rc >= 0) { /* a failure to start is not cached: it may be a passing shortage */
        pthread_mutex_lock(&s->mu);
        s->anim[s->anim_next++ % ANIM_CACHE] = e;
        pthread_mutex_unlock(&s->mu);
    }
    *frames = e.frames, *fps = e.fps;
    snprintf(msg, size, "%s", e.msg);
    return e.ok ? 0 : -1;
}

void sv_json_anim(sv_buf *b, sv_server *s, struct MHD_Connection *c, uint64_t hash, const char *what,
                      const char *text, size_t len)
{
    long frames = 0;
    double fps = 0;
    char msg[2048];
    if (anim_info(s, c, hash, what, text, len, &frames, &fps, msg, sizeof msg)) {
        sv_puts(b, ",\"anim\":{\"frames\":0,\"error\":");
        sv_json(b, msg);
        sv_puts(b, "}");
        return;
    }
    sv_printf(b, ",\"anim\":{\"frames\":%ld,\"fps\":", frames);
    sv_num(b, fps);
    sv_puts(b, "}");
}

/* FNV-1a of a built-in animation's name (its cache key). */
uint64_t sv_name_hash(const char *name)
{
    uint64_t h = 0xcbf29ce484222325ull ^ 0x40; /* apart from scene hashes' start */
    for (; *name; name++)
        h = (h ^ (unsigned char)*name) * 0x100000001b3ull;
    return h;
}
