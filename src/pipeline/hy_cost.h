/* SPDX-License-Identifier: MIT */
/* hy_cost.h: the work budget's cost model (issue 36 item 1), one table.
 *
 * A scene's work estimate is Σ weight[kind] × count[kind] over the kinds of
 * work below, in units; HY_COST_UNITS_PER_S units are one second of CPU on
 * the machine that calibrated the weights.  Every estimate function of the
 * pipeline (model_friction.c, scene_run.c's raster, scene_rateind.c,
 * model_boucwen.c, scene_forc.c) counts through hy_cost():
 *
 *     *work = hy_cost(r->cost_counts, HY_COST_PREISACH, moves)
 *           + hy_cost(r->cost_counts, HY_COST_ANNOTATION, (double)na);
 *
 * r->cost_counts (NULL, or HY_COST_COUNT doubles) receives the raw counts
 * (`hystviz render --print-work` prints them; tests/bench/bench_cost.py
 * fits the weights from them and the measured CPU time).
 *
 * The weights were fitted by tests/bench/bench_cost.py (least squares of
 * log CPU time on the counts; the run below HY_COST_KINDS); that run's
 * cases, estimates and times are tests/bench/cost_cases.txt, which
 * tests/bench/test_cost.py checks the estimate against (within 3x).
 */
#ifndef HY_COST_H
#define HY_COST_H

#include <stddef.h>

/* A unit of work: 100 ns of CPU (the budgets' meaning before issue 36:
 * render's 1e8 about 10 s; serve's 5e6 about 0.5 s, every gallery figure
 * but the Bouc-Wen sinc study's 1.6e7 (five_models_minor_loops: 3.2e6)). */
#define HY_COST_UNITS_PER_S 1e7

/* X(ID, name, weight in units per count, what one count is).  The weights:
 * tests/bench/bench_cost.py --runs 5, 2026-11-27 22:10 UTC, x86-64 with 2
 * cores shared with other builds (load average 12.9-16.9 during the run),
 * release build (-O2); worst case within a factor 1.85 of the measured CPU
 * time.  A point's 2.32 holds a figure's drawing too (the friction cases are
 * the lightest per count); play's 1.2 stands for the Bouc-Wen operator too
 * (not calibrated apart). */
#define HY_COST_KINDS(X)                                                                                               \
    X(POINT, "point", 2.32, "a grid point of a Dahl/LuGre solve or a sample of one of its series")                     \
    X(NEWMARK, "newmark", 1.25, "a Newmark step of Bouc-Wen or a sample of one of its series")                        \
    X(JILES, "ja-move", 26.9, "a move of the Jiles-Atherton model (a series sample or a turning point fed)")            \
    X(PREISACH, "preisach-move", 136.0, "a move of the Preisach model (a series sample or a turning point fed)")           \
    X(PLAY, "play-move", 1.2, "a move of the play or Bouc-Wen operator (a series sample or a turning point fed)")          \
    X(FORC, "forc", 154.0, "a FORC point times its regression's weight")                                             \
    X(ANNOTATION, "annotation", 15600.0, "an annotation placed")                                                      \
    X(PIXEL, "pixel", 0.157, "a pixel of a PNG raster drawn")

#define HY__COST_ID(id, name, w, what) HY_COST_##id,
enum { HY_COST_KINDS(HY__COST_ID) HY_COST_COUNT };
#undef HY__COST_ID

/* The weight of kind k (0 <= k < HY_COST_COUNT), in units per count. */
static inline double hy_cost_weight(int k)
{
#define HY__COST_W(id, name, w, what) w,
    static const double weight[] = {HY_COST_KINDS(HY__COST_W)};
#undef HY__COST_W
    return weight[k];
}

/* The name of kind k ("point", ...; --print-work, the benchmark). */
static inline const char *hy_cost_name(int k)
{
#define HY__COST_N(id, name, w, what) name,
    static const char *const names[] = {HY_COST_KINDS(HY__COST_N)};
#undef HY__COST_N
    return names[k];
}

/* n counts of kind k in units; adds n to counts[k] when counts is not NULL. */
static inline double hy_cost(double *counts, int k, double n)
{
    if (counts)
        counts[k] += n;
    return hy_cost_weight(k) * n;
}

#endif
