/* SPDX-License-Identifier: MIT */
/* test_scene_policy.c: the scene file policy (docs/SCENES.md, "Files a scene may read
 * and write"): includes, input files, output directory, caps, the include bomb, large
 * scenes, number magnitudes, quality presets.  Every file lives in a temp dir. */
#include "scene_test.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdarg.h>

#include "hy_input.h"
#include "hy_quality.h"
#include "hy_scene_policy.h"

static char dir[512], outside[512];

static void run(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static void run(const char *fmt, ...)
{
    char cmd[2048];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(cmd, sizeof cmd, fmt, ap);
    va_end(ap);
    if (system(cmd) != 0) {
        fprintf(stderr, "command failed: %s\n", cmd);
        exit(1);
    }
}

/* Parses dir/name under pol; returns the code and the message in msg. */
static int parse(const char *name, const hy_scene_policy *pol, hy_scene **s, char *msg, size_t n)
{
    char p[1024];
    hy_error err = {0, ""};
    snprintf(p, sizeof p, "%s/%s", dir, name);
    *s = NULL;
    int rc = hy_scene_parse_file_policy(p, pol, s, &err);
    snprintf(msg, n, "%s", rc ? err.msg : "");
    return rc;
}

/* Expects dir/name to be refused with a message containing want (and, if
 * secret is not NULL, not containing it). */
static void refused(const char *name, const hy_scene_policy *pol, const char *want, const char *secret, int line)
{
    hy_scene *s;
    char msg[1024];
    if (!parse(name, pol, &s, msg, sizeof msg)) {
        fprintf(stderr, "line %d: %s parsed, expected an error containing '%s'\n", line, name, want);
        st_failures++;
        hy_scene_free(s);
        return;
    }
    if (!strstr(msg, want)) {
        fprintf(stderr, "line %d: message '%s' lacks '%s'\n", line, msg, want);
        st_failures++;
    }
    if (secret && strstr(msg, secret)) {
        fprintf(stderr, "line %d: message '%s' leaks '%s'\n", line, msg, secret);
        st_failures++;
    }
    char loc[600]; /* every message names file:line:col */
    snprintf(loc, sizeof loc, "%s/%s:", dir, name);
    if (strncmp(msg, loc, strlen(loc)) != 0) {
        fprintf(stderr, "line %d: message '%s' does not start at %s\n", line, msg, loc);
        st_failures++;
    }
}
#define REFUSED(name, want, secret) refused(name, NULL, want, secret, __LINE__)

static void includes(void)
{
    st_write(outside, "secret.scene", "root:SECRETSECRET:19000:0:99999:7:::\n");
    st_write(outside, "token.txt", "tok_SECRETSECRET\n");
    st_write(dir, "inc_abs.scene", "include \"/dev/zero\"\n");
    REFUSED("inc_abs.scene", "include paths must be relative", NULL);
    char text[1200];
    snprintf(text, sizeof text, "include \"../%s/secret.scene\"\n", strrchr(outside, '/') + 1);
    st_write(dir, "inc_up.scene", text);
    REFUSED("inc_up.scene", "lies outside the scene's directory", "SECRET");
    st_write(dir, "inc_txt.scene", "include \"token.txt\"\n");
    REFUSED("inc_txt.scene", "must be a scene file named *.scene", "SECRET");
    /* a symlink inside the scene's directory pointing out of it */
    run("ln -s '%s/secret.scene' '%s/link.scene'", outside, dir);
    st_write(dir, "inc_link.scene", "[model]\ninclude \"link.scene\"\n");
    REFUSED("inc_link.scene", "lies outside the scene's directory", "SECRET");
    /* a directory, a FIFO */
    run("mkdir '%s/d.scene' && mkfifo '%s/f.scene'", dir, dir);
    st_write(dir, "inc_dir.scene", "include \"d.scene\"\n");
    REFUSED("inc_dir.scene", "cannot include 'd.scene': it is a directory, not a scene file", NULL);
    st_write(dir, "inc_fifo.scene", "include \"f.scene\"\n");
    REFUSED("inc_fifo.scene", "is a FIFO, not a regular file", NULL);
    /* a name of control and high bytes, longer than a message: quoted escaped and cut at 32 bytes,
     * never raw and never cut right after the location (a fuzzer finding) */
    char longname[400] = "include \"st\x01";
    for (int i = 0; i < 300; i++)
        strcat(longname, "\xff");
    strcat(longname, ".scene\"\n");
    st_write(dir, "inc_bytes.scene", longname);
    REFUSED("inc_bytes.scene", "cannot read included file 'st\\x01\\xff\\xff", NULL);
    REFUSED("inc_bytes.scene", "\\xff...': File name too long", "\xff");
    /* no argument */
    st_write(dir, "inc_none.scene", "[model]\ninclude\n");
    REFUSED("inc_none.scene", ":2:8: include needs a file name in quotes", NULL);
    /* --include-dir: found there, and allowed there */
    st_write(outside, "house.scene", "[figure]\ndpi = 123\n");
    st_write(dir, "inc_house.scene", "include \"house.scene\"\n");
    REFUSED("inc_house.scene", "cannot read included file 'house.scene'", NULL);
    const char *dirs[] = {outside};
    hy_scene_policy pol = hy_scene_policy_default();
    pol.include_dirs = dirs;
    pol.ninclude_dirs = 1;
    hy_scene *s;
    char msg[1024];
    CHECK(parse("inc_house.scene", &pol, &s, msg, sizeof msg) == 0);
    long dpi = 0;
    CHECK(s && hy_scene_get_int(s, "figure", NULL, "dpi", &dpi) == HY_SCENE_SET && dpi == 123);
    hy_scene_free(s);
    const char *nodir[] = {"/nonexistent/inc"};
    pol.include_dirs = nodir;
    CHECK(parse("inc_house.scene", &pol, &s, msg, sizeof msg) == HY_EINVAL);
    CHECK(strstr(msg, "--include-dir /nonexistent/inc: no such directory") != NULL);
}

/* 16 files of 10 lines, each including the next 10 times (as deep as
 * includes may nest): 10^15 includes without the cap; refused at the 257th. */
static void include_bomb(void)
{
    char name[64], text[400];
    for (int i = 0; i < 16; i++) {
        size_t o = 0;
        for (int k = 0; k < 10; k++)
            o += (size_t)snprintf(text + o, sizeof text - o, i < 15 ? "include \"bomb%02d.scene\"\n" : "# leaf\n", i + 1);
        snprintf(name, sizeof name, "bomb%02d.scene", i);
        st_write(dir, name, text);
    }
    hy_scene *s;
    char msg[1024];
    CHECK(parse("bomb00.scene", NULL, &s, msg, sizeof msg) == HY_EINVAL);
    CHECK(strstr(msg, "bomb14.scene:10:9: more than 256 included files in one scene (repeats counted) at 'bomb15.scene'"));
    /* a repeated include below the caps is fine */
    st_write(dir, "twice.scene", "include \"bomb15.scene\"\ninclude \"bomb15.scene\"\n");
    CHECK(parse("twice.scene", NULL, &s, msg, sizeof msg) == 0);
    hy_scene_free(s);
}

static void size_caps(void)
{
    char p[1024];
    snprintf(p, sizeof p, "%s/huge.scene", dir);
    FILE *f = fopen(p, "w");
    CHECK(f != NULL);
    for (size_t n = 0; f && n <= HY_SCENE_MAX_FILE_BYTES; n += 64)
        fprintf(f, "# %61s\n", "filler");
    if (f)
        fclose(f);
    hy_scene *s;
    char msg[1024];
    hy_error err;
    CHECK(hy_scene_parse_file(p, &s, &err) != 0 && strstr(err.msg, "larger than the 4194304 bytes allowed"));
    st_write(dir, "inc_huge.scene", "include \"huge.scene\"\n");
    REFUSED("inc_huge.scene", "larger than the 4194304 bytes allowed", NULL);
    /* the top scene itself must be a regular file */
    CHECK(hy_scene_parse_file("/dev/zero", &s, &err) != 0 && strstr(err.msg, "character device"));
    (void)msg;
}

/* [input] file: below the scene's directory, regular, nothing of it quoted. */
static void input_files(void)
{
    char text[1200], msg[1024];
    hy_scene *s;
    char *buf;
    size_t len;
    int user = -1;
    hy_error err;
    snprintf(text, sizeof text, "[input]\nkind = file\nfile = \"%s/token.txt\"\n", outside);
    st_write(dir, "in_out.scene", text);
    CHECK(parse("in_out.scene", NULL, &s, msg, sizeof msg) == 0);
    CHECK(hy_scene_read_path(s, "input", NULL, "file", &buf, &len, &user, &err) == HY_EINVAL);
    CHECK(strstr(err.msg, "in_out.scene:3:1: ") && strstr(err.msg, "lies outside the scene's directory"));
    CHECK(!strstr(err.msg, "SECRET"));
    /* --set: the user's choice, read as it is */
    snprintf(text, sizeof text, "input.file=%s/token.txt", outside);
    CHECK(hy_scene_set(s, text, &err) == 0);
    CHECK(hy_scene_read_path(s, "input", NULL, "file", &buf, &len, &user, &err) == 0 && user == 1);
    CHECK(len == 17);
    free(buf);
    CHECK(hy_scene_set(s, "input.file=/dev/zero", &err) == 0);
    CHECK(hy_scene_read_path(s, "input", NULL, "file", &buf, &len, &user, &err) == HY_EINVAL);
    CHECK(strstr(err.msg, "is a character device, not a regular file") != NULL);
    hy_scene_free(s);
    /* a FIFO inside the scene's directory: refused at once, no hang */
    st_write(dir, "in_fifo.scene", "[input]\nkind = file\nfile = \"f.scene\"\n");
    CHECK(parse("in_fifo.scene", NULL, &s, msg, sizeof msg) == 0);
    CHECK(hy_scene_read_path(s, "input", NULL, "file", &buf, &len, &user, &err) == HY_EINVAL);
    CHECK(strstr(err.msg, "is a FIFO") != NULL);
    hy_scene_free(s);
    /* a scene-named file that does not parse: no text and no value from it */
    hy_input in;
    const char *bad = "0 1\n1 SECRETSECRET\n";
    CHECK(hy_input_text(&in, bad, strlen(bad), "u.txt", 0, &err) == HY_EINVAL);
    CHECK(strstr(err.msg, "u.txt:2:") && !strstr(err.msg, "SECRET"));
    const char *t0 = "123456 7\n";
    CHECK(hy_input_text(&in, t0, strlen(t0), "u.txt", 0, &err) == HY_EINVAL && !strstr(err.msg, "123456"));
    /* a file the user named: at most 20 bytes of the line, escaped */
    snprintf(text, sizeof text, "%s/shadow", outside);
    FILE *f = fopen(text, "w");
    CHECK(f && fputs("root:$6$abcdefghijklmnop\x01qrstuvwxyz:19000\n", f) >= 0 && fclose(f) == 0);
    CHECK(hy_input_file(&in, text, &err) == HY_EINVAL);
    CHECK(strstr(err.msg, "'root:$6$abcdefghijkl...'") != NULL && !strstr(err.msg, "mnop"));
    const char *ctl = "\x1b[2Jx y\n";
    CHECK(hy_input_text(&in, ctl, strlen(ctl), "c.txt", 1, &err) == HY_EINVAL && strstr(err.msg, "\\x1b[2Jx y"));
    const char *nul = "0 1\n1\0 2\n";
    CHECK(hy_input_text(&in, nul, 9, "n.txt", 1, &err) == HY_EINVAL && strstr(err.msg, "n.txt:2:2: NUL byte"));
}

/* [output] dir: relative to the scene's directory and below it; -o and --set are free. */
static void output_dir(void)
{
    hy_scene *s;
    char msg[1024], want[1200], *out = NULL;
    hy_error err;
    static const char *const bad[] = {"/tmp/x", "../../../..", "a/../../b", ""};
    for (size_t i = 0; i < 4; i++) {
        char text[200];
        snprintf(text, sizeof text, "[output]\ndir = \"%s\"\n", bad[i]);
        st_write(dir, "out_bad.scene", text);
        CHECK(parse("out_bad.scene", NULL, &s, msg, sizeof msg) == 0);
        CHECK(hy_scene_output_dir(s, NULL, &out, &err) == HY_EINVAL && out == NULL);
        CHECK(strstr(err.msg, "out_bad.scene:2:1: 'dir' in [output] must") != NULL);
        /* -o is the user's choice */
        CHECK(hy_scene_output_dir(s, "/anywhere/at/all", &out, &err) == 0 && !strcmp(out, "/anywhere/at/all"));
        free(out);
        hy_scene_free(s);
    }
    st_write(dir, "out_ok.scene", "[output]\ndir = \"figs/./a/../b\"\n");
    CHECK(parse("out_ok.scene", NULL, &s, msg, sizeof msg) == 0);
    CHECK(hy_scene_output_dir(s, NULL, &out, &err) == 0);
    snprintf(want, sizeof want, "%s/figs/b", dir);
    CHECK_STR(out, want);
    free(out);
    CHECK(hy_scene_set(s, "output.dir=/elsewhere", &err) == 0);
    CHECK(hy_scene_output_dir(s, NULL, &out, &err) == 0 && !strcmp(out, "/elsewhere"));
    free(out);
    hy_scene_free(s);
    /* the default: the scene's own directory */
    st_write(dir, "out_def.scene", "[model]\n");
    CHECK(parse("out_def.scene", NULL, &s, msg, sizeof msg) == 0);
    CHECK(hy_scene_output_dir(s, NULL, &out, &err) == 0 && !strcmp(out, dir));
    free(out);
    hy_scene_free(s);
    /* a symlink on the way out of the scene's directory */
    run("ln -s '%s' '%s/escape'", outside, dir);
    st_write(dir, "out_link.scene", "[output]\ndir = \"escape/figs\"\n");
    CHECK(parse("out_link.scene", NULL, &s, msg, sizeof msg) == 0);
    CHECK(hy_scene_output_dir(s, NULL, &out, &err) == HY_EINVAL && strstr(err.msg, "symbolic link"));
    hy_scene_free(s);
}

/* 64,000 sections (1.8 MB) parse, and every one is found by name and by index;
 * the benchmark (tests/bench bench_scene) times this, here it only has to finish. */
static void large_scene(void)
{
    enum { N = 64000 };
    size_t cap = (size_t)N * 40, o = 0;
    char *text = malloc(cap);
    CHECK(text != NULL);
    if (!text)
        return;
    for (int i = 0; i < N; i++)
        o += (size_t)snprintf(text + o, cap - o, "[series s%d]\ndata = input\nat = %d\n", i, i);
    hy_scene *s = NULL;
    hy_error err;
    CHECK(hy_scene_parse_buffer("big.scene", text, o, &s, &err) == 0);
    CHECK(s && hy_scene_count(s, "series") == N);
    int bad = 0;
    for (int i = 0; s && i < N; i += 997) {
        char name[32];
        double at = -1;
        snprintf(name, sizeof name, "s%d", i);
        bad += !hy_scene_name_at(s, "series", (size_t)i) || strcmp(hy_scene_name_at(s, "series", (size_t)i), name);
        bad += hy_scene_get_num(s, "series", name, "at", &at) != HY_SCENE_SET || at != i;
    }
    CHECK(bad == 0);
    hy_scene_free(s);
    /* a duplicate far apart is still found */
    o += (size_t)snprintf(text + o, cap - o, "[series s5]\n");
    CHECK(hy_scene_parse_buffer("big.scene", text, o, &s, &err) == HY_EINVAL);
    CHECK(strstr(err.msg, "duplicate section [series s5] (first at line 16)") != NULL);
    free(text);
}

static void numbers_and_presets(void)
{
    PARSE_FAILS("[model]\nsigma0 = 4.9e-324\n",
                "t.scene:2:10: 'sigma0' in [model] must be > 0 and at least 2.2250738585072014e-308 in magnitude "
                "(subnormal numbers are refused), got 4.9e-324");
    PARSE_FAILS("[figure]\nylim = -1e-310, 1\n",
                "t.scene:2:8: 'ylim' in [figure] must be 0 or at least 2.2250738585072014e-308 in magnitude "
                "(subnormal numbers are refused), got -1e-310");
    hy_scene *s = PARSE_OK("t.scene", "[model]\nx0 = 0\nsigma0 = 2.2250738585072014e-308\n[figure]\nxlim = -1e307, 1e308\n");
    hy_scene_free(s);
    /* [animation] quality takes every preset of hystviz animate --quality */
#define TRY(name, w, h, fps)                                                     \
    s = PARSE_OK("t.scene", "[animation]\nquality = " name "\n");              \
    hy_scene_free(s);
    HY_QUALITY_PRESETS(TRY)
#undef TRY
    size_t nsec;
    const hy_scene_section_spec *spec = hy_scene_schema(&nsec);
    int sec = hy_scene_schema_section("animation"), k = hy_scene_schema_key(sec, "quality");
    size_t n = 0;
    while (spec[sec].keys[k].enums[n])
        n++;
    CHECK(n == 8);
}

int main(void)
{
    st_tempdir(dir, sizeof dir);
    st_tempdir(outside, sizeof outside);
    includes();
    include_bomb();
    size_caps();
    input_files();
    output_dir();
    large_scene();
    numbers_and_presets();
    run("rm -rf '%s' '%s'", dir, outside);
    return st_result("test_scene_policy");
}
