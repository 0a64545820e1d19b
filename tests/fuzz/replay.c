/* SPDX-License-Identifier: MIT */
/* replay.c: the fuzz regression test of the normal suite.  Every file given (or every
 * file in a directory given) runs through the fuzz harness in a child process, and,
 * with --hystviz PATH, through `hystviz data` as a second child, each with a time
 * limit.  A file passes when the harness child exits 0 and `hystviz data` exits 0, 1
 * or 2, both within the limit and with no sanitizer report or broken invariant on
 * standard error.
 *
 *     fuzz_replay [-v] [--hystviz PATH] [--timeout SECONDS] FILE|DIR...
 *     fuzz_replay --sandbox-test
 *
 * `hystviz data` reads the file as fuzz.scene in a temporary directory holding the
 * harness's fixed files, so includes and `[input] file` find what they find under
 * the fuzzer.  In a directory, the scenes are the files named *.scene or without
 * a dot (libFuzzer's names); the other files (not *.md) are data: copied into
 * that directory next to fuzz.scene for every scene of the directory.  --sandbox-test checks that the harness's sandbox refuses files
 * outside its directory and lets the fixed files through. */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "fuzz_harness.h"
#include "../tmpdir.h"

static unsigned timeout_s = 10;
static int verbose;
static const char *hystviz;
static int stage_count[5]; /* skipped, parse failed, parsed, loaded, computed */
/* The data files of the directory being replayed (e.g. an [input] file of a
 * reproducer): copied next to fuzz.scene in each child's harness directory. */
static char **companions;
static size_t ncompanions;

static int read_file(const char *path, char **buf, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return -1;
    size_t cap = 4096, n = 0;
    char *b = malloc(cap);
    size_t got;
    while (b && (got = fread(b + n, 1, cap - n, f)) > 0) {
        n += got;
        if (n == cap) {
            char *nb = realloc(b, cap *= 2);
            if (!nb) {
                free(b);
                b = NULL;
            }
            b = nb;
        }
    }
    int bad = !b || ferror(f);
    fclose(f);
    if (bad) {
        free(b);
        return -1;
    }
    *buf = b;
    *len = n;
    return 0;
}

/* Copies the companions into the harness directory (created here). */
static int copy_companions(void)
{
    if (hy_fuzz_init())
        return -1;
    for (size_t i = 0; i < ncompanions; i++) {
        char *buf, dst[600];
        size_t len;
        const char *base = strrchr(companions[i], '/');
        snprintf(dst, sizeof dst, "%s/%s", hy_fuzz_dir(), base ? base + 1 : companions[i]);
        if (read_file(companions[i], &buf, &len))
            return -1;
        FILE *f = fopen(dst, "wb");
        int bad = !f || (len && fwrite(buf, 1, len, f) != len);
        if (f)
            bad |= fclose(f) != 0;
        free(buf);
        if (bad)
            return -1;
    }
    return 0;
}

/* In the harness child: the file through hy_fuzz_one; the stage goes to fd. */
static int child_harness(const char *path, int stage_fd)
{
    char *buf;
    size_t len;
    if (copy_companions() || read_file(path, &buf, &len)) {
        fprintf(stderr, "%s: cannot read: %s\n", path, strerror(errno));
        return 3;
    }
    alarm(timeout_s);
    hy_fuzz_one((const uint8_t *)buf, len);
    alarm(0);
    free(buf);
    if (verbose)
        printf("%s: stage %d%s%s\n", path, hy_fuzz_stage(), hy_fuzz_message()[0] ? ": " : "", hy_fuzz_message());
    char st = (char)('1' + hy_fuzz_stage());
    if (write(stage_fd, &st, 1) != 1)
        return 3;
    return 0;
}

/* In the `hystviz data` child: the file as the scene of a fresh harness
 * directory; returns what the checks need: 0 for exit status 0-2, else 1. */
static int child_hystviz(const char *path)
{
    char *buf;
    size_t len;
    if (copy_companions() || read_file(path, &buf, &len)) {
        fprintf(stderr, "%s: cannot read or copy: %s\n", path, strerror(errno));
        return 3;
    }
    char scene[600];
    snprintf(scene, sizeof scene, "%s/fuzz.scene", hy_fuzz_dir());
    FILE *f = fopen(scene, "wb");
    int bad = !f || (len && fwrite(buf, 1, len, f) != len);
    if (f)
        bad |= fclose(f) != 0;
    free(buf);
    if (bad) {
        fprintf(stderr, "%s: cannot write %s\n", path, scene);
        return 3;
    }
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        int null = open("/dev/null", O_WRONLY);
        if (null >= 0)
            dup2(null, 1);
        alarm(timeout_s); /* kept across exec */
        execl(hystviz, hystviz, "data", scene, (char *)NULL);
        fprintf(stderr, "cannot run %s: %s\n", hystviz, strerror(errno));
        _exit(127);
    }
    int st;
    if (pid < 0 || waitpid(pid, &st, 0) != pid)
        return 3;
    if (WIFSIGNALED(st)) {
        fprintf(stderr, "hystviz data: killed by signal %d%s\n", WTERMSIG(st),
                WTERMSIG(st) == SIGALRM ? " (time limit)" : "");
        return 1;
    }
    if (WEXITSTATUS(st) > 2) {
        fprintf(stderr, "hystviz data: exit status %d (0, 1 or 2 expected)\n", WEXITSTATUS(st));
        return 1;
    }
    return 0;
}

static int sanitizer_report(const char *text)
{
    static const char *const marks[] = {"runtime error:", "Sanitizer", "hy_fuzz: invariant", NULL};
    for (size_t i = 0; marks[i]; i++)
        if (strstr(text, marks[i]))
            return 1;
    return 0;
}

/* Runs one check of path in a child whose standard error is collected. */
static int run_child(const char *path, int which)
{
    int err_pipe[2], stage_pipe[2];
    if (pipe(err_pipe) || pipe(stage_pipe)) {
        perror("pipe");
        return 1;
    }
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0) {
        perror("fork");
        return 1;
    }
    if (pid == 0) {
        close(err_pipe[0]);
        close(stage_pipe[0]);
        dup2(err_pipe[1], 2);
        close(err_pipe[1]);
        exit(which ? child_hystviz(path) : child_harness(path, stage_pipe[1]));
    }
    close(err_pipe[1]);
    close(stage_pipe[1]);
    size_t cap = 1 << 16, n = 0;
    char *text = malloc(cap + 1);
    ssize_t got;
    char sink[4096];
    while ((got = read(err_pipe[0], n < cap ? text + n : sink, n < cap ? cap - n : sizeof sink)) > 0 ||
           (got < 0 && errno == EINTR))
        if (got > 0 && n < cap)
            n += (size_t)got;
    close(err_pipe[0]);
    text[n] = '\0';
    char st = 0;
    if (read(stage_pipe[0], &st, 1) == 1 && st >= '0' && st <= '4')
        stage_count[st - '0']++;
    close(stage_pipe[0]);
    int status;
    waitpid(pid, &status, 0);
    const char *what = which ? "hystviz data" : "harness";
    int bad = 0;
    if (WIFSIGNALED(status)) {
        printf("FAIL %s (%s): killed by signal %d%s\n", path, what, WTERMSIG(status),
               WTERMSIG(status) == SIGALRM ? " (time limit)" : "");
        bad = 1;
    } else if (WEXITSTATUS(status) != 0) {
        printf("FAIL %s (%s): exit status %d\n", path, what, WEXITSTATUS(status));
        bad = 1;
    } else if (sanitizer_report(text)) {
        printf("FAIL %s (%s): sanitizer report or broken invariant\n", path, what);
        bad = 1;
    }
    if (bad)
        printf("---- standard error ----\n%s\n------------------------\n", text);
    free(text);
    return bad;
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static int is_scene(const char *path)
{
    const char *base = strrchr(path, '/'), *dot;
    base = base ? base + 1 : path;
    dot = strrchr(base, '.');
    return !dot || !strcmp(dot, ".scene");
}

static int replay(const char *path, int *nfiles)
{
    struct stat st;
    if (stat(path, &st)) {
        printf("FAIL %s: %s\n", path, strerror(errno));
        return 1;
    }
    if (!S_ISDIR(st.st_mode)) {
        (*nfiles)++;
        int bad = run_child(path, 0);
        if (hystviz)
            bad |= run_child(path, 1);
        return bad;
    }
    DIR *d = opendir(path);
    if (!d) {
        printf("FAIL %s: %s\n", path, strerror(errno));
        return 1;
    }
    char **names = NULL;
    size_t n = 0, cap = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        size_t len0 = strlen(e->d_name);
        if (e->d_name[0] == '.' || (len0 > 3 && !strcmp(e->d_name + len0 - 3, ".md")))
            continue; /* hidden files and notes */
        if (n == cap) {
            cap = cap ? 2 * cap : 64;
            char **nn = realloc(names, cap * sizeof *names);
            if (!nn)
                abort();
            names = nn;
        }
        size_t len = strlen(path) + strlen(e->d_name) + 2;
        names[n] = malloc(len);
        if (!names[n])
            abort();
        snprintf(names[n++], len, "%s/%s", path, e->d_name);
    }
    closedir(d);
    qsort(names, n, sizeof *names, cmp_str);
    /* scenes: NAME.scene, or a name without a dot (libFuzzer's); the other
     * files are their data */
    char **saved = companions;
    size_t nsaved = ncompanions;
    companions = malloc((n ? n : 1) * sizeof *companions);
    ncompanions = 0;
    if (!companions)
        abort();
    for (size_t i = 0; i < n; i++)
        if (!is_scene(names[i]))
            companions[ncompanions++] = names[i];
    int bad = 0;
    for (size_t i = 0; i < n; i++)
        if (is_scene(names[i]))
            bad |= replay(names[i], nfiles);
    for (size_t i = 0; i < n; i++)
        free(names[i]);
    free(names);
    free(companions);
    companions = saved;
    ncompanions = nsaved;
    return bad;
}

static int sandbox_test(void)
{
    static const struct {
        const char *text;
        int stage;    /* hy_fuzz_stage() expected       */
        int refusals; /* whether the sandbox must refuse */
    } cases[] = {
        /* the scene file policy (hy_scene_policy.c) refuses these two by name, before any file operation */
        {"include \"/etc/passwd\"\n", 0, 0},
        {"include \"../../../../../../../../etc/passwd\"\n", 0, 0},
        /* a *.scene name: looked up (the sandbox refuses the lookup), then refused as outside */
        {"include \"sub/../../outside.scene\"\n", 0, 1},
        {"include \"part.scene\"\n[input]\nkind = triangle\n[series u]\ndata = input\n", 3, 0},
        {"include \"sub/inner.scene\"\n[series u]\ndata = input\n", 3, 0},
    };
    int bad = 0;
    for (size_t i = 0; i < sizeof cases / sizeof *cases; i++) {
        unsigned long before = hy_fuzz_refused();
        hy_fuzz_one((const uint8_t *)cases[i].text, strlen(cases[i].text));
        int refused = hy_fuzz_refused() > before, stage = hy_fuzz_stage();
        if (refused != cases[i].refusals || stage != cases[i].stage) {
            printf("FAIL sandbox case %zu (%s): stage %d (expected %d), %s\n", i, cases[i].text, stage,
                   cases[i].stage, refused ? "refused" : "nothing refused");
            bad = 1;
        }
    }
    printf("sandbox: %lu file operations outside %s refused\n", hy_fuzz_refused(), hy_fuzz_dir());
    return bad;
}

int main(int argc, char **argv)
{
    int bad = 0, nfiles = 0, nargs = 0;
    /* every sandbox of the children (hy_fuzz_init: $TMPDIR/hyfuzz.XXXXXX,
       left behind by a child the time limit kills) inside one directory that
       this process removes at exit */
    setenv("TMPDIR", test_tmpdir(), 1);
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--sandbox-test"))
            return sandbox_test();
        if (!strcmp(argv[i], "-v"))
            verbose = 1;
        else if (!strcmp(argv[i], "--hystviz") && i + 1 < argc)
            hystviz = argv[++i];
        else if (!strcmp(argv[i], "--timeout") && i + 1 < argc)
            timeout_s = (unsigned)atoi(argv[++i]);
        else {
            nargs++;
            bad |= replay(argv[i], &nfiles);
        }
    }
    if (!nargs) {
        fprintf(stderr, "usage: fuzz_replay [-v] [--hystviz PATH] [--timeout S] FILE|DIR... | --sandbox-test\n");
        return 2;
    }
    printf("%d files: %d parse errors, %d parsed (load refused), %d loaded (load ok, compute failed), "
           "%d computed, %d over the work cap%s\n",
           nfiles, stage_count[1], stage_count[2], stage_count[3], stage_count[4], stage_count[0],
           hystviz ? "; each also through hystviz data" : "");
    if (nfiles == 0) {
        printf("FAIL: no files to replay\n");
        return 1;
    }
    return bad;
}
