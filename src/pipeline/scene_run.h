/* SPDX-License-Identifier: MIT */
/* scene_run.h: from a parsed scene to computed series, a figure and its files
 * (DESIGN.md: parse → plan → compute → draw → write).
 *
 * The plan reads what the scene draws and computes only that: the steady
 * state and loops only if a series or annotation needs them, one y_γ solve per
 * distinct γ (shared by its transient and steady-state series), no ODE solver
 * for an analytic figure, never a GL context.
 *
 *     hy_scene_run r;
 *     if (hy_scene_run_load(&r, "scenes/fig15.scene", sets, nsets, &err)) ...
 *     if (hy_scene_run_compute(&r, verbose_stream, &err)) ...
 *     hy_scene_run_write(&r, outdir, formats_or_NULL, written, &err);
 *     hy_scene_run_free(&r);
 */
#ifndef HY_SCENE_RUN_H
#define HY_SCENE_RUN_H

#include "hy_scene_policy.h"
#include "scene_run_types.h" /* hy_run_series, hy_run_data, hy_scene_run */

/* Parses the scene, applies the overrides ("section.key=value") and builds the
 * model and input.  Errors name file:line:col.  On error r is freed. */
int hy_scene_run_load(hy_scene_run *r, const char *path, char *const *sets, size_t nsets, hy_error *err);

/* What can be checked before computing beyond hy_scene_decode's checks:
 * annotation texts (braces, placeholder names).  hy_scene_run_load calls it
 * (issue 20 item 11: refused after seconds of computing before). */
int hy_scene_run_validate(const hy_scene_run *r, hy_error *err);

/* As hy_scene_run_load under pol (include dirs, work budget; NULL: defaults). */
int hy_scene_run_load_policy(hy_scene_run *r, const char *path, char *const *sets, size_t nsets,
                             const hy_scene_policy *pol, hy_error *err);

/* As hy_scene_run_load on a scene the caller parsed and overrode: r->scene
 * is scene, which r does not free (the caller keeps it alive while r lives,
 * and unchanged); budget as hy_scene_policy_budget gives it.  On error r is
 * freed (not the scene). */
int hy_scene_run_load_scene(hy_scene_run *r, hy_scene *scene, const char *path, double budget, hy_error *err);

/* As hy_scene_run_load_scene with the scene already decoded by the caller:
 * doc is what hy_scene_decode gives for scene (hystviz sweep writes its grid
 * values into a copy of the decoded fields); its section arrays are lent,
 * never freed nor changed by the run.  validated: the caller loaded a doc
 * that differs from this one only in NUMBER/INTEGER fields of [model],
 * [input] or [compute] before, without error: the annotation placeholders
 * (which depend on no such value) are not checked again. */
int hy_scene_run_load_doc(hy_scene_run *r, hy_scene *scene, const hy_scene_doc *doc, int validated, const char *path,
                          double budget, hy_error *err);

/* As hy_scene_run_load_scene on a scene marked (hy_scene_mark) when base was
 * decoded from it and since changed only by overrides: the run's doc is base
 * with the sections they changed decoded again (hy_scene_decode_marked).
 * base NULL: as hy_scene_run_load_scene. */
int hy_scene_run_load_marked(hy_scene_run *r, hy_scene *scene, const hy_scene_doc *base, const char *path,
                             double budget, hy_error *err);

/* As hy_scene_run_load_policy from the scene's text, already read (the
 * caller opened the file once); path names it in messages and is where its
 * includes and relative paths are looked up. */
int hy_scene_run_load_text(hy_scene_run *r, const char *path, const char *text, size_t len, char *const *sets,
                           size_t nsets, const hy_scene_policy *pol, hy_error *err);

/* The work the scene asks for, before computing: for Dahl/LuGre scenes the
 * grid points of every distinct gamma solve plus the points of every series;
 * for Bouc-Wen scenes the Newmark steps plus the series samples (docs/SCENES.md,
 * "Work budget").  what (may be NULL) receives the breakdown. */
int hy_scene_run_estimate(const hy_scene_run *r, double *work, char *what, size_t size, hy_error *err);
/* The same, with the PNG raster's work given (pixel_work: hy_cost of
 * hy_scene_run_png_pixels, which reads only [figure] and the formats: the
 * sweep's kernel computes it once for all its points). */
int hy_scene_run_estimate_px(const hy_scene_run *r, double pixel_work, double *work, char *what, size_t size,
                             hy_error *err);

/* What computing and drawing the scene reads of [model] and [input], as the
 * plan decides from its series: HY_READS_MODEL, the model's dynamics (any
 * series but input, psi, g and measured); HY_READS_G, its g(v) only (Fc, Fs, vs, beta;
 * data = g); HY_READS_INPUT, the input (any series but g).  An annotation's
 * {model.KEY} or {input.KEY} placeholder reads that section too.  hystviz
 * serve shows controls only for what is read.  (The bits: hy_scene.h.) */
unsigned hy_scene_reads(const hy_scene *s);

/* The same of a decoded scene. */
unsigned hy_scene_doc_reads(const hy_scene_doc *d);

/* Writes the budget refusal (at [compute] points/cycles/tspan/gamma if written,
 * else at the first series, else file:1:1) and returns HY_EINVAL. */
int hy_scene_run_over_budget(const hy_scene_doc *d, double work, double budget, const char *what, hy_error *err);

/* hy_scene_run_check_cancel: scene_run_types.h (the stages call it too). */


/* Plans and computes every series (refused at once with HY_EINVAL if the
 * estimate passes r->budget); log (may be NULL) receives the plan and
 * per-step times, errors against exact answers where they exist. */
int hy_scene_run_compute(hy_scene_run *r, FILE *log, hy_error *err);

/* Writes the figure in the scene's formats (or the comma-separated formats
 * override) into dir (NULL: the scene's [output] dir); the paths written are
 * appended to written (may be NULL), one per line.  All or nothing: every
 * format is written to a temporary first (hy_out.h) and renamed only when all
 * of them are complete; on failure none is replaced and err names the file. */
int hy_scene_run_write(const hy_scene_run *r, const char *dir, const char *formats, char *written,
                       size_t written_size, hy_error *err);

/* Checks before any computing what hy_scene_run_write will need: known
 * formats and a PNG within the raster limits (hy_figure_check).  HY_EINVAL
 * with a message naming the scene file. */
int hy_scene_run_check_output(const hy_scene_run *r, const char *formats, hy_error *err);

/* The pixels of the PNG raster the figure is drawn on when r->formats (or,
 * NULL, the scene's [output] formats) include png; else 0. */
double hy_scene_run_png_pixels(const hy_scene_run *r);

/* Parses a comma-separated format list ("svg,png") into HY_FORMAT_* values
 * (duplicates dropped); HY_EINVAL naming an unknown one or an empty list. */
int hy_scene_formats_parse(const char *list, int fmt[HY_FORMAT_COUNT], size_t *n, hy_error *err);

/* Draws the figure into memory as HY_FORMAT_SVG, _PDF or _PNG: *buf
 * (malloc'd, the caller frees) holds the *len bytes that hy_scene_run_write
 * would write to the file of that format.  map (may be NULL) receives where
 * the panel was drawn (for values under the cursor).  Re-entrant. */
int hy_scene_run_render(const hy_scene_run *r, int format, unsigned char **buf, size_t *len, hy_panel_map *map,
                        hy_error *err);

/* hy_scene_run_data into memory: *buf (malloc'd, NUL-terminated) of *len bytes. */
int hy_scene_run_csv(const hy_scene_run *r, char **buf, size_t *len, hy_error *err);

/* Prints every series as CSV: header "series,x,y", values %.17g. */
int hy_scene_run_data(const hy_scene_run *r, FILE *out, hy_error *err);


/* ---- measured data (scene_data.c, docs/SCENES.md "[data NAME]") ---- */

/* What hy_scene_run_driving gives: the data that drive the model, read at
 * load.  Arrays are the run's (valid while it lives): the chosen records one
 * after another, record j the rows rec[j] - rec[0] .. rec[j+1] - rec[0] - 1. */
typedef struct hy_data_view {
    const char *name;       /* the [data NAME]                          */
    size_t n;               /* measured points                          */
    const double *u, *y;    /* measured input and output, scaled        */
    size_t nrec;
    const size_t *rec;      /* nrec + 1 row offsets into the file's rows */
} hy_data_view;

/* The measured data that drive r's model ([input] kind = data) into *v:
 * HY_OK, or HY_EINVAL (with a message) when the scene has none. */
int hy_scene_run_driving(const hy_scene_run *r, hy_data_view *v, hy_error *err);

/* The fitter's evaluation: r's model (its [model] as decoded, after --set or
 * hy_scene_run_set_model) at the measured inputs of the data that drive it,
 * each record from [input] start, into y_model[0 .. v.n) (the caller's array,
 * v from hy_scene_run_driving); draws nothing, reads no file.  A model that
 * refuses a move returns its status, y_model then partly written. */
int hy_scene_run_model_at_data(const hy_scene_run *r, double *y_model, hy_error *err);

/* Sets [model] keys of a loaded run ("model.KEY=4.1", parsed and checked
 * as --set): each call starts from the scene as loaded (the previous call's
 * overrides undone, hy_scene_mark), so memory does not grow with calls; the
 * decoded [model] and the model's parameters change, the data stay as read.
 * HY_EINVAL for another section's key or model.kind; a value the schema or
 * the model refuses leaves the run's model as it was. */
int hy_scene_run_set_model(hy_scene_run *r, char *const *sets, size_t nsets, hy_error *err);

/* Where a scene file goes in the catalogue (gallery page, hystviz serve), from
 * its name: 0 the minor-loops paper's figures (figNN_), 1 the Bouc-Wen
 * benchmark's (bw_figNx_), 2 figures beyond the papers, 3 animations (anim_);
 * file-name order within a part. */
int hy_scene_catalogue_part(const char *file);

/* The paper's figure number of a part 0 or 1 file ("Fig. 4", "Fig. 1a"),
 * else an empty string. */
void hy_scene_figure_label(const char *file, char *buf, size_t size);

/* The output base name: [output] name, or the scene file's name without .scene. */
void hy_scene_run_name(const hy_scene_run *r, char *buf, size_t size);

/* The same name for a scene parsed but not loaded (a catalogue's probe),
 * from its decoded [output] and the path it was read from. */
void hy_scene_probe_name(const hy_scene *s, const char *path, char *buf, size_t size);

void hy_scene_run_free(hy_scene_run *r);

/* The figure of a computed run and the arrays it points into; fig points
 * into this struct and into r's series, so both must outlive it. */
typedef struct hy_scene_fig {
    struct hy_scene_fig *panels; /* a [panel] figure: each panel's figure ... */
    hy_axes *axes;               /* ... and their axes, row-major             */
    size_t npanels;
    hy_series *series;
    hy_mark *marks;
    hy_text *texts;
    char (*textbuf)[256];
    char (*labelbuf)[256];    /* series labels with their {section.key} placeholders filled in */
    hy_axes ax;
    hy_figure fig;
    char note[200];           /* a line for render -v (an inset left out), or "" */
    char *title, *desc;       /* the SVG's <title> and <desc> (fig.svg_title, fig.svg_desc) */
} hy_scene_fig;

/* Builds the scene's figure (styles, markers, labels, annotations with their
 * placeholders expanded, size and fonts) into *st.  On error (a bad
 * placeholder, out of memory) returns a status; call hy_scene_fig_free anyway. */
int hy_scene_run_figure(const hy_scene_run *r, hy_scene_fig *st, hy_error *err);

/* Whether the text between an annotation's braces is a placeholder ({energy},
 * {nminor} or anything with a '.') rather than a markup group (u_{min,2}). */
int hy_scene_is_placeholder(const char *inner);

/* Whether an annotation text holds a placeholder. */
int hy_scene_text_has_placeholder(const char *text);

/* Frees what hy_scene_run_figure allocated (not r's series). */
void hy_scene_fig_free(hy_scene_fig *st);

#endif
