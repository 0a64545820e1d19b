/* SPDX-License-Identifier: MIT */
/* sweep_merge.c: `hystviz sweep --merge DIR`: row i of the study comes from
 * shard i mod N, in order, so the joined table is the unsharded run's
 * sweep.csv byte for byte; nothing is written unless every shard is there,
 * from the same study, complete. */
#include "sweep_merge.h"

#include <dirent.h>
#include <errno.h>
#include <inttypes.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "hy_grid.h"
#include "hy_out.h"
#include "sweep_plot.h"

void hy_sweep_shard_path(const char *dir, long k, long n, const char *ext, char *buf, size_t size)
{
    snprintf(buf, size, "%s/sweep.shard-%ld-of-%ld.%s", dir, k, n, ext);
}

/* Reads an .npy v1.0 header from f: its descr text into descr (size bytes)
 * and its row count; -1 if f holds none. */
static int npy_read_header(FILE *f, char *descr, size_t size, size_t *nrows)
{
    unsigned char pre[10];
    static char dict[65536];
    if (fread(pre, 1, 10, f) != 10 || memcmp(pre, "\x93NUMPY\x01\x00", 8))
        return -1;
    size_t hl = pre[8] | (size_t)pre[9] << 8;
    if (fread(dict, 1, hl, f) != hl)
        return -1;
    dict[hl] = 0;
    const char *d = strstr(dict, "{'descr': "), *e = strstr(dict, ", 'fortran_order': False, 'shape': (");
    if (d != dict || !e || (size_t)(e - d - 10) >= size ||
        sscanf(e + 36, "%zu,)", nrows) != 1)
        return -1;
    memcpy(descr, d + 10, (size_t)(e - d - 10));
    descr[e - d - 10] = 0;
    return 0;
}

void hy_sweep_shard_head(FILE *f, long k, long n, size_t npoints, uint64_t hash, const char *rerun)
{
    fprintf(f, "# hystviz sweep shard %ld/%ld points %zu study %016" PRIx64 "%s\n", k, n, npoints, hash,
            rerun ? rerun : "");
}

/* A growing text; err set once a realloc failed. */
typedef struct text {
    char *b;
    size_t len, cap;
    int err;
} text;

static void text_add(text *t, const char *s, size_t n)
{
    if (!t->err && t->len + n + 1 > t->cap) {
        size_t cap = 2 * (t->len + n + 1);
        char *nb = realloc(t->b, cap);
        if (nb) {
            t->b = nb;
            t->cap = cap;
        } else
            t->err = 1;
    }
    if (t->err)
        return;
    memcpy(t->b + t->len, s, n);
    t->len += n;
    t->b[t->len] = 0;
}

/* Appends s quoted for sh: as is when it holds only safe characters, else
 * in single quotes ('\'' for a quote). */
static void text_quote(text *t, const char *s)
{
    if (*s && strspn(s, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_@%+=:,./-") == strlen(s)) {
        text_add(t, s, strlen(s));
        return;
    }
    text_add(t, "'", 1);
    for (const char *c = s; *c; c++)
        text_add(t, *c == '\'' ? "'\\''" : c, *c == '\'' ? 4 : 1);
    text_add(t, "'", 1);
}

char *hy_sweep_shard_rerun(int argc, char **argv)
{
    char cwd[4096];
    if (!getcwd(cwd, sizeof cwd) || strpbrk(cwd, "\t\n"))
        return NULL;
    text t = {NULL, 0, 0, 0};
    text_add(&t, "\t", 1);
    text_quote(&t, cwd);
    text_add(&t, "\t", 1);
    for (int i = 0; i < argc; i++) {
        if (strpbrk(argv[i], "\t\n"))
            t.err = 1;
        else if (i && i + 1 < argc &&
                 (!strcmp(argv[i], "-j") || !strcmp(argv[i], "--jobs") || !strcmp(argv[i], "--shard")))
            i++; /* the re-run gives its own */
        else if (i && (!strncmp(argv[i], "--jobs=", 7) || !strncmp(argv[i], "--shard=", 8)))
            continue; /* the same, as one argument */
        else {
            if (i)
                text_add(&t, " ", 1);
            text_quote(&t, argv[i]);
        }
    }
    if (t.err) {
        free(t.b);
        return NULL;
    }
    return t.b;
}

/* The re-run text (see sweep_merge.h) of DIR's shard k/n into *cwd and
 * *args (quoted for sh; pointers into buf); 0 if it has none. */
static int read_rerun(const char *dir, const char *ext, long k, long n, char *buf, size_t size, char **cwd,
                      char **args)
{
    char path[4400];
    hy_sweep_shard_path(dir, k, n, ext, path, sizeof path);
    FILE *f = fopen(path, "r");
    if (!f)
        return 0;
    int ok = fgets(buf, (int)size, f) != NULL;
    fclose(f);
    char *nl = ok ? strchr(buf, '\n') : NULL;
    *cwd = ok ? strchr(buf, '\t') : NULL;
    *args = *cwd ? strchr(*cwd + 1, '\t') : NULL;
    if (!nl || !*args)
        return 0;
    *nl = 0;
    *(*cwd)++ = 0;
    *(*args)++ = 0;
    return 1;
}

/* Prints the commands that re-run the missing shards: each by hand (or
 * from GNU parallel), all as one Slurm array of tools/cluster/shard.sbatch. */
static void print_reruns(long n, const unsigned char *present, long missing, const char *qcwd, const char *args)
{
    char here[4096];
    text t = {NULL, 0, 0, 0};
    if (getcwd(here, sizeof here))
        text_quote(&t, here);
    int same_dir = !t.err && t.b && !strcmp(t.b, qcwd);
    free(t.b);
    const char *hv = getenv("HYSTVIZ"), *cl = getenv("HYSTVIZ_CLUSTER");
    text prog = {NULL, 0, 0, 0};
    text_quote(&prog, hv && *hv ? hv : "hystviz");
    fprintf(stderr, "  re-run %s by hand (or in tools/cluster/parallel.sh's place), then merge again:\n",
            missing > 1 ? "each" : "it");
    long shown = 0;
    for (long k = 0; k < n && shown < 20; k++)
        if (!present[k]) {
            fprintf(stderr, "    %s%s%s%s %s --shard %ld/%ld\n", same_dir ? "" : "cd ", same_dir ? "" : qcwd,
                    same_dir ? "" : " && ", prog.err ? "hystviz" : prog.b, args, k, n);
            shown++;
        }
    if (missing > shown)
        fprintf(stderr, "    ... (%ld more: the same with their --shard K/%ld)\n", missing - shown, n);
    text arr = {NULL, 0, 0, 0}; /* the missing K as Slurm's --array list: 1,4-6 */
    for (long k = 0; k < n; k++)
        if (!present[k] && (k == 0 || present[k - 1])) {
            long e = k;
            while (e + 1 < n && !present[e + 1])
                e++;
            char r[64];
            int len = e > k ? snprintf(r, sizeof r, "%s%ld-%ld", arr.len ? "," : "", k, e)
                            : snprintf(r, sizeof r, "%s%ld", arr.len ? "," : "", k);
            text_add(&arr, r, (size_t)len);
        }
    text sh = {NULL, 0, 0, 0};
    if (cl && *cl) {
        text_quote(&sh, cl);
        text_add(&sh, "/shard.sbatch", 13);
    } else
        text_add(&sh, "tools/cluster/shard.sbatch", 26);
    if (!arr.err && !sh.err) {
        fprintf(stderr, "  or as Slurm array tasks, then merge again:\n    ");
        if (hv && *hv && !prog.err)
            fprintf(stderr, "HYSTVIZ=%s ", prog.b);
        fprintf(stderr, "sbatch%s%s --array=%s %s %ld %s\n", same_dir ? "" : " --chdir=", same_dir ? "" : qcwd,
                arr.b, sh.b, n, args);
    }
    free(arr.b);
    free(sh.b);
    free(prog.b);
}

/* When a present shard's manifest tells how it was run, prints the commands
 * that re-run the missing ones, else the general advice. */
static void rerun_help(const char *dir, const char *ext, long n, const unsigned char *present, long missing)
{
    long any = 0;
    while (any < n && !present[any])
        any++;
    static char line[65536];
    char *cwd, *args;
    if (any < n && read_rerun(dir, ext, any, n, line, sizeof line, &cwd, &args))
        print_reruns(n, present, missing, cwd, args);
    else
        fprintf(stderr, "  (run the same `hystviz sweep ... --shard K/%ld` for each, then merge again)\n", n);
}

/* The N of DIR's shard manifests, checked complete; 2 with a message when
 * there are none, several splits or missing shards. */
static int find_shards(const char *dir, const char *ext, long *nshards)
{
    unsigned char *present = NULL;
    hy_error err = {0};
    char suffix[8];
    snprintf(suffix, sizeof suffix, ".%s", ext);
    if (hy_shard_find(dir, "sweep.shard-", suffix, nshards, &present, &err)) {
        fprintf(stderr, "hystviz sweep --merge: %s\n", err.msg);
        return 2;
    }
    char list[512];
    long missing = hy_shard_missing(*nshards, present, list, sizeof list);
    if (missing) {
        fprintf(stderr, "hystviz sweep --merge: %s: %ld of %ld shards missing:%s\n", dir, missing, *nshards, list);
        rerun_help(dir, ext, *nshards, present, missing);
    }
    free(present);
    return missing ? 2 : 0;
}

typedef struct shard_in {
    FILE *f;
    char path[4400];
} shard_in;

/* The table being merged: CSV, or .npy with its descr and record size. */
typedef struct merge_fmt {
    const char *ext;      /* "csv" or "npy" */
    int npy;
    size_t rec;           /* .npy: bytes a row */
} merge_fmt;

/* The .npy header of shard k/n of a study of p points: its descr into *line
 * (the same as shard 0's, *line then being first's copy, is checked by the
 * caller) and the record size from the file's size; nonzero if damaged. */
static int npy_shard_header(shard_in *in, long k, long n, size_t p, char **line, size_t *cap, merge_fmt *fm)
{
    if (*cap < 60000) {
        char *nl = realloc(*line, 60000);
        if (!nl)
            return -1;
        *line = nl;
        *cap = 60000;
    }
    size_t rows, mine = hy_shard_count(p, k, n);
    struct stat st;
    if (npy_read_header(in[k].f, *line, *cap, &rows) || rows != mine || fstat(fileno(in[k].f), &st))
        return -1;
    long here = ftell(in[k].f);
    size_t data = (size_t)st.st_size - (size_t)here, rec = mine ? data / mine : fm->rec;
    if (here < 0 || (mine && (data % mine || rec < 9 || (fm->rec && rec != fm->rec))))
        return -1;
    if (mine)
        fm->rec = rec;
    return 0;
}

/* Opens every shard and checks its first line and header against shard 0's;
 * *npoints gets the study's point count.  2 with a message on a mismatch. */
static int open_shards(const char *dir, long n, shard_in *in, char **header, size_t *npoints, merge_fmt *fm)
{
    char *line = NULL, *first = NULL;
    size_t cap = 0;
    uint64_t hash0 = 0;
    int rc = 0;
    for (long k = 0; k < n && !rc; k++) {
        hy_sweep_shard_path(dir, k, n, fm->ext, in[k].path, sizeof in[k].path);
        if (!(in[k].f = fopen(in[k].path, "r"))) {
            fprintf(stderr, "hystviz sweep --merge: cannot open '%s': %s%s\n", in[k].path, strerror(errno),
                    errno == EMFILE ? " (raise the limit of open files: ulimit -n)" : "");
            rc = errno == EMFILE ? 1 : 2;
            break;
        }
        long kk, nn;
        size_t p;
        uint64_t h;
        if (getline(&line, &cap, in[k].f) < 0 ||
            sscanf(line, "# hystviz sweep shard %ld/%ld points %zu study %" SCNx64, &kk, &nn, &p, &h) != 4 || kk != k ||
            nn != n) {
            fprintf(stderr, "hystviz sweep --merge: '%s' is not a shard manifest of hystviz sweep\n", in[k].path);
            rc = 2;
        } else if (k && (p != *npoints || h != hash0)) {
            fprintf(stderr,
                    "hystviz sweep --merge: '%s' belongs to another study than shard 0/%ld (other scene, grid, "
                    "options or version): re-run shard %ld/%ld with the same command\n",
                    in[k].path, n, k, n);
            rc = 2;
        } else if ((fm->npy ? npy_shard_header(in, k, n, p, &line, &cap, fm) : getline(&line, &cap, in[k].f) < 0) ||
                   (k && strcmp(line, first))) {
            fprintf(stderr, "hystviz sweep --merge: '%s': its table header is missing or differs from shard 0/%ld\n",
                    in[k].path, n);
            rc = 2;
        } else if (!k) {
            *npoints = p;
            hash0 = h;
            if (!(first = strdup(line)))
                rc = 2;
        }
    }
    free(line);
    *header = first;
    return rc;
}

/* Copies row i from shard i mod n into out; counts statuses. */
static int join_rows(const char *dir, long n, shard_in *in, size_t npoints, FILE *out, size_t count[3])
{
    char *line = NULL;
    size_t cap = 0;
    int rc = 0;
    for (size_t i = 0; i < npoints && !rc; i++) {
        shard_in *s = &in[i % (size_t)n];
        char status[16] = "";
        size_t idx = (size_t)-1;
        ssize_t len = getline(&line, &cap, s->f);
        if (len < 1 || line[len - 1] != '\n' || sscanf(line, "%zu,%15[a-z],", &idx, status) != 2 || idx != i) {
            fprintf(stderr, "hystviz sweep --merge: '%s' is incomplete or damaged at point %zu: re-run that shard\n",
                    s->path, i);
            rc = 2;
            break;
        }
        count[!strcmp(status, "ok") ? 0 : !strcmp(status, "invalid") ? 1 : 2]++;
        if (fputs(line, out) < 0)
            rc = 1;
    }
    for (long k = 0; k < n && !rc; k++)
        if (getline(&line, &cap, in[k].f) >= 0) {
            fprintf(stderr, "hystviz sweep --merge: '%s' has more rows than its share of %zu points\n", in[k].path,
                    npoints);
            rc = 2;
        }
    (void)dir;
    free(line);
    return rc;
}

/* .npy: copies record i from shard i mod n into out, checking its index;
 * counts statuses (the byte after the index). */
static int join_records(long n, shard_in *in, size_t npoints, size_t rec, FILE *out, size_t count[3])
{
    unsigned char *b = malloc(rec ? rec : 1);
    int rc = b ? 0 : 1;
    for (size_t i = 0; i < npoints && !rc; i++) {
        shard_in *s = &in[i % (size_t)n];
        uint64_t idx = 0;
        if (fread(b, 1, rec, s->f) == rec)
            for (int k = 7; k >= 0; k--)
                idx = idx << 8 | b[k];
        if (idx != i || b[8] > 2) {
            fprintf(stderr, "hystviz sweep --merge: '%s' is incomplete or damaged at point %zu: re-run that shard\n",
                    s->path, i);
            rc = 2;
            break;
        }
        count[b[8]]++;
        if (fwrite(b, 1, rec, out) != rec)
            rc = 1;
    }
    for (long k = 0; k < n && !rc; k++)
        if (fgetc(in[k].f) != EOF) {
            fprintf(stderr, "hystviz sweep --merge: '%s' has more rows than its share of %zu points\n", in[k].path,
                    npoints);
            rc = 2;
        }
    free(b);
    return rc;
}

/* Whether DIR holds a sweep.npy whose rows are whole and numbered; counts
 * them and their statuses (may be NULL). */
static int merged_before_npy(const char *dir, size_t *npoints, size_t count[3])
{
    char path[4400], descr[8];
    snprintf(path, sizeof path, "%s/sweep.npy", dir);
    FILE *f = fopen(path, "r");
    if (!f)
        return 0;
    static char d[65536];
    size_t rows = 0, c[3] = {0, 0, 0};
    struct stat st;
    int ok = !npy_read_header(f, d, sizeof d, &rows) && rows > 0 && !fstat(fileno(f), &st);
    long here = ok ? ftell(f) : -1;
    size_t data = here >= 0 ? (size_t)st.st_size - (size_t)here : 0, rec = rows ? data / rows : 0;
    ok = ok && here >= 0 && data % rows == 0 && rec >= 9;
    unsigned char head[9];
    for (size_t i = 0; ok && i < rows; i++) {
        ok = fseek(f, here + (long)(i * rec), SEEK_SET) == 0 && fread(head, 1, 9, f) == 9 && head[0] == (i & 0xff) &&
             head[8] <= 2;
        if (ok)
            c[head[8]]++;
    }
    (void)descr;
    fclose(f);
    if (ok && npoints)
        *npoints = rows;
    for (int k = 0; ok && count && k < 3; k++)
        count[k] = c[k];
    return ok;
}

/* Whether DIR holds the sweep.csv a merge (or an unsharded run) wrote, its
 * rows well formed; counts them and their statuses (may be NULL). */
static int merged_before(const char *dir, size_t *npoints, size_t count[3])
{
    char path[4400];
    snprintf(path, sizeof path, "%s/sweep.csv", dir);
    FILE *f = fopen(path, "r");
    if (!f)
        return 0;
    char *line = NULL;
    size_t cap = 0, rows = 0, c[3] = {0, 0, 0};
    ssize_t len = getline(&line, &cap, f); /* the header */
    int ok = len > 0 && line[len - 1] == '\n';
    while (ok && (len = getline(&line, &cap, f)) > 0) {
        size_t idx;
        char status[16] = "";
        ok = line[len - 1] == '\n' && sscanf(line, "%zu,%15[a-z],", &idx, status) == 2 && idx == rows;
        c[!strcmp(status, "ok") ? 0 : !strcmp(status, "invalid") ? 1 : 2]++;
        rows++;
    }
    ok = ok && !ferror(f) && rows > 0;
    free(line);
    fclose(f);
    if (ok && npoints)
        *npoints = rows;
    for (int k = 0; ok && count && k < 3; k++)
        count[k] = c[k];
    return ok;
}

/* Whether DIR holds any sweep shard manifest of ext (sweep.shard-*.csv, .npy). */
static int has_shards(const char *dir, const char *ext)
{
    DIR *d = opendir(dir);
    int found = 0;
    for (struct dirent *de; d && !found && (de = readdir(d));) {
        size_t n = strlen(de->d_name);
        found = !strncmp(de->d_name, "sweep.shard-", 12) && n > 16 && de->d_name[n - 4] == '.' &&
                !strcmp(de->d_name + n - 3, ext);
    }
    if (d)
        closedir(d);
    return found;
}

/* A merge run again after one that joined (and removed) the manifests: the
 * same sweep.csv, summary figure and exit status (issue 20 item 11: it
 * failed with "no shard manifests"). */
static int merge_again(const char *dir, const char *plot, int quiet, int npy)
{
    size_t npoints = 0, count[3] = {0, 0, 0};
    if (npy)
        merged_before_npy(dir, &npoints, count);
    else
        merged_before(dir, &npoints, count);
    hy_error perr = {0};
    if (plot && hy_sweep_plot(dir, plot, &perr)) {
        fprintf(stderr, "hystviz sweep --merge: %s\n", perr.msg);
        return perr.code == HY_EINVAL ? 2 : 1;
    }
    if (!quiet)
        fprintf(stderr, "sweep --merge: already merged, %zu points: %zu ok, %zu invalid, %zu failed; %s/sweep.%s\n",
                npoints, count[0], count[1], count[2], dir, npy ? "npy" : "csv");
    return count[1] ? 2 : count[2] ? 1 : 0;
}

int hy_sweep_merge(const char *dir, const char *plot, int quiet)
{
    long n = 0;
    merge_fmt fm = {"csv", 0, 0};
    if (!has_shards(dir, "csv") && has_shards(dir, "npy"))
        fm = (merge_fmt){"npy", 1, 0};
    else if (!has_shards(dir, "csv") && merged_before(dir, NULL, NULL))
        return merge_again(dir, plot, quiet, 0);
    else if (!has_shards(dir, "csv") && merged_before_npy(dir, NULL, NULL))
        return merge_again(dir, plot, quiet, 1);
    int rc = find_shards(dir, fm.ext, &n);
    if (rc)
        return rc;
    struct rlimit rl; /* every shard is open at once: allow that many files */
    if (!getrlimit(RLIMIT_NOFILE, &rl) && rl.rlim_cur < rl.rlim_max && rl.rlim_cur < (rlim_t)n + 16) {
        rl.rlim_cur = rl.rlim_max;
        setrlimit(RLIMIT_NOFILE, &rl);
    }
    shard_in *in = calloc((size_t)n, sizeof *in);
    if (!in) {
        fprintf(stderr, "hystviz sweep --merge: out of memory\n");
        return 1;
    }
    char *header = NULL;
    size_t npoints = 0, count[3] = {0, 0, 0};
    rc = open_shards(dir, n, in, &header, &npoints, &fm);
    char path[4400];
    snprintf(path, sizeof path, "%s/sweep.%s", dir, fm.ext);
    if (!rc && fm.npy && plot) {
        fprintf(stderr, "hystviz sweep --merge: --plot reads a CSV table: this study's table is .npy\n");
        rc = 2;
    }
    hy_out o;
    hy_error err = {0};
    int opened = 0;
    if (!rc && hy_out_open(&o, path, 0, &err)) {
        fprintf(stderr, "hystviz sweep --merge: %s\n", err.msg);
        rc = 1;
    } else if (!rc)
        opened = 1;
    FILE *out = opened ? hy_out_file(&o) : NULL;
    if (!rc && fm.npy) {
        static char head[65536 + 64];
        size_t hl = hy_npy_header(header, npoints, head, sizeof head);
        rc = !hl || fwrite(head, 1, hl, out) != hl;
        if (!rc)
            rc = join_records(n, in, npoints, fm.rec, out, count);
    } else if (!rc && fputs(header, out) < 0)
        rc = 1;
    else if (!rc)
        rc = join_rows(dir, n, in, npoints, out, count);
    if (opened && rc)
        hy_out_abort(&o);
    else if (opened && hy_out_commit(&o, &err)) {
        fprintf(stderr, "hystviz sweep --merge: %s\n", err.msg);
        rc = 1;
    }
    for (long k = 0; k < n; k++)
        if (in[k].f)
            fclose(in[k].f);
    if (!rc)
        for (long k = 0; k < n; k++)
            remove(in[k].path);
    free(in);
    free(header);
    if (rc)
        return rc;
    hy_error perr = {0};
    if (plot && hy_sweep_plot(dir, plot, &perr)) {
        fprintf(stderr, "hystviz sweep --merge: %s\n", perr.msg);
        return perr.code == HY_EINVAL ? 2 : 1;
    }
    if (!quiet)
        fprintf(stderr, "sweep --merge: %ld shards, %zu points: %zu ok, %zu invalid, %zu failed; %s\n", n, npoints,
                count[0], count[1], count[2], path);
    return count[1] ? 2 : count[2] ? 1 : 0;
}
