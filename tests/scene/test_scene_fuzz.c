/* SPDX-License-Identifier: MIT */
/* test_scene_fuzz.c: deterministic mutation fuzzing of the parser and --set: no crash, and every error is one located line. */
#include <ctype.h>

#include "scene_test.h"

static const char *corpus[] = {
    "# Fig. 15\n[model]\nkind = lugre\nsigma0 = 6\n[input]\nkind = bimodal\numin2 = 0.5\n"
    "[figure]\nkind = loop\nsize = 12cm, 9cm\nxlabel = \"u\"\nylabel = \"y^\\circ_u\"\nxlim = 0, 1.5\n"
    "[series ystar]\ndata = ystar\nstyle = solid\ncolor = #0072b2\nwidth = 1.5pt\n"
    "[output]\nname = fig15\nformats = svg, pdf, png\n",
    "[compute]\ngamma = 1, 10, 100\nk = 0, 1, 2\ntspan = 0, 4.6\n[annotation a]\ntext = \"t_1\"\nx = 1\ny = 2\n"
    "[animation]\nduration = 3\nfps = 60\nquality = 1080p60\n",
};

static unsigned long long rng = 0x2545F4914F6CDD1DULL;

static unsigned rnd(unsigned n)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (unsigned)(rng % n);
}

static void mutate(char *buf, size_t *len, size_t cap)
{
    static const char alphabet[] = "[]=\",#\\ \n\t.-+e0123456789abcdefxyzpt_";
    int edits = 1 + (int)rnd(4);
    for (int e = 0; e < edits; e++) {
        size_t at = *len ? rnd((unsigned)*len) : 0;
        switch (rnd(3)) {
        case 0:
            if (*len)
                buf[at] = alphabet[rnd(sizeof alphabet - 1)];
            break;
        case 1:
            if (*len) {
                memmove(buf + at, buf + at + 1, *len - at - 1);
                (*len)--;
            }
            break;
        default:
            if (*len + 1 < cap) {
                memmove(buf + at + 1, buf + at, *len - at);
                buf[at] = alphabet[rnd(sizeof alphabet - 1)];
                (*len)++;
            }
            break;
        }
    }
}

/* An error must read "<name>:<line>:<col>: ..." on one line (or "--set ...: ..."). */
static int well_formed(const char *msg, const char *prefix)
{
    size_t n = strlen(prefix);
    if (strncmp(msg, prefix, n) != 0 || strchr(msg, '\n'))
        return 0;
    if (prefix[0] == '-')
        return msg[n] == ':' && msg[n + 1] == ' ' && msg[n + 2];
    const char *p = msg + n;
    if (*p++ != ':' || !isdigit((unsigned char)*p))
        return 0;
    while (isdigit((unsigned char)*p))
        p++;
    if (*p++ != ':' || !isdigit((unsigned char)*p))
        return 0;
    while (isdigit((unsigned char)*p))
        p++;
    return p[0] == ':' && p[1] == ' ' && p[2];
}

/* Reads every key of every section through the getters (must not crash). */
static void read_all(const hy_scene *s)
{
    size_t n;
    const hy_scene_section_spec *sec = hy_scene_schema(&n);
    for (size_t i = 0; i < n; i++) {
        size_t count = hy_scene_count(s, sec[i].name);
        for (size_t c = 0; c < (count ? count : 1); c++) {
            const char *name = sec[i].takes_name ? hy_scene_name_at(s, sec[i].name, c) : NULL;
            if (sec[i].takes_name && !name)
                continue;
            for (size_t j = 0; j < sec[i].nkeys; j++) {
                double d, p[2];
                const double *v;
                const char *t;
                size_t m;
                hy_scene_color col;
                hy_scene_loc loc;
                int a;
                hy_scene_get_num(s, sec[i].name, name, sec[i].keys[j].name, &d);
                hy_scene_get_str(s, sec[i].name, name, sec[i].keys[j].name, &t);
                hy_scene_get_list(s, sec[i].name, name, sec[i].keys[j].name, &v, &m);
                hy_scene_get_pair(s, sec[i].name, name, sec[i].keys[j].name, p, &a);
                hy_scene_get_color(s, sec[i].name, name, sec[i].keys[j].name, &col);
                hy_scene_get_length_pt(s, sec[i].name, name, sec[i].keys[j].name, &d);
                hy_scene_get_enum(s, sec[i].name, name, sec[i].keys[j].name, &a, &t);
                hy_scene_get_loc(s, sec[i].name, name, sec[i].keys[j].name, &loc);
            }
        }
    }
}

int main(void)
{
    enum { ROUNDS = 4000, CAP = 2048 };
    char buf[CAP];
    int ok = 0, bad = 0;
    for (int r = 0; r < ROUNDS; r++) {
        const char *src = corpus[r % 2];
        size_t len = strlen(src);
        memcpy(buf, src, len);
        mutate(buf, &len, CAP);
        hy_scene *s = NULL;
        hy_error err = {0, ""};
        if (hy_scene_parse_buffer("fz.scene", buf, len, &s, &err) == 0) {
            ok++;
            read_all(s);
            /* a line of the mutated text as an override */
            char set[128];
            size_t at = rnd((unsigned)len), k = 0;
            snprintf(set, sizeof set, "model.");
            k = strlen(set);
            while (at < len && buf[at] != '\n' && k + 1 < sizeof set)
                set[k++] = buf[at++];
            set[k] = '\0';
            char prefix[sizeof err.msg];
            char raw[160];
            snprintf(raw, sizeof raw, "--set %s", set);
            hy_text_shown(raw, prefix, sizeof prefix); /* messages are text (issue 20 item 10) */
            if (hy_scene_set(s, set, &err) && !well_formed(err.msg, prefix)) {
                fprintf(stderr, "badly formed override error: %s\n", err.msg);
                st_failures++;
            }
            hy_scene_free(s);
        } else {
            bad++;
            CHECK(s == NULL);
            if (!well_formed(err.msg, "fz.scene")) {
                fprintf(stderr, "badly formed error: %s\n", err.msg);
                st_failures++;
            }
        }
    }
    fprintf(stderr, "%d parsed, %d rejected\n", ok, bad);
    CHECK(ok > 100 && bad > 100);
    return st_result("test_scene_fuzz");
}
