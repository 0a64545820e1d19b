/* SPDX-License-Identifier: MIT */
/* test_serve_util.c: the HTTP-free parts of `hystviz serve`: scene names,
 * override checks, JSON and shell quoting, shortest numbers, slider ranges,
 * "save as new scene" text and the never-overwriting writer. */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "scene_fit.h"
#include "serve_util.h"
#include "../hy_test.h"

/* the test's check: tests/hy_test.h's, naming the condition */
#define CHECK(c) HY_CHECK(c, "%s", #c)

static const char *json(const char *s)
{
    static sv_buf b;
    free(b.s);
    memset(&b, 0, sizeof b);
    sv_json(&b, s);
    return b.s;
}

static const char *shell(const char *s)
{
    static sv_buf b;
    free(b.s);
    memset(&b, 0, sizeof b);
    sv_shell(&b, s);
    return b.s;
}

static const char *num(double v)
{
    static sv_buf b;
    free(b.s);
    memset(&b, 0, sizeof b);
    sv_num(&b, v);
    return b.s;
}

static const hy_scene_key_spec *spec(const char *sec, const char *key)
{
    size_t n;
    const hy_scene_section_spec *s = hy_scene_schema(&n);
    int si = hy_scene_schema_section(sec);
    return &s[si].keys[hy_scene_schema_key(si, key)];
}

int main(void)
{
    /* names */
    CHECK(sv_scene_name_ok("fig15_minor_loop_ex4.scene"));
    CHECK(sv_scene_name_ok("a-b.c.scene"));
    CHECK(!sv_scene_name_ok("../x.scene"));
    CHECK(!sv_scene_name_ok("a/b.scene"));
    CHECK(!sv_scene_name_ok(".hidden.scene"));
    CHECK(!sv_scene_name_ok("a..b.scene"));
    CHECK(!sv_scene_name_ok("x.scene.txt"));
    CHECK(!sv_scene_name_ok(".scene"));
    CHECK(!sv_scene_name_ok("/etc/passwd"));
    CHECK(!sv_scene_name_ok("a b.scene"));
    CHECK(!sv_scene_name_ok("a%2f.scene"));

    /* overrides a page may send */
    hy_error err;
    CHECK(sv_set_ok("model.sigma0=3", &err) == HY_OK);
    CHECK(sv_set_ok("series.minor.width=2pt", &err) == HY_OK);
    CHECK(sv_set_ok("input.file=/etc/passwd", &err) == HY_EINVAL && strstr(err.msg, "file path"));
    CHECK(sv_set_ok("output.dir=/tmp", &err) == HY_EINVAL);
    CHECK(sv_set_ok("output.name=x", &err) == HY_EINVAL);
    CHECK(sv_set_ok("nosuch.key=1", &err) == HY_EINVAL);
    CHECK(sv_set_ok("sigma0", &err) == HY_EINVAL);
    /* issue 20: the check parses as hy_scene_set does (blanks before '=' are
       trimmed by both), and it is an allow-list */
    CHECK(sv_set_ok("input.file =/etc/passwd", &err) == HY_EINVAL && strstr(err.msg, "file path"));
    CHECK(sv_set_ok("input.file\t=/etc/passwd", &err) == HY_EINVAL);
    CHECK(sv_set_ok(" input.file \t =/etc/passwd", &err) == HY_EINVAL);
    CHECK(sv_set_ok(" output.dir=/tmp", &err) == HY_EINVAL);
    CHECK(sv_set_ok("figure.title=x", &err) == HY_EINVAL);
    CHECK(sv_set_ok("model.sigma0 = 3", &err) == HY_OK);
    CHECK(sv_set_ok("input.kind=sine", &err) == HY_OK);
    char longset[400];
    memset(longset, 'a', sizeof longset - 1);
    longset[sizeof longset - 1] = '\0';
    memcpy(longset, "model.sigma0=", 13);
    CHECK(sv_set_ok(longset, &err) == HY_EINVAL);

    /* JSON: quotes, backslashes, controls, and < > & escaped for HTML */
    CHECK(!strcmp(json("a\"b\\c"), "\"a\\\"b\\\\c\""));
    CHECK(!strcmp(json("x\ny\t\x01"), "\"x\\ny\\t\\u0001\""));
    CHECK(!strcmp(json("</script>&"), "\"\\u003c/script\\u003e\\u0026\""));
    CHECK(!strcmp(json("σ0"), "\"σ0\""));

    /* shell quoting */
    CHECK(!strcmp(shell("model.sigma0=3.5"), "model.sigma0=3.5"));
    CHECK(!strcmp(shell("series.x.label=a b"), "'series.x.label=a b'"));
    CHECK(!strcmp(shell("it's"), "'it'\\''s'"));
    CHECK(!strcmp(shell(""), "''"));

    /* shortest round-trip numbers */
    CHECK(!strcmp(num(0.1), "0.1"));
    CHECK(!strcmp(num(6), "6"));
    CHECK(!strcmp(num(1.0 / 3), "0.3333333333333333"));
    CHECK(!strcmp(num(1e-300), "1e-300"));
    CHECK(!strcmp(num(NAN), "null"));
    CHECK(!strcmp(num(30), "30"));
    CHECK(!strcmp(num(600), "600"));
    CHECK(!strcmp(num(-2400), "-2400"));
    CHECK(!strcmp(num(1e20), "1e+20"));
    CHECK(!strcmp(num(123456.5), "123456.5"));

    /* slider ranges: sigma0 (> 0) log over four decades around the value */
    double lo, hi;
    int lg;
    hy_scene_key_range(spec("model", "sigma0"), 6, &lo, &hi, &lg);
    CHECK(lg && fabs(lo - 0.06) < 1e-15 && fabs(hi - 600) < 1e-12);
    /* sigma2 = 0 (>= 0): linear from 0 */
    hy_scene_key_range(spec("model", "sigma2"), 0, &lo, &hi, &lg);
    CHECK(!lg && lo == 0 && hi > 0);
    /* umin2 (unbounded): linear around the value */
    hy_scene_key_range(spec("input", "umin2"), 0.5, &lo, &hi, &lg);
    CHECK(!lg && lo == 0 && hi == 1);
    /* dpi in [36, 2400]: kept inside the documented bounds */
    hy_scene_key_range(spec("figure", "dpi"), 200, &lo, &hi, &lg);
    CHECK(lo >= 36 && hi <= 2400 && lo < 200 && hi > 200);
    /* rtol in (0, 1]: never above 1, never 0 */
    hy_scene_key_range(spec("compute", "rtol"), 1e-8, &lo, &hi, &lg);
    CHECK(lg && lo > 0 && hi <= 1);

    /* save as new scene: replaced lines, inserted keys, a new section */
    char dir[200];
    CHECK(mkdtemp(test_tmppath(dir, sizeof dir, "serve_util_XXXXXX")) != NULL);
    char path[256], newpath[256];
    snprintf(path, sizeof path, "%s/a.scene", dir);
    snprintf(newpath, sizeof newpath, "%s/b.scene", dir);
    const char *text = "# a scene\n[model]\nkind = lugre\nsigma0 = 6 # stiff\n\n[input]\nkind = bimodal\n\n"
                       "[series s]\ndata = ystar\n\n[output]\nname = a\n";
    CHECK(sv_write_new(path, text, strlen(text), &err) == HY_OK);
    CHECK(sv_write_new(path, "x", 1, &err) == HY_EINVAL); /* never overwrites */
    size_t len;
    char *back = sv_read_file(path, 1 << 16, &len);
    CHECK(back && !strcmp(back, text));
    free(back);
    hy_scene *s = NULL;
    CHECK(hy_scene_parse_file(path, &s, &err) == HY_OK);
    char *sets[] = {"model.sigma0=2.5", "model.fc=3", "compute.points=300", "compute.cycles=2", "series.s.width=2pt"};
    char *nt = s ? sv_scene_with_sets(s, path, text, sets, 5, "b", &err) : NULL;
    CHECK(nt != NULL);
    hy_scene *want = NULL, *got = NULL;
    if (nt) {
        CHECK(strstr(nt, "sigma0 = 2.5\n") && !strstr(nt, "sigma0 = 6"));
        CHECK(strstr(nt, "[model]\nfc = 3\n"));
        CHECK(strstr(nt, "\n[compute]\npoints = 300\ncycles = 2\n"));
        CHECK(strstr(nt, "[series s]\nwidth = 2pt\n"));
        CHECK(strstr(nt, "name = b\n") && !strstr(nt, "name = a\n"));
        CHECK(hy_scene_parse_buffer(newpath, nt, strlen(nt), &got, &err) == HY_OK);
        CHECK(hy_scene_parse_file(path, &want, &err) == HY_OK);
        for (size_t i = 0; want && i < 5; i++)
            CHECK(hy_scene_set(want, sets[i], &err) == HY_OK);
        CHECK(want && hy_scene_set(want, "output.name=b", &err) == HY_OK);
        double v1, v2;
        long p1, p2;
        CHECK(got && hy_scene_get_num(got, "model", NULL, "sigma0", &v1) == HY_SCENE_SET && v1 == 2.5);
        CHECK(got && hy_scene_get_num(got, "model", NULL, "fc", &v2) == HY_SCENE_SET && v2 == 3);
        CHECK(got && hy_scene_get_int(got, "compute", NULL, "points", &p1) == HY_SCENE_SET && p1 == 300);
        CHECK(got && hy_scene_get_int(got, "compute", NULL, "cycles", &p2) == HY_SCENE_SET && p2 == 2);
        CHECK(got && want && hy_scene_get_length_pt(got, "series", "s", "width", &v1) == HY_SCENE_SET &&
              hy_scene_get_length_pt(want, "series", "s", "width", &v2) == HY_SCENE_SET && v1 == v2);
    }
    hy_scene_free(want);
    hy_scene_free(got);
    hy_scene_free(s);
    free(nt);

    /* a [param] read by two series: one control for it, with the readers'
       symbol, none for the readers; a page may set it */
    {
        static const char linked[] = "[series t]\ndata = transient\ngamma = $g\n[series y]\ndata = ygamma\n"
                                     "gamma = $g\n[series z]\ndata = ygamma\ngamma = 5\n[param g]\nvalue = 20\n";
        hy_scene *ls = NULL;
        CHECK(hy_scene_parse_buffer("l.scene", linked, strlen(linked), &ls, &err) == HY_OK);
        sv_buf cb = {0};
        hy_scene_doc ld = {0};
        if (ls && hy_scene_decode_fill(ls, &ld, &err) == HY_OK)
            sv_controls_json(&cb, ls, &ld, HY_READS_MODEL | HY_READS_G | HY_READS_INPUT);
        hy_scene_doc_free(&ld);
        const char *p = cb.s ? strstr(cb.s, "{\"key\":\"param.g.value\",\"value\":\"20\"") : NULL;
        CHECK(p && strstr(p, "\"sym\":\"γ\"") && !strstr(p + 20, "param.g.value"));
        CHECK(cb.s && !strstr(cb.s, "series.t.gamma") && !strstr(cb.s, "series.y.gamma") && strstr(cb.s, "series.z.gamma"));
        CHECK(sv_set_ok("param.g.value=30", &err) == HY_OK);
        free(cb.s);
        hy_scene_free(ls);
    }

    /* sv_read_beneath: the file itself, a link inside; never a link out, a
       directory or a FIFO (issue 20: read through the descriptor checked) */
    char sub[300], lin[300], lout[300], fifo[300], outside[300];
    snprintf(sub, sizeof sub, "%s/d.scene", dir);
    snprintf(lin, sizeof lin, "%s/in.scene", dir);
    snprintf(lout, sizeof lout, "%s/out.scene", dir);
    snprintf(fifo, sizeof fifo, "%s/f.scene", dir);
    snprintf(outside, sizeof outside, "%s.outside", dir);
    CHECK(mkdir(sub, 0700) == 0 && symlink("a.scene", lin) == 0 && symlink(outside, lout) == 0 &&
          mkfifo(fifo, 0600) == 0);
    FILE *o = fopen(outside, "w");
    CHECK(o && fputs("outside\n", o) >= 0 && fclose(o) == 0);
    int dfd = open(dir, O_RDONLY | O_DIRECTORY);
    CHECK(dfd >= 0);
    char *t = sv_read_beneath(dfd, "a.scene", 1 << 16, &len);
    CHECK(t && !strcmp(t, text));
    free(t);
    CHECK(!sv_read_beneath(dfd, "a.scene", 10, &len) && errno == EFBIG);
    CHECK(!sv_read_beneath(dfd, "out.scene", 1 << 16, &len));
    CHECK(!sv_read_beneath(dfd, "d.scene", 1 << 16, &len));
    CHECK(!sv_read_beneath(dfd, "f.scene", 1 << 16, &len)); /* and it did not block on the FIFO */
    CHECK(!sv_read_beneath(dfd, "../x.scene", 1 << 16, &len));
    CHECK(!sv_read_beneath(dfd, "missing.scene", 1 << 16, &len) && errno == ENOENT);
    t = sv_read_beneath(dfd, "in.scene", 1 << 16, &len); /* a link inside: followed only where openat2 exists */
    CHECK(!t || !strcmp(t, text));
    free(t);
    close(dfd);
    unlink(lin);
    unlink(lout);
    unlink(fifo);
    unlink(outside);
    rmdir(sub);
    unlink(path);
    rmdir(dir);
    return hy_test_finish("serve-util");
}
