/* SPDX-License-Identifier: MIT */
/* hy_anim.c: animation engine: keyframe tracks and easing, quality presets,
 * a pool of threads each owning an OSMesa context, ordered ffmpeg piping,
 * atomic PNG frames and a terminal progress bar. */
#include "hy_anim.h"

#include "hy_quality.h"

#include <cairo.h>
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "hy_cairo.h"
#include "hy_os.h"
#include "hy_out.h"

/* ---- timeline ---- */

double hy_ease(int ease, double x)
{
    x = x < 0 ? 0 : x > 1 ? 1 : x;
    return ease == HY_EASE_SMOOTH ? x * x * (3.0 - 2.0 * x) : x;
}

double hy_track_eval(const hy_track *tr, double t)
{
    if (!tr->n)
        return 0.0;
    if (t <= tr->keys[0].t)
        return tr->keys[0].v;
    size_t i = 1;
    while (i < tr->n && tr->keys[i].t < t)
        i++;
    if (i == tr->n)
        return tr->keys[tr->n - 1].v;
    const hy_key *a = &tr->keys[i - 1], *b = &tr->keys[i];
    double span = b->t - a->t, f = span > 0 ? hy_ease(b->ease, (t - a->t) / span) : 1.0;
    if (tr->log && a->v > 0 && b->v > 0)
        return exp(log(a->v) + f * (log(b->v) - log(a->v)));
    return a->v + f * (b->v - a->v);
}

/* ---- presets ---- */

static const struct preset {
    const char *name;
    int w, h;
    double fps;
} presets[] = {
#define QUALITY_ROW(name, w, h, fps) {name, w, h, fps},
    HY_QUALITY_PRESETS(QUALITY_ROW)
#undef QUALITY_ROW
};
#define NPRESETS (sizeof presets / sizeof presets[0])

const char *const *hy_anim_quality_names(void)
{
    static const char *names[NPRESETS + 1];
    for (size_t i = 0; i < NPRESETS; i++)
        names[i] = presets[i].name;
    return names;
}

int hy_anim_quality(const char *name, int *width, int *height, double *fps, hy_error *err)
{
    for (size_t i = 0; name && i < NPRESETS; i++)
        if (!strcmp(name, presets[i].name)) {
            *width = presets[i].w, *height = presets[i].h, *fps = presets[i].fps;
            return HY_OK;
        }
    char known[160];
    size_t o = 0;
    for (size_t i = 0; i < NPRESETS && o < sizeof known; i++)
        o += (size_t)snprintf(known + o, sizeof known - o, "%s%s", i ? " " : "", presets[i].name);
    return hy_error_set(err, HY_EINVAL, "unknown quality '%s' (known: %s)", name ? name : "", known);
}

hy_anim_params hy_anim_defaults(void)
{
    hy_anim_params p;
    memset(&p, 0, sizeof p);
    p.outdir = ".";
    p.name = "animation";
    p.width = 1280, p.height = 720, p.fps = 30, p.duration = 4;
    p.last = -1;
    p.jobs = 1;
    p.poster = 1;
    p.png = hy_png_frame_defaults();
    return p;
}

long hy_anim_nframes(const hy_anim_params *p)
{
    double n = floor(p->duration * p->fps + 0.5);
    return n < 1 ? 1 : n > 1e7 ? 10000000L : (long)n;
}

int hy_anim_on_path(const char *prog)
{
    const char *path = getenv("PATH");
    char buf[4096];
    while (path && *path) {
        const char *end = strchr(path, ':');
        size_t n = end ? (size_t)(end - path) : strlen(path);
        if (n && snprintf(buf, sizeof buf, "%.*s/%s", (int)n, path, prog) < (int)sizeof buf &&
            access(buf, X_OK) == 0)
            return 1;
        path = end ? end + 1 : NULL;
    }
    return 0;
}

/* ---- the run ---- */

typedef struct run {
    const hy_anim_params *p;
    hy_anim_draw_fn draw;
    void *state;
    long nframes, first, last, next, done, piped;
    char dir[4096];
    FILE *video;              /* ffmpeg's standard input */
    pid_t video_pid;
    hy_out video_out;         /* ffmpeg writes its temporary; renamed when complete */
    pthread_mutex_t mu;
    pthread_cond_t cv;
    int failed;
    hy_error err;
    double t0, last_bar, draw_s, read_s, png_s;
    int bar;
} run;

static void fail(run *r, const hy_error *e)
{
    pthread_mutex_lock(&r->mu);
    if (!r->failed)
        r->err = *e, r->failed = 1;
    pthread_cond_broadcast(&r->cv);
    pthread_mutex_unlock(&r->mu);
}

/* Progress bar, called with the mutex held: frames done, frames/s, time left. */
static void progress(run *r, int final)
{
    double t = hy_now();
    if (!r->bar || (!final && t - r->last_bar < 0.1))
        return;
    r->last_bar = t;
    long total = r->last - r->first;
    double el = t - r->t0, fps = el > 0 ? (double)r->done / el : 0;
    double left = fps > 0 ? (double)(total - r->done) / fps : 0;
    int width = 30, fill = total > 0 ? (int)(width * r->done / total) : width;
    char bar[40];
    for (int i = 0; i < width; i++)
        bar[i] = i < fill ? '#' : '.';
    bar[width] = '\0';
    fprintf(stderr, "\r%s [%s] %ld/%ld frames  %.1f frames/s  %.1f s left ", r->p->name, bar, r->done, total,
            fps, left);
    if (final)
        fputc('\n', stderr);
    fflush(stderr);
}

/* Sends frame i to ffmpeg in order: waits until every earlier frame went. */
static int pipe_frame(run *r, long i, const unsigned char *rgb, size_t n)
{
    pthread_mutex_lock(&r->mu);
    while (r->piped != i && !r->failed)
        pthread_cond_wait(&r->cv, &r->mu);
    int ok = !r->failed && fwrite(rgb, 1, n, r->video) == n;
    r->piped++;
    pthread_cond_broadcast(&r->cv);
    pthread_mutex_unlock(&r->mu);
    return ok ? HY_OK : -1;
}

typedef struct worker {
    hy_gl *gl;
    cairo_surface_t *frame;   /* the GL context's own buffer as a cairo RGB24 image */
    double draw_s, read_s, png_s;
    double t_drawn;           /* when compose's draw function returned */
} worker;

/* Draws frame i of nframes of p's animation in w's GL context: the draw
 * function records the overlay (text, axes) while it gives the GL canvas the
 * data; GL finishes into its own buffer, which is a cairo RGB24 image; the
 * recorded overlay is painted over it there.  *fb is that buffer (stride
 * 4 * width), valid until the next frame of w: it goes to libpng (and
 * ffmpeg) as it is, with no readback copy, compositing or RGB pass. */
static int compose(const hy_anim_params *p, hy_anim_draw_fn draw, void *state, long nframes, worker *w, long i,
                   const unsigned char **fb, hy_error *err)
{
    int W = p->width, H = p->height, stride = 4 * W;
    cairo_rectangle_t ext = {0, 0, W, H};
    cairo_surface_t *rec = cairo_recording_surface_create(CAIRO_CONTENT_COLOR_ALPHA, &ext);
    cairo_t *cr = cairo_create(rec);
    double k = p->scale > 0 ? p->scale : H / HY_ANIM_POINTS_HIGH;
    cairo_scale(cr, k, k);
    hy_cairo_canvas cc;
    hy_anim_frame f = {i, nframes, (double)i / p->fps, p->duration,
                       nframes > 1 ? (double)i / (double)(nframes - 1) : 0.0, W, H, k, w->gl,
                       hy_gl_canvas(w->gl, k), hy_canvas_cairo(&cc, cr, NULL)};
    hy_gl_begin(w->gl, (hy_rgb){1, 1, 1});
    int st = draw(state, &f, err);
    cairo_destroy(cr);
    if (!st && cairo_surface_status(rec))
        st = hy_error_set(err, HY_ENOMEM, "cairo could not record the frame's overlay: %s",
                          cairo_status_to_string(cairo_surface_status(rec)));
    double t1 = hy_now();
    *fb = st ? NULL : hy_gl_finish(w->gl, err);
    if (!st && !*fb)
        st = err && err->code ? err->code : HY_ENUM;
    if (!st && !w->frame) {
        w->frame = cairo_image_surface_create_for_data((unsigned char *)*fb, CAIRO_FORMAT_RGB24, W, H, stride);
        if (cairo_surface_status(w->frame))
            st = hy_error_set(err, HY_ENOMEM, "out of memory for %d x %d frames", W, H);
    }
    if (!st) {
        cairo_surface_mark_dirty(w->frame);
        cairo_t *c2 = cairo_create(w->frame);
        cairo_set_source_surface(c2, rec, 0, 0);
        cairo_paint(c2);
        cairo_destroy(c2);
        cairo_surface_flush(w->frame);
    }
    cairo_surface_destroy(rec);
    w->t_drawn = t1;
    return st;
}

/* One frame of the run: composed, then written as a PNG frame (and the
 * poster, and piped to ffmpeg). */
static int render_one(run *r, worker *w, long i, hy_error *err)
{
    const hy_anim_params *p = r->p;
    int W = p->width, H = p->height, stride = 4 * W;
    double t0 = hy_now();
    const unsigned char *fb = NULL;
    int st = compose(p, r->draw, r->state, r->nframes, w, i, &fb, err);
    double t1 = w->t_drawn, t2 = hy_now();
    char path[4200];
    if (!st && !p->no_frames) {
        snprintf(path, sizeof path, "%s/frame_%05ld.png", r->dir, i);
        st = hy_png_write_xrgb(path, W, H, fb, stride, &p->png, err);
    }
    if (!st && p->poster && i == r->nframes - 1) {
        snprintf(path, sizeof path, "%s/%s.png", p->outdir, p->name);
        st = hy_png_write_xrgb(path, W, H, fb, stride, &p->png, err);
    }
    if (!st && r->video && pipe_frame(r, i, fb, (size_t)stride * (size_t)H))
        st = hy_error_set(err, HY_EIO, "ffmpeg stopped reading frames (see its messages above)");
    double t3 = hy_now();
    if (st)
        t1 = t2;
    w->draw_s += t1 - t0, w->read_s += t2 - t1, w->png_s += t3 - t2;
    return st;
}

static pthread_mutex_t create_mu = PTHREAD_MUTEX_INITIALIZER;

static void *work(void *arg)
{
    run *r = arg;
    const hy_anim_params *p = r->p;
    worker w;
    memset(&w, 0, sizeof w);
    hy_error err = {0, ""};
    pthread_mutex_lock(&create_mu);    /* OSMesa context creation, one at a time */
    int st = hy_gl_create(&w.gl, p->width, p->height, &err);
    pthread_mutex_unlock(&create_mu);
    while (!st) {
        pthread_mutex_lock(&r->mu);
        long i = r->failed ? r->last : r->next++;
        pthread_mutex_unlock(&r->mu);
        if (i >= r->last)
            break;
        st = render_one(r, &w, i, &err);
        pthread_mutex_lock(&r->mu);
        r->done += !st;
        progress(r, 0);
        pthread_mutex_unlock(&r->mu);
    }
    if (st)
        fail(r, &err);
    pthread_mutex_lock(&r->mu);
    r->draw_s += w.draw_s, r->read_s += w.read_s, r->png_s += w.png_s;
    pthread_mutex_unlock(&r->mu);
    if (w.frame)
        cairo_surface_destroy(w.frame);
    hy_gl_free(w.gl);
    return NULL;
}

static int make_dir(const char *d, hy_error *err)
{
    char buf[4096];
    size_t n = strlen(d);
    if (n >= sizeof buf)
        return hy_error_set(err, HY_EINVAL, "output directory name is too long");
    memcpy(buf, d, n + 1);
    for (size_t i = 1; i <= n; i++)
        if (buf[i] == '/' || buf[i] == '\0') {
            char c = buf[i];
            buf[i] = '\0';
            if (mkdir(buf, 0755) != 0 && errno != EEXIST)
                return hy_error_set(err, HY_EIO, "cannot create directory '%s': %s", buf, strerror(errno));
            buf[i] = c;
        }
    return HY_OK;
}

static int check_params(const hy_anim_params *p, long nframes, hy_error *err)
{
    if (!p->outdir || !p->name || !*p->name || strchr(p->name, '/'))
        return hy_error_set(err, HY_EINVAL, "an animation needs an output directory and a name without '/'");
    if (p->width < 16 || p->height < 16 || p->width > 8192 || p->height > 8192)
        return hy_error_set(err, HY_EINVAL, "frame size %d x %d is outside 16..8192 pixels", p->width, p->height);
    if (!(p->fps > 0 && p->fps <= 240) || !(p->duration > 0 && p->duration <= 3600))
        return hy_error_set(err, HY_EINVAL, "fps %g must be in (0, 240] and duration %g s in (0, 3600]",
                            p->fps, p->duration);
    long last = p->last < 0 ? nframes : p->last;
    if (p->first < 0 || p->first >= last || last > nframes)
        return hy_error_set(err, HY_EINVAL, "frame range %ld:%ld is outside the animation's %ld frames "
                            "(0:%ld)", p->first, last, nframes, nframes);
    if (p->jobs < 0 || p->jobs > 64)
        return hy_error_set(err, HY_EINVAL, "jobs %d must be in 1..64", p->jobs);
    if (p->no_frames && !p->video)
        return hy_error_set(err, HY_EINVAL, "no PNG frames and no video: nothing to write (--no-frames needs --video)");
    return HY_OK;
}

static int open_video(run *r, hy_error *err)
{
    const hy_anim_params *p = r->p;
    const char *v = p->video;
    if (strcmp(v, "mp4") && strcmp(v, "webm") && strcmp(v, "gif"))
        return hy_error_set(err, HY_EINVAL, "unknown video format '%s' (mp4, webm or gif)", v);
    if (!hy_anim_on_path("ffmpeg"))
        return hy_error_set(err, HY_EUNSUP, "--video %s needs ffmpeg, which is not on PATH: install it "
                            "(Debian: apt-get install ffmpeg), or render the PNG frames and encode them "
                            "later with: ffmpeg -framerate %g -i %s/%s/frame_%%05d.png %s/%s.%s",
                            v, p->fps, p->outdir, p->name, p->outdir, p->name, v);
    const char *codec = !strcmp(v, "mp4") ? "libx264" : !strcmp(v, "webm") ? "libvpx-vp9" : NULL;
    char path[4200];
    if (snprintf(path, sizeof path, "%s/%s.%s", p->outdir, p->name, v) >= (int)sizeof path)
        return hy_error_set(err, HY_EINVAL, "output directory name is too long");
    /* an empty temporary, locked, that ffmpeg fills (-y) and publish renames */
    int st = hy_out_open(&r->video_out, path, 0, err);
    if (!st)
        st = hy_out_finish(&r->video_out, err);
    if (st)
        return st;
    char size[64], rate[40];
    snprintf(size, sizeof size, "%dx%d", p->width, p->height);
    snprintf(rate, sizeof rate, "%g", p->fps);
    /* the container named with -f: the temporary name has no telling extension;
     * bitexact: no random segment UID, no encoder version (identical runs give
     * identical files; anim_assemble.c does the same) */
    char *argv[32] = {"ffmpeg", "-loglevel", "error", "-y", "-f", "rawvideo", "-pix_fmt",
                      hy_little_endian() ? "bgr0" : "0rgb", "-s", size, "-r", rate, "-i", "-"};
    int a = 14;
    if (codec) {
        argv[a++] = "-c:v", argv[a++] = (char *)codec;
        argv[a++] = "-pix_fmt", argv[a++] = "yuv420p";
    }
    argv[a++] = "-fflags", argv[a++] = "+bitexact", argv[a++] = "-flags:v", argv[a++] = "+bitexact";
    argv[a++] = "-f", argv[a++] = (char *)v;
    argv[a++] = (char *)hy_out_tmp_path(&r->video_out);
    argv[a] = NULL;
    /* started through hy_out: a signal that ends this process stops it first */
    int fd = -1, e = hy_out_spawn(argv, &fd, &r->video_pid);
    if (!e && !(r->video = fdopen(fd, "w"))) {
        e = errno;
        close(fd);
        hy_out_wait(r->video_pid);
    }
    if (e) {
        hy_out_abort(&r->video_out);
        return hy_error_set(err, HY_EIO, "cannot start ffmpeg: %s", strerror(e));
    }
    return HY_OK;
}

/* Removes DIR/frame_N.png for N >= nframes (a longer earlier run's frames,
 * which `ffmpeg -i frame_%05d.png` would encode after ours) and the frame
 * directory's stale temporaries. */
static void remove_frames_after(const char *dir, long nframes)
{
    hy_out_sweep(dir);
    DIR *d = opendir(dir);
    if (!d)
        return;
    for (struct dirent *de; (de = readdir(d));) {
        const char *s = de->d_name;
        char *end;
        if (strncmp(s, "frame_", 6) || s[6] < '0' || s[6] > '9')
            continue;
        errno = 0;
        unsigned long long i = strtoull(s + 6, &end, 10);
        if (strcmp(end, ".png") || end - (s + 6) < 5 || errno || i < (unsigned long long)nframes)
            continue;
        unlinkat(dirfd(d), s, 0);
    }
    closedir(d);
}

static int start(run *r, hy_error *err)
{
    const hy_anim_params *p = r->p;
    if (check_params(p, r->nframes, err))
        return HY_EINVAL;
    if (snprintf(r->dir, sizeof r->dir, "%s/%s", p->outdir, p->name) >= (int)sizeof r->dir)
        return hy_error_set(err, HY_EINVAL, "output directory name is too long");
    int st = make_dir(p->no_frames ? p->outdir : r->dir, err); /* before ffmpeg, which writes next to it */
    if (!st) { /* what killed runs left, and frames past this animation's end */
        hy_out_sweep(p->outdir);
        if (!p->no_frames)
            remove_frames_after(r->dir, r->nframes);
    }
    if (!st && p->video && open_video(r, err))
        st = err ? err->code : HY_EINVAL;
    return st;
}

int hy_anim_run(const hy_anim_params *p, hy_anim_draw_fn draw, void *state, hy_anim_stats *stats,
                hy_error *err)
{
    run r;
    memset(&r, 0, sizeof r);
    r.p = p, r.draw = draw, r.state = state;
    r.nframes = hy_anim_nframes(p);
    r.first = r.next = r.piped = p->first;
    r.last = p->last < 0 ? r.nframes : p->last;
    /* An ffmpeg that exits early must not kill the process with SIGPIPE: the
     * write fails (EPIPE) and the run reports it.  Restored on return. */
    struct sigaction ign, old_pipe;
    memset(&ign, 0, sizeof ign);
    ign.sa_handler = SIG_IGN;
    if (p->video)
        sigaction(SIGPIPE, &ign, &old_pipe);
    int st = start(&r, err);
    if (st) {
        if (r.video)
            fclose(r.video), hy_out_wait(r.video_pid);
        hy_out_abort(&r.video_out);
        if (p->video)
            sigaction(SIGPIPE, &old_pipe, NULL);
        return st;
    }
    pthread_mutex_init(&r.mu, NULL);
    pthread_cond_init(&r.cv, NULL);
    r.bar = !p->quiet && isatty(2);
    r.t0 = hy_now();
    int jobs = p->jobs > 0 ? p->jobs : 1;
    if (jobs > r.last - r.first)
        jobs = (int)(r.last - r.first);
    pthread_t th[64];
    int started = 0;
    for (; started < jobs - 1; started++)
        if (pthread_create(&th[started], NULL, work, &r) != 0)
            break;
    work(&r);                         /* the calling thread is a worker too */
    for (int i = 0; i < started; i++)
        pthread_join(th[i], NULL);
    pthread_mutex_lock(&r.mu);
    progress(&r, 1);
    pthread_mutex_unlock(&r.mu);
    int ff = 0; /* ffmpeg reads to the end of its input, then exits */
    if (r.video) {
        ff = fclose(r.video) != 0;
        ff = hy_out_wait(r.video_pid) != 0 || ff;
    }
    if (ff && !r.failed)
        hy_error_set(&r.err, HY_EIO, "ffmpeg failed to encode '%s'", r.video_out.path), r.failed = 1;
    if (r.video && !r.failed && hy_out_publish(&r.video_out, &r.err))
        r.failed = 1;
    hy_out_abort(&r.video_out);       /* no half-written video */
    if (p->video)
        sigaction(SIGPIPE, &old_pipe, NULL);
    pthread_mutex_destroy(&r.mu);
    pthread_cond_destroy(&r.cv);
    if (stats)
        *stats = (hy_anim_stats){r.done, hy_now() - r.t0, r.draw_s, r.read_s, r.png_s};
    if (r.failed) {
        if (err)
            *err = r.err;
        return r.err.code ? r.err.code : HY_EIO;
    }
    return HY_OK;
}

/* ---- a warm renderer (hystviz-animate --worker) ---- */

struct hy_anim_renderer {
    worker w;
    int width, height;
};

int hy_anim_renderer_new(hy_anim_renderer **out, int width, int height, hy_error *err)
{
    *out = NULL;
    hy_anim_renderer *r = calloc(1, sizeof *r);
    if (!r)
        return hy_error_set(err, HY_ENOMEM, "out of memory");
    pthread_mutex_lock(&create_mu);
    int st = hy_gl_create(&r->w.gl, width, height, err);
    pthread_mutex_unlock(&create_mu);
    if (st) {
        free(r);
        return st;
    }
    r->width = width, r->height = height;
    *out = r;
    return HY_OK;
}

int hy_anim_renderer_size(const hy_anim_renderer *r, int *width, int *height)
{
    *width = r->width, *height = r->height;
    return HY_OK;
}

int hy_anim_renderer_png(hy_anim_renderer *r, const hy_anim_params *p, hy_anim_draw_fn draw, void *state, long index,
                         FILE *png, hy_error *err)
{
    if (p->width != r->width || p->height != r->height)
        return hy_error_set(err, HY_EINVAL, "frame size %d x %d is not the renderer's %d x %d", p->width, p->height,
                            r->width, r->height);
    long nframes = hy_anim_nframes(p);
    if (index < 0 || index >= nframes)
        return hy_error_set(err, HY_EINVAL, "frame %ld is outside the animation's %ld frames (0:%ld)", index, nframes,
                            nframes);
    const unsigned char *fb = NULL;
    int st = compose(p, draw, state, nframes, &r->w, index, &fb, err);
    return st ? st : hy_png_encode_xrgb(png, p->width, p->height, fb, 4 * p->width, &p->png, err);
}

void hy_anim_renderer_free(hy_anim_renderer *r)
{
    if (!r)
        return;
    if (r->w.frame)
        cairo_surface_destroy(r->w.frame);
    hy_gl_free(r->w.gl);
    free(r);
}
