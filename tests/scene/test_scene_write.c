/* SPDX-License-Identifier: MIT */
/* test_scene_write.c: hy_scene_write round trip: the written effective scene parses back to the same values. */
#include "scene_test.h"

static const char *text =
    "[model]\nkind = dahl\nsigma0 = 0.1\nrho = 3.25e-7\n"
    "[input]\nkind = pwl\npoints = 0, 0, 1, 1.5, 2, 0\nfile = \"/abs/u.txt\"\n"
    "[compute]\ngamma = 1, 10, 100\nk = 0, 2\ntspan = -1, 4.6\n"
    "[figure]\nxlabel = \"y^\\circ_u \\\"q\\\" \\\\\"\nylim = auto\nxlim = 0, 1.5\nsize = 3in, 50mm\n"
    "fontsize = 24px\ngrid = true\n"
    "[series b]\ndata = ystar\ncolor = #0a0b0c\nwidth = 0.5cm\n"
    "[series a]\ndata = ygamma\ncolor = reddishpurple\nlabel = \"a # b\"\n"
    "[output]\nname = fig\nformats = png, svg\n";

/* Writes the scene into a string and drops the origin comments. */
static char *written(const hy_scene *s, int defaults)
{
    char *buf = NULL;
    size_t n = 0;
    FILE *f = open_memstream(&buf, &n);
    CHECK(f && hy_scene_write(s, f, defaults) == HY_OK);
    fclose(f);
    char *out = malloc(n + 1), *o = out;
    for (const char *p = strchr(buf, '\n') + 1; *p;) {
        const char *nl = strchr(p, '\n'), *c = strstr(p, "    # ");
        if (c && c < nl)
            o += snprintf(o, n + 1 - (size_t)(o - out), "%.*s\n", (int)(c - p), p);
        else
            o += snprintf(o, n + 1 - (size_t)(o - out), "%.*s\n", (int)(nl - p), p);
        p = nl + 1;
    }
    free(buf);
    return out;
}

int main(void)
{
    hy_scene *s = PARSE_OK("w.scene", text);
    hy_error err;
    CHECK(s && hy_scene_set(s, "series.a.style=dotted", &err) == 0);
    for (int defaults = 0; defaults < 2 && s; defaults++) {
        char *w1 = written(s, defaults);
        hy_scene *r = PARSE_OK("w2.scene", w1);
        char *w2 = r ? written(r, defaults) : NULL;
        CHECK(w2 && strcmp(w1, w2) == 0);
        if (w2 && strcmp(w1, w2) != 0)
            fprintf(stderr, "first:\n%s\nsecond:\n%s\n", w1, w2);
        if (r) {
            const char *t;
            hy_scene_color c;
            double p[2];
            CHECK(hy_scene_get_str(r, "figure", NULL, "xlabel", &t) == HY_SCENE_SET);
            CHECK_STR(t, "y^\\circ_u \"q\" \\");
            CHECK(hy_scene_get_color(r, "series", "b", "color", &c) == HY_SCENE_SET && c.index == 0);
            CHECK_NEAR(c.g, 11 / 255.0, 1e-15);
            CHECK(hy_scene_get_length_pair_pt(r, "figure", NULL, "size", p) == HY_SCENE_SET);
            CHECK_NEAR(p[1], 50 * 72 / 25.4, 1e-12);
            CHECK(hy_scene_get_enum(r, "series", "a", "style", NULL, &t) == HY_SCENE_SET);
            CHECK_STR(t, "dotted");
            CHECK_STR(hy_scene_name_at(r, "series", 0), "b");
            CHECK(hy_scene_get_enum(r, "figure", NULL, "legend", NULL, &t) ==
                  (defaults ? HY_SCENE_SET : HY_SCENE_DEFAULT));
        }
        free(w1);
        free(w2);
        hy_scene_free(r);
    }
    /* the origin comments name file and line, or the override */
    char *buf = NULL;
    size_t n = 0;
    FILE *f = open_memstream(&buf, &n);
    hy_scene_write(s, f, 0);
    fclose(f);
    CHECK(buf && strstr(buf, "sigma0 = 0.10000000000000001    # w.scene:3\n"));
    CHECK(buf && strstr(buf, "style = dotted    # --set series.a.style=dotted\n"));
    CHECK(buf && strncmp(buf, "# effective scene of w.scene\n", 29) == 0);
    free(buf);
    hy_scene_free(s);
    return st_result("test_scene_write");
}
