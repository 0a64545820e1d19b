/* SPDX-License-Identifier: MIT */
/* hy_gl.c: the OpenGL 3.3 core backend of hy_canvas (instanced capsule
 * strokes with coverage AA, dashes, colour-map effects) and the lit 3-D
 * ribbon, on either off-screen backend (hy_gl_backend.h: OSMesa or EGL). */
#include "hy_gl.h"

#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hy_frame.h"
#include "hy_gl_backend.h"
#include "hy_shaders.h"

/* Context creation and destruction, one at a time in the whole process (they
 * touch the backends' process-wide state: OSMesa's framebuffer list, the EGL
 * display).  With OSMesa (backend->serialise) each frame's GL work, from its
 * first GL call to hy_gl_finish, holds it too: all surfaces draw with one
 * OSMesa context (backend->one_context), and before that, with a context per
 * thread, Mesa 22.3's llvmpipe under OSMesa crashed inside glReadPixels of
 * one context while another drew, about 1 run in 10 of the -j 2 ribbon test
 * on a loaded machine (see docs/ARCHITECTURE.md, "GL backends").  EGL
 * contexts draw concurrently: each has its own pipe context and framebuffer
 * object.  The caller's drawing calls (recorded, not sent), cairo overlay
 * and PNG encoding always run in parallel, and llvmpipe rasterises each
 * frame with its own threads. */
static pthread_mutex_t gl_mu = PTHREAD_MUTEX_INITIALIZER;

/* The context current on this thread and its entry points (gl->Clear(...)). */
static _Thread_local hy_gl *cur;
static _Thread_local const hy_gl_fns *gl;

#define MAX_EFFECTS 8
#define MAX_CLIP 8
#define RIBBON_SAMPLES 4      /* multisampling of the 3-D pass */

typedef struct inst {
    float p[4], c0[4], c1[4], w[4], m[4];   /* m: joint split-plane normals at p0, p1 */
} inst;

/* A recorded draw: instances [first, first + count) with a dash pattern and clip. */
typedef struct cmd {
    int clear;                /* 1: clear the clip rectangle to colour (an opaque pixel-aligned fill) */
    float colour[4];
    size_t first, count;
    float dash[8], total;
    int ndash, clipped, clip[4];
} cmd;

/* A context's GL objects: with one_context (OSMesa) made once for all
 * surfaces, else one set per context. */
typedef struct gl_objs {
    GLuint stroke_prog, stroke_dash_prog, ribbon_prog, plane_prog, vao, vbo, ribbon_vao, ribbon_vbo, ribbon_ibo;
    GLint u_size, u_size_dash, u_ndash, u_dash, u_dash_total;
    GLint u_ribbon[3];                /* ribbon.vert's uniforms, in ribbon_uniforms' order */
    GLint u_plane[11];                /* plane.frag's uniforms, in plane_uniforms' order */
} gl_objs;

struct hy_gl {
    const hy_gl_backend *be;
    hy_gl_surface *surf;               /* the backend's context and frame */
    const hy_gl_fns *fns;              /* its GL entry points */
    GLuint fbo0;                       /* the framebuffer that is the frame (0: the default) */
    int w, h;
    double scale;
    gl_objs own, *o;                  /* o: own, or the one context's shared_objs */
    GLuint ms_fbo, ms_rb[2];          /* 4x multisampled frame, used once a frame has 3-D */
    int in_ms;                        /* this frame draws into ms_fbo (resolved at hy_gl_read) */
    hy_rgb bg;                        /* the frame's clear colour */
    int cleared;                      /* the frame's clear was sent to GL */
    int holding;                      /* one_context: this frame's GL work holds gl_mu */
    double *pts;                       /* current path: x, y pairs (pixels) */
    size_t npts, cap;
    size_t *starts;                    /* subpath start indices */
    size_t nstarts, scap;
    inst *buf;
    size_t nbuf, bcap, cmd_start;
    cmd *cmds;
    size_t ncmds, ccap;
    hy_gl_effect effects[MAX_EFFECTS];
    int neffects;
    int clip[MAX_CLIP][4], nclip;
    char desc[256];
};

/* one_context (OSMesa): the context's GL objects (made with its first
 * surface; the context lives as long as the process), and the surface bound
 * to it now (both under gl_mu). */
static gl_objs shared_objs;
static int shared_built;
static hy_gl *bound;

/* Makes g current on this thread if another context is (with one_context:
 * if another surface is bound to the context). */
static void use(hy_gl *g)
{
    if (cur == g && (!g->be->one_context || bound == g))
        return;
    g->be->make_current(g->surf);
    cur = g, gl = g->fns;
    if (g->be->one_context)
        bound = g;
}

/* Binds framebuffer fbo, whole, and clears it to the frame's colour (and
 * its depth, where it has one). */
static void clear_to_bg(hy_gl *g, GLuint fbo)
{
    gl->BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl->Disable(GL_SCISSOR_TEST);
    gl->Viewport(0, 0, g->w, g->h);
    gl->ClearColor((float)g->bg.r, (float)g->bg.g, (float)g->bg.b, 1.0f);
    gl->ClearDepth(1.0);
    gl->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

/* The frame's clear (hy_gl_begin's colour), sent with its first GL work. */
static void clear_frame(hy_gl *g)
{
    if (!g->cleared)
        g->cleared = 1, clear_to_bg(g, g->fbo0);
}

/* Takes g's context for GL work of its frame: the lock where the backend
 * serialises, g current, the frame's clear sent.  With one_context the lock
 * stays held until the frame ends (release(g, 1)): another thread's frame on
 * the same context would otherwise land between this one's clear and draws. */
static void acquire(hy_gl *g)
{
    if (g->be->serialise && !g->holding)
        pthread_mutex_lock(&gl_mu);
    g->holding = g->be->one_context;
    use(g);
    clear_frame(g);
}

static void release(hy_gl *g, int frame_end)
{
    if (g->be->one_context && !frame_end)
        return;
    g->holding = 0;
    if (g->be->serialise)
        pthread_mutex_unlock(&gl_mu);
}

/* ---- colour maps ---- */

/* viridis at 0, 1/8, ..., 7/8 (matplotlib's table), two anchors towards yellow, 1. */
static const double viridis[][4] = {
    {0.0, 0.267004, 0.004874, 0.329415},   {0.125, 0.282623, 0.140926, 0.457517},
    {0.25, 0.253935, 0.265254, 0.529983},  {0.375, 0.206756, 0.371758, 0.553117},
    {0.5, 0.163625, 0.471133, 0.558148},   {0.625, 0.127568, 0.566949, 0.550556},
    {0.75, 0.134692, 0.658636, 0.517649},  {0.875, 0.266941, 0.748751, 0.440573},
    {0.94, 0.565000, 0.830000, 0.270000},  {1.0, 0.993248, 0.906157, 0.143936},
};

static const hy_rgb okabe_ito[7] = {
    {0.902, 0.624, 0.000}, {0.337, 0.706, 0.914}, {0.000, 0.620, 0.451}, {0.941, 0.894, 0.259},
    {0.000, 0.447, 0.698}, {0.835, 0.369, 0.000}, {0.800, 0.475, 0.655},
};

hy_rgb hy_cmap(int cmap, double t)
{
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    if (cmap == HY_CMAP_OKABE_ITO) {
        int i = (int)(t * 7.0);
        return okabe_ito[i > 6 ? 6 : i];
    }
    if (cmap != HY_CMAP_VIRIDIS)
        return (hy_rgb){0, 0, 0};
    size_t i = 1;
    while (i + 1 < sizeof viridis / sizeof viridis[0] && viridis[i][0] < t)
        i++;
    const double *a = viridis[i - 1], *b = viridis[i];
    double f = (t - a[0]) / (b[0] - a[0]);
    return (hy_rgb){a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2]), a[3] + f * (b[3] - a[3])};
}

/* ---- shaders ---- */

static const char *stage_name(unsigned stage)
{
    switch (stage) {
    case GL_VERTEX_SHADER: return "vertex";
    case GL_FRAGMENT_SHADER: return "fragment";
    case GL_GEOMETRY_SHADER: return "geometry";
    default: return "unknown";
    }
}

static void trim_log(char *log)
{
    size_t n = strlen(log);
    while (n > 0 && (log[n - 1] == '\n' || log[n - 1] == ' ' || log[n - 1] == '\0'))
        log[--n] = '\0';
    for (size_t i = 0; i < n; i++)
        if (log[i] == '\n')
            log[i] = ' ';
}

static GLuint compile_stage(const hy_gl_stage *s, hy_error *err)
{
    GLuint sh = gl->CreateShader(s->stage);
    if (!sh) {
        hy_error_set(err, HY_ENUM, "%s (%s shader): glCreateShader failed", s->file, stage_name(s->stage));
        return 0;
    }
    const char *ver = s->defines ? strstr(s->src, "#version") : NULL;
    const char *eol = ver ? strchr(ver, '\n') : NULL;
    if (eol) {                        /* head through the #version line, the defines, the rest */
        const char *parts[3] = {s->src, s->defines, eol + 1};
        const GLint lens[3] = {(GLint)(eol + 1 - s->src), -1, -1};
        gl->ShaderSource(sh, 3, parts, lens);
    } else
        gl->ShaderSource(sh, 1, &s->src, NULL);
    gl->CompileShader(sh);
    GLint ok = 0;
    gl->GetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (ok)
        return sh;
    char log[400] = "";
    gl->GetShaderInfoLog(sh, sizeof log, NULL, log);
    trim_log(log);
    hy_error_set(err, HY_ENUM, "%s (%s shader): compile error: %s", s->file, stage_name(s->stage), log);
    gl->DeleteShader(sh);
    return 0;
}

int hy_gl_program(const hy_gl_stage *stages, int n, unsigned *program, hy_error *err)
{
    GLuint sh[4], prog = gl ? gl->CreateProgram() : 0;
    if (n < 1 || n > 4 || !prog)
        return hy_error_set(err, HY_EINVAL, "a GL program needs 1 to 4 stages and a current context");
    int got = 0, st = HY_OK;
    for (; got < n; got++) {
        sh[got] = compile_stage(&stages[got], err);
        if (!sh[got]) {
            st = HY_ENUM;
            break;
        }
        gl->AttachShader(prog, sh[got]);
    }
    if (!st) {
        gl->LinkProgram(prog);
        GLint ok = 0;
        gl->GetProgramiv(prog, GL_LINK_STATUS, &ok);
        if (!ok) {
            char log[400] = "";
            gl->GetProgramInfoLog(prog, sizeof log, NULL, log);
            trim_log(log);
            st = hy_error_set(err, HY_ENUM, "program %s + %s: link error: %s", stages[0].file,
                              stages[n - 1].file, log);
        }
    }
    for (int i = 0; i < got; i++)
        gl->DeleteShader(sh[i]);
    if (st) {
        gl->DeleteProgram(prog);
        return st;
    }
    *program = prog;
    return HY_OK;
}

static int build_programs(hy_gl *g, hy_error *err)
{
    const hy_gl_stage stroke[2] = {
        {hy_shader_stroke_vert_file, GL_VERTEX_SHADER, hy_shader_stroke_vert, NULL},
        {hy_shader_stroke_frag_file, GL_FRAGMENT_SHADER, hy_shader_stroke_frag, NULL},
    };
    const hy_gl_stage stroke_dash[2] = {
        {hy_shader_stroke_vert_file, GL_VERTEX_SHADER, hy_shader_stroke_vert, NULL},
        {hy_shader_stroke_frag_file, GL_FRAGMENT_SHADER, hy_shader_stroke_frag, "#define HY_DASHES 1\n"},
    };
    if (hy_gl_program(stroke, 2, &g->o->stroke_prog, err) || hy_gl_program(stroke_dash, 2, &g->o->stroke_dash_prog, err))
        return HY_ENUM;
    g->o->u_size = gl->GetUniformLocation(g->o->stroke_prog, "u_size");
    g->o->u_size_dash = gl->GetUniformLocation(g->o->stroke_dash_prog, "u_size");
    g->o->u_ndash = gl->GetUniformLocation(g->o->stroke_dash_prog, "u_ndash");
    g->o->u_dash = gl->GetUniformLocation(g->o->stroke_dash_prog, "u_dash");
    g->o->u_dash_total = gl->GetUniformLocation(g->o->stroke_dash_prog, "u_dash_total");
    return HY_OK;
}

/* Program *prog from a vertex and a fragment stage, built at its first use,
 * with the locations of its uniforms names (NULL-terminated) in locs: the
 * ribbon and the relay plane, which only some animations draw (building them
 * at every context's start made each renderer pay llvmpipe's compile). */
static int program_once(GLuint *prog, const hy_gl_stage stages[2], const char *const *names, GLint *locs,
                        hy_error *err)
{
    if (*prog)
        return HY_OK;
    if (hy_gl_program(stages, 2, prog, err))
        return HY_ENUM;
    for (int i = 0; names[i]; i++)
        locs[i] = gl->GetUniformLocation(*prog, names[i]);
    return HY_OK;
}

enum { RIBBON_MVP, RIBBON_MV, RIBBON_LIGHT };

static int ribbon_program(hy_gl *g, hy_error *err)
{
    static const char *const ribbon_uniforms[4] = {"u_mvp", "u_mv", "u_light", NULL};
    const hy_gl_stage ribbon[2] = {
        {hy_shader_ribbon_vert_file, GL_VERTEX_SHADER, hy_shader_ribbon_vert, NULL},
        {hy_shader_ribbon_frag_file, GL_FRAGMENT_SHADER, hy_shader_ribbon_frag, NULL},
    };
    return program_once(&g->o->ribbon_prog, ribbon, ribbon_uniforms, g->o->u_ribbon, err);
}

static void setup_buffers(hy_gl *g)
{
    gl->GenVertexArrays(1, &g->o->vao);
    gl->BindVertexArray(g->o->vao);
    gl->GenBuffers(1, &g->o->vbo);
    gl->BindBuffer(GL_ARRAY_BUFFER, g->o->vbo);
    for (GLuint i = 0; i < 5; i++) {
        gl->EnableVertexAttribArray(i);
        gl->VertexAttribPointer(i, 4, GL_FLOAT, GL_FALSE, sizeof(inst), (const void *)(i * 4 * sizeof(float)));
        gl->VertexAttribDivisor(i, 1);
    }
    gl->GenVertexArrays(1, &g->o->ribbon_vao);
    gl->BindVertexArray(g->o->ribbon_vao);
    gl->GenBuffers(1, &g->o->ribbon_vbo);
    gl->GenBuffers(1, &g->o->ribbon_ibo);
    gl->BindBuffer(GL_ARRAY_BUFFER, g->o->ribbon_vbo);
    gl->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, g->o->ribbon_ibo);
    for (GLuint i = 0; i < 3; i++) {
        gl->EnableVertexAttribArray(i);
        gl->VertexAttribPointer(i, 3, GL_FLOAT, GL_FALSE, 9 * sizeof(float), (const void *)(i * 3 * sizeof(float)));
    }
    gl->BindVertexArray(0);
}

/* ---- context ---- */

static void gl_free_unlocked(hy_gl *g);

static int gl_create_unlocked(hy_gl **out, int width, int height, hy_error *err)
{
    if (width < 16 || height < 16 || width > 8192 || height > 8192)
        return hy_error_set(err, HY_EINVAL, "frame size %d x %d is outside 16..8192 pixels", width, height);
    const hy_gl_backend *be = hy_gl_backend_current(err);
    if (!be)
        return err->code;
    hy_gl *g = calloc(1, sizeof *g);
    if (!g)
        return hy_error_set(err, HY_ENOMEM, "out of memory for a %d x %d GL frame", width, height);
    g->w = width, g->h = height, g->scale = 1.0, g->be = be;
    int st = be->open(&g->surf, width, height, &g->fns, &g->fbo0, err);
    if (st) {
        free(g);
        cur = NULL, gl = NULL;        /* whatever was current may not be any more */
        return st;
    }
    cur = g, gl = g->fns;
    if (be->one_context)
        bound = g;
    snprintf(g->desc, sizeof g->desc, "%s / %s (%s)", (const char *)gl->GetString(GL_VERSION),
             (const char *)gl->GetString(GL_RENDERER), be->name);
    g->o = be->one_context ? &shared_objs : &g->own;
    if (!be->one_context || !shared_built) {   /* the one context's objects exist after its first surface */
        if (build_programs(g, err)) {
            gl_free_unlocked(g);
            return HY_ENUM;
        }
        setup_buffers(g);
        shared_built = be->one_context;
    }
    gl->BindFramebuffer(GL_FRAMEBUFFER, g->fbo0);
    gl->Viewport(0, 0, width, height);
    *out = g;
    return HY_OK;
}

int hy_gl_create(hy_gl **out, int width, int height, hy_error *err)
{
    pthread_mutex_lock(&gl_mu);
    int rc = gl_create_unlocked(out, width, height, err);
    pthread_mutex_unlock(&gl_mu);
    return rc;
}

static void gl_free_unlocked(hy_gl *g)
{
    if (!g)
        return;
    if (g->be->one_context) {
        if (g->ms_fbo) {                /* the context lives on: g's own objects go */
            use(g);
            gl->DeleteFramebuffers(1, &g->ms_fbo);
            gl->DeleteRenderbuffers(2, g->ms_rb);
        }
        if (bound == g)
            bound = NULL;
    }
    g->be->close(g->surf, cur == g);
    if (cur == g)
        cur = NULL, gl = NULL;
    free(g->pts);
    free(g->starts);
    free(g->buf);
    free(g->cmds);
    free(g);
}

void hy_gl_free(hy_gl *g)
{
    if (!g || !g->holding)            /* a frame left unfinished (an error) still holds it */
        pthread_mutex_lock(&gl_mu);
    gl_free_unlocked(g);
    pthread_mutex_unlock(&gl_mu);
}

const char *hy_gl_describe(const hy_gl *g) { return g->desc; }

int hy_gl_info(FILE *f, hy_error *err)
{
    const hy_gl_backend *b = hy_gl_backend_current(err);
    fprintf(f, "backends built: %s\n", *hy_gl_backends() ? hy_gl_backends() : "none");
    if (!b) {
        fprintf(f, "backend: none (%s)\n", err->msg);
        return err->code;
    }
    fprintf(f, "backend: %s (%s)\n", b->name, hy_gl_backend_origin());
    b->info(f);
    hy_gl *g;
    int st = hy_gl_create(&g, 64, 64, err);
    if (st) {
        fprintf(f, "renderer: none (%s)\n", err->msg);
        return st;
    }
    fprintf(f, "renderer: %s\n", hy_gl_describe(g));
    hy_gl_free(g);
    return HY_OK;
}

/* A new frame: nothing reaches GL until its first GL work (acquire), which
 * sends the clear first. */
void hy_gl_begin(hy_gl *g, hy_rgb c)
{
    if (g->holding)                   /* the last frame ended without hy_gl_finish (an error) */
        release(g, 1);
    g->neffects = 0;
    g->nclip = 0;
    g->ncmds = 0;
    g->nbuf = g->cmd_start = 0;
    g->in_ms = 0;
    g->bg = c;
    g->cleared = 0;
}

int hy_gl_set_effect(hy_gl *g, const hy_gl_effect *e, hy_error *err)
{
    if (g->neffects >= MAX_EFFECTS)
        return hy_error_set(err, HY_EINVAL, "at most %d stroke effects per frame", MAX_EFFECTS);
    g->effects[g->neffects++] = *e;
    return HY_OK;
}

/* ---- instance batches ---- */

static inst *push(hy_gl *g)
{
    if (g->nbuf == g->bcap) {
        size_t cap = g->bcap ? 2 * g->bcap : 1024;
        inst *nb = realloc(g->buf, cap * sizeof *nb);
        if (!nb)
            return NULL;            /* the primitive is dropped; frames stay well-formed */
        g->buf = nb, g->bcap = cap;
    }
    inst *q = &g->buf[g->nbuf++];
    memset(q, 0, sizeof *q);
    return q;
}

static void set4(float *d, double a, double b, double c, double e)
{
    d[0] = (float)a, d[1] = (float)b, d[2] = (float)c, d[3] = (float)e;
}

/* Closes the primitives pushed since the last command into a draw command
 * with this dash pattern (pixels) and the current clip.  Nothing reaches GL
 * until submit: one upload and a few draw calls per frame keep llvmpipe from
 * synchronising on every stroke. */
static void flush(hy_gl *g, const double *dash, int ndash)
{
    if (g->nbuf == g->cmd_start)
        return;
    if (g->ncmds == g->ccap) {
        size_t cap = g->ccap ? 2 * g->ccap : 64;
        cmd *nc = realloc(g->cmds, cap * sizeof *nc);
        if (!nc) {
            g->nbuf = g->cmd_start;   /* dropped; frames stay well-formed */
            return;
        }
        g->cmds = nc, g->ccap = cap;
    }
    cmd *c = &g->cmds[g->ncmds++];
    memset(c, 0, sizeof *c);
    c->first = g->cmd_start, c->count = g->nbuf - g->cmd_start;
    int nd = ndash > 8 ? 8 : ndash;
    nd -= nd % 2;
    for (int i = 0; i < nd; i++)
        c->dash[i] = (float)(dash[i] * g->scale), c->total += c->dash[i];
    c->ndash = c->total > 0 ? nd : 0;
    if (g->nclip)
        memcpy(c->clip, g->clip[g->nclip - 1], sizeof c->clip), c->clipped = 1;
    g->cmd_start = g->nbuf;
}

static void set_scissor(const hy_gl *g, const cmd *c)
{
    if (!c->clipped) {
        gl->Disable(GL_SCISSOR_TEST);
        return;
    }
    gl->Enable(GL_SCISSOR_TEST);
    gl->Scissor(c->clip[0], g->h - c->clip[3], c->clip[2] - c->clip[0], c->clip[3] - c->clip[1]);
}

/* Sends every recorded command to GL: one buffer upload, one draw per command. */
static void submit(hy_gl *g)
{
    if (!g->ncmds)
        return;
    gl->UseProgram(g->o->stroke_dash_prog);
    gl->Uniform2f(g->o->u_size_dash, (float)g->w, (float)g->h);
    gl->UseProgram(g->o->stroke_prog);     /* solid strokes: the variant without dash code */
    gl->Uniform2f(g->o->u_size, (float)g->w, (float)g->h);
    GLuint current = g->o->stroke_prog;
    gl->Enable(GL_BLEND);
    gl->BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    gl->Disable(GL_DEPTH_TEST);
    gl->BindVertexArray(g->o->vao);
    gl->BindBuffer(GL_ARRAY_BUFFER, g->o->vbo);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(g->nbuf * sizeof(inst)), g->buf, GL_STREAM_DRAW);
    int last_nd = -1;
    float last_dash[8] = {0};
    for (size_t k = 0; k < g->ncmds; k++) {
        const cmd *c = &g->cmds[k];
        GLuint want = c->ndash > 0 ? g->o->stroke_dash_prog : g->o->stroke_prog;
        if (want != current)
            gl->UseProgram(current = want);
        if (c->ndash > 0 && (c->ndash != last_nd || memcmp(c->dash, last_dash, sizeof last_dash))) {
            gl->Uniform1i(g->o->u_ndash, c->ndash);
            gl->Uniform1fv(g->o->u_dash, 8, c->dash);
            gl->Uniform1f(g->o->u_dash_total, c->total > 0 ? c->total : 1.0f);
            last_nd = c->ndash;
            memcpy(last_dash, c->dash, sizeof last_dash);
        }
        for (GLuint i = 0; i < 5; i++)
            gl->VertexAttribPointer(i, 4, GL_FLOAT, GL_FALSE, sizeof(inst),
                                  (const void *)(c->first * sizeof(inst) + i * 4 * sizeof(float)));
        set_scissor(g, c);
        if (c->clear) {
            gl->ClearColor(c->colour[0], c->colour[1], c->colour[2], 1.0f);
            gl->Clear(GL_COLOR_BUFFER_BIT);
            continue;
        }
        gl->DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, (GLsizei)c->count);
    }
    gl->Disable(GL_SCISSOR_TEST);
    gl->BindVertexArray(0);
    g->ncmds = 0;
    g->nbuf = g->cmd_start = 0;
}

/* ---- canvas operations ---- */

static void g_begin_path(void *ctx)
{
    hy_gl *g = ctx;
    g->npts = 0;
    g->nstarts = 0;
}

static void add_point(hy_gl *g, double x, double y, int start)
{
    if (g->npts == g->cap) {
        size_t cap = g->cap ? 2 * g->cap : 1024;
        double *np = realloc(g->pts, cap * 2 * sizeof *np);
        if (!np)
            return;
        g->pts = np, g->cap = cap;
    }
    if (start || g->nstarts == 0) {
        if (g->nstarts == g->scap) {
            size_t cap = g->scap ? 2 * g->scap : 64;
            size_t *ns = realloc(g->starts, cap * sizeof *ns);
            if (!ns)
                return;
            g->starts = ns, g->scap = cap;
        }
        g->starts[g->nstarts++] = g->npts;
    }
    g->pts[2 * g->npts] = x * g->scale;
    g->pts[2 * g->npts + 1] = y * g->scale;
    g->npts++;
}

static void g_move_to(void *ctx, double x, double y) { add_point(ctx, x, y, 1); }
static void g_line_to(void *ctx, double x, double y) { add_point(ctx, x, y, 0); }

static const hy_gl_effect *effect_for(const hy_gl *g, hy_rgb c)
{
    for (int i = 0; i < g->neffects; i++)
        if (g->effects[i].key.r == c.r && g->effects[i].key.g == c.g && g->effects[i].key.b == c.b)
            return &g->effects[i];
    return NULL;
}

static void colour_at(const hy_pen *pen, const hy_gl_effect *e, double s, float *out)
{
    double a = pen->alpha > 0 ? pen->alpha : 1.0;
    hy_rgb c = pen->colour;
    if (e) {
        if (e->cmap != HY_CMAP_NONE)
            c = hy_cmap(e->cmap, e->t0 + (e->t1 - e->t0) * s);
        a *= e->fade + (1.0 - e->fade) * s;
    }
    set4(out, c.r, c.g, c.b, a);
}

/* Whether every point strictly between a and b lies within tol pixels of the chord a-b. */
static int chord_ok(const double *p, size_t a, size_t b, double tol)
{
    double dx = p[2 * b] - p[2 * a], dy = p[2 * b + 1] - p[2 * a + 1], len = hypot(dx, dy);
    if (!(len > 0))
        return 0;
    for (size_t i = a + 1; i < b; i++) {
        double qx = p[2 * i] - p[2 * a], qy = p[2 * i + 1] - p[2 * a + 1], t = qx * dx + qy * dy;
        if (fabs(qx * dy - qy * dx) > tol * len || t < 0 || t > len * len)
            return 0;
    }
    return 1;
}

/* Drops points of [i0, i1) that lie within 0.1 px of the chord that skips
 * them (dense curves become fewer, longer segments: llvmpipe pays per
 * triangle); keeps the ends.  Returns the kept indices' count in keep. */
static size_t simplify(const double *p, size_t i0, size_t i1, size_t *keep)
{
    size_t n = 0, a = i0;
    keep[n++] = i0;
    while (a + 1 < i1) {
        size_t b = a + 1;
        while (b + 1 < i1 && b + 1 - a <= 32 && chord_ok(p, a, b + 1, 0.1))
            b++;
        keep[n++] = b;
        a = b;
    }
    return n;
}

/* The plane that splits a joint between directions (dx0, dy0) and (dx1, dy1)
 * (unit) at the bisector of the turn: its normal, pointing forward, in n.
 * Both segments end in round caps there (a round join, as cairo draws data
 * strokes), each drawn only on its own side of the plane, so every pixel is
 * blended once.  Returns 0 for an exact reversal, which has no bisector: the
 * two caps then overlap. */
static int split_plane(double dx0, double dy0, double dx1, double dy1, double *n)
{
    double bx = dx0 + dx1, by = dy0 + dy1, bl = hypot(bx, by);
    if (!(bl > 1e-9))
        return 0;
    n[0] = bx / bl, n[1] = by / bl;
    return 1;
}

static void unit(const double *p, size_t a, size_t b, double *d)
{
    double dx = p[2 * b] - p[2 * a], dy = p[2 * b + 1] - p[2 * a + 1], l = hypot(dx, dy);
    d[0] = l > 0 ? dx / l : 1.0, d[1] = l > 0 ? dy / l : 0.0;
}

/* Flags and split-plane normals of segment k (of n kept points) for pen. */
static int joint_flags(const double *p, const size_t *keep, size_t k, size_t n, const hy_pen *pen, float *m)
{
    if (pen->round_caps)
        return 4;
    int flags = (k == 1 ? 1 : 0) | (k + 1 == n ? 2 : 0);
    double d[2], e[2], nm[2];
    unit(p, keep[k - 1], keep[k], d);
    if (k > 1) {
        unit(p, keep[k - 2], keep[k - 1], e);
        if (split_plane(e[0], e[1], d[0], d[1], nm))
            flags |= 8, m[0] = (float)nm[0], m[1] = (float)nm[1];
    }
    if (k + 1 < n) {
        unit(p, keep[k], keep[k + 1], e);
        if (split_plane(d[0], d[1], e[0], e[1], nm))
            flags |= 16, m[2] = (float)nm[0], m[3] = (float)nm[1];
    }
    return flags;
}

static void stroke_subpath(hy_gl *g, size_t i0, size_t i1, const hy_pen *pen, const hy_gl_effect *e)
{
    const double *p = g->pts;
    size_t *keep = malloc((i1 - i0) * sizeof *keep);
    if (!keep)
        return;
    size_t n = simplify(p, i0, i1, keep);
    double total = 0, s = 0, hw = 0.5 * pen->width * g->scale;
    for (size_t k = 1; k < n; k++)   /* arc length along the drawn chords, as the shader measures it */
        total += hypot(p[2 * keep[k]] - p[2 * keep[k - 1]], p[2 * keep[k] + 1] - p[2 * keep[k - 1] + 1]);
    for (size_t k = 1; k < n; k++) {
        size_t a = keep[k - 1], b = keep[k];
        double len = hypot(p[2 * b] - p[2 * a], p[2 * b + 1] - p[2 * a + 1]);
        inst *q = push(g);
        if (!q)
            break;
        int flags = joint_flags(p, keep, k, n, pen, q->m);
        set4(q->p, p[2 * a], p[2 * a + 1], p[2 * b], p[2 * b + 1]);
        colour_at(pen, e, total > 0 ? s / total : 0, q->c0);
        colour_at(pen, e, total > 0 ? (s + len) / total : 1, q->c1);
        set4(q->w, hw, s, 0, flags);
        s += len;
    }
    free(keep);
}

static void g_stroke(void *ctx, const hy_pen *pen)
{
    hy_gl *g = ctx;
    const hy_gl_effect *e = effect_for(g, pen->colour);
    for (size_t k = 0; k < g->nstarts; k++) {
        size_t i0 = g->starts[k], i1 = k + 1 < g->nstarts ? g->starts[k + 1] : g->npts;
        if (i1 > i0 + 1)
            stroke_subpath(g, i0, i1, pen, e);
    }
    flush(g, pen->dash, pen->dash ? pen->ndash : 0);
    g_begin_path(g);
}

static void box(hy_gl *g, double x0, double y0, double x1, double y1, hy_rgb c, double a)
{
    inst *q = push(g);
    if (!q)
        return;
    set4(q->p, x0, y0, x1, y1);
    set4(q->c0, c.r, c.g, c.b, a);
    memcpy(q->c1, q->c0, sizeof q->c0);
    set4(q->w, 0, 0, 1, 0);
}

/* An opaque fill on whole pixels inside the clip becomes a scissored clear
 * (llvmpipe clears far faster than it shades a full-frame quad). */
static int fill_as_clear(hy_gl *g, double x0, double y0, double x1, double y1, hy_rgb c)
{
    if (x0 != floor(x0) || y0 != floor(y0) || x1 != floor(x1) || y1 != floor(y1) || x1 <= x0 || y1 <= y0)
        return 0;
    int r[4] = {(int)x0, (int)y0, (int)x1, (int)y1};
    if (g->nclip) {
        const int *cl = g->clip[g->nclip - 1];
        r[0] = r[0] > cl[0] ? r[0] : cl[0], r[1] = r[1] > cl[1] ? r[1] : cl[1];
        r[2] = r[2] < cl[2] ? r[2] : cl[2], r[3] = r[3] < cl[3] ? r[3] : cl[3];
        if (r[2] <= r[0] || r[3] <= r[1])
            return 1;
    }
    r[0] = r[0] < 0 ? 0 : r[0], r[1] = r[1] < 0 ? 0 : r[1];
    r[2] = r[2] > g->w ? g->w : r[2], r[3] = r[3] > g->h ? g->h : r[3];
    flush(g, NULL, 0);
    int saved = g->nclip;
    if (g->nclip < MAX_CLIP) {
        memcpy(g->clip[g->nclip++], r, sizeof r);
        if (!push(g)) {                /* a placeholder instance so flush records a command */
            g->nclip = saved;
            return 0;
        }
        flush(g, NULL, 0);
        cmd *cm = &g->cmds[g->ncmds - 1];
        cm->clear = 1;
        cm->colour[0] = (float)c.r, cm->colour[1] = (float)c.g, cm->colour[2] = (float)c.b;
    }
    g->nclip = saved;
    return 1;
}

static void g_fill_rect(void *ctx, double x, double y, double w, double h, hy_rgb c, double alpha)
{
    hy_gl *g = ctx;
    double k = g->scale;
    if ((alpha <= 0 || alpha >= 1) && fill_as_clear(g, x * k, y * k, (x + w) * k, (y + h) * k, c))
        return;
    box(g, x * k, y * k, (x + w) * k, (y + h) * k, c, alpha > 0 ? alpha : 1.0);
    flush(g, NULL, 0);
}

static void g_marker(void *ctx, int shape, double x, double y, double size, const hy_pen *pen,
                     const hy_rgb *fill)
{
    hy_gl *g = ctx;
    double k = g->scale, r = 0.5 * size * k, hw = 0.5 * pen->width * k, a = pen->alpha > 0 ? pen->alpha : 1;
    hy_rgb c = pen->colour;
    x *= k, y *= k;
    if (shape == HY_SHAPE_SQUARE) {
        if (fill)
            box(g, x - r, y - r, x + r, y + r, *fill, 1.0);
        box(g, x - r - hw, y - r - hw, x + r + hw, y - r + hw, c, a);
        box(g, x - r - hw, y + r - hw, x + r + hw, y + r + hw, c, a);
        box(g, x - r - hw, y - r + hw, x - r + hw, y + r - hw, c, a);
        box(g, x + r - hw, y - r + hw, x + r + hw, y + r - hw, c, a);
    } else {
        inst *q = fill ? push(g) : NULL;
        if (q) {
            set4(q->p, x, y, 0, 0);
            set4(q->c0, fill->r, fill->g, fill->b, 1.0);
            memcpy(q->c1, q->c0, sizeof q->c0);
            set4(q->w, r, 0, 2, 0);
        }
        if ((q = push(g))) {
            set4(q->p, x, y, r, 0);
            set4(q->c0, c.r, c.g, c.b, a);
            memcpy(q->c1, q->c0, sizeof q->c0);
            set4(q->w, hw, 0, 3, 0);
        }
    }
    flush(g, NULL, 0);
}

static void g_text(void *ctx, double x, double y, const char *utf8, double size, int italic,
                   int vertical, hy_rgb c)
{
    (void)ctx, (void)x, (void)y, (void)utf8, (void)size, (void)italic, (void)vertical, (void)c;
}

static void g_measure(void *ctx, const char *utf8, double size, int italic, hy_text_extents *ext)
{
    (void)ctx, (void)utf8, (void)italic;
    memset(ext, 0, sizeof *ext);
    ext->ascent = 0.8 * size, ext->descent = 0.2 * size;
}

static void g_clip(void *ctx, double x, double y, double w, double h)
{
    hy_gl *g = ctx;
    double k = g->scale;
    int x0 = (int)floor(x * k), y0 = (int)floor(y * k), x1 = (int)ceil((x + w) * k), y1 = (int)ceil((y + h) * k);
    if (g->nclip) {               /* intersect with the enclosing clip, as cairo does */
        const int *c = g->clip[g->nclip - 1];
        x0 = x0 > c[0] ? x0 : c[0], y0 = y0 > c[1] ? y0 : c[1];
        x1 = x1 < c[2] ? x1 : c[2], y1 = y1 < c[3] ? y1 : c[3];
    }
    if (x1 < x0)
        x1 = x0;
    if (y1 < y0)
        y1 = y0;
    if (g->nclip < MAX_CLIP) {
        int *c = g->clip[g->nclip++];
        c[0] = x0, c[1] = y0, c[2] = x1, c[3] = y1;
    }
}

static void g_unclip(void *ctx)
{
    hy_gl *g = ctx;
    if (g->nclip)
        g->nclip--;
}

static const hy_canvas_ops gl_ops = {
    "gl", g_begin_path, g_move_to, g_line_to, g_stroke, g_fill_rect,
    g_marker, g_text, g_measure, g_clip, g_unclip,
};

hy_canvas hy_gl_canvas(hy_gl *g, double scale)
{
    g->scale = scale > 0 ? scale : 1.0;
    return (hy_canvas){&gl_ops, g};
}

/* ---- 3-D ribbon ---- */

typedef struct mat4 { double m[16]; } mat4;   /* column-major */

static mat4 mat_mul(const mat4 *a, const mat4 *b)
{
    mat4 r;
    for (int c = 0; c < 4; c++)
        for (int rr = 0; rr < 4; rr++) {
            double s = 0;
            for (int k = 0; k < 4; k++)
                s += a->m[k * 4 + rr] * b->m[c * 4 + k];
            r.m[c * 4 + rr] = s;
        }
    return r;
}

static void to_float(const mat4 *m, float *f)
{
    for (int i = 0; i < 16; i++)
        f[i] = (float)m->m[i];
}

/* View matrix of a camera orbiting the origin (y up) and a perspective projection. */
static void camera(const hy_gl_ribbon *r, double aspect, mat4 *mv, mat4 *proj)
{
    double d = r->distance > 0 ? r->distance : 3.2;
    double ex = d * cos(r->elevation) * sin(r->azimuth), ey = d * sin(r->elevation);
    double ez = d * cos(r->elevation) * cos(r->azimuth);
    double f[3] = {-ex / d, -ey / d, -ez / d}, up[3] = {0, 1, 0};
    double s[3] = {f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2], f[0] * up[1] - f[1] * up[0]};
    double sl = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    for (int i = 0; i < 3; i++)
        s[i] /= sl;
    double u[3] = {s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2], s[0] * f[1] - s[1] * f[0]};
    memset(mv, 0, sizeof *mv);
    for (int i = 0; i < 3; i++) {
        mv->m[i * 4 + 0] = s[i];
        mv->m[i * 4 + 1] = u[i];
        mv->m[i * 4 + 2] = -f[i];
    }
    mv->m[12] = -(s[0] * ex + s[1] * ey + s[2] * ez);
    mv->m[13] = -(u[0] * ex + u[1] * ey + u[2] * ez);
    mv->m[14] = f[0] * ex + f[1] * ey + f[2] * ez;
    mv->m[15] = 1;
    double fov = 38.0 * M_PI / 180.0, t = 1.0 / tan(0.5 * fov), zn = 0.1, zf = 20.0;
    memset(proj, 0, sizeof *proj);
    proj->m[0] = t / aspect;
    proj->m[5] = t;
    proj->m[10] = (zf + zn) / (zn - zf);
    proj->m[11] = -1;
    proj->m[14] = 2 * zf * zn / (zn - zf);
}

/* The ribbon's viewport in pixels (y down). */
static void ribbon_viewport(const hy_gl *g, const hy_gl_ribbon *r, double *v)
{
    int all = !(r->vw > 0 && r->vh > 0);
    v[0] = all ? 0 : r->vx, v[1] = all ? 0 : r->vy, v[2] = all ? g->w : r->vw, v[3] = all ? g->h : r->vh;
}

int hy_gl_ribbon_project(const hy_gl *g, const hy_gl_ribbon *r, const double xyz[3], double *px, double *py)
{
    double v[4];
    ribbon_viewport(g, r, v);
    mat4 mv, proj;
    camera(r, v[2] / v[3], &mv, &proj);
    mat4 mvp = mat_mul(&proj, &mv);
    double c[4];
    for (int i = 0; i < 4; i++)
        c[i] = mvp.m[i] * xyz[0] + mvp.m[4 + i] * xyz[1] + mvp.m[8 + i] * xyz[2] + mvp.m[12 + i];
    if (!(c[3] > 1e-9))
        return 0;
    *px = v[0] + (0.5 + 0.5 * c[0] / c[3]) * v[2];
    *py = v[1] + (0.5 - 0.5 * c[1] / c[3]) * v[3];
    return 1;
}

static const double *rp(const hy_gl_ribbon *r, int i, int j)
{
    i = i < 0 ? 0 : i >= r->nloops ? r->nloops - 1 : i;
    j = j < 0 ? 0 : j >= r->npts ? r->npts - 1 : j;
    return r->pts + 3 * ((size_t)i * (size_t)r->npts + (size_t)j);
}

static void ribbon_vertex(const hy_gl_ribbon *r, int i, int j, float *v)
{
    const double *p = rp(r, i, j), *a = rp(r, i, j + 1), *b = rp(r, i, j - 1);
    const double *c = rp(r, i + 1, j), *d = rp(r, i - 1, j);
    double t1[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]}, t2[3] = {c[0] - d[0], c[1] - d[1], c[2] - d[2]};
    double n[3] = {t1[1] * t2[2] - t1[2] * t2[1], t1[2] * t2[0] - t1[0] * t2[2], t1[0] * t2[1] - t1[1] * t2[0]};
    double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(nl > 0))
        n[0] = 0, n[1] = 1, n[2] = 0, nl = 1;
    hy_rgb col = hy_cmap(r->cmap ? r->cmap : HY_CMAP_VIRIDIS, r->nloops > 1 ? (double)i / (r->nloops - 1) : 0);
    const double vals[9] = {p[0], p[1], p[2], n[0] / nl, n[1] / nl, n[2] / nl, col.r, col.g, col.b};
    for (int k = 0; k < 9; k++)
        v[k] = (float)vals[k];
}

/* The 4x multisampled colour + depth framebuffer, made on first use.  A
 * frame that draws 3-D moves into it (2-D commands included, so the ribbon
 * lies over what was drawn before it) and is resolved by a blit at
 * hy_gl_read: no texture sampling.  HY_EUNSUP if it is incomplete. */
static int msaa_target(hy_gl *g, hy_error *err)
{
    if (g->ms_fbo)
        return HY_OK;
    gl->GenFramebuffers(1, &g->ms_fbo);
    gl->BindFramebuffer(GL_FRAMEBUFFER, g->ms_fbo);
    gl->GenRenderbuffers(2, g->ms_rb);
    gl->BindRenderbuffer(GL_RENDERBUFFER, g->ms_rb[0]);
    gl->RenderbufferStorageMultisample(GL_RENDERBUFFER, RIBBON_SAMPLES, GL_RGBA8, g->w, g->h);
    gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, g->ms_rb[0]);
    gl->BindRenderbuffer(GL_RENDERBUFFER, g->ms_rb[1]);
    gl->RenderbufferStorageMultisample(GL_RENDERBUFFER, RIBBON_SAMPLES, GL_DEPTH_COMPONENT24, g->w, g->h);
    gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, g->ms_rb[1]);
    int ok = gl->CheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    gl->BindFramebuffer(GL_FRAMEBUFFER, g->fbo0);
    return ok ? HY_OK : hy_error_set(err, HY_EUNSUP, "the 4x multisampled framebuffer of the 3-D pass is incomplete");
}

/* Moves the frame into the multisampled framebuffer (cleared to the frame's
 * colour; nothing was sent to GL yet but the clear of hy_gl_begin). */
static void enter_msaa(hy_gl *g)
{
    if (!g->in_ms)
        g->in_ms = 1, clear_to_bg(g, g->ms_fbo);
}

/* Resolves the multisampled frame into the default framebuffer. */
static void leave_msaa(hy_gl *g)
{
    if (!g->in_ms)
        return;
    gl->Disable(GL_SCISSOR_TEST);
    gl->BindFramebuffer(GL_READ_FRAMEBUFFER, g->ms_fbo);
    gl->BindFramebuffer(GL_DRAW_FRAMEBUFFER, g->fbo0);
    gl->BlitFramebuffer(0, 0, g->w, g->h, 0, 0, g->w, g->h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    gl->BindFramebuffer(GL_FRAMEBUFFER, g->fbo0);
    g->in_ms = 0;
}

/* The ribbon's vertices (position, normal, colour) and triangle indices. */
static int ribbon_mesh(const hy_gl_ribbon *r, float **vout, unsigned **iout, size_t *nv, size_t *ni)
{
    *nv = (size_t)r->nloops * (size_t)r->npts, *ni = (size_t)(r->nloops - 1) * (size_t)(r->npts - 1) * 6;
    float *v = malloc(*nv * 9 * sizeof *v);
    unsigned *idx = malloc(*ni * sizeof *idx);
    if (!v || !idx) {
        free(v), free(idx);
        return -1;
    }
    for (int i = 0; i < r->nloops; i++)
        for (int j = 0; j < r->npts; j++)
            ribbon_vertex(r, i, j, v + 9 * ((size_t)i * (size_t)r->npts + (size_t)j));
    size_t k = 0;
    for (unsigned i = 0; i + 1 < (unsigned)r->nloops; i++)
        for (unsigned j = 0; j + 1 < (unsigned)r->npts; j++) {
            unsigned a = i * (unsigned)r->npts + j, b = a + (unsigned)r->npts;
            const unsigned q[6] = {a, b, a + 1, a + 1, b, b + 1};
            memcpy(idx + k, q, sizeof q);
            k += 6;
        }
    *vout = v, *iout = idx;
    return 0;
}

static void ribbon_pass(hy_gl *g, const hy_gl_ribbon *r, const double *vp)
{
    mat4 mv, proj;
    camera(r, vp[2] / vp[3], &mv, &proj);
    mat4 mvp = mat_mul(&proj, &mv);
    float fm[16], fmv[16];
    to_float(&mvp, fm);
    to_float(&mv, fmv);
    gl->Disable(GL_SCISSOR_TEST);
    gl->Clear(GL_DEPTH_BUFFER_BIT);
    gl->Viewport((GLint)lround(vp[0]), (GLint)lround(g->h - vp[1] - vp[3]), (GLsizei)lround(vp[2]),
               (GLsizei)lround(vp[3]));
    gl->Enable(GL_DEPTH_TEST);
    gl->DepthFunc(GL_LESS);
    gl->Disable(GL_BLEND);
    gl->UseProgram(g->o->ribbon_prog);
    gl->UniformMatrix4fv(g->o->u_ribbon[RIBBON_MVP], 1, GL_FALSE, fm);
    gl->UniformMatrix4fv(g->o->u_ribbon[RIBBON_MV], 1, GL_FALSE, fmv);
    gl->Uniform3f(g->o->u_ribbon[RIBBON_LIGHT], 0.4f, 0.8f, 0.6f);
}

static int gl_draw_ribbon_unlocked(hy_gl *g, const hy_gl_ribbon *r, hy_error *err)
{
    if (!r->pts || r->nloops < 2 || r->npts < 2 || (size_t)r->nloops * (size_t)r->npts > 4000000)
        return hy_error_set(err, HY_EINVAL, "a ribbon needs 2+ loops of 2+ points (got %d x %d)",
                            r->nloops, r->npts);
    float *v;
    unsigned *idx;
    size_t nv, ni;
    if (ribbon_program(g, err))
        return HY_ENUM;
    if (ribbon_mesh(r, &v, &idx, &nv, &ni))
        return hy_error_set(err, HY_ENOMEM, "out of memory for a %d x %d ribbon", r->nloops, r->npts);
    if (msaa_target(g, err)) {
        free(v), free(idx);
        return HY_EUNSUP;
    }
    enter_msaa(g);
    submit(g);                        /* 2-D data drawn so far stays underneath */
    double vp[4];
    ribbon_viewport(g, r, vp);
    ribbon_pass(g, r, vp);
    gl->BindVertexArray(g->o->ribbon_vao);
    gl->BindBuffer(GL_ARRAY_BUFFER, g->o->ribbon_vbo);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(nv * 9 * sizeof *v), v, GL_STREAM_DRAW);
    gl->BufferData(GL_ELEMENT_ARRAY_BUFFER, (GLsizeiptr)(ni * sizeof *idx), idx, GL_STREAM_DRAW);
    gl->DrawElements(GL_TRIANGLES, (GLsizei)ni, GL_UNSIGNED_INT, NULL);
    gl->BindVertexArray(0);
    gl->Disable(GL_DEPTH_TEST);
    gl->Viewport(0, 0, g->w, g->h);
    free(v);
    free(idx);
    return HY_OK;
}

int hy_gl_draw_ribbon(hy_gl *g, const hy_gl_ribbon *r, hy_error *err)
{
    acquire(g);
    int rc = gl_draw_ribbon_unlocked(g, r, err);
    release(g, 0);
    return rc;
}

/* ---- the relay plane ---- */

static int plane_program(hy_gl *g, hy_error *err)
{
    static const char *const plane_uniforms[11] = {"u_rect", "u_height", "u_range", "u_s", "u_n", "u_kind0",
                                                   "u_dist", "u_dens", "u_up", "u_down", NULL};
    const hy_gl_stage plane[2] = {
        {hy_shader_plane_vert_file, GL_VERTEX_SHADER, hy_shader_plane_vert, NULL},
        {hy_shader_plane_frag_file, GL_FRAGMENT_SHADER, hy_shader_plane_frag, NULL},
    };
    return program_once(&g->o->plane_prog, plane, plane_uniforms, g->o->u_plane, err);
}

static int gl_draw_plane_unlocked(hy_gl *g, const hy_gl_plane *pl, hy_error *err)
{
    if (!(pl->vw >= 1 && pl->vh >= 1 && pl->xlo < pl->xhi && pl->ylo < pl->yhi && pl->sa > 0 && pl->sb > 0) ||
        pl->n < 0 || pl->n > HY_GL_PLANE_MAX || !pl->s)
        return hy_error_set(err, HY_EINVAL, "a relay plane needs a panel, ranges, widths > 0 and at most %d "
                            "extrema (got %d)", HY_GL_PLANE_MAX, pl->n);
    if (plane_program(g, err))
        return HY_ENUM;
    submit(g);                        /* the 2-D data drawn so far stays underneath */
    float s[HY_GL_PLANE_MAX + 1];
    for (int j = 0; j <= pl->n; j++) /* the saturations as far-off finite values */
        s[j] = (float)(pl->s[j] > 1e30 ? 1e30 : pl->s[j] < -1e30 ? -1e30 : pl->s[j]);
    const GLint *u = g->o->u_plane;
    gl->UseProgram(g->o->plane_prog);
    gl->Uniform4f(u[0], (float)pl->vx, (float)pl->vy, (float)pl->vw, (float)pl->vh);
    gl->Uniform1f(u[1], (float)g->h);
    gl->Uniform4f(u[2], (float)pl->xlo, (float)pl->xhi, (float)pl->ylo, (float)pl->yhi);
    gl->Uniform1fv(u[3], pl->n + 1, s);
    gl->Uniform1i(u[4], pl->n);
    gl->Uniform1i(u[5], pl->kind0 > 0 ? 1 : -1);
    gl->Uniform1i(u[6], pl->dist);
    gl->Uniform4f(u[7], (float)pl->ma, (float)pl->sa, (float)pl->mb, (float)pl->sb);
    gl->Uniform3f(u[8], (float)pl->up.r, (float)pl->up.g, (float)pl->up.b);
    gl->Uniform3f(u[9], (float)pl->down.r, (float)pl->down.g, (float)pl->down.b);
    gl->Disable(GL_BLEND);
    gl->Disable(GL_DEPTH_TEST);
    gl->Enable(GL_SCISSOR_TEST);      /* whole pixels of the panel only */
    GLint x0 = (GLint)lround(pl->vx), y1 = (GLint)lround(pl->vy + pl->vh);
    GLint x1 = (GLint)lround(pl->vx + pl->vw), y0 = (GLint)lround(pl->vy);
    gl->Scissor(x0, g->h - y1, x1 - x0, y1 - y0);
    gl->Viewport(0, 0, g->w, g->h);
    gl->BindVertexArray(g->o->vao);
    gl->DrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    gl->BindVertexArray(0);
    gl->Disable(GL_SCISSOR_TEST);
    return HY_OK;
}

int hy_gl_draw_plane(hy_gl *g, const hy_gl_plane *pl, hy_error *err)
{
    acquire(g);
    int rc = gl_draw_plane_unlocked(g, pl, err);
    release(g, 0);
    return rc;
}

static int gl_read_unlocked(hy_gl *g, unsigned char *rgba, hy_error *err)
{
    submit(g);
    leave_msaa(g);
    gl->BindFramebuffer(GL_FRAMEBUFFER, g->fbo0);
    gl->PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl->ReadPixels(0, 0, g->w, g->h, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    GLenum e = gl->GetError();
    if (e != GL_NO_ERROR)
        return hy_error_set(err, HY_ENUM, "OpenGL error 0x%04x while drawing or reading the frame", e);
    return HY_OK;
}

static const unsigned char *gl_finish_unlocked(hy_gl *g, hy_error *err)
{
    submit(g);
    leave_msaa(g);
    const unsigned char *fb = g->be->frame(g->surf);
    GLenum e = gl->GetError();
    if (e != GL_NO_ERROR) {
        hy_error_set(err, HY_ENUM, "OpenGL error 0x%04x while drawing the frame", e);
        return NULL;
    }
    return fb;
}

const unsigned char *hy_gl_finish(hy_gl *g, hy_error *err)
{
    acquire(g);
    const unsigned char *fb = gl_finish_unlocked(g, err);
    release(g, 1);
    return fb;
}

int hy_gl_read(hy_gl *g, unsigned char *rgba, hy_error *err)
{
    acquire(g);
    int rc = gl_read_unlocked(g, rgba, err);
    release(g, 1);
    return rc;
}
