/* SPDX-License-Identifier: MIT */
/* test_scene_include.c: includes: merge, precedence, relative paths, cycles, depth, missing files, content hash. */
#include "scene_test.h"

static char dir[512];

static hy_scene *parse_path(const char *name, int line)
{
    char p[1024];
    hy_scene *s = NULL;
    hy_error err = {0, ""};
    snprintf(p, sizeof p, "%s/%s", dir, name);
    if (hy_scene_parse_file(p, &s, &err)) {
        fprintf(stderr, "line %d: unexpected error: %s\n", line, err.msg);
        st_failures++;
    }
    return s;
}
#define PARSE_PATH(name) parse_path(name, __LINE__)

/* Parses dir/name expecting an error whose text is want with every "@" replaced by dir. */
static void path_fails(const char *name, const char *want, int line)
{
    char p[1024], w[2048];
    size_t n = 0;
    for (const char *c = want; *c && n + 600 < sizeof w; c++) {
        if (*c == '@')
            n += (size_t)snprintf(w + n, sizeof w - n, "%s", dir);
        else
            w[n++] = *c;
    }
    w[n] = '\0';
    hy_scene *s = NULL;
    hy_error err = {0, ""};
    snprintf(p, sizeof p, "%s/%s", dir, name);
    if (!hy_scene_parse_file(p, &s, &err)) {
        fprintf(stderr, "line %d: parse succeeded, expected: %s\n", line, w);
        st_failures++;
        hy_scene_free(s);
    } else if (strcmp(err.msg, w) != 0) {
        fprintf(stderr, "line %d: message\n    \"%s\"\n expected\n    \"%s\"\n", line, err.msg, w);
        st_failures++;
    }
}
#define PATH_FAILS(name, want) path_fails(name, want, __LINE__)

static void merge_and_precedence(void)
{
    st_write(dir, "style.scene",
             "# house style\n[figure]\nfont = \"Times\"\nfontsize = 10pt\ngrid = true\n"
             "[series ystar]\nstyle = dashed\ncolor = 3\n");
    st_write(dir, "main.scene",
             "[figure]\nfontsize = 12pt\ninclude \"style.scene\"\ngrid = false\n"
             "[series ystar]\ndata = ystar\ncolor = 5\n");
    hy_scene *s = PARSE_PATH("main.scene");
    const char *t;
    double v;
    int b;
    hy_scene_loc loc;
    char want[1024];
    CHECK(hy_scene_get_str(s, "figure", NULL, "font", &t) == HY_SCENE_SET);
    CHECK_STR(t, "Times");
    CHECK(hy_scene_get_loc(s, "figure", NULL, "font", &loc) == 1);
    snprintf(want, sizeof want, "%s/style.scene", dir);
    CHECK_STR(loc.file, want);
    CHECK(loc.line == 3 && loc.col == 1);
    /* set before the include: the including file wins */
    CHECK(hy_scene_get_length_pt(s, "figure", NULL, "fontsize", &v) == HY_SCENE_SET);
    CHECK_NEAR(v, 12, 0);
    CHECK(hy_scene_get_loc(s, "figure", NULL, "fontsize", &loc) == 1 && loc.line == 2);
    /* set after the include, still in [figure]: the including file wins */
    CHECK(hy_scene_get_bool(s, "figure", NULL, "grid", &b) == HY_SCENE_SET && b == 0);
    CHECK(hy_scene_get_loc(s, "figure", NULL, "grid", &loc) == 1 && loc.line == 4);
    snprintf(want, sizeof want, "%s/main.scene", dir);
    CHECK_STR(loc.file, want);
    /* a named section merges across files */
    CHECK(hy_scene_count(s, "series") == 1);
    CHECK(hy_scene_get_enum(s, "series", "ystar", "style", NULL, &t) == HY_SCENE_SET);
    CHECK_STR(t, "dashed");
    hy_scene_color c;
    CHECK(hy_scene_get_color(s, "series", "ystar", "color", &c) == HY_SCENE_SET && c.index == 5);
    /* the section was first seen in the included file */
    CHECK(hy_scene_get_loc(s, "series", "ystar", NULL, &loc) == 1 && loc.line == 6);
    hy_scene_free(s);

    /* siblings: the later include wins; the including file beats both */
    st_write(dir, "a.scene", "[figure]\ndpi = 100\nlegend = none\n");
    st_write(dir, "b.scene", "[figure]\ndpi = 200\n");
    st_write(dir, "sib.scene", "include \"a.scene\"\ninclude \"b.scene\"\ninclude \"a.scene\"\n"
                               "[figure]\nlegend = top-left\n");
    s = PARSE_PATH("sib.scene");
    long dpi;
    CHECK(hy_scene_get_int(s, "figure", NULL, "dpi", &dpi) == HY_SCENE_SET && dpi == 100);
    CHECK(hy_scene_get_enum(s, "figure", NULL, "legend", NULL, &t) == HY_SCENE_SET);
    CHECK_STR(t, "top-left");
    hy_scene_free(s);

    st_write(dir, "sib2.scene", "include \"a.scene\"\ninclude \"b.scene\"\n");
    s = PARSE_PATH("sib2.scene");
    CHECK(hy_scene_get_int(s, "figure", NULL, "dpi", &dpi) == HY_SCENE_SET && dpi == 200);
    hy_scene_free(s);
}

static void nested_and_paths(void)
{
    char sub[600], want[1024];
    snprintf(sub, sizeof sub, "%s/sub", dir);
    CHECK(mkdir(sub, 0700) == 0);
    st_write(sub, "leaf.scene", "[model]\nx0 = 2\nsigma0 = 7\n[input]\nkind = file\nfile = \"u.txt\"\n");
    st_write(sub, "mid.scene", "[model]\nx0 = 1\ninclude \"leaf.scene\"\n");
    st_write(dir, "top.scene", "include \"sub/mid.scene\"\n[model]\nsigma0 = 8\n");
    hy_scene *s = PARSE_PATH("top.scene");
    double v;
    const char *t;
    /* mid set x0 before including leaf: mid (an including file) wins */
    CHECK(hy_scene_get_num(s, "model", NULL, "x0", &v) == HY_SCENE_SET);
    CHECK_NEAR(v, 1, 0);
    CHECK(hy_scene_get_num(s, "model", NULL, "sigma0", &v) == HY_SCENE_SET);
    CHECK_NEAR(v, 8, 0);
    /* paths are relative to the file that wrote them */
    CHECK(hy_scene_get_str(s, "input", NULL, "file", &t) == HY_SCENE_SET);
    snprintf(want, sizeof want, "%s/sub/u.txt", dir);
    CHECK_STR(t, want);
    hy_scene_free(s);

    /* a duplicate inside an included file is an error located in that file */
    st_write(sub, "dup.scene", "[model]\nfc = 1\nfc = 2\n");
    st_write(dir, "incdup.scene", "[model]\nfc = 3\ninclude \"sub/dup.scene\"\n");
    PATH_FAILS("incdup.scene", "@/sub/dup.scene:3:1: duplicate key 'fc' in [model] (first set at line 2)");
    /* an error inside an included file names the included file */
    st_write(sub, "bad.scene", "[figure]\ndpi = 10\n");
    st_write(dir, "incbad.scene", "# x\ninclude \"sub/bad.scene\"\n");
    PATH_FAILS("incbad.scene", "@/sub/bad.scene:2:7: 'dpi' in [figure] must be in [36, 2400], got 10");
    const char *const names[] = {"leaf.scene", "mid.scene", "dup.scene", "bad.scene", NULL};
    st_cleanup(sub, names);
}

static void failures(void)
{
    st_write(dir, "miss.scene", "[model]\n  include   \"nope.scene\"\n");
    PATH_FAILS("miss.scene",
               "@/miss.scene:2:13: cannot read included file 'nope.scene': No such file or directory");
    st_write(dir, "c1.scene", "include \"c2.scene\"\n");
    st_write(dir, "c2.scene", "[model]\ninclude \"c1.scene\"\n");
    PATH_FAILS("c1.scene", "@/c2.scene:2:9: include cycle: @/c1.scene -> @/c2.scene -> @/c1.scene");
    st_write(dir, "self.scene", "include \"./self.scene\"\n");
    PATH_FAILS("self.scene", "@/self.scene:1:9: include cycle: @/self.scene -> @/./self.scene");
    st_write(dir, "inc_noname.scene", "include \"\"\n");
    PATH_FAILS("inc_noname.scene", "@/inc_noname.scene:1:9: include needs a file name");
    st_write(dir, "inc_junk.scene", "include \"a.scene\" x\n");
    PATH_FAILS("inc_junk.scene",
               "@/inc_junk.scene:1:19: unexpected 'x' after the value of 'include' (quote text that contains spaces)");
    /* a chain of 17 files is one too deep */
    for (int i = 0; i < 17; i++) {
        char name[32], text[64];
        snprintf(name, sizeof name, "d%02d.scene", i);
        snprintf(text, sizeof text, "include \"d%02d.scene\"\n", i + 1);
        st_write(dir, name, text);
    }
    st_write(dir, "d17.scene", "[model]\n");
    PATH_FAILS("d00.scene", "@/d15.scene:1:9: includes nested deeper than 16 levels at 'd16.scene'");
    /* a chain of 16 files is fine */
    hy_scene *s = PARSE_PATH("d02.scene");
    CHECK(s && hy_scene_count(s, "model") == 1);
    hy_scene_free(s);
}

static void hashes(void)
{
    st_write(dir, "hstyle.scene", "[figure]\ngrid = true\n");
    st_write(dir, "hmain.scene", "include \"hstyle.scene\"\n[model]\nsigma0 = 2\n");
    hy_scene *s1 = PARSE_PATH("hmain.scene"), *s2 = PARSE_PATH("hmain.scene");
    if (!s1 || !s2)
        return;
    CHECK(s1 && s2 && hy_scene_hash(s1) == hy_scene_hash(s2));
    uint64_t h = hy_scene_hash(s1);
    hy_scene_free(s2);
    st_write(dir, "hstyle.scene", "[figure]\ngrid = false\n");
    s2 = PARSE_PATH("hmain.scene");
    CHECK(s2 && hy_scene_hash(s2) != h);
    hy_scene_free(s2);
    st_write(dir, "hstyle.scene", "[figure]\ngrid = true\n");
    s2 = PARSE_PATH("hmain.scene");
    CHECK(s2 && hy_scene_hash(s2) == h);
    /* an override changes the hash; the same override gives the same hash */
    hy_error err;
    CHECK(hy_scene_set(s2, "model.sigma0=3", &err) == 0);
    CHECK(hy_scene_set(s1, "model.sigma0=3", &err) == 0);
    CHECK(hy_scene_hash(s2) != h && hy_scene_hash(s1) == hy_scene_hash(s2));
    hy_scene_free(s1);
    hy_scene_free(s2);
    /* a known value: FNV-1a of the empty scene text and the file separator "\n\377" */
    hy_scene *e = PARSE_OK("e.scene", "");
    uint64_t want = 0xcbf29ce484222325ULL;
    want = (want ^ 0x0a) * 0x100000001b3ULL;
    want = (want ^ 0xff) * 0x100000001b3ULL;
    CHECK(e && hy_scene_hash(e) == want);
    hy_scene_free(e);
}

int main(void)
{
    st_tempdir(dir, sizeof dir);
    merge_and_precedence();
    nested_and_paths();
    failures();
    hashes();
    const char *const names[] = {
        "style.scene", "main.scene", "a.scene", "b.scene", "sib.scene", "sib2.scene",
        "top.scene", "incdup.scene", "incbad.scene", "miss.scene", "c1.scene", "c2.scene",
        "self.scene", "inc_noname.scene", "inc_junk.scene", "hstyle.scene", "hmain.scene",
        "d00.scene", "d01.scene", "d02.scene", "d03.scene", "d04.scene", "d05.scene",
        "d06.scene", "d07.scene", "d08.scene", "d09.scene", "d10.scene", "d11.scene",
        "d12.scene", "d13.scene", "d14.scene", "d15.scene", "d16.scene", "d17.scene", "sub", NULL};
    st_cleanup(dir, names);
    return st_result("test_scene_include");
}
