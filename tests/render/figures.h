/* SPDX-License-Identifier: MIT */
/* figures.h: fixed test figures shared by the render tests and the demo (not a public API). */
#ifndef HY_TEST_FIGURES_H
#define HY_TEST_FIGURES_H

#include "hy_plot.h"

#define FIG_COUNT 4

/* Fills fig with test figure i (0 <= i < FIG_COUNT) and returns its name;
 * the data live in static storage, so the figure stays valid. */
const char *fig_build(int i, hy_figure *fig);

#endif
