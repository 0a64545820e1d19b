/* SPDX-License-Identifier: MIT */
/* sweep_plot.h: the summary figure of a sweep: one table column against the
 * first grid key, one curve per value of the second (issue 13). */
#ifndef HY_SWEEP_PLOT_H
#define HY_SWEEP_PLOT_H

#include "hy_status.h"

/* Reads DIR/sweep.csv and writes DIR/sweep_COLUMN.svg and .png: COLUMN
 * against the first grid key (log axis when its values span a factor of 100
 * or more), a curve per value of the second grid key if there is one (a
 * legend for up to 8 curves), empty or non-numeric values as gaps.  HY_EINVAL
 * naming the column for an unknown column or a non-numeric first key;
 * HY_EIO/HY_ENOMEM otherwise.  The figure depends only on the table. */
int hy_sweep_plot(const char *dir, const char *column, hy_error *err);

#endif
