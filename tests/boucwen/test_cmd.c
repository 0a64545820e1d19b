/* SPDX-License-Identifier: MIT */
/* test_cmd.c: `hystviz boucwen` driven in-process: Table 2 text, CSV output
 * through a temporary file, the validation signal reproduced through the
 * command, and usage errors refused with status 2. */
#include "bw_test.h"
#include "cmd_boucwen.h"
#include "hy_signal.h"

#include <fcntl.h>
#include <math.h>
#include <stdarg.h>
#include <unistd.h>
#include "../tmpdir.h"

/* Runs hy_cmd_boucwen with the NULL-terminated arguments. */
static int run(const char *a0, ...)
{
    char *argv[32];
    int argc = 0;
    va_list ap;
    va_start(ap, a0);
    for (const char *a = a0; a && argc < 31; a = va_arg(ap, const char *))
        argv[argc++] = (char *)a;
    va_end(ap);
    argv[argc] = NULL;
    fflush(stdout);
    return hy_cmd_boucwen(argc, argv);
}

/* Reads a t,u,y CSV written by the command; returns the row count. */
static size_t read_csv(const char *path, double **u, double **y)
{
    FILE *f = fopen(path, "r");
    char line[256];
    size_t n = 0, cap = 1 << 14;
    *u = malloc(cap * sizeof **u);
    *y = malloc(cap * sizeof **y);
    if (!f || !fgets(line, sizeof line, f) || strcmp(line, "t,u,y\n") != 0) {
        if (f)
            fclose(f);
        return 0;
    }
    double t;
    while (n < cap && fscanf(f, "%lf,%lf,%lf", &t, *u + n, *y + n) == 3)
        n++;
    fclose(f);
    return n;
}

int main(void)
{
    char dir[200], out[256], tab[256];
    CHECK(mkdtemp(test_tmppath(dir, sizeof dir, "cmd_XXXXXX")) != NULL, "mkdtemp");
    snprintf(out, sizeof out, "%s/y.csv", dir);
    snprintf(tab, sizeof tab, "%s/table2.txt", dir);

    /* Table 2, printed to stdout: redirect to a file to read it back */
    fflush(stdout);
    int saved = dup(1), fd = open(tab, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    CHECK(saved >= 0 && fd >= 0, "redirect");
    dup2(fd, 1);
    close(fd);
    int rc = run("boucwen", "table2", NULL);
    fflush(stdout);
    dup2(saved, 1);
    close(saved);
    CHECK(rc == 0, "table2 status %d", rc);
    FILE *f = fopen(tab, "r");
    char text[1024] = "";
    size_t got = f ? fread(text, 1, sizeof text - 1, f) : 0;
    text[got] = '\0';
    if (f)
        fclose(f);
    CHECK(strstr(text, "35.59") && strstr(text, "1.12"), "table2 printed '%s'", text);

    /* --help names every option and every signal the parser accepts */
    fflush(stdout);
    saved = dup(1);
    fd = open(tab, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    dup2(fd, 1);
    close(fd);
    rc = run("boucwen", "--help", NULL);
    fflush(stdout);
    dup2(saved, 1);
    close(saved);
    char help[8192] = "";
    f = fopen(tab, "r");
    got = f ? fread(help, 1, sizeof help - 1, f) : 0;
    help[got] = '\0';
    if (f)
        fclose(f);
    static const char *const documented[] = {
        "--signal", "--input", "--data-dir", "-o FILE", "--periods", "--noise", "--seed", "--fs",
        "--upsample", "--single-stage", "--set-param", "--help", "table2", "data",
        "multisine", "validation", "sweep", "sine", "file", "HY_BOUCWEN_DATA", "validation-sweep",
        "yval_sinesweep", "--band", "--rate", "--amp", "ONE stage"};
    CHECK(rc == 0, "--help status %d", rc);
    for (size_t i = 0; i < sizeof documented / sizeof *documented; i++)
        CHECK(strstr(help, documented[i]) != NULL, "--help does not mention %s", documented[i]);

    /* usage errors: status 2, nothing written */
    CHECK(run("boucwen", "data", "--signal", "nope", "-o", out, NULL) == 2, "bad signal");
    CHECK(run("boucwen", "data", "--signal", "sine", "--set-param", "mu=1", "-o", out, NULL) == 2, "bad param");
    CHECK(run("boucwen", "data", "--signal", "sine", "--set-param", "m=-1", "-o", out, NULL) == 2, "m < 0");
    CHECK(run("boucwen", "data", "--signal", "sine", "--periods", "0", "-o", out, NULL) == 2, "0 periods");
    CHECK(run("boucwen", "frobnicate", NULL) == 2, "bad subcommand");
    /* issue 10 item 1: --fs 1e-20 overflowed the multisine's line index */
    CHECK(run("boucwen", "data", "--signal", "multisine", "--fs", "1e-20", "-o", out, NULL) == 2, "--fs 1e-20");
    CHECK(run("boucwen", "data", "--signal", "multisine", "--fs", "1e308", "-o", out, NULL) == 2, "--fs 1e308");
    CHECK(access(out, F_OK) != 0, "a refused run left %s", out);

    /* a sine run with noise: rows = P periods, noise RMS as asked */
    rc = run("boucwen", "data", "--signal", "sine", "--periods", "2", "--noise", "0", "-o", out, NULL);
    double *u2, *y2;
    size_t n2 = read_csv(out, &u2, &y2);
    CHECK(rc == 0 && n2 == 1500, "sine rows %zu", n2);
    rc = run("boucwen", "data", "--signal", "sine", "--periods", "2", "--noise", "1e-5", "-o", out, NULL);
    double *u3, *y3;
    size_t n3 = read_csv(out, &u3, &y3);
    CHECK(rc == 0 && n3 == 1500, "sine rows %zu", n3);
    if (n2 == 1500 && n3 == 1500) /* %.17g round trip: the noise exactly */
        CHECK(fabs(hy_signal_erms(y2, y3, 1500) - 1e-5) < 1e-12, "noise rms %g", hy_signal_erms(y2, y3, 1500));
    /* a t,u file at 500 Hz: fs from t, one output row per input row; a
     * malformed file is refused (status 2) and leaves no output */
    char in[300];
    snprintf(in, sizeof in, "%s/in.csv", dir);
    FILE *fi = fopen(in, "w");
    for (int i = 0; i < 300; i++)
        fprintf(fi, "%.17g,%.17g\n", i / 500.0, 50 * sin(2 * M_PI * 7 * i / 500.0));
    fclose(fi);
    rc = run("boucwen", "data", "--input", in, "--noise", "0", "-o", out, NULL);
    double *u4, *y4;
    size_t n4 = read_csv(out, &u4, &y4);
    CHECK(rc == 0 && n4 == 300, "file rows %zu (status %d)", n4, rc);
    if (n4 == 300)
        CHECK(fabs(u4[7] - 50 * sin(2 * M_PI * 7 * 7 / 500.0)) < 1e-12 && fabs(y4[150]) > 1e-5,
              "file run: u %g y %g", u4[7], y4[150]);
    free(u4);
    free(y4);
    unlink(out);
    fi = fopen(in, "w");
    fputs("0,1\n0.002,oops\n", fi);
    fclose(fi);
    CHECK(run("boucwen", "data", "--input", in, "-o", out, NULL) == 2, "malformed file accepted");
    CHECK(access(out, F_OK) != 0, "a refused file run left %s", out);
    unlink(in);

    /* the validation signal through the command reproduces yval */
    unlink(tab);
    const char *data = bw_data_dir();
    rc = run("boucwen", "data", "--signal", "validation", "--data-dir", data, "-o", out, NULL);
    CHECK(rc == 0, "validation status %d", rc);
    double *u = NULL, *y = NULL, *yref = NULL, *uref = NULL, fs;
    size_t n = read_csv(out, &u, &y), nr = 0;
    char py[4096], pu[4096];
    snprintf(py, sizeof py, "%s/yval_multisine.txt", data);
    snprintf(pu, sizeof pu, "%s/uval_multisine.txt", data);
    hy_error e;
    CHECK(hy_signal_read(py, &yref, &nr, &fs, &e) == HY_OK, "%s", e.msg);
    CHECK(hy_signal_read(pu, &uref, &nr, &fs, &e) == HY_OK, "%s", e.msg);
    CHECK(n == 8192 && nr == 8192, "rows %zu", n);
    if (n == 8192) {
        double er = hy_signal_erms(y, yref, n);
        printf("hystviz boucwen data --signal validation: e_RMS %.3e m\n", er);
        /* same bound as test_validation: the CSV's %.17g is exact */
        CHECK(er < 5e-15, "e_RMS %g", er);
        CHECK(memcmp(u, uref, n * sizeof *u) == 0, "u column differs from uval");
    }
    unlink(out);
    /* without --data-dir and $HY_BOUCWEN_DATA the command finds the data by itself
     * (installed, or the source tree's tests/data/boucwen): the same u column */
    unsetenv("HY_BOUCWEN_DATA");
    rc = run("boucwen", "data", "--signal", "validation", "-o", out, NULL);
    CHECK(rc == 0, "validation without --data-dir: status %d", rc);
    double *u5 = NULL, *y5 = NULL;
    size_t n5 = read_csv(out, &u5, &y5);
    CHECK(n5 == 8192 && nr == 8192 && memcmp(u5, uref, n5 * sizeof *u5) == 0,
          "validation without --data-dir: %zu rows, u column %s", n5,
          n5 == 8192 && memcmp(u5, uref, n5 * sizeof *u5) == 0 ? "equal" : "differs");
    free(u5);
    free(y5);
    unlink(out);
    unlink(tab);
    rmdir(dir);
    free(u); free(y); free(yref); free(uref); free(u2); free(y2); free(u3); free(y3);
    return hy_test_finish("test_cmd");
}
