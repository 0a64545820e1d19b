/* SPDX-License-Identifier: MIT */
/* hy_figure_names.h: the names of a figure's looks, one table per fact, for
 * the scene schema (src/scene) and the renderer (src/render), two floors that
 * do not include each other: this header sits below both, in the core, and
 * includes nothing.
 *
 * Each HY_<FACT>(X) calls X(ID, "name") once per value, in the order of the
 * values: the renderer's enums (HY_LINE_<ID> in hy_plot.h, HY_EASE_<ID> in
 * hy_anim.h, ...) and the schema's enum strings are generated from it, so the
 * scene's value and the renderer's number cannot drift:
 *
 *     #define NAME(id, name) name,
 *     static const char *const styles[] = {HY_LINE_STYLES(NAME) NULL};
 *     enum { HY_LINE_STYLES(HY_NAMES_ENUM_LINE) HY_LINE_COUNT };
 *
 * tests/render/test_names.c round-trips every value through its name and the
 * schema's list.
 */
#ifndef HY_FIGURE_NAMES_H
#define HY_FIGURE_NAMES_H

/* [series] style: the stroke's dash pattern (none: markers alone). */
#define HY_LINE_STYLES(X)   \
    X(SOLID, "solid")       \
    X(DASHED, "dashed")     \
    X(DOTTED, "dotted")     \
    X(DASHDOT, "dashdot")   \
    X(NONE, "none")

/* [series] marker. */
#define HY_MARKERS(X)       \
    X(NONE, "none")         \
    X(CIRCLE, "circle")     \
    X(SQUARE, "square")

/* [figure] legend: where the legend goes. */
#define HY_LEGEND_PLACES(X)            \
    X(NONE, "none")                    \
    X(BEST, "best")                    \
    X(TOP_LEFT, "top-left")            \
    X(TOP_RIGHT, "top-right")          \
    X(BOTTOM_LEFT, "bottom-left")      \
    X(BOTTOM_RIGHT, "bottom-right")

/* [figure] theme: paper (black on white) or slides (light on dark, lines
 * twice as thick, text 1.4 times as large; for a projector). */
#define HY_THEMES(X)        \
    X(PAPER, "paper")       \
    X(SLIDES, "slides")

/* [animation] and [keyframe] easing: linear or smoothstep. */
#define HY_EASINGS(X)       \
    X(LINEAR, "linear")     \
    X(SMOOTH, "smooth")

/* An X that gives the name, then a comma: {HY_MARKERS(HY_NAME_OF) NULL}. */
#define HY_NAME_OF(id, name) name,
/* An X that counts: (0 HY_MARKERS(HY_COUNT_OF)) is the number of markers. */
#define HY_COUNT_OF(id, name) +1

#endif
