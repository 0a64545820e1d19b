/* SPDX-License-Identifier: MIT */
/* test_out.c: the output writer (src/io/hy_out.h) in-process: temporary
 * names and modes, all-or-nothing groups, HY_OUT_HOLD on standard output,
 * the sweep of stale temporaries (a locked one stays), and the state
 * machine (abort after commit, publish before finish).  Runs in its build
 * directory's io_test/ (never in the source tree). */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "hy_out.h"

#include "../render/rcheck.h"

/* Entries of dir other than . and .. */
static int entries(const char *dir)
{
    DIR *d = opendir(dir);
    int n = 0;
    for (struct dirent *e; d && (e = readdir(d));)
        n += strcmp(e->d_name, ".") && strcmp(e->d_name, "..");
    if (d)
        closedir(d);
    return n;
}

/* Whether the file at path holds exactly text (no: it cannot be read). */
static int file_is(const char *path, const char *text)
{
    char *t = hy_test_slurp(path, NULL);
    int same = t && !strcmp(t, text);
    free(t);
    return same;
}

static void test_names_and_mode(void)
{
    hy_out o;
    hy_error err;
    CHECK(!hy_out_open(&o, "d/a.csv", 0, &err), "%s", err.msg);
    const char *t = hy_out_tmp_path(&o), *base = strrchr(t, '/') + 1;
    CHECK(!strncmp(t, "d/.a.csv.hystviz-tmp.", 21) && strlen(base) == strlen(".a.csv.hystviz-tmp.XXXXXX"),
          "temporary name %s", t);
    CHECK(hy_out_is_tmp_name(base) && !hy_out_is_tmp_name("a.csv") && !hy_out_is_tmp_name(".hystviz-tmp."),
          "hy_out_is_tmp_name");
    struct stat st;
    CHECK(stat(t, &st) == 0 && (st.st_mode & 0777) == 0640, "temporary mode %o under umask 027", st.st_mode & 0777);
    CHECK(hy_out_sweep("d") == 0 && access(t, F_OK) == 0, "a live (locked) temporary was swept");
    fputs("hello\n", hy_out_file(&o));
    CHECK(!hy_out_commit(&o, &err), "%s", err.msg);
    CHECK(stat("d/a.csv", &st) == 0 && (st.st_mode & 0777) == 0640 && file_is("d/a.csv", "hello\n"),
          "committed file: mode %o", st.st_mode & 0777);
    CHECK(entries("d") == 1, "temporary left after commit");
    hy_out_abort(&o); /* done: a no-op */
    CHECK(access("d/a.csv", F_OK) == 0, "abort after commit removed the file");
}

static void test_group(void)
{
    hy_out a, b;
    hy_error err;
    CHECK(!hy_out_open(&a, "d/g1.svg", HY_OUT_HOLD, &err) && !hy_out_open(&b, "d/g2.png", HY_OUT_HOLD, &err), "%s",
          err.msg);
    fputs("1", hy_out_file(&a));
    fputs("2", hy_out_file(&b));
    CHECK(!hy_out_finish(&a, &err) && !hy_out_finish(&b, &err), "%s", err.msg);
    CHECK(access("d/g1.svg", F_OK) != 0 && access("d/g2.png", F_OK) != 0, "a finished file is visible before publish");
    hy_out_abort(&a);
    hy_out_abort(&b);
    CHECK(entries("d") == 1, "aborted group left %d entries", entries("d"));
    CHECK(hy_out_publish(&a, &err) == HY_EINVAL, "publish after abort");
    hy_out c;
    CHECK(!hy_out_open(&c, "d/g3", 0, &err) && hy_out_publish(&c, &err) == HY_EINVAL, "publish before finish");
    hy_out_abort(&c);
    CHECK(entries("d") == 1, "publish before finish left a file");
}

/* HY_OUT_HOLD on standard output: nothing reaches it on abort, all on publish. */
static void test_hold_stdout(void)
{
    fflush(stdout);
    int saved = dup(1), fd = open("held.txt", O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    close(fd);
    hy_out o;
    hy_error err;
    int r1 = hy_out_open(&o, "-", HY_OUT_HOLD, &err);
    fputs("dropped\n", hy_out_file(&o));
    hy_out_finish(&o, &err);
    hy_out_abort(&o);
    int r2 = hy_out_open(&o, "-", HY_OUT_HOLD, &err);
    fputs("kept\n", hy_out_file(&o));
    int r3 = hy_out_commit(&o, &err);
    fflush(stdout);
    dup2(saved, 1);
    close(saved);
    char *held = hy_test_slurp("held.txt", NULL);
    CHECK(!r1 && !r2 && !r3 && held && !strcmp(held, "kept\n"), "held stdout got '%s'", held ? held : "(nothing)");
    free(held);
}

static void test_sweep(void)
{
    mkdir("s", 0755);
    static const char *const stale[] = {"s/.x.svg.hystviz-tmp.AbC123", "s/x.png.tmp.Xy9Zq1", "s/.manifest.tmp.q1w2e3"};
    static const char *const keep[] = {"s/.live.svg.hystviz-tmp.LiVe01", "s/notes.tmp.txt", "s/x.svg", "s/x.png.tmp.1"};
    for (size_t i = 0; i < 3; i++)
        fclose(fopen(stale[i], "w"));
    for (size_t i = 0; i < 4; i++)
        fclose(fopen(keep[i], "w"));
    int live = open(keep[0], O_RDONLY);
    CHECK(live >= 0 && !flock(live, LOCK_EX), "lock");
    mkdir("s/.dir.hystviz-tmp.AAAAAA", 0755); /* not a regular file: left alone */
    int n = hy_out_sweep("s");
    CHECK(n == 3, "swept %d, expected the 3 stale temporaries", n);
    for (size_t i = 0; i < 3; i++)
        CHECK(access(stale[i], F_OK) != 0, "%s kept", stale[i]);
    for (size_t i = 0; i < 4; i++)
        CHECK(access(keep[i], F_OK) == 0, "%s removed", keep[i]);
    close(live);
    CHECK(hy_out_sweep("s") == 1 && access(keep[0], F_OK) != 0, "an unlocked temporary stays");
    CHECK(hy_out_sweep("no_such_dir") == 0, "a missing directory");
}

static void test_failures(void)
{
    hy_out o;
    hy_error err;
    CHECK(hy_out_open(&o, "no_such_dir/x.csv", 0, &err) == HY_EIO && strstr(err.msg, "'no_such_dir/x.csv'"), "%s",
          err.msg);
    CHECK(hy_out_open(&o, "d", 0, &err) == HY_EIO && strstr(err.msg, "it is a directory"), "%s", err.msg);
    CHECK(hy_out_open(&o, "", 0, &err) == HY_EINVAL, "an empty name");
    /* the directory goes away between open and publish: an error naming the path, nothing left */
    mkdir("gone", 0755);
    CHECK(!hy_out_open(&o, "gone/x.csv", 0, &err), "%s", err.msg);
    fputs("x", hy_out_file(&o));
    CHECK(!hy_out_finish(&o, &err), "%s", err.msg);
    char tmp[256];
    snprintf(tmp, sizeof tmp, "%s", hy_out_tmp_path(&o));
    unlink(tmp);
    rmdir("gone");
    CHECK(hy_out_publish(&o, &err) == HY_EIO && strstr(err.msg, "gone/x.csv"), "%s", err.msg);
}

/* issue 20 item 1: a name's link is followed only below the name's own
 * directory; HY_OUT_FOLLOW (the user's -o FILE) follows it anywhere. */
static void test_links(void)
{
    hy_out o;
    hy_error err = {0};
    mkdir("tree", 0755);
    mkdir("tree/sub", 0755);
    mkdir("outside", 0755);
    FILE *f = fopen("outside/victim", "w");
    if (f)
        fputs("victim\n", f), fclose(f);
    CHECK(!symlink("../outside/victim", "tree/evil.svg") && !symlink("../../outside", "tree/sub/up"),
          "symlink: %s", strerror(errno));
    CHECK(hy_out_open(&o, "tree/evil.svg", 0, &err) == HY_EINVAL && strstr(err.msg, "refusing to write 'tree/evil.svg'") &&
              strstr(err.msg, "outside 'tree'"), "a link out of the directory: %s", err.msg);
    CHECK(file_is("outside/victim", "victim\n") && entries("outside") == 1 && entries("tree") == 2,
          "the refused open touched a file");
    /* a link through a directory link out of the tree, too */
    CHECK(!symlink("sub/up/victim", "tree/evil2.svg"), "symlink");
    CHECK(hy_out_open(&o, "tree/evil2.svg", HY_OUT_HOLD, &err) == HY_EINVAL, "a link via a directory link out: %s",
          err.msg);
    /* a link that stays below: its file replaced, the link kept */
    CHECK(!symlink("sub/in.svg", "tree/ok.svg"), "symlink");
    f = fopen("tree/sub/in.svg", "w");
    if (f)
        fputs("old\n", f), fclose(f);
    CHECK(!hy_out_open(&o, "tree/ok.svg", 0, &err), "a link below: %s", err.msg);
    fputs("new\n", hy_out_file(&o));
    CHECK(!hy_out_commit(&o, &err), "%s", err.msg);
    struct stat st;
    CHECK(file_is("tree/sub/in.svg", "new\n") && !lstat("tree/ok.svg", &st) && S_ISLNK(st.st_mode),
          "a link below was not followed");
    /* the user's own file follows the link out */
    CHECK(!hy_out_open(&o, "tree/evil.svg", HY_OUT_FOLLOW, &err), "HY_OUT_FOLLOW: %s", err.msg);
    fputs("mine\n", hy_out_file(&o));
    CHECK(!hy_out_commit(&o, &err) && file_is("outside/victim", "mine\n"), "HY_OUT_FOLLOW: %s", err.msg);
    /* a link swapped in after open is replaced by the rename, never followed */
    unlink("tree/sub/in.svg");
    CHECK(!hy_out_open(&o, "tree/sub/in.svg", 0, &err), "%s", err.msg);
    CHECK(!symlink("../../outside/victim", "tree/sub/in.svg"), "symlink");
    fputs("late\n", hy_out_file(&o));
    CHECK(!hy_out_commit(&o, &err), "%s", err.msg);
    CHECK(file_is("outside/victim", "mine\n") && !lstat("tree/sub/in.svg", &st) && S_ISREG(st.st_mode),
          "a link planted after the check was followed");
}

/* issue 20 item 11: the user's own file sweeps its stale temporaries (a
 * killed `data -o FILE`), never a live writer's or another name's. */
static void test_own_sweep(void)
{
    hy_out live, o;
    hy_error err = {0};
    mkdir("own", 0755);
    CHECK(!hy_out_open(&live, "own/s.csv", HY_OUT_FOLLOW, &err), "%s", err.msg);
    FILE *f = fopen("own/.s.csv.hystviz-tmp.STALE1", "w");
    if (f)
        fclose(f);
    f = fopen("own/.t.csv.hystviz-tmp.STALE2", "w");
    if (f)
        fclose(f);
    CHECK(!hy_out_open(&o, "own/s.csv", HY_OUT_FOLLOW, &err), "%s", err.msg);
    CHECK(access("own/.s.csv.hystviz-tmp.STALE1", F_OK) != 0, "the stale temporary of the same file stayed");
    CHECK(access("own/.t.csv.hystviz-tmp.STALE2", F_OK) == 0, "another file's temporary was swept");
    CHECK(access(hy_out_tmp_path(&live), F_OK) == 0, "a live writer's temporary was swept");
    CHECK(!hy_out_commit(&o, &err) && !hy_out_commit(&live, &err), "%s", err.msg);
}

int main(void)
{
    umask(027); /* before the first open: the writer reads the umask once */
    if (system("rm -rf io_test") != 0 || mkdir("io_test", 0755) || chdir("io_test") || mkdir("d", 0755)) {
        printf("cannot set up io_test/\n");
        return 1;
    }
    test_names_and_mode();
    test_group();
    test_hold_stdout();
    test_sweep();
    test_failures();
    test_links();
    test_own_sweep();
    return hy_test_finish("out");
}
