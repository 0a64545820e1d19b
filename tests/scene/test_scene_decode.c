/* SPDX-License-Identifier: MIT */
/* test_scene_decode.c: the field table and hy_scene_decode: every decoded key fills a field of its
 * kind's C type, values and defaults arrive in the structs, and each keeps where it was written. */
#include "hy_scene_decl.h" /* first: the header compiles on its own */

#include "scene_test.h"

/* Every row that names a field names one of its kind's C type, inside its
 * struct's head-free part, and no two rows of a section fill one field. */
static void table(void)
{
    size_t n;
    const hy_scene_section_spec *sec = hy_scene_schema(&n);
    size_t decoded = 0;
    for (size_t i = 0; i < n; i++) {
        CHECK(sec[i].nkeys <= HY_SCENE_KEYS_MAX);
        for (size_t j = 0; j < sec[i].nkeys; j++) {
            const hy_scene_key_spec *k = &sec[i].keys[j];
            if (!k->ctype)
                continue;
            decoded++;
            if (k->ctype != hy_scene_kind_ctype(k->kind) || k->field < sizeof(hy_decl_head))
                fprintf(stderr, "%s.%s: ctype %d, its kind wants %d; field at %zu\n", sec[i].name, k->name, k->ctype,
                        hy_scene_kind_ctype(k->kind), k->field), st_failures++;
            size_t par = offsetof(hy_decl_model, par); /* a model's own rows: inside par */
            if (k->model && (i != 0 || k->field < par || k->field >= par + HY_MODEL_PAR_MAX))
                fprintf(stderr, "%s.%s (model %s) fills no byte of hy_decl_model.par\n", sec[i].name, k->name,
                        k->model), st_failures++;
            for (size_t m = 0; m < j; m++) /* two models' own rows share par */
                if (sec[i].keys[m].ctype && sec[i].keys[m].field == k->field &&
                    (!k->model || !sec[i].keys[m].model || !strcmp(k->model, sec[i].keys[m].model)))
                    fprintf(stderr, "%s: %s and %s fill one field\n", sec[i].name, sec[i].keys[m].name, k->name),
                        st_failures++;
        }
    }
    CHECK(decoded >= 100); /* model, input, compute, figure, series, annotation, panel, output */
}

/* A model's own rows (hy_scene_model_rows.h): those of the scene's kind fill
 * its struct (set or default), those of another kind fill nothing but keep
 * where they were written. */
static void own_rows(void)
{
    int sec = hy_scene_schema_section("model");
    const hy_scene_section_spec *ms = hy_scene_schema(NULL) + sec;
    const char *a = NULL, *b = NULL, *kind_a = NULL; /* a row of one model, b of another */
    for (size_t j = 0; j < ms->nkeys; j++)
        if (ms->keys[j].model && ms->keys[j].kind == HY_KIND_NUMBER && ms->keys[j].def) {
            if (!a)
                a = ms->keys[j].name, kind_a = ms->keys[j].model;
            else if (!b && strcmp(ms->keys[j].model, kind_a))
                b = ms->keys[j].name;
        }
    CHECK(a && b);
    if (!a || !b)
        return;
    char text[256];
    snprintf(text, sizeof text, "[model]\nkind = %s\n%s = 7\n%s = 5\n", kind_a, b, a);
    hy_scene *s = PARSE_OK("m.scene", text);
    if (!s)
        return;
    hy_scene_doc d;
    hy_error err = {0, ""};
    CHECK(hy_scene_decode(s, &d, &err) == HY_OK);
    double v = 0;
    CHECK(hy_scene_doc_num(&d, "model", a, &v) == 0 && v == 5);
    size_t off = hy_decl_offset(&d.model.h, a);
    CHECK(off != HY_DECL_HEAD && hy_decl_got(&d.model.h, off) == HY_SCENE_SET);
    CHECK(hy_decl_loc(&d.model.h, off).line == 4);
    double at;
    memcpy(&at, (const char *)&d.model + off, sizeof at);
    CHECK(at == 5);
    CHECK(hy_decl_offset(&d.model.h, b) == HY_DECL_HEAD && hy_scene_doc_num(&d, "model", b, &v) == -1);
    int jb = hy_scene_schema_key(sec, b);
    CHECK(d.model.h.at[jb].got == HY_SCENE_BADKEY && d.model.h.at[jb].set && d.model.h.at[jb].loc.line == 3);
    hy_decl_error_row(&d.model.h, (size_t)jb, &err, HY_EINVAL, "no");
    CHECK_STR(err.msg, "m.scene:3:1: no");
    hy_scene_doc_free(&d);
    char set[128]; /* an override of another model's row: set, at no line */
    snprintf(set, sizeof set, "model.%s=2", b);
    CHECK(hy_scene_set(s, set, &err) == HY_OK);
    snprintf(set, sizeof set, "model.%s=9", a);
    CHECK(hy_scene_set(s, set, &err) == HY_OK);
    CHECK(hy_scene_decode(s, &d, &err) == HY_OK);
    CHECK(d.model.h.at[jb].got == HY_SCENE_BADKEY && d.model.h.at[jb].set);
    CHECK(hy_scene_doc_num(&d, "model", a, &v) == 0 && v == 9);
    hy_scene_doc_free(&d);
    hy_scene_free(s);
}

/* Values, defaults, absent keys and their locations. */
static void values(void)
{
    hy_scene *s = PARSE_OK("d.scene", "[model]\nkind = dahl\nsigma0 = 3\n\n[figure]\n  xlim = 0, 4\nsize = 10cm, 2in\n"
                                      "zoom_follow = none\n[series b]\ndata = ygamma\ngamma = 10\ncolor = #ff0000\n"
                                      "[series a]\ndata = input\nlabel = \"u\"\n[output]\nformats = png, svg\n");
    if (!s)
        return;
    hy_scene_doc d;
    hy_error err = {0, ""};
    CHECK(hy_scene_decode(s, &d, &err) == HY_OK);
    CHECK_STR(hy_decl_enum_text(&d.model.h, offsetof(hy_decl_model, kind), d.model.kind), "dahl");
    CHECK_NEAR(d.model.sigma0, 3, 0);
    CHECK_NEAR(d.model.fs, 2, 0); /* the schema default */
    CHECK(hy_decl_got(&d.model.h, offsetof(hy_decl_model, sigma0)) == HY_SCENE_SET);
    CHECK(hy_decl_got(&d.model.h, offsetof(hy_decl_model, fs)) == HY_SCENE_DEFAULT);
    CHECK(d.model.h.at[1].loc.line == 3 && d.model.h.at[1].loc.col == 1);
    CHECK(!d.figure.xlim.is_auto && d.figure.xlim.v[0] == 0 && d.figure.xlim.v[1] == 4);
    CHECK(d.figure.ylim.is_auto);
    CHECK_NEAR(d.figure.size[0], 10 * 72 / 2.54, 1e-12);
    CHECK_NEAR(d.figure.size[1], 144, 0);
    CHECK(d.figure.dpi == 300);
    CHECK(hy_decl_got(&d.figure.h, offsetof(hy_decl_figure, xlabel)) == HY_SCENE_ABSENT && !d.figure.xlabel);
    CHECK(d.nseries == 2 && !strcmp(d.series[0].h.name, "b") && !strcmp(d.series[1].h.name, "a"));
    CHECK(hy_scene_doc_series(&d, "a") == &d.series[1] && !hy_scene_doc_series(&d, "c"));
    CHECK(d.series[0].color.r == 1 && d.series[0].color.g == 0 && d.series[0].gamma == 10);
    CHECK_STR(d.series[1].label, "u");
    CHECK_NEAR(d.series[1].width, 1, 0);
    CHECK(d.output.formats.n == 2);
    CHECK_STR(hy_decl_enum_text(&d.output.h, offsetof(hy_decl_output, formats), (int)d.output.formats.v[0]), "png");
    double x;
    CHECK(!hy_scene_doc_num(&d, "model", "sigma0", &x) && x == 3);
    CHECK(!hy_scene_doc_num(&d, "compute", "cycles", &x) && x == 1); /* an integer, by default */
    CHECK(hy_scene_doc_num(&d, "model", "kind", &x) < 0 && hy_scene_doc_num(&d, "model", "nosuch", &x) < 0);
    /* an error at a field names where it was written, else the section, else the file */
    hy_decl_error(&d.figure.h, offsetof(hy_decl_figure, xlim), &err, HY_EINVAL, "bad %s", "xlim");
    CHECK_STR(err.msg, "d.scene:6:3: bad xlim");
    hy_decl_error(&d.figure.h, offsetof(hy_decl_figure, ylim), &err, HY_EINVAL, "bad");
    CHECK_STR(err.msg, "d.scene:5:1: bad");
    hy_decl_error(&d.compute.h, offsetof(hy_decl_compute, points), &err, HY_EINVAL, "bad");
    CHECK_STR(err.msg, "d.scene: bad");
    hy_scene_doc_free(&d);
    hy_scene_free(s);
}

/* The checks that span keys and sections, each at the place it names, all
 * before anything is computed. */
static void refused(const char *text, const char *want, int line)
{
    hy_scene *s = st_parse_ok("c.scene", text, line);
    if (!s)
        return;
    hy_scene_doc d;
    hy_error err = {0, ""};
    int rc = hy_scene_decode(s, &d, &err);
    if (rc != HY_EINVAL || strcmp(err.msg, want)) {
        fprintf(stderr, "line %d: got %d \"%s\"\n expected \"%s\"\n", line, rc, err.msg, want);
        st_failures++;
    }
    hy_scene_doc_free(&d);
    hy_scene_free(s);
}
#define REFUSED(text, want) refused(text, want, __LINE__)

static void cross(void)
{
    REFUSED("[series a]\ndata = input\n[annotation t]\ntext = \"a\"\nx = 0\n", "c.scene:3:1: annotation 't' needs x and y");
    REFUSED("[series a]\ndata = input\n[annotation t]\ntext = \"a\"\nx = 0\ny = 1\npoint_y = 2\n",
            "c.scene:3:1: annotation 't' needs both point_x and point_y, or neither");
    REFUSED("[series a]\ndata = input\n[figure]\nzoom_y = 0, 1\n", "c.scene:4:1: a zoomed inset needs both zoom_x and zoom_y");
    REFUSED("[series a]\ndata = input\n[figure]\nzoom_follow = minor\n",
            "c.scene:4:1: zoom_follow = minor needs a [series] with data = minor to follow");
    REFUSED("[series a]\ndata = yk\n", "c.scene:2:1: series 'a' (data = yk) needs 'k'");
    REFUSED("[panel a]\n", "c.scene:1:1: [panel a] needs 'scene = \"FILE\"'");
    REFUSED("[figure]\ncolumns = 2\n[panel a]\nscene = \"a.scene\"\n[panel b]\nscene = \"a.scene\"\n[panel c]\nscene = \"a.scene\"\n",
            "c.scene:2:1: columns = 2 does not divide the 3 panels into full rows");
    REFUSED("[series a]\ndata = input\n[controls]\nmain = \"model.kind\"\n",
            "c.scene:4:1: main: 'model.kind' is not a numeric key of [model], [input], [compute] or a [series NAME], "
            "written as for --set (model.sigma0, series.NAME.gamma)");
}

/* Both docs the same, section by section (decoded from one scene state, the
 * structs are equal byte for byte: both start zeroed). */
static int same_doc(const hy_scene_doc *a, const hy_scene_doc *b)
{
    int same = 1;
#define ONE(sec) same &= !memcmp(&a->sec, &b->sec, sizeof a->sec);
    HY_DOC_UNNAMED(ONE)
#undef ONE
#define NAMED(sec) same &= a->n##sec == b->n##sec && (!a->n##sec || !memcmp(a->sec, b->sec, a->n##sec * sizeof *a->sec));
    HY_DOC_NAMED(NAMED)
#undef NAMED
    return same;
}

/* A sweep's point: the scene marked and decoded once, then overrides (one
 * of them a parameter that two series read) and hy_scene_decode_marked,
 * which decodes only what changed: equal to decoding the whole scene (an
 * override of a section the file lacks makes it: the whole is decoded); the
 * checks still run. */
static void marked(void)
{
    static const char *text = "[model]\nkind = dahl\nsigma0 = 3\n[series t20]\ndata = transient\ngamma = $g\n"
                              "[series g20]\ndata = ygamma\ngamma = $g\n[series y]\ndata = ystar\n"
                              "[param g]\nvalue = 20\n[figure]\nzoom_x = 0, 1\nzoom_y = 0, 1\n";
    hy_error err = {0, ""};
    hy_scene *s = PARSE_OK("k.scene", text);
    if (!s)
        return;
    hy_scene_doc base, full, part;
    CHECK(hy_scene_mark(s) == HY_OK && hy_scene_decode(s, &base, &err) == HY_OK);
    static const char *const sets[][2] = {{"model.sigma0=7", NULL},
                                          {"param.g.value=35.5", "series.y.color=#ff0000"},
                                          {"figure.zoom_x=0.25, 0.5", "input.period=3"},
                                          {"series.g20.gamma=4", "compute.points=500"}};
    for (size_t i = 0; i < sizeof sets / sizeof sets[0]; i++) {
        hy_scene_restore(s);
        for (size_t k = 0; k < 2 && sets[i][k]; k++)
            CHECK(hy_scene_set(s, sets[i][k], &err) == HY_OK);
        CHECK(hy_scene_decode(s, &full, &err) == HY_OK);
        CHECK(hy_scene_decode_marked(s, &base, &part, &err) == HY_OK);
        CHECK(same_doc(&full, &part));
        CHECK(!same_doc(&base, &part)); /* the override is seen */
        hy_scene_doc_free(&full);
        hy_scene_doc_free(&part);
    }
    /* the checks run on the changed doc: the inset's zoom_y taken away is refused */
    hy_scene_restore(s);
    CHECK(hy_scene_set(s, "figure.zoom_follow=minor", &err) == HY_OK);
    CHECK(hy_scene_decode_marked(s, &base, &part, &err) == HY_EINVAL);
    CHECK(strstr(err.msg, "zoom_follow = minor needs a [series] with data = minor") != NULL);
    hy_scene_doc_free(&part);
    hy_scene_doc_free(&base);
    hy_scene_free(s);
}

int main(void)
{
    table();
    values();
    own_rows();
    cross();
    marked();
    return st_done("test_scene_decode");
}
