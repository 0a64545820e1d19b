/* SPDX-License-Identifier: MIT */
/* figures.c: four fixed figures (gamma sweep, loop with annotations, log-log panels, markup) for render tests. */
#include "figures.h"

#include <math.h>
#include <string.h>

#define N 401

static double t[N], ys[N], yg1[N], yg10[N], yg100[N];
static double lu[N], ly[N];
static double cost[3][6], errv[3][6], gam[12], gerr[12];

/* Triangle input of period 2 and a rate-independent-looking response. */
static void gamma_data(void)
{
    for (int i = 0; i < N; i++) {
        t[i] = 6.0 * i / (N - 1);
        double ph = fmod(t[i], 2.0), u = ph < 1.0 ? ph : 2.0 - ph;
        ys[i] = (ph < 1.0 ? 1.0 : -1.0) * (1.0 - exp(-3.0 * (ph < 1.0 ? ph : ph - 1.0))) * 0.8 + 0.2 * u;
        yg1[i] = ys[i] * (1.0 - exp(-0.7 * t[i])) - 0.3 * exp(-t[i]) * sin(3 * t[i]);
        yg10[i] = ys[i] * (1.0 - exp(-3.0 * t[i]));
        yg100[i] = ys[i] * (1.0 - exp(-12.0 * t[i]));
    }
}

static const char *fig_gamma(hy_figure *fig)
{
    static hy_series s[4];
    static hy_axes ax;
    gamma_data();
    memset(s, 0, sizeof s);
    memset(&ax, 0, sizeof ax);
    const double *y[4] = {yg1, yg10, yg100, ys};
    static const char *lab[4] = {"\\gamma = 1", "\\gamma = 10", "\\gamma = 100", "y^*_u(t)"};
    static const int sty[4] = {HY_LINE_DASHED, HY_LINE_DASHDOT, HY_LINE_DOTTED, HY_LINE_SOLID};
    static const int col[4] = {6, 5, 3, 0};
    for (int i = 0; i < 4; i++)
        s[i] = (hy_series){.x = t, .y = y[i], .n = N, .style = sty[i], .colour = {.palette = col[i]},
                           .width = i == 3 ? 1.2 : 1.0, .label = lab[i]};
    ax = (hy_axes){.series = s, .nseries = 4, .xlabel = "t", .ylabel = "y_\\gamma(t)", .x = {.tight = 1},
                   .legend = HY_LEGEND_BEST, .band = 1, .band_lo = 2.0, .band_hi = 4.0};
    *fig = (hy_figure){.width = hy_cm(8.5), .height = hy_cm(6.0), .dpi = 150, .axes = &ax,
                       .nrows = 1, .ncols = 1};
    return "gamma";
}

static const char *fig_loop(hy_figure *fig)
{
    static hy_series s[1];
    static hy_axes ax;
    static hy_mark mk[3];
    static hy_text tx[2];
    /* A major loop with a minor lobe: u bimodal, y lagging. */
    for (int i = 0; i < N; i++) {
        double th = 2 * M_PI * i / (N - 1);
        lu[i] = 0.75 - 0.75 * cos(th) + 0.25 * sin(2 * th);
        ly[i] = 6.0 * (0.6 * sin(th) + 0.3 * (1 - cos(th)) - 0.5 + 0.1 * sin(3 * th));
    }
    memset(&ax, 0, sizeof ax);
    s[0] = (hy_series){.x = lu, .y = ly, .n = N, .colour = {.palette = 0}, .width = 1.0,
                       .label = "y^\\circ_u"};
    mk[0] = (hy_mark){.x = lu[0], .y = ly[0], .marker = HY_MARKER_CIRCLE, .filled = 1,
                      .colour = {.palette = 6}};
    mk[1] = (hy_mark){.x = lu[N / 2], .y = ly[N / 2], .marker = HY_MARKER_SQUARE, .size = 5,
                      .colour = {.palette = 5}};
    mk[2] = (hy_mark){.x = lu[N / 4], .y = ly[N / 4], .marker = HY_MARKER_CIRCLE,
                      .colour = {.palette = HY_RGB_EXPLICIT, .rgb = {0.4, 0.4, 0.4}}};
    tx[0] = (hy_text){.x = 0.75, .y = -0.5, .text = "area = 0.123", .anchor = HY_ANCHOR_CENTER};
    tx[1] = (hy_text){.x = lu[N / 2], .y = ly[N / 2], .text = "\\varrho_2", .dx = 4, .dy = 3};
    ax = (hy_axes){.series = s, .nseries = 1, .marks = mk, .nmarks = 3, .texts = tx, .ntexts = 2,
                   .xlabel = "\\psi_u(\\varrho)", .ylabel = "y^\\circ(\\varrho)",
                   .title = "\\sigma_0 = 6", .legend = HY_LEGEND_TOP_LEFT};
    *fig = (hy_figure){.width = hy_cm(7.0), .height = hy_cm(6.0), .dpi = 150, .axes = &ax,
                       .nrows = 1, .ncols = 1};
    return "loop";
}

static const char *fig_loglog(hy_figure *fig)
{
    static hy_series s[5];
    static hy_axes ax[2];
    static const char *names[3] = {"exact", "rk45", "bdf"};
    for (int m = 0; m < 3; m++)
        for (int k = 0; k < 6; k++) {
            cost[m][k] = 1e-4 * pow(10.0, 0.6 * k) * (1 + m);
            errv[m][k] = pow(10.0, -2.0 - (m + 1) * 1.1 * k);
        }
    for (int k = 0; k < 12; k++) {
        gam[k] = pow(10.0, 0.3 * k);
        gerr[k] = 0.8 / (1.0 + gam[k]);
    }
    memset(s, 0, sizeof s);
    for (int m = 0; m < 3; m++)
        s[m] = (hy_series){.x = cost[m], .y = errv[m], .n = 6, .style = m, .colour = {.palette = m * 2 + 1},
                           .marker = m == 1 ? HY_MARKER_SQUARE : HY_MARKER_CIRCLE,
                           .marker_filled = m == 0, .label = names[m]};
    s[3] = (hy_series){.x = gam, .y = gerr, .n = 12, .style = HY_LINE_SOLID,
                       .marker = HY_MARKER_SQUARE, .marker_size = 3.5, .colour = {.palette = 5}};
    ax[0] = (hy_axes){.series = s, .nseries = 3, .xlabel = "CPU time (s)", .ylabel = "max error",
                      .x = {.log = 1}, .y = {.log = 1}, .legend = HY_LEGEND_BEST, .grid = 1};
    ax[1] = (hy_axes){.series = &s[3], .nseries = 1, .xlabel = "\\gamma",
                      .ylabel = "\\|y_\\gamma - y^*_u\\|_\\infty", .x = {.log = 1},
                      .y = {.lo = 0.0, .hi = 0.45}, .grid = 1};
    *fig = (hy_figure){.width = hy_cm(14.0), .height = hy_cm(5.5), .dpi = 150, .axes = ax,
                       .nrows = 1, .ncols = 2};
    return "loglog";
}

/* Two stacked panels: the paper's labels as text, and a bimodal input with
 * wider tick labels (the frames must still align). */
static const char *fig_markup(hy_figure *fig)
{
    static hy_axes ax[2];
    static hy_text tx[6];
    static hy_series s;
    static double ut[6] = {0, 1, 1.8, 3.1, 4.6, 5.6}, uu[6] = {0, 1000, 200, 1500, 0, 1000};
    static const char *lab[6] = {"y^\\circ_u", "y^*_{u,k}(t)", "\\sigma_0 = 6", "\\psi_u(\\varrho)",
                                 "\\|y_\\gamma - y^*_u\\|_\\infty", "g(v)"};
    for (int i = 0; i < 6; i++)
        tx[i] = (hy_text){.x = 0.1 + 0.45 * (i % 2), .y = 2.6 - i / 2, .text = lab[i]};
    s = (hy_series){.x = ut, .y = uu, .n = 6, .marker = HY_MARKER_CIRCLE, .marker_filled = 1,
                    .colour = {.palette = 5}, .label = "u_{\\min,2} = 200"};
    ax[0] = (hy_axes){.texts = tx, .ntexts = 6, .x = {.lo = 0, .hi = 1}, .y = {.lo = 0, .hi = 3},
                      .xlabel = "u_{\\min,2} - u_{\\min,1}", .ylabel = "F_s"};
    ax[1] = (hy_axes){.series = &s, .nseries = 1, .xlabel = "t", .ylabel = "u(t)",
                      .legend = HY_LEGEND_BEST, .band = 1, .band_lo = 0.0, .band_hi = 4.6};
    *fig = (hy_figure){.width = hy_cm(8.0), .height = hy_cm(10.0), .dpi = 150, .font_size = 10,
                       .axes = ax, .nrows = 2, .ncols = 1};
    return "markup";
}

const char *fig_build(int i, hy_figure *fig)
{
    switch (i) {
    case 0: return fig_gamma(fig);
    case 1: return fig_loop(fig);
    case 2: return fig_loglog(fig);
    default: return fig_markup(fig);
    }
}
