/* SPDX-License-Identifier: MIT */
/* hystviz.h: libhystviz, the hystviz pipeline as a C library.
 *
 * Include this one header; it brings the numerical core with it (hy_model.h,
 * hy_input.h, hy_limit.h, hy_loops.h, hy_gamma.h, hy_boucwen.h, the reader of
 * measured data hy_table.h, ...: each is its own manual).  Build against the
 * installed library with
 *
 *     cc prog.c $(pkg-config --cflags --libs hystviz)
 *
 * or, from CMake, find_package(hystviz) and the target hystviz::hystviz.  The
 * headers serve C++ as they are (extern "C"); hystviz_version.h gives their
 * version (HYSTVIZ_VERSION_CHECK).  Each function has a man page in section 3.
 *
 * The core computes on structs you own (a model, an input, the steady state
 * y° and its loops).  The pipeline below takes a scene (the text of a .scene
 * file, docs/SCENES.md) and overrides ("section.key=value", as `--set`),
 * computes what the scene asks for and gives its series, its loops and its
 * figure in memory, byte for byte what `hystviz data` and `hystviz render`
 * write.  Errors are an int status (hy_status.h) and, with a non-NULL
 * hy_error, one sentence naming file:line:col.
 *
 * Thread safety: no global state; a hy_result is used by one thread at a
 * time; distinct results may be computed and drawn concurrently.
 *
 * Pointers: every pointer argument is either "may be NULL" (said where it
 * is, with what NULL means) or must not be NULL; a NULL where one is needed
 * is an error (HY_EINVAL and a message in err), never a crash.  err itself
 * may always be NULL (no message).  Out-pointers are set on every return.
 *
 *     hy_result *r;
 *     hy_error err;
 *     const char *sets[] = {"model.sigma0=2"};
 *     if (hy_result_from_file("fig15.scene", sets, 1, 0, &r, &err)) {
 *         fprintf(stderr, "%s\n", err.msg);
 *         return 2;
 *     }
 *     const double *x, *y;
 *     size_t n = hy_result_series(r, 0, &x, &y);
 *     hy_result_free(r);
 */
#ifndef HYSTVIZ_H
#define HYSTVIZ_H

#include <stddef.h>

#include "hy_boucwen.h"
#include "hy_gamma.h"
#include "hy_input.h"
#include "hy_limit.h"
#include "hy_loops.h"
#include "hy_model.h"
#include "hy_status.h"
#include "hy_table.h"
#include "hystviz_version.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The library's version, "MAJOR.MINOR.PATCH" (that of the hystviz command
 * built with it); never NULL. */
const char *hy_version(void);

/* Turns GSL's error handler off (gsl_set_error_handler_off) so that a GSL
 * error inside a library call comes back to the library (as a GSL status or
 * an error bound it checks, then as the call's status) instead of GSL's
 * default handler aborting the process.  GSL's
 * handler is one per process: this changes it for the caller's own GSL calls
 * too, which is why the library does not call it on its own behalf, except
 * in fits (hy_fit_scene and a scene's fit turn it off, as hystviz fit does:
 * their threads must not abort).  For hosts that cannot know GSL is inside
 * (the Python package calls it when imported); a C program may as well keep
 * its own handler.  Returns nothing; cannot fail. */
void hy_gsl_quiet(void);

/* A computed scene: its series, loops and figure. */
typedef struct hy_result hy_result;

/* Parses the scene text (len bytes; name is used in messages and is where
 * includes and relative paths are looked up, as a file's path would be),
 * applies the nsets overrides "section.key=value", checks everything that
 * can be checked before computing and computes.  max_work is the work budget
 * (docs/SCENES.md; <= 0: the default of `hystviz render`; NaN and infinities
 * are refused: there is no unlimited budget).  On success *out is the result
 * (free it with hy_result_free); on error *out is NULL and err names
 * file:line:col.
 * Pointers: name may be NULL ("<scene>"); text must not be NULL (even for
 * len 0); sets may be NULL only when nsets is 0, and each sets[i] must not be
 * NULL; out must not be NULL (HY_EINVAL, nothing computed). */
int hy_result_from_text(const char *name, const char *text, size_t len, const char *const *sets, size_t nsets,
                        double max_work, hy_result **out, hy_error *err);

/* As hy_result_from_text on the file at path (must not be NULL); sets,
 * max_work and out as there. */
int hy_result_from_file(const char *path, const char *const *sets, size_t nsets, double max_work, hy_result **out,
                        hy_error *err);

/* Frees r (NULL is allowed). */
void hy_result_free(hy_result *r);

/* A parameter study in memory (docs/STUDIES.md, issue 37): the scene file at
 * path with the nsets overrides "section.key=value", table only, at every
 * point of the grid whose axis a is the key keys[a] with the counts[a] values
 * values[a] (points in row-major order, the first axis outermost, as `hystviz
 * sweep --grid`), on jobs threads (< 1: one).  On success *npy (free it with
 * free()) holds *len bytes: the sweep.npy that `hystviz sweep PATH --set ...
 * --grid KEY=V1,V2,... --formats none --table npy` writes, byte for byte, each
 * V the shortest of %.15g/%.16g/%.17g that reads back to the value (a
 * structured array, one field per column; a point the scene refuses is a
 * record with status 1 invalid or 2 failed and its message).  shard_k of
 * shard_n (0 <= shard_k < shard_n; 0 of 1: all) computes only the points i
 * with i mod shard_n = shard_k, as `--shard K/N` does: their records are
 * those of the whole study (global index, name, error sample), so the
 * shards' records interleaved are the whole study's.  max_work as
 * for hy_result_from_text, per point.  On error (HY_EINVAL: a key the scene
 * does not have, a value it refuses, a non-finite value, a bad scene or
 * override, with a message naming it) *npy is NULL and *len 0.
 * Pointers: sets may be NULL only when nsets is 0; keys, values and counts
 * only when naxes is 0; path, npy and len must not be NULL. */
int hy_sweep_npy(const char *path, const char *const *sets, size_t nsets, const char *const *keys,
                 const double *const *values, const size_t *counts, size_t naxes, long shard_k, long shard_n,
                 long jobs, double max_work, unsigned char **npy, size_t *len, hy_error *err);

/* The number of series (the scene's [series NAME] sections, in order); 0
 * for r NULL.  Every reader below takes r NULL as "no result" (0, NULL or
 * NaN, as it says for i out of range). */
size_t hy_result_nseries(const hy_result *r);

/* Series i: its name, what it draws ("input", "ysteady", "ygamma", "minor",
 * ...: the key data of docs/SCENES.md) and its n points; *x and *y (either
 * may be NULL) point into r and live as long as r.  NaN separates pieces.
 * Returns n (0 for i out of range). */
size_t hy_result_series(const hy_result *r, size_t i, const double **x, const double **y);
/* Copies series i's first min(n, cap) points into x and y (either may be
 * NULL: that coordinate is not copied), arrays the caller owns, and returns
 * its n (0 for i out of range): one call where a foreign caller (the Python
 * package) would otherwise make three. */
size_t hy_result_series_copy(const hy_result *r, size_t i, double *x, double *y, size_t cap);
/* Series i's name (hy_result_series_name) and its data key
 * (hy_result_series_data); NULL for i out of range or r NULL. */
const char *hy_result_series_name(const hy_result *r, size_t i);
const char *hy_result_series_data(const hy_result *r, size_t i);

/* The largest error of series i against its exact reference, or NaN where
 * none was measured; *ref (may be NULL) says against what, or why not. */
double hy_result_series_error(const hy_result *r, size_t i, const char **ref);

/* The steady state's loops (major loop, minor loops with their areas, energy
 * per cycle; hy_loops.h) where the scene computed them, else NULL (also for
 * r NULL). */
const hy_loops *hy_result_loops(const hy_result *r);

/* The figure as "svg", "pdf" or "png" bytes (malloc'd; free with free()),
 * byte for byte what `hystviz render` writes.  bytes and len must not be
 * NULL (HY_EINVAL); on error *bytes is NULL and *len 0 where they are not.
 * r NULL and format NULL are errors (HY_EINVAL). */
int hy_result_render(const hy_result *r, const char *format, unsigned char **bytes, size_t *len, hy_error *err);

/* Every series as the CSV `hystviz data` prints ("series,x,y", %.17g), a
 * malloc'd NUL-terminated text of *len bytes.  text and len must not be
 * NULL (HY_EINVAL); on error *text is NULL and *len 0 where they are not;
 * r NULL is an error. */
int hy_result_csv(const hy_result *r, char **text, size_t *len, hy_error *err);

/* The steady state y° of a model under a periodic input over one period
 * (docs/SCENES.md, data = ysteady): time t (s), the input u and the output
 * y at the points + 1 samples t_i = i T / points, both ends included, into
 * arrays of points + 1 doubles the caller owns; bit for bit what `hystviz
 * data` prints for the scene of the two sections with [compute] points =
 * points and the series data = input and data = ysteady, and what the Python
 * package's steady_loop returns (it is this call).  model and input are the
 * scene text of the [model] and [input] sections, each from its header line
 * ("[model]\nkind = lugre\nsigma0 = 6\n"); the nsets overrides
 * "section.key=value" apply after them; name as for hy_result_from_text.
 * points is checked as the scene's [compute] points (its range in
 * docs/SCENES.md).  Errors: HY_EINVAL with file:line:col for a key, a value
 * or a points the scene refuses, any status of hy_result_from_text; on error
 * t, u and y are not written.
 * Pointers: name may be NULL ("<scene>"); model and input must not be NULL;
 * sets may be NULL only when nsets is 0, and each sets[i] must not be NULL;
 * t, u and y may each be NULL (that array is not written). */
int hy_steady_loop(const char *name, const char *model, const char *input, const char *const *sets, size_t nsets,
                   size_t points, double *t, double *u, double *y, hy_error *err);

/* Writes the len bytes at data to path through hystviz's one output writer
 * (hy_out, as every file `hystviz` writes): a temporary beside the target
 * made with O_EXCL under a random name, renamed onto path when complete, so
 * path is whole or untouched; a symbolic link at path is followed only to a
 * file in path's own directory or below (one out of it is refused, never
 * followed or replaced); a FIFO or character device at path is written as
 * it is, never replaced; a directory, socket or block device is refused;
 * "-" is standard output.  path must not be NULL; data may be NULL only
 * when len is 0.  Errors: HY_EINVAL, HY_EIO with "cannot write 'PATH':
 * reason"; no temporary is left. */
int hy_write_file(const char *path, const void *data, size_t len, hy_error *err);

/* The scene vocabulary (sections, keys, kinds, ranges, defaults, units,
 * symbols, one-line descriptions) as JSON, malloc'd; for bindings that build their classes
 * from it (the Python package does).  NULL when out of memory. */
char *hy_schema_json(void);

/* The Bouc-Wen benchmark's output y (n samples, caller's array) for the force
 * u (n samples at fs Hz, integrated at that rate from rest) with the
 * benchmark's parameters and Newmark integrator (Table 1; hy_boucwen.h):
 * what `hystviz boucwen data --input FILE --upsample 1 --fs FS --noise 0`
 * prints (no measurement noise).  u and y must not be NULL and n >= 1;
 * fs finite and > 0 (HY_EINVAL otherwise). */
int hy_boucwen_run(const double *u, size_t n, double fs, double *y, hy_error *err);

/* ---- fitting a scene to its measured data (docs/FIT.md "Fitting a scene") ---- */

/* A scene's [model] keys fitted to its measured data: `hystviz fit SCENE
 * --free KEY,...` as a call, the same numbers bit for bit. */
typedef struct hy_scene_fitted hy_scene_fitted;

/* Fits the nfree [model] number keys free_keys ("sigma0" or "model.sigma0") of
 * the scene file path to the measured data that drive its model (data NULL
 * or ndata 0), or to each [data] name in data[0 .. ndata) in turn, all at
 * once; start 0 is the scene's values, starts more from the Latin
 * hypercube of seed; jobs threads (the result does not depend on them).
 * path, free_keys (1 to 16 non-NULL keys) and out must not be NULL
 * (HY_EINVAL); HY_EINVAL with one line for a bad key or data file, HY_ENUM
 * when every start failed; *out is NULL on error. */
int hy_fit_scene(const char *path, const char *const *free_keys, size_t nfree, const char *const *data, size_t ndata,
                 size_t starts, unsigned long long seed, int jobs, hy_scene_fitted **out, hy_error *err);

/* Frees f (NULL is allowed). */
void hy_scene_fitted_free(hy_scene_fitted *f);

/* The fit's array `what` and its length into *len (may be NULL), or NULL (len
 * 0) for an unknown name or f NULL: per parameter "theta", "se", "ci_lo",
 * "ci_hi", "start", "lo", "hi", "unident" (0, or the HY_FIT_NULLDIR 1 |
 * HY_FIT_WIDE 2 bits as numbers); "corr" (p x p, row-major); per measured
 * point "u", "y" (measured), "model" (at the estimate), "resid" (model -
 * measured); "offsets" (one more than the data sets: where each begins). */
const double *hy_scene_fitted_array(const hy_scene_fitted *f, const char *what, size_t *len);

/* A number of the fit: "rss", "rms", "nrms", "max_abs", "fit_index", "cond",
 * "dof", "iterations", "evaluations", "seconds", "starts", "failed"; NaN for
 * an unknown name or f NULL. */
double hy_scene_fitted_stat(const hy_scene_fitted *f, const char *what);

/* Parameter j's key (hy_scene_fitted_key), data set j's name
 * (hy_scene_fitted_data); NULL out of range or f NULL. */
const char *hy_scene_fitted_key(const hy_scene_fitted *f, size_t j);
const char *hy_scene_fitted_data(const hy_scene_fitted *f, size_t j);

/* The fitted scene's text (the scene with the estimates written in, what
 * hystviz fit -o writes), owned by f; NULL for f NULL. */
const char *hy_scene_fitted_text(const hy_scene_fitted *f);

#ifdef __cplusplus
}
#endif

#endif
