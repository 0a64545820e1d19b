/* SPDX-License-Identifier: MIT */
/* hy_scene_internal.h: private structures shared by the scene parser, values and getters. */
#ifndef HY_SCENE_INTERNAL_H
#define HY_SCENE_INTERNAL_H

#include <ctype.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>

#include "hy_scene_schema.h"
#include "hy_scene_types.h"
#include "hy_status.h"
#include "hy_file.h"

/* A character of a [param NAME] reference's NAME: letters, digits, _ - . */
static inline int hy__name_char(int ch)
{
    return isalnum(ch) || ch == '_' || ch == '-' || ch == '.';
}

enum { HY__UNIT_PT, HY__UNIT_CM, HY__UNIT_MM, HY__UNIT_IN, HY__UNIT_PX };

/* One typed value; which fields are used depends on kind. */
typedef struct hy__value {
    hy_scene_kind kind;
    double num;           /* NUMBER, INTEGER                                   */
    long ival;            /* INTEGER, BOOL, ENUM (index)                       */
    char *str;            /* STRING, NAME, PATH (owned)                        */
    double *list;         /* *_LIST (owned); ENUM_LIST holds enum indices      */
    size_t n;
    double a[2];          /* LENGTH (a[0]), LENGTH_PAIR, PAIR, LIMITS          */
    int unit[2];          /* LENGTH, LENGTH_PAIR                               */
    int is_auto;          /* LIMITS                                            */
    hy_scene_color color; /* COLOR                                             */
} hy__value;

/* One key of one section instance. */
typedef struct hy__slot {
    int set;
    int inst; /* index in scene->files of the file (or override) that wrote it */
    hy__value v;
    hy_scene_loc loc;
    size_t ref; /* 1 + index in scene->refs of the [param NAME] the value reads ($NAME), 0 for none */
    int refcol; /* column of the '$' (0 in an override) */
} hy__slot;

/* One [section] or [section NAME] of the scene (merged over all files). */
typedef struct hy__section {
    int spec;
    char *name;
    hy_scene_loc loc;
    hy__slot *slots; /* one per key of the spec */
} hy__section;

/* A slot as it was before an override made after hy_scene_mark. */
typedef struct hy__undo {
    size_t sec; /* index in secs */
    size_t key;
    hy__slot old;
} hy__undo;

/* The sections of one kind in order of first appearance (indices in secs). */
typedef struct hy__kind_list {
    size_t *idx;
    size_t n, cap;
} hy__kind_list;

struct hy_scene {
    char **files; /* display names of every file read and every override, in order */
    size_t nfiles, capfiles;
    hy__section *secs;
    size_t nsecs, capsecs;
    size_t *table;        /* open addressing over (kind, name): secs index + 1, 0 empty */
    size_t captable;      /* a power of two, at least twice nsecs                    */
    hy__kind_list *kinds; /* one per schema section kind                             */
    char *root;           /* directory of the top scene file (realpath), or NULL     */
    char **incdirs;       /* --include-dir roots (realpath), owned                   */
    size_t nincdirs;
    size_t inc_files;     /* included files read so far (repeats counted)            */
    size_t inc_bytes;     /* bytes read so far, the top file and every include       */
    hy__value *defaults;  /* flattened: defoff[sec] + key */
    size_t *defoff;
    uint64_t hash;
    /* hy_scene_mark / hy_scene_restore: the state at the mark and the slots
     * overridden since (oldest first) */
    int marked;
    size_t mark_files, mark_secs;
    uint64_t mark_hash;
    hy__undo *undo;
    size_t nundo, capundo;
    char **refs; /* the parameter names that values reference ($NAME), owned, never removed */
    size_t nrefs, caprefs;
    /* hy__param_propagate, set by the parser (hy_scene_parse.c): hy_scene_set
     * calls it after a [param NAME] value override, so hy_scene.c calls
     * nothing of hy_scene_param.c (which reads the scene through hy_scene.c) */
    int (*propagate)(hy_scene *s, const char *name, double x, const char *a, int record, hy_error *err);
};

/* Writes the value of key spec parsed from text[0..len) (the text after '=',
 * possibly followed by a comment) into *out.  col0 is the column of text[0];
 * dir (may be NULL) resolves relative PATH values; where names the section in
 * messages ("[model]").  On error returns nonzero, sets *errcol and writes a
 * message without location into msg. */
int hy__value_parse(const hy_scene_key_spec *spec, const char *where, const char *dir,
                    const char *text, size_t len, int col0, hy__value *out, int *errcol,
                    char *msg, size_t msgsz);

/* Writes the value as scene text that parses back to the same value. */
void hy__value_write(const hy_scene_key_spec *k, const hy__value *v, FILE *f);

/* Frees what the value owns and zeroes it. */
void hy__value_clear(hy__value *v);

/* True if text at p starts a comment ('#' not opening a #rrggbb colour). */
int hy__is_comment(const char *p, const char *end);

/* How many bytes of a scene's value a message quotes (hy_file_shown cuts
 * there and escapes what is not printable). */
#define HY_SCENE_SHOWN_MAX 40

/* Writes ch as it should appear in a message: itself if printable, else \xNN. */
const char *hy__char_text(int ch, char buf[8]);

/* Optimal-string-alignment edit distance (typos, transpositions). */
size_t hy__edit_distance(const char *a, const char *b);

/* The candidate closest to word if close enough to be a likely typo, else NULL. */
const char *hy__suggest(const char *word, const char *const *cands, size_t n);

/* Appends a new file/override display name to the scene; returns its index or -1. */
int hy__scene_add_file(hy_scene *s, const char *name);

/* Finds the instance of section spec sec labelled name (NULL for unnamed). */
hy__section *hy__scene_find(const hy_scene *s, int sec, const char *name);

/* Finds or creates that instance; NULL on allocation failure. */
hy__section *hy__scene_touch(hy_scene *s, int sec, const char *name, hy_scene_loc loc);

/* Folds bytes into the FNV-1a hash. */
void hy__scene_hash_bytes(hy_scene *s, const void *p, size_t n);

/* Sets the scene's read roots: realpath of top_dir (the top file's directory)
 * and of each include dir of pol (an include dir that is not a directory is
 * an error); counts the top file's len bytes. */
int hy__policy_roots(hy_scene *s, const char *top_dir, const hy_scene_policy *pol,
                     size_t len, hy_error *err);

/* Finds (relative to dir, then in each include dir), checks and reads the
 * include rel: path as opened, its text (buf, len) and its real path (canon),
 * all malloc'ed.  On error returns a status with the reason in why. */
int hy__policy_include(hy_scene *s, const char *dir, const char *rel, char **path, char **buf,
                       size_t *len, char **canon, char *why, size_t whysz);

/* Writes "file:line:col: <fmt ...>" (just "file: ..." for line 0) into err
 * with code; the arguments may include err->msg. */
void hy__error_vat(hy_scene_loc loc, hy_error *err, int code, const char *fmt, va_list ap);

/* A parameter reference (hy_scene_param.c, docs/SCENES.md "Named parameters").
 * If text[0..len) (after blanks) is `$NAME` (and then only a comment), stores
 * 1 + the index of NAME in s->refs into *ref and returns HY_OK; returns -1
 * when the text is no reference; on a malformed one returns HY_EINVAL with
 * *errcol and msg (col0 is the column of text[0]), HY_ENOMEM likewise. */
int hy__ref_parse(hy_scene *s, const hy_scene_key_spec *spec, const char *where, const char *text,
                  size_t len, int col0, size_t *ref, int *errcol, char *msg, size_t msgsz);

/* Gives every slot that references a parameter the parameter's value, checked
 * against the slot's own key (its kind and range).  An unknown name, a [param]
 * without a value or a value the key refuses is an error at the reference. */
int hy__scene_resolve(hy_scene *s, hy_error *err);

/* After an override a (already applied) of [param name] value: gives the
 * new value x to every slot that references name, first checking them all
 * (on error nothing changed; the caller undoes the override).  With
 * record, each slot's old state goes to the undo log (hy_scene_restore). */
int hy__param_propagate(hy_scene *s, const char *name, double x, const char *a, int record,
                        hy_error *err);

/* Keeps a slot's old state for hy_scene_restore (hy_scene.c); -1 on
 * allocation failure. */
int hy__undo_push(hy_scene *s, size_t sec, size_t key, const hy__slot *slot);

/* A fresh scene with defaults prepared; NULL and err on failure. */
hy_scene *hy__scene_new(hy_error *err);

#endif
