/* SPDX-License-Identifier: MIT */
/* export_anim.c: an animation as one offline page (export_anim.h): the
 * frames from hystviz-animate, each distinct PNG base64 in the template
 * src/app/export/anim.html. */
#include "export_anim.h"

#include <dirent.h>
#include <fcntl.h>
#include <errno.h>
#include <signal.h>
#include <spawn.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "export_page.h"
#include "hy_child.h"
#include "hy_file.h"
#include "hy_out.h"

extern const char hy_export_anim_html[];
extern const size_t hy_export_anim_html_len;

#define MAX_ARGS (16 + 2 * 64 + 2 * 64)

/* ---- hystviz-animate ---------------------------------------------------- */

typedef struct argvec {
    char *v[MAX_ARGS];
    size_t n;
    char work[64];
} argvec;

static int push(argvec *a, const char *s)
{
    if (a->n + 2 > MAX_ARGS)
        return -1;
    a->v[a->n++] = (char *)s;
    a->v[a->n] = NULL;
    return 0;
}

/* The renderer's command line up to its own options: the program, the
 * animation and the options the page passes on. */
static int base_args(const exp_anim_opts *o, char *prog, argvec *a)
{
    a->n = 0;
    int bad = push(a, prog) || push(a, "animate") || push(a, o->name);
    for (size_t k = 0; k < o->nsets; k++)
        bad |= push(a, "--set") || push(a, o->sets[k]);
    for (size_t k = 0; o->pol && k < o->pol->ninclude_dirs; k++)
        bad |= push(a, "--include-dir") || push(a, o->pol->include_dirs[k]);
    if (o->pol && o->pol->max_work > 0) {
        snprintf(a->work, sizeof a->work, "%.17g", o->pol->max_work);
        bad |= push(a, "--max-work") || push(a, a->work);
    }
    if (o->size)
        bad |= push(a, "--size") || push(a, o->size);
    return bad ? -1 : 0;
}

/* Runs argv (its stderr the user's, signals unblocked); its standard output
 * into out (NUL-terminated, at most size - 1 bytes) when out is given, else
 * to /dev/null.  Returns its exit status, or -1 if it could not run or was
 * killed (a message printed). */
static int run(char *const *argv, char *out, size_t size)
{
    int fd[2] = {-1, -1};
    if (out && pipe(fd)) {
        fprintf(stderr, "hystviz export: cannot make a pipe: %s\n", strerror(errno));
        return -1;
    }
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    if (out) {
        posix_spawn_file_actions_adddup2(&fa, fd[1], 1);
        posix_spawn_file_actions_addclose(&fa, fd[0]);
    } else
        posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
    pid_t pid;
    int sp = hy_child_spawn(&pid, argv, &fa);
    posix_spawn_file_actions_destroy(&fa);
    size_t n = 0;
    if (out) {
        close(fd[1]);
        while (!sp && hy_child_read(fd[0], out, size, &n) > 0)
            ;
        close(fd[0]);
        out[n] = '\0';
    }
    if (sp) {
        fprintf(stderr, "hystviz export: cannot run %s: %s\n", argv[0], strerror(sp));
        return -1;
    }
    int status;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR)
            return -1;
    if (!WIFEXITED(status)) {
        fprintf(stderr, "hystviz export: %s was killed (signal %d)\n", argv[0], WTERMSIG(status));
        return -1;
    }
    return WEXITSTATUS(status);
}

/* The renderer's status as export's (export_anim.h). */
static int status_of(int st)
{
    return st == 2 || st == 3 ? st : 1;
}

/* ---- the frames --------------------------------------------------------- */

typedef struct frames {
    long n;                    /* frames of the clip */
    double fps, duration;
    int width, height;
    unsigned char **png;       /* distinct PNGs, in order of first use */
    size_t *len;
    uint64_t *hash;
    size_t ndistinct;
    long *order;               /* frame i -> its distinct PNG */
} frames;

static void frames_free(frames *f)
{
    for (size_t k = 0; k < f->ndistinct; k++)
        free(f->png[k]);
    free(f->png);
    free(f->len);
    free(f->hash);
    free(f->order);
}

static uint64_t fnv(const unsigned char *s, size_t n)
{
    uint64_t h = 14695981039346656037ULL;
    for (size_t i = 0; i < n; i++)
        h = (h ^ s[i]) * 1099511628211ULL;
    return h;
}

static unsigned char *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    unsigned char *b = NULL;
    size_t cap = 0;
    *len = 0;
    for (;;) {
        if (*len == cap) {
            unsigned char *nb = realloc(b, cap = cap ? 2 * cap : 65536);
            if (!nb)
                break;
            b = nb;
        }
        size_t r = fread(b + *len, 1, cap - *len, f);
        *len += r;
        if (r == 0)
            break;
    }
    int bad = ferror(f) || !feof(f);
    fclose(f);
    if (bad) {
        free(b);
        return NULL;
    }
    return b;
}

/* Reads dir/frame_%05d.png for every frame, storing each distinct one once. */
static int read_frames(const char *dir, frames *f)
{
    f->png = calloc((size_t)f->n, sizeof *f->png);
    f->len = calloc((size_t)f->n, sizeof *f->len);
    f->hash = calloc((size_t)f->n, sizeof *f->hash);
    f->order = calloc((size_t)f->n, sizeof *f->order);
    if (!f->png || !f->len || !f->hash || !f->order) {
        fprintf(stderr, "hystviz export: out of memory\n");
        return 1;
    }
    for (long i = 0; i < f->n; i++) {
        char path[4400];
        size_t len;
        unsigned char *b = snprintf(path, sizeof path, "%s/frame_%05ld.png", dir, i) < (int)sizeof path
                               ? slurp(path, &len) : NULL;
        if (!b) {
            fprintf(stderr, "hystviz export: cannot read the renderer's frame '%s': %s\n", path, strerror(errno));
            return 1;
        }
        uint64_t h = fnv(b, len);
        size_t k = 0;
        while (k < f->ndistinct && !(f->hash[k] == h && f->len[k] == len && !memcmp(f->png[k], b, len)))
            k++;
        if (k < f->ndistinct)
            free(b);
        else {
            f->png[k] = b;
            f->len[k] = len;
            f->hash[k] = h;
            f->ndistinct++;
        }
        f->order[i] = (long)k;
    }
    return 0;
}

/* Removes the renderer's output under tmp (two levels: NAME/frame_*.png and
 * the poster NAME.png), then tmp. */
void exp_remove_tree(const char *tmp, int depth)
{
    DIR *d = opendir(tmp);
    struct dirent *e;
    while (d && (e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        char path[4400];
        if (snprintf(path, sizeof path, "%s/%s", tmp, e->d_name) >= (int)sizeof path)
            continue;
        struct stat st;
        if (depth > 0 && !lstat(path, &st) && S_ISDIR(st.st_mode))
            exp_remove_tree(path, depth - 1);
        else
            unlink(path);
    }
    if (d)
        closedir(d);
    rmdir(tmp);
}

/* The one directory the renderer made under tmp (NAME/) into sub. */
static int frame_dir(const char *tmp, char *sub, size_t size)
{
    DIR *d = opendir(tmp);
    struct dirent *e;
    int found = 0;
    while (d && (e = readdir(d))) {
        char path[4400];
        struct stat st;
        if (snprintf(path, sizeof path, "%s/%s", tmp, e->d_name) >= (int)sizeof path)
            continue;
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..") && !lstat(path, &st) && S_ISDIR(st.st_mode)) {
            snprintf(sub, size, "%s", path);
            found++;
        }
    }
    if (d)
        closedir(d);
    return found == 1 ? 0 : -1;
}

/* Renders every frame into a temporary directory and reads them. */
static int render_frames(const exp_anim_opts *o, char *prog, frames *f)
{
    argvec a;
    char info[512];
    if (base_args(o, prog, &a) || push(&a, "--info")) {
        fprintf(stderr, "hystviz export: too many options for the renderer\n");
        return 2;
    }
    int st = run(a.v, info, sizeof info);
    if (st)
        return st < 0 ? 1 : status_of(st);
    if (sscanf(info, "frames %ld fps %lf size %dx%d duration %lf", &f->n, &f->fps, &f->width, &f->height,
               &f->duration) != 5 || f->n < 1) {
        fprintf(stderr, "hystviz export: the renderer's --info is not understood: '%.100s'\n", info);
        return 1;
    }
    const char *td = getenv("TMPDIR");
    char tmp[4200], jobs[32], sub[4400];
    snprintf(tmp, sizeof tmp, "%s/hystviz-export-XXXXXX", td && *td ? td : "/tmp");
    if (!mkdtemp(tmp)) {
        fprintf(stderr, "hystviz export: cannot make a temporary directory '%s': %s\n", tmp, strerror(errno));
        return 1;
    }
    snprintf(jobs, sizeof jobs, "%ld", o->jobs);
    if (base_args(o, prog, &a) || push(&a, "-o") || push(&a, tmp) || push(&a, "-j") || push(&a, jobs) ||
        push(&a, "--quiet"))
        st = 2;
    else
        st = run(a.v, NULL, 0);
    if (st)
        st = st < 0 ? 1 : status_of(st);
    else if (frame_dir(tmp, sub, sizeof sub)) {
        fprintf(stderr, "hystviz export: the renderer left no frame directory in '%s'\n", tmp);
        st = 1;
    } else
        st = read_frames(sub, f);
    exp_remove_tree(tmp, 2);
    return st;
}

/* ---- the page ----------------------------------------------------------- */

static void write_meta(FILE *f, const exp_anim_opts *o, const frames *fr)
{
    const char *base = strrchr(o->name, '/') ? strrchr(o->name, '/') + 1 : o->name;
    size_t n = strlen(base);
    if (n > 6 && !strcmp(base + n - 6, ".scene"))
        n -= 6;
    fputs("{\"title\":", f);
    exp_json_str(f, base, n);
    fputs(",\"name\":", f);
    exp_json_str(f, base, n);
    fprintf(f, ",\"fps\":%.17g,\"frames\":%ld,\"width\":%d,\"height\":%d,\"duration\":%.17g,\"order\":[", fr->fps,
            fr->n, fr->width, fr->height, fr->duration);
    for (long i = 0; i < fr->n; i++)
        fprintf(f, "%s%ld", i ? "," : "", fr->order[i]);
    char *cmd = NULL;
    size_t clen = 0;
    FILE *c = open_memstream(&cmd, &clen);
    if (c) {
        fprintf(c, "hystviz animate %s", o->name);
        for (size_t k = 0; k < o->nsets; k++)
            fprintf(c, " --set %s", o->sets[k]);
        if (o->size)
            fprintf(c, " --size %s", o->size);
        fclose(c);
    }
    fputs("],\"command\":", f);
    exp_json_str(f, cmd ? cmd : "", cmd ? clen : 0);
    fputc('}', f);
    free(cmd);
}

static int write_page(const exp_anim_opts *o, const frames *fr, FILE *f)
{
    const char *t = hy_export_anim_html, *meta = strstr(t, "@META@"), *fm = meta ? strstr(meta, "@FRAMES@") : NULL;
    if (!fm) {
        fprintf(stderr, "hystviz export: the page template lacks its @META@ and @FRAMES@ marks\n");
        return 1;
    }
    fwrite(t, 1, (size_t)(meta - t), f);
    write_meta(f, o, fr);
    fwrite(meta + 6, 1, (size_t)(fm - meta - 6), f);
    for (size_t k = 0; k < fr->ndistinct; k++) {
        fputs("<script class=\"frame\" type=\"application/octet-stream\">\n", f);
        exp_base64(f, fr->png[k], fr->len[k]);
        fputs("\n</script>\n", f);
    }
    fwrite(fm + 8, 1, hy_export_anim_html_len - (size_t)(fm + 8 - t), f);
    return 0;
}

int exp_anim_run(const exp_anim_opts *o)
{
    char prog[4200];
    if (hy_file_installed(HY_INSTALLED_LIBEXEC, "hystviz-animate", prog, sizeof prog)) {
        fprintf(stderr, "hystviz export: hystviz-animate (the animation renderer) not found next to hystviz\n");
        return 3;
    }
    hy_out out;
    hy_error err = {0};
    if (hy_out_open(&out, o->out, HY_OUT_FOLLOW, &err)) { /* a bad target fails before rendering */
        fprintf(stderr, "hystviz export: %s\n", err.msg);
        return 1;
    }
    frames fr;
    memset(&fr, 0, sizeof fr);
    int rc = render_frames(o, prog, &fr);
    if (!rc)
        rc = write_page(o, &fr, hy_out_file(&out));
    rc = exp_out_finish(&out, rc);
    if (!rc && !o->quiet)
        fprintf(stderr, "export: %s, %ld frames at %.6g fps (%zu distinct) %dx%d; %s\n", o->name, fr.n, fr.fps,
                fr.ndistinct, fr.width, fr.height, o->out);
    frames_free(&fr);
    return rc;
}
