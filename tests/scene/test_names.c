/* SPDX-License-Identifier: MIT */
/* test_names.c: the X-macro tables and their lists cannot drift (issue 34,
 * item 3).  Every value of each table goes through its name and the schema's
 * enum list for the key it feeds, both ways: index i of the schema's list is
 * the renderer's (or pipeline's) value i, the list has as many names as the
 * enum has values, and no name is written twice.  The counts are also held
 * at compile time (static asserts). */
#include "scene_test.h"

#include "hy_anim.h"
#include "hy_figure_names.h"
#include "hy_formats.h"
#include "hy_ode.h"
#include "hy_plot.h"
#include "hy_scene_schema.h"

#define COUNT2(id, name) +1
#define COUNT3(id, name, more) +1
_Static_assert((0 HY_LINE_STYLES(COUNT2)) == HY_LINE_COUNT, "line styles: table and enum");
_Static_assert((0 HY_MARKERS(COUNT2)) == HY_MARKER_COUNT, "markers: table and enum");
_Static_assert((0 HY_LEGEND_PLACES(COUNT2)) == HY_LEGEND_COUNT, "legend places: table and enum");
_Static_assert((0 HY_THEMES(COUNT2)) == HY_THEME_COUNT, "themes: table and enum");
_Static_assert((0 HY_EASINGS(COUNT2)) == HY_EASE_COUNT, "easings: table and enum");
_Static_assert((0 HY_INPUT_KINDS(COUNT3)) == HY_INPUT_KIND_COUNT, "input kinds: table and enum");
_Static_assert((0 HY_FIGURE_FORMATS(COUNT3)) == HY_FORMAT_COUNT, "formats: table and enum");
/* values used by name in the code keep their meaning */
_Static_assert(HY_LINE_SOLID == 0 && HY_MARKER_NONE == 0 && HY_LEGEND_NONE == 0, "0 is the default look");
_Static_assert(HY_THEME_PAPER == 0 && HY_EASE_LINEAR == 0, "0 is the default look");

/* The schema's enum list of [sec] key, or NULL (a failed check). */
static const char *const *schema_enums(const char *sec, const char *key)
{
    size_t n;
    const hy_scene_section_spec *s = hy_scene_schema(&n);
    int i = hy_scene_schema_section(sec);
    int k = i < 0 ? -1 : hy_scene_schema_key(i, key);
    CHECK(i >= 0 && k >= 0);
    return k < 0 ? NULL : s[i].keys[k].enums;
}

/* names[0..n) (one table, in enum order) == the schema's list for [sec] key,
 * with no name twice. */
static void check_list(const char *sec, const char *key, const char *const *names, size_t n)
{
    const char *const *e = schema_enums(sec, key);
    if (!e)
        return;
    size_t m = 0;
    while (e[m])
        m++;
    if (m != n)
        fprintf(stderr, "[%s] %s: the schema has %zu values, the table %zu\n", sec, key, m, n);
    CHECK(m == n);
    for (size_t i = 0; i < n && i < m; i++) {
        if (strcmp(e[i], names[i]))
            fprintf(stderr, "[%s] %s: value %zu is '%s' in the schema, '%s' in the table\n", sec, key, i, e[i],
                    names[i]);
        CHECK_STR(e[i], names[i]);
        for (size_t j = 0; j < i; j++)
            CHECK(strcmp(names[j], names[i]) != 0);
    }
}

#define NAME2(id, name) name,
#define NAME3(id, name, more) name,
#define N(a) (sizeof(a) / sizeof((a)[0]))

static void test_figure_names(void)
{
    /* the enum value indexes the list: [HY_LINE_DOTTED] is "dotted" */
#define AT_LINE(id, name) [HY_LINE_##id] = name,
    static const char *const lines[] = {HY_LINE_STYLES(AT_LINE)};
#define AT_MARKER(id, name) [HY_MARKER_##id] = name,
    static const char *const markers[] = {HY_MARKERS(AT_MARKER)};
#define AT_LEGEND(id, name) [HY_LEGEND_##id] = name,
    static const char *const legends[] = {HY_LEGEND_PLACES(AT_LEGEND)};
#define AT_THEME(id, name) [HY_THEME_##id] = name,
    static const char *const themes[] = {HY_THEMES(AT_THEME)};
#define AT_EASE(id, name) [HY_EASE_##id] = name,
    static const char *const easings[] = {HY_EASINGS(AT_EASE)};
    check_list("series", "style", lines, N(lines));
    check_list("series", "marker", markers, N(markers));
    check_list("figure", "legend", legends, N(legends));
    check_list("figure", "theme", themes, N(themes));
    check_list("animation", "easing", easings, N(easings));
    check_list("keyframe", "easing", easings, N(easings));
    CHECK_STR(lines[HY_LINE_DASHDOT], "dashdot");
    CHECK_STR(legends[HY_LEGEND_BOTTOM_RIGHT], "bottom-right");
    CHECK_STR(easings[HY_EASE_SMOOTH], "smooth");
}

static void test_inputs_formats(void)
{
#define AT_INPUT(id, name, takers) [HY_INPUT_##id] = name,
    static const char *const inputs[] = {HY_INPUT_KINDS(AT_INPUT)};
    check_list("input", "kind", inputs, N(inputs));
    CHECK_STR(inputs[HY_INPUT_SWEEP], "sweep");
    CHECK(hy_input_kind_takers(HY_INPUT_SINE) == HY_INPUT_ALL);
    CHECK(hy_input_kind_takers(HY_INPUT_SWEEP) == HY_INPUT_BOUCWEN);
    CHECK(hy_input_kind_takers(HY_INPUT_BIMODAL) == HY_INPUT_OTHERS);
    CHECK(hy_input_kind_takers(HY_INPUT_KIND_COUNT) == 0 && hy_input_kind_takers(-1) == 0);
#define AT_FORMAT(id, ext, mime) [HY_FORMAT_##id] = ext,
    static const char *const formats[] = {HY_FIGURE_FORMATS(AT_FORMAT)};
    check_list("output", "formats", formats, N(formats));
    static const char *const mime[] = {HY_FIGURE_FORMATS(HY_FORMAT_MIME)};
    CHECK(N(mime) == HY_FORMAT_COUNT);
    CHECK_STR(mime[HY_FORMAT_PNG], "image/png");
}

/* The schema's solvers: "exact", then every stepper of hy_ode.h once, each at
 * its place; hy_ode_stepper_names() is the table in its own order. */
static void test_solvers(void)
{
#define NAME_S(name, kind, order, place) #name,
    static const char *const table[] = {HY_ODE_STEPPERS(NAME_S)};
#define PLACE_S(name, kind, order, place) place,
    static const int place[] = {HY_ODE_STEPPERS(PLACE_S)};
    const char *const *e = schema_enums("compute", "solver");
    const char *const *s = hy_ode_stepper_names();
    if (!e)
        return;
    size_t m = 0;
    while (e[m])
        m++;
    CHECK(m == N(table) + 1);
    CHECK_STR(e[0], "exact");
    for (size_t i = 0; i < N(table); i++) {
        CHECK(place[i] >= 1 && (size_t)place[i] < m + (m == 0));
        if (place[i] >= 1 && (size_t)place[i] < m)
            CHECK_STR(e[place[i]], table[i]);
        CHECK_STR(s[i], table[i]);
        CHECK(hy_ode_stepper_known(table[i]));
    }
    CHECK(s[N(table)] == NULL);
    CHECK(!hy_ode_stepper_known("exact"));
}

int main(void)
{
    test_figure_names();
    test_inputs_formats();
    test_solvers();
    return st_done("test_names");
}
