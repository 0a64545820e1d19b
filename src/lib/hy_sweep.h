/* SPDX-License-Identifier: MIT */
/* hy_sweep.h: the engine of `hystviz sweep` (docs/STUDIES.md), inside
 * libhystviz so that the command and hy_sweep_npy (hystviz.h, Python's
 * hystviz.sweep) compute and write a study's rows with the same code:
 * a pool of workers computes the points (typed grid writes into the decoded
 * scene where the grid allows, issue 37) and the rows (CSV) or records
 * (.npy) are written to one FILE in point order.
 *
 *     hy_sweep_study s = {.o = &opts};
 *     if (hy_sweep_check(&s, &hash, &err) || hy_sweep_prepare(&s, &err)) ...
 *     hy_sweep_write_header(&s, f);    (CSV; .npy: hy_npy_header(s.descr, ...))
 *     s.table = f;
 *     hy_sweep_run_pool(&s);
 *     hy_sweep_study_free(&s);
 *
 * Not installed: the library's own internal interface. */
#ifndef HY_SWEEP_H
#define HY_SWEEP_H

#include <pthread.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "hy_grid.h"
#include "hy_out.h"
#include "hy_scene_policy.h"
#include "hy_status.h"

/* Errors are measured at points i with i mod HY_SWEEP_VERIFY_EVERY = 0
 * (--verify: all). */
#define HY_SWEEP_VERIFY_EVERY 1000

typedef struct hy_sweep_opts {
    const char *scene, *out, *formats, *merge, *plot;
    char **sets;
    size_t nsets;
    hy_grid grid;
    hy_scene_policy pol;   /* --include-dir, --max-work: as render's, per point */
    const char **dirs;
    long jobs, shard_k, shard_n;
    long verify_every;     /* errors measured at points i with i mod this = 0 */
    int sharded, times, quiet, figures;
    int npy;               /* --table npy */
    char *rerun;           /* a shard's re-run text for its manifest (or NULL) */
} hy_sweep_opts;

typedef struct hy_sweep_study {
    const hy_sweep_opts *o;
    char **series;       /* the base scene's series names                */
    int *series_dist;    /* ... and whether each gets a .dist column      */
    size_t nseries;
    char **short_keys;   /* the key of each axis as a file name uses it   */
    char ***name_parts;  /* per axis and value: "_KEY-VALUE" in point names */
    int index_width;
    size_t nmine;        /* points of this shard                          */
    hy_out out;          /* the table (sweep.csv or the shard manifest)   */
    /* --table npy: the record's layout */
    char *descr;         /* the structured dtype, as the .npy header says  */
    size_t name_w;       /* bytes of the name field                        */
    size_t *axis_w;      /* per axis: 0 float64, else bytes of its text    */
    double **axis_num;   /* per float64 axis: its values                   */
    FILE *table;
    char table_path[4400];
    /* streaming in point order */
    pthread_mutex_t mu;
    pthread_cond_t cv;
    size_t next, written, window;
    struct rowbuf *slots; /* the window's rows, formatted in place, reused     */
    unsigned char *ready; /* ... and which of them are done                   */
    size_t nok, ninvalid, nfailed;
    size_t nclosed;       /* of the ok points: how many the closed-form kernel
                           * computed (hy_sweep.c; the rest: the pipeline)   */
    int io_error;
} hy_sweep_study;


/* Checks the study before anything is written: the scene loads at point 0,
 * every grid value is accepted by the scene on its own; fills the series
 * columns and the study hash.  2 on bad input, with the message in msg
 * (without the "hystviz sweep: " prefix). */
int hy_sweep_check(hy_sweep_study *s, uint64_t *hash, hy_error *msg);

/* After hy_sweep_check: the axes' short keys, the index width, the points of
 * this shard and (npy) the record layout.  -1 when out of memory or the .npy
 * header would pass 64 KiB (message in err). */
int hy_sweep_prepare(hy_sweep_study *s, hy_error *err);

/* The CSV header line of the study into f. */
void hy_sweep_write_header(const hy_sweep_study *s, FILE *f);

/* Computes this shard's points with o->jobs threads and writes their rows
 * (records) to s->table in point order; counts nok/ninvalid/nfailed.  -1
 * when out of memory; s->io_error after a failed write. */
int hy_sweep_run_pool(hy_sweep_study *s);

/* Frees what hy_sweep_check and hy_sweep_prepare allocated (not s). */
void hy_sweep_study_free(hy_sweep_study *s);

/* The longest .npy header dictionary (v1.0: its length is 16 bits). */
#define HY_NPY_HEAD_MAX 65000

/* An .npy v1.0 header (magic, version, length, the dict with descr, not
 * Fortran order, shape (nrows,), padded with spaces and '\n' to a multiple
 * of 64 bytes) into buf; its length, 0 if it would not fit size or 64 KiB. */
size_t hy_npy_header(const char *descr, size_t nrows, char *buf, size_t size);

#endif
