/* SPDX-License-Identifier: MIT */
/* hy_markup.h: a tiny TeX subset for plot labels, parsed into text runs.
 *
 * Supported: Greek letters (\alpha ... \omega, \varrho, \varepsilon, \vartheta,
 * \varphi and capitals), \infty \circ (°) \| (‖) \cdot \times \pm \le \ge
 * \approx \to \partial \dots, operator names (\min \max \sin \exp \log ...)
 * and \mathrm{...} / \text{...} upright, escapes \_ \^ \{ \} \\ \$, spaces \, \; \quad,
 * sub/superscripts _x ^x _{...} ^{...} (one level of nesting is kept: a
 * script inside a script is drawn at the script level).  A '-' between
 * non-letters becomes a minus sign; isolated Latin letters are set in italic.
 * Units are upright by one rule: a compound unit ("A/m", "J/m³", "kA/m")
 * anywhere, a lone one ("T", "N", "s") after a number or alone in
 * parentheses ("B (T)").  After an integral sign (∮, ∫, \oint, \int) the
 * spaces become a thin space and a word "dB" is the differential d B (d
 * upright, thin space before it): "∮ H dB" is set ∮ H d B.
 * '$' signs are ignored, so "$\sigma_0$" and "\sigma_0" are the same.
 *
 *     hy_mrun runs[HY_MARKUP_MAX]; size_t n; hy_error err;
 *     if (hy_markup_parse("y^*_{u,k}(t)", runs, HY_MARKUP_MAX, &n, &err)) ...
 *     // runs: "y" italic base, "*" sup, "u" sub stacked, ",", "k" sub, "(" ...
 */
#ifndef HY_MARKUP_H
#define HY_MARKUP_H

#include <stddef.h>

#include "hy_canvas.h"
#include "hy_status.h"

#define HY_MARKUP_MAX 64      /* runs in one label */
#define HY_MRUN_BYTES 48      /* bytes of UTF-8 in one run, with the NUL */

enum { HY_SCRIPT_BASE = 0, HY_SCRIPT_SUP = 1, HY_SCRIPT_SUB = 2 };

/* One run of text drawn with one style. */
typedef struct hy_mrun {
    char text[HY_MRUN_BYTES]; /* UTF-8 */
    int script;               /* HY_SCRIPT_* */
    int italic;
    int group;                /* script group id: a sup and a sub on the same
                                 base share it and start at the same x; 0 for base */
} hy_mrun;

/* Parses src into at most cap runs; *n receives the count.  Returns HY_EINVAL
 * with a message naming the label on unbalanced braces, an unknown command or
 * too many runs (runs and *n are then unspecified). */
int hy_markup_parse(const char *src, hy_mrun *runs, size_t cap, size_t *n, hy_error *err);

/* Label geometry at a base font size, in points. */
typedef struct hy_markup_box {
    double width;
    double ascent, descent;   /* above / below the baseline, >= 0, scripts included */
} hy_markup_box;

/* Measures (and, if draw, draws with its baseline starting at (x, y)) a
 * parsed label on cv; vertical turns it a quarter counter-clockwise.  Scripts
 * are set at 70 % size, superscripts raised 0.38 em, subscripts lowered 0.22 em.
 * Ascent/descent are typographic (0.78 / 0.24 em per run), not ink. */
void hy_markup_layout(const hy_canvas *cv, const hy_mrun *runs, size_t n, double size,
                      int draw, int vertical, double x, double y, hy_rgb colour,
                      hy_markup_box *box);

/* Writes v as label markup with at most sig significant digits, as a reader
 * expects it: whole numbers below 10^6 without decimals ("1000", not
 * "1e+03"), others in [10^-3, 10^sig) as decimals ("0.043"), the rest as
 * "m\\times10^{e}" (set as m × 10 with a raised e; "10^{e}" when m is 1).
 * Returns buf. */
char *hy_markup_number(char *buf, size_t size, double v, int sig);

/* Convenience: parse and measure/draw src; an unparsable label is drawn verbatim. */
void hy_markup_text(const hy_canvas *cv, const char *src, double size, int draw,
                    int vertical, double x, double y, hy_rgb colour, hy_markup_box *box);

#endif
