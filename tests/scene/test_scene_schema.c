/* SPDX-License-Identifier: MIT */
/* test_scene_schema.c: consistency of the schema table: names, kinds, ranges, defaults, lookups. */
#include "hy_scene.h" /* first: the public header compiles on its own */

#include <ctype.h>

#include "scene_test.h"

static int is_key_name(const char *s)
{
    if (!islower((unsigned char)*s))
        return 0;
    for (; *s; s++)
        if (!islower((unsigned char)*s) && !isdigit((unsigned char)*s) && *s != '_')
            return 0;
    return 1;
}

/* Reads the default of k through the typed getter matching its kind. */
static int get_any(const hy_scene *s, const char *sec, const char *name, const hy_scene_key_spec *k)
{
    double d, p[2];
    long l;
    int b, a;
    const char *t;
    const double *v;
    size_t n;
    hy_scene_color c;
    switch (k->kind) {
    case HY_KIND_NUMBER: return hy_scene_get_num(s, sec, name, k->name, &d);
    case HY_KIND_INTEGER: return hy_scene_get_int(s, sec, name, k->name, &l);
    case HY_KIND_BOOL: return hy_scene_get_bool(s, sec, name, k->name, &b);
    case HY_KIND_ENUM: return hy_scene_get_enum(s, sec, name, k->name, &b, &t);
    case HY_KIND_STRING:
    case HY_KIND_NAME:
    case HY_KIND_PATH: return hy_scene_get_str(s, sec, name, k->name, &t);
    case HY_KIND_NUMBER_LIST:
    case HY_KIND_INTEGER_LIST: return hy_scene_get_list(s, sec, name, k->name, &v, &n);
    case HY_KIND_ENUM_LIST: return hy_scene_get_enum_at(s, sec, name, k->name, 0, &t, &n);
    case HY_KIND_LENGTH: return hy_scene_get_length_pt(s, sec, name, k->name, &d);
    case HY_KIND_LENGTH_PAIR: return hy_scene_get_length_pair_pt(s, sec, name, k->name, p);
    case HY_KIND_COLOR: return hy_scene_get_color(s, sec, name, k->name, &c);
    case HY_KIND_PAIR:
    case HY_KIND_LIMITS: return hy_scene_get_pair(s, sec, name, k->name, p, &a);
    }
    return HY_SCENE_BADKEY;
}

int main(void)
{
    size_t n;
    const hy_scene_section_spec *sec = hy_scene_schema(&n);
    hy_scene *s = PARSE_OK("empty.scene", ""); /* parses every schema default */
    CHECK(s != NULL);
    CHECK(n >= 8);
    for (size_t i = 0; i < n; i++) {
        CHECK(is_key_name(sec[i].name));
        CHECK(sec[i].doc && sec[i].doc[0]);
        CHECK(hy_scene_schema_section(sec[i].name) == (int)i);
        CHECK(!sec[i].repeatable || sec[i].takes_name);
        CHECK(sec[i].nkeys > 0);
        for (size_t j = 0; j < sec[i].nkeys; j++) {
            const hy_scene_key_spec *k = &sec[i].keys[j];
            int is_enum = k->kind == HY_KIND_ENUM || k->kind == HY_KIND_ENUM_LIST;
            int numeric = k->kind == HY_KIND_NUMBER || k->kind == HY_KIND_INTEGER ||
                          k->kind == HY_KIND_NUMBER_LIST || k->kind == HY_KIND_INTEGER_LIST ||
                          k->kind == HY_KIND_LENGTH || k->kind == HY_KIND_LENGTH_PAIR;
            int list = k->kind == HY_KIND_NUMBER_LIST || k->kind == HY_KIND_INTEGER_LIST ||
                       k->kind == HY_KIND_ENUM_LIST;
            /* a key hystviz serve may show as a slider (a number or integer of
               the sections serve_util.c's sv_controls_json reads) is labelled
               with its symbol as the papers print it */
            static const char *const ctl_secs[] = {"model", "input", "compute", "series"};
            int ctl = 0;
            for (size_t c = 0; c < sizeof ctl_secs / sizeof ctl_secs[0]; c++)
                ctl |= !strcmp(sec[i].name, ctl_secs[c]) && (k->kind == HY_KIND_NUMBER || k->kind == HY_KIND_INTEGER);
            if (ctl && (!k->symbol || !k->symbol[0]))
                fprintf(stderr, "%s.%s: a numeric key with a control has no symbol\n", sec[i].name, k->name);
            CHECK(!ctl || (k->symbol && k->symbol[0]));
            if (!is_key_name(k->name) || !k->doc || !k->doc[0])
                fprintf(stderr, "bad name or doc: %s.%s\n", sec[i].name, k->name);
            CHECK(is_key_name(k->name) && k->doc && k->doc[0]);
            CHECK(hy_scene_schema_key((int)i, k->name) == (int)j); /* unique in its section */
            CHECK(is_enum == (k->enums != NULL));
            CHECK(!is_enum || (k->enums[0] && k->enums[1]));
            CHECK(numeric || (k->flags & (HY_SPEC_MIN | HY_SPEC_MAX)) == 0);
            CHECK(!((k->flags & HY_SPEC_MIN) && (k->flags & HY_SPEC_MAX)) || k->min < k->max);
            CHECK(list || (k->min_len == 0 && k->max_len == 0 && !(k->flags & HY_SPEC_EVEN)));
            CHECK(!k->max_len || k->min_len <= k->max_len);
            const char *name = sec[i].takes_name ? "any" : NULL;
            int rc = get_any(s, sec[i].name, name, k);
            if (rc != (k->def ? HY_SCENE_DEFAULT : HY_SCENE_ABSENT))
                fprintf(stderr, "%s.%s: getter returned %d\n", sec[i].name, k->name, rc);
            CHECK(rc == (k->def ? HY_SCENE_DEFAULT : HY_SCENE_ABSENT));
        }
    }
    CHECK(hy_scene_schema_section("nope") == -1);
    CHECK(hy_scene_schema_key(-1, "kind") == -1);
    CHECK(hy_scene_schema_key(0, "nope") == -1);
    CHECK_STR(hy_scene_kind_name(HY_KIND_LIMITS), "limits");
    hy_scene_free(s);
    return st_result("test_scene_schema");
}
