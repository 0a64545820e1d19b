/* SPDX-License-Identifier: MIT */
/* hy_scene_schema.c: the scene vocabulary, one static table (models and inputs of seed 000,
 * Sections 2-4; the Bouc-Wen benchmark of seed 001, Tables 1-2 and Sections 4-5). */
#include "hy_scene_schema.h"
#include "hy_scene_decl.h"
#include "hy_scene_model_rows.h"

#include "hy_figure_names.h"
#include "hy_formats.h"
#include "hy_ode.h"
#include "hy_quality.h"

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* NOLIM, POS and NONNEG stand for the three fields flags, min, max; K expands
 * them before splitting its arguments. */
#define NOLIM 0u, 0.0, 0.0
#define POS (HY_SPEC_MIN | HY_SPEC_MIN_EXCL), 0.0, 0.0
#define NONNEG HY_SPEC_MIN, 0.0, 0.0
#define POS_G (HY_SPEC_MIN | HY_SPEC_MIN_EXCL | HY_SPEC_G), 0.0, 0.0 /* POS, and read by g(v) */
#define K(...) K_(__VA_ARGS__)
#define K_(name, kind, enums, flags, lo, hi, nmin, nmax, def, doc) \
    { name, kind, enums, flags, lo, hi, nmin, nmax, def, doc, NULL, NULL, 0, HY_CTYPE_NONE, NULL, HY_SCENE_NO_DOMAIN }
/* KQ: a quantity's key, its symbol and unit first (see hy_scene_key_spec). */
#define KQ(sym, unit, ...) KQ_(sym, unit, __VA_ARGS__)
#define KQ_(sym, unit, name, kind, enums, flags, lo, hi, nmin, nmax, def, doc) \
    { name, kind, enums, flags, lo, hi, nmin, nmax, def, doc, sym, unit, 0, HY_CTYPE_NONE, NULL, HY_SCENE_NO_DOMAIN }
/* F and FQ: as K and KQ for a key that hy_scene_decode writes into the field
 * of the same name of the section's struct SECT (hy_scene_decl.h): the row
 * records the field's offset and C type, so the name is written once. */
#define FIELD_OF(name) offsetof(SECT, name), HY_CTYPE_OF(((SECT *)0)->name)
#define F(...) F_(__VA_ARGS__)
#define F_(name, kind, enums, flags, lo, hi, nmin, nmax, def, doc) \
    { #name, kind, enums, flags, lo, hi, nmin, nmax, def, doc, NULL, NULL, FIELD_OF(name), NULL, HY_SCENE_NO_DOMAIN }
#define FQ(sym, unit, ...) FQ_(sym, unit, __VA_ARGS__)
#define FQ_(sym, unit, name, kind, enums, flags, lo, hi, nmin, nmax, def, doc) \
    { #name, kind, enums, flags, lo, hi, nmin, nmax, def, doc, sym, unit, FIELD_OF(name), NULL, HY_SCENE_NO_DOMAIN }
/* FQD: FQ with the key's slider domain (hy_scene_domain): FQD((kind, takers,
 * above, below, per, lo, hi, work), sym, unit, ...). */
#define DOMAIN_OF(kind, takers, above, below, per, lo, hi, work) { kind, takers, above, below, per, lo, hi, work }
#define FQD(dom, sym, unit, ...) FQD_(dom, sym, unit, __VA_ARGS__)
#define FQD_(dom, sym, unit, name, kind, enums, flags, lo, hi, nmin, nmax, def, doc) \
    { #name, kind, enums, flags, lo, hi, nmin, nmax, def, doc, sym, unit, FIELD_OF(name), NULL, DOMAIN_OF dom }
/* The domains' conditions: a bimodal input's order (Definition 1: u_min,1 <=
 * u_min,2 < u_max,1 <= u_max,2), a triangle's min < max; a force's sine
 * (HY_INPUT_BOUCWEN: Newmark's period x fs whole samples); work alone. */
#define BIMODAL(above, below) ("bimodal", 0u, above, below, NULL, 0.0, 0.0, 0)
#define TRIANGLE(above, below) ("triangle", 0u, above, below, NULL, 0.0, 0.0, 0)
#define FORCE_SINE(per) ("sine", HY_INPUT_BOUCWEN, NULL, NULL, per, 0.0, 0.0, 1)
#define WORK (NULL, 0u, NULL, NULL, NULL, 0.0, 0.0, 1)
#define NKEYS(a) (sizeof(a) / sizeof((a)[0]))

#define MODEL_NAME(id, name) name,
static const char *const model_kinds[] = {HY_MODEL_KINDS(MODEL_NAME) NULL};
#define INPUT_NAME(id, name, takers) name,
static const char *const input_kinds[] = {HY_INPUT_KINDS(INPUT_NAME) NULL};
static const char *const data_starts[] = {"zero", "first", "periodic", NULL};
static const char *const input_shapes[] = {"linear", "cosine", NULL};
/* "exact", then the GSL steppers at their documented places (hy_ode.h) */
#define SOLVER_AT(name, kind, order, place) [place] = #name,
#define NSOLVERS (1 HY_ODE_STEPPERS(HY_ODE_COUNT_OF))
static const char *const solvers[NSOLVERS + 1] = {[0] = "exact", HY_ODE_STEPPERS(SOLVER_AT)[NSOLVERS] = NULL};
#define FIGURE_NAME(id, name) name,
static const char *const figure_kinds[] = {HY_FIGURE_KINDS(FIGURE_NAME) NULL};
static const char *const legends[] = {HY_LEGEND_PLACES(HY_NAME_OF) NULL};
#define DATA_NAME(id, name) name,
static const char *const series_data[] = {HY_SERIES_DATA(DATA_NAME) NULL};
static const char *const line_styles[] = {HY_LINE_STYLES(HY_NAME_OF) NULL};
#define QUANTITY_NAME(id, name, bw) name,
static const char *const bw_quantities[] = {HY_SERIES_QUANTITIES(QUANTITY_NAME) NULL};
static const char *const decimations[] = {"staged", "single", "none", NULL};
static const char *const markers[] = {HY_MARKERS(HY_NAME_OF) NULL};
static const char *const formats[] = {HY_FIGURE_FORMATS(HY_FORMAT_EXT) NULL};
static const char *const forc_draws[] = {"diagram", "curves", NULL};
static const char *const forc_protocols[] = {"regular", "file", NULL};
static const char *const themes[] = {HY_THEMES(HY_NAME_OF) NULL};
static const char *const zoom_follows[] = {"none", "minor", NULL};
static const char *const easings[] = {HY_EASINGS(HY_NAME_OF) NULL};
#define QUALITY_NAME(name, w, h, fps) name,
static const char *const qualities[] = {HY_QUALITY_PRESETS(QUALITY_NAME) NULL};

#define SECT hy_decl_model
static const hy_scene_key_spec model_keys[] = {
    F(kind, HY_KIND_ENUM, model_kinds, NOLIM, 0, 0, HY_MODEL_DEFAULT,
      "hysteresis model: Dahl, LuGre (Eq. 3), the Example-1 filter system, the Bouc-Wen benchmark oscillator, "
      "Jiles-Atherton (ferromagnetic, input H in A/m, output B in T), classical Preisach, the Bouc-Wen "
      "hysteresis operator (Eq. 3 of the benchmark driven by u), the play operator, or the Duhem model"),
    FQ("σ_0", NULL, sigma0, HY_KIND_NUMBER, NULL, POS, 0, 0, "1", "bristle stiffness sigma0 of Eq. (3)"),
    FQ("σ_1", NULL, sigma1, HY_KIND_NUMBER, NULL, NONNEG, 0, 0, "1", "micro-damping sigma1 of Eq. (3) (LuGre)"),
    FQ("σ_2", NULL, sigma2, HY_KIND_NUMBER, NULL, NONNEG, 0, 0, "0",
      "viscous friction sigma2; f(v) = sigma2 v (the paper takes f = 0)"),
    FQ("F_c", NULL, fc, HY_KIND_NUMBER, NULL, POS_G, 0, 0, "1", "Coulomb friction force Fc"),
    FQ("F_s", NULL, fs, HY_KIND_NUMBER, NULL, POS_G, 0, 0, "2", "stiction force Fs"),
    FQ("v_s", NULL, vs, HY_KIND_NUMBER, NULL, POS_G, 0, 0, "1", "Stribeck velocity vs"),
    FQ("β", NULL, beta, HY_KIND_NUMBER, NULL, POS_G, 0, 0, "1", "Stribeck exponent beta of g(v)"),
    FQ("ρ", NULL, rho, HY_KIND_NUMBER, NULL, POS_G, 0, 0, "1", "constant g of the Dahl model"),
    FQ("x_0", NULL, x0, HY_KIND_NUMBER, NULL, NOLIM, 0, 0, "0", "initial state x(0)"),
    FQ("τ", NULL, tau, HY_KIND_NUMBER, NULL, POS, 0, 0, "1", "time constant of the dahl-filter system"),
    FQ("m_L", "kg", m, HY_KIND_NUMBER, NULL, POS, 0, 0, "2", "boucwen: mass m_L in kg (Table 1)"),
    FQ("c_L", "N s/m", c, HY_KIND_NUMBER, NULL, NONNEG, 0, 0, "10", "boucwen: viscous damping c_L in N s/m"),
    FQ("k_L", "N/m", k, HY_KIND_NUMBER, NULL, NONNEG, 0, 0, "5e4", "boucwen: linear stiffness k_L in N/m"),
    FQ("α", "N/m", alpha, HY_KIND_NUMBER, NULL, NONNEG, 0, 0, "5e4",
      "boucwen, boucwen-operator: alpha of Eq. (3) in N/m (k + alpha > 0: the linearised stiffness of Table 2)"),
    FQ("β", "1/m^ν", bw_beta, HY_KIND_NUMBER, NULL, NONNEG, 0, 0, "1e3",
      "boucwen, boucwen-operator: beta of Eq. (3) in 1/m^nu; 0 gives the linear oscillator of Fig. 1(b)"),
    FQ("γ", NULL, bw_gamma, HY_KIND_NUMBER, NULL, NOLIM, 0, 0, "0.8", "boucwen, boucwen-operator: gamma of Eq. (3)"),
    FQ("δ", NULL, delta, HY_KIND_NUMBER, NULL, NOLIM, 0, 0, "-1.1", "boucwen, boucwen-operator: delta of Eq. (3)"),
    FQD((NULL, HY_INPUT_BOUCWEN, NULL, NULL, NULL, 0.5, 2.0, 0), "ν", NULL, nu, HY_KIND_NUMBER, NULL, POS, 0, 0, "1",
        "boucwen, boucwen-operator (1 only): exponent nu of Eq. (3)"),
};
#undef SECT

#define SECT hy_decl_input
static const hy_scene_key_spec input_keys[] = {
    F(kind, HY_KIND_ENUM, input_kinds, NOLIM, 0, 0, "bimodal",
      "input family: bimodal (Eq. 10), multimodal, triangle, sine, pwl, samples from a file; boucwen models take sine, multisine or sweep"),
    FQD(BIMODAL(NULL, "input.umin2"), "u_{min,1}", NULL, umin1, HY_KIND_NUMBER, NULL, NOLIM, 0, 0, "0", "bimodal input: first minimum u_min,1"),
    FQD(BIMODAL("input.umin1", "input.umax1"), "u_{min,2}", NULL, umin2, HY_KIND_NUMBER, NULL, NOLIM, 0, 0, "0.2", "bimodal input: second minimum u_min,2"),
    FQD(BIMODAL("input.umin2", "input.umax2"), "u_{max,1}", NULL, umax1, HY_KIND_NUMBER, NULL, NOLIM, 0, 0, "1", "bimodal input: first maximum u_max,1"),
    FQD(BIMODAL("input.umax1", NULL), "u_{max,2}", NULL, umax2, HY_KIND_NUMBER, NULL, NOLIM, 0, 0, "1.5", "bimodal input: second maximum u_max,2"),
    F(t, HY_KIND_NUMBER_LIST, NULL, NONNEG, 4, 4, NULL,
      "bimodal input: times t1, t2, t3, t4 of the extrema (default: normalised, t = rho)"),
    F(shape, HY_KIND_ENUM, input_shapes, NOLIM, 0, 0, "linear",
      "how a monotone piece goes from one extremum to the next"),
    F(extrema, HY_KIND_NUMBER_LIST, NULL, NOLIM, 2, 0, NULL,
      "multimodal input: the successive extrema of one period"),
    F(times, HY_KIND_NUMBER_LIST, NULL, NONNEG, 2, 0, NULL,
      "multimodal input: the times of the extrema (default: normalised)"),
    FQ("A", NULL, amp, HY_KIND_NUMBER, NULL, NONNEG, 0, 0, "1",
      "triangle or sine input: amplitude (a force in N for a boucwen model); sweep input: force in N, default 40 "
      "(the paper's sweep, as `hystviz boucwen data --signal sweep`)"),
    FQ("u_0", NULL, offset, HY_KIND_NUMBER, NULL, NOLIM, 0, 0, "0", "triangle or sine input: mean value"),
    FQD(FORCE_SINE("input.fs"), "T", "s", period, HY_KIND_NUMBER, NULL, POS, 0, 0, "2", "triangle or sine input: period T"),
    FQD(TRIANGLE(NULL, "input.max"), "u_{min}", NULL, min, HY_KIND_NUMBER, NULL, NOLIM, 0, 0, NULL,
      "triangle input: minimum (instead of amp and offset)"),
    FQD(TRIANGLE("input.min", NULL), "u_{max}", NULL, max, HY_KIND_NUMBER, NULL, NOLIM, 0, 0, NULL,
      "triangle input: maximum (instead of amp and offset)"),
    F(points, HY_KIND_NUMBER_LIST, NULL, HY_SPEC_EVEN, 0, 0, 4, 0, NULL,
      "pwl input: one period as t0, u0, t1, u1, ..."),
    F(file, HY_KIND_PATH, NULL, NOLIM, 0, 0, NULL,
      "file input: two-column text file t u, relative to the scene file"),
    FQD(FORCE_SINE("input.period"), "f_s", "Hz", fs, HY_KIND_NUMBER, NULL, POS, 0, 0, "750",
      "boucwen inputs: working sampling rate in Hz (the figures' samples; a sine needs period x fs whole)"),
    FQD(WORK, "N", NULL, samples, HY_KIND_INTEGER, NULL, HY_SPEC_MIN | HY_SPEC_MAX, 64, 10000000, 0, 0, "8192",
      "multisine input: samples per period at fs (frequency resolution fs / samples)"),
    F(band, HY_KIND_PAIR, NULL, NOLIM, 0, 0, "5, 150",
      "multisine input: excited band in Hz; sweep input: start and end frequency in Hz, default 20, 50 (the paper's)"),
    FQ("u_{RMS}", "N", rms, HY_KIND_NUMBER, NULL, NONNEG, 0, 0, "50",
      "multisine input: standard deviation (RMS) in N"),
    FQ("seed", NULL, seed, HY_KIND_INTEGER, NULL, NONNEG, 0, 0, "1", "multisine input: seed of the random phases; boucwen: also of the output noise"),
    FQ("r", "Hz/min", rate, HY_KIND_NUMBER, NULL, POS, 0, 0, "10", "sweep input: sweep rate in Hz per minute (the paper's 10)"),
    F(data, HY_KIND_NAME, NULL, NOLIM, 0, 0, NULL,
      "data input: the [data NAME] whose measured u drives the model: a rate-independent model its records in "
      "order, each from 'start' (t is the sample index); Dahl, LuGre or the filter system one record's t and u "
      "(exact solution at gamma = 1, from x0)"),
    F(start, HY_KIND_ENUM, data_starts, NOLIM, 0, 0, "zero",
      "data input: the state each record starts from: zero (the model's initial state, as its [model] keys give "
      "it, at u = 0, then along a monotone path to the record's first u: a demagnetised magnet follows its initial "
      "curve), first (that state put at the first u), periodic (the record driven over and over until it repeats)"),
};
#undef SECT

#define SECT hy_decl_compute
static const hy_scene_key_spec compute_keys[] = {
    F(gamma, HY_KIND_NUMBER_LIST, NULL, POS, 1, 0, "1, 10, 100",
      "time scales gamma for y_gamma (Figs. 4, 7, 11)"),
    F(k, HY_KIND_INTEGER_LIST, NULL, NONNEG, 1, 0, "0, 1, 2, 3",
      "periods k for `y*_{u,k}` (Figs. 8, 12, 13)"),
    FQD(WORK, "periods", NULL, cycles, HY_KIND_INTEGER, NULL, HY_SPEC_MIN | HY_SPEC_MAX, 1, 100000, 0, 0, "1",
      "number of input periods simulated"),
    F(solver, HY_KIND_ENUM, solvers, NOLIM, 0, 0, "exact",
      "integrator: exact (piecewise exponential) or a GSL odeiv2 stepper"),
    FQ("rtol", NULL, rtol, HY_KIND_NUMBER, NULL, HY_SPEC_MIN | HY_SPEC_MIN_EXCL | HY_SPEC_MAX, 0, 1, 0, 0,
      "1e-8", "relative tolerance of adaptive solvers"),
    FQ("atol", NULL, atol, HY_KIND_NUMBER, NULL, POS, 0, 0, "1e-10", "absolute tolerance of adaptive solvers"),
    F(tspan, HY_KIND_PAIR, NULL, NOLIM, 0, 0, NULL,
      "time interval computed and drawn (default: the periods simulated)"),
    FQD(WORK, "points", "per period", points, HY_KIND_INTEGER, NULL, HY_SPEC_MIN | HY_SPEC_MAX, 2, 10000000, 0, 0, "2000",
      "output samples per input period (a curve over the time span has points x periods)"),
    FQD(WORK, "settle", "periods", settle, HY_KIND_INTEGER, NULL, HY_SPEC_MIN | HY_SPEC_MAX, 0, 100000, 0, 0, "0",
      "boucwen: input periods integrated from rest and discarded before the 'cycles' drawn"),
    FQD(WORK, "upsample", NULL, upsample, HY_KIND_INTEGER, NULL, HY_SPEC_MIN | HY_SPEC_MAX, 1, 1000, 0, 0, "20",
      "boucwen: Newmark integration rate as a multiple of the input's fs (15000 Hz = 20 x 750 Hz)"),
    F(decimate, HY_KIND_ENUM, decimations, NOLIM, 0, 0, "staged",
      "boucwen: back to fs like MATLAB decimate(y, r, 'fir') in prime-factor stages or one stage, or none (keep fs x upsample)"),
    FQ("noise", "mm", noise, HY_KIND_NUMBER, NULL, NONNEG, 0, 0, "0",
      "boucwen: RMS in mm of Gaussian noise added to y, white up to half the output rate (the benchmark's data: 8e-3)"),
};
#undef SECT

#define SECT hy_decl_figure
static const hy_scene_key_spec figure_keys[] = {
    F(kind, HY_KIND_ENUM, figure_kinds, NOLIM, 0, 0, "timeseries",
      "what the axes show: signals versus t, an output-versus-input loop, u(t), g(v), psi_u"),
    F(title, HY_KIND_STRING, NULL, NOLIM, 0, 0, "\"\"", "title above the axes (empty: none)"),
    F(caption, HY_KIND_STRING, NULL, NOLIM, 0, 0, "\"\"",
      "one-line caption of what the figure shows (the gallery page and serve print it; not drawn); "
      "{section.key} or {section.NAME.key} is replaced by that key's value: \"LuGre, σ0 = {model.sigma0}\""),
    F(xlabel, HY_KIND_STRING, NULL, NOLIM, 0, 0, NULL,
      "x-axis label; TeX-like markup such as `y^\\circ_u` passes through (default: from kind)"),
    F(ylabel, HY_KIND_STRING, NULL, NOLIM, 0, 0, NULL, "y-axis label (default: from kind)"),
    F(xlim, HY_KIND_LIMITS, NULL, NOLIM, 0, 0, "auto", "x-axis range, or auto"),
    F(ylim, HY_KIND_LIMITS, NULL, NOLIM, 0, 0, "auto", "y-axis range, or auto"),
    F(xlog, HY_KIND_BOOL, NULL, NOLIM, 0, 0, "false", "logarithmic x axis"),
    F(ylog, HY_KIND_BOOL, NULL, NOLIM, 0, 0, "false", "logarithmic y axis"),
    F(size, HY_KIND_LENGTH_PAIR, NULL, POS, 0, 0, "12cm, 9cm", "width, height of the figure"),
    F(dpi, HY_KIND_INTEGER, NULL, HY_SPEC_MIN | HY_SPEC_MAX, 36, 2400, 0, 0, "300",
      "raster resolution of PNG output and of px lengths"),
    F(full_resolution, HY_KIND_BOOL, NULL, NOLIM, 0, 0, "false",
      "draw every computed point of each line (an SVG to zoom or reuse); false: lines within 0.1 px at dpi (docs/ARCHITECTURE.md)"),
    F(legend, HY_KIND_ENUM, legends, NOLIM, 0, 0, "best", "where the legend goes"),
    F(font, HY_KIND_STRING, NULL, NOLIM, 0, 0, "\"serif\"", "font family of all text"),
    F(fontsize, HY_KIND_LENGTH, NULL, POS, 0, 0, "9pt", "size of axis labels and legend text"),
    F(grid, HY_KIND_BOOL, NULL, NOLIM, 0, 0, "false", "draw grid lines at the ticks"),
    F(shade, HY_KIND_PAIR, NULL, NOLIM, 0, 0, NULL,
      "x interval highlighted in grey (e.g. the minor loop's time span)"),
    F(zoom_x, HY_KIND_PAIR, NULL, NOLIM, 0, 0, NULL,
      "x range of a zoomed inset (with zoom_y): the same curves enlarged, placed where they cover least; "
      "left out when nothing drawn falls in it at the values given or it would enlarge it less than 1.5 times"),
    F(zoom_y, HY_KIND_PAIR, NULL, NOLIM, 0, 0, NULL, "y range of the zoomed inset"),
    F(zoom_follow, HY_KIND_ENUM, zoom_follows, NOLIM, 0, 0, "none",
      "minor: the inset zooms on the minor loop's bounding box (12 % margin) whatever the parameters, "
      "in place of zoom_x and zoom_y; none: zoom_x and zoom_y"),
    F(theme, HY_KIND_ENUM, themes, NOLIM, 0, 0, "paper",
      "paper (black on white) or slides (light on dark, lines twice as thick, text 1.4 times as large: a projector)"),
    F(columns, HY_KIND_INTEGER, NULL, HY_SPEC_MIN | HY_SPEC_MAX, 1, 64, 0, 0, NULL,
      "[panel] figures: panels per row (default: all in one row); it must divide the number of panels"),
};
#undef SECT

#define SECT hy_decl_forc
static const hy_scene_key_spec forc_keys[] = {
    F(file, HY_KIND_PATH, NULL, NOLIM, 0, 0, NULL,
      "a measured FORC file (MicroMag 2900/3900 text or CSV rows H_a,H_b,M; docs/FORC.md) drawn instead of the "
      "model's protocol, relative to the scene file and below its directory"),
    F(drift, HY_KIND_BOOL, NULL, NOLIM, 0, 0, "false",
      "file: drift correction from its calibration points (each curve's M times cal(first)/cal(curve))"),
    FQ("H_{sat}", NULL, hsat, HY_KIND_NUMBER, NULL, NOLIM, 0, 0, NULL,
       "model: saturating field before each curve, in input units (default: the range's upper end + its width)"),
    F(range, HY_KIND_PAIR, NULL, NOLIM, 0, 0, "-1, 1",
      "model: the reversal fields H_a, lowest and highest, in input units (the curves' step is their span / (curves - 1))"),
    FQ("H_{b,max}", NULL, hb_max, HY_KIND_NUMBER, NULL, NOLIM, 0, 0, NULL,
       "model: where each curve ends, in input units (default: the range's upper end)"),
    FQ("N", NULL, curves, HY_KIND_INTEGER, NULL, HY_SPEC_MIN | HY_SPEC_MAX, 2, 2000, 0, 0, "100",
       "model: the number of reversal curves (the field step is the same along H_a and H_b)"),
    FQ("SF", NULL, sf, HY_KIND_NUMBER, NULL, HY_SPEC_MIN | HY_SPEC_MAX, 1, 12, 0, 0, "3",
       "smoothing factor: the regression uses the points within (SF + 1/2) steps of a node ((2 SF + 1)^2 on a "
       "regular grid)"),
    FQ("SF_0", NULL, sc0, HY_KIND_NUMBER, NULL, HY_SPEC_MIN | HY_SPEC_MAX, 1, 12, 0, 0, "2",
       "variable smoothing (with sc1): SF at H_c = 0"),
    FQ("SF_1", NULL, sc1, HY_KIND_NUMBER, NULL, HY_SPEC_MIN | HY_SPEC_MAX, 0, 12, 0, 0, "0",
       "variable smoothing: SF at the grid's largest H_c, linear in H_c from sc0 (0: off, sf for every node)"),
    F(extend, HY_KIND_BOOL, NULL, NOLIM, 0, 0, "true",
      "extend every curve below its first point at constant M (Pike 2003) so that H_c = 0 is defined"),
    FQ("ρ_{max}", NULL, vmax, HY_KIND_NUMBER, NULL, NONNEG, 0, 0, "0",
       "colour scale -vmax .. vmax in rho's unit (0: the largest |rho| beyond the extension's reach)"),
    F(field_to_tesla, HY_KIND_NUMBER, NULL, NONNEG, 0, 0, "0",
      "model: mu0 H in T per input unit (1.25663706212e-6 for A/m; 0: the axes in input units, no unit); "
      "a file's own units are used otherwise"),
    F(rho_unit, HY_KIND_STRING, NULL, NOLIM, 0, 0, "\"\"", "model: the unit of rho on the colour bar (a file: from its units)"),
    F(reproduce, HY_KIND_BOOL, NULL, NOLIM, 0, 0, "false",
      "take rho, clipped to rho >= 0, as a tabulated Preisach density and compute that model's FORCs at the data's "
      "points (its saturation output by least squares): render -v prints the RMS of M over all points"),
    F(draw, HY_KIND_ENUM, forc_draws, NOLIM, 0, 0, "diagram",
      "diagram: the heat map of rho; curves: the FORCs M(H_b), one line per curve (with reproduce, the tabulated "
      "Preisach model's dashed over them, its RMS in the legend)"),
    F(protocol, HY_KIND_ENUM, forc_protocols, NOLIM, 0, 0, "regular",
      "regular: the model's curves from range and curves (no file); file: the model run at the fields of the "
      "measured file (each curve from hsat, default the file's HSat, to its H_a, then through its H_b), its "
      "distribution drawn, the RMS of model against measured M printed (render -v) and, with draw = curves, the "
      "measured curves dashed over the model's"),
};
#undef SECT

#define SECT hy_decl_panel
static const hy_scene_key_spec panel_keys[] = {
    F(scene, HY_KIND_PATH, NULL, NOLIM, 0, 0, NULL,
      "a scene file drawn in this panel (its model, input, series, axes and annotations; relative to this file)"),
};
#undef SECT

#define SECT hy_decl_series
static const hy_scene_key_spec series_keys[] = {
    F(data, HY_KIND_ENUM, series_data, NOLIM, 0, 0, NULL, "which computed signal is drawn"),
    FQ("γ", NULL, gamma, HY_KIND_NUMBER, NULL, POS, 0, 0, NULL, "time scale of a ygamma curve"),
    FQ("k", NULL, k, HY_KIND_INTEGER, NULL, NONNEG, 0, 0, NULL, "period index of a yk curve"),
    F(style, HY_KIND_ENUM, line_styles, NOLIM, 0, 0, "solid", "line dash pattern"),
    F(color, HY_KIND_COLOR, NULL, NOLIM, 0, 0, NULL,
      "line colour (default: next Okabe-Ito colour)"),
    F(width, HY_KIND_LENGTH, NULL, POS, 0, 0, "1pt", "line width"),
    F(marker, HY_KIND_ENUM, markers, NOLIM, 0, 0, "none", "marker drawn at the point 'at'"),
    F(label, HY_KIND_STRING, NULL, NOLIM, 0, 0, NULL,
      "legend entry (default: none); {section.key} placeholders as in [figure] caption: \"\\gamma = {param.g20.value}\""),
    FQ("t", NULL, at, HY_KIND_NUMBER, NULL, NOLIM, 0, 0, NULL,
      "parameter value (e.g. t1) where the marker is placed"),
    F(quantity, HY_KIND_ENUM, bw_quantities, NOLIM, 0, 0, "output",
      "data = boucwen: y in mm, u in N, |y| in dB re 1 mm, transient y - y(last period) in dB, the last period's spectrum, "
      "the largest |y| in mm each second, or (sweep) the windowed-sinc route's largest error each second in u (N) or y (mm)"),
    FQ("y-scale", NULL, yscale, HY_KIND_NUMBER, NULL, NOLIM, 0, 0, "1",
      "factor applied to the series' y values (and its marker), e.g. 1/Ms to draw M/Ms or B/B_s normalised to saturation"),
    FQ("floor", "dB", floor, HY_KIND_NUMBER, NULL, NOLIM, 0, 0, NULL,
      "data = boucwen, dB quantities: values below it and exact zeros are drawn at this level (default: zeros leave gaps)"),
    F(of, HY_KIND_NAME, NULL, NOLIM, 0, 0, NULL,
      "data = measured: the [data NAME] drawn (its records, each a piece); data = modelled: the [data NAME] that "
      "drives the model ([input] data), the model's output at its measured inputs"),
};
#undef SECT

#define SECT hy_decl_data
static const hy_scene_key_spec data_keys[] = {
    F(file, HY_KIND_PATH, NULL, NOLIM, 0, 0, NULL,
      "measured samples: CSV or whitespace-separated text, # comments, relative to the scene file and below its "
      "directory (caps: docs/SCENES.md)"),
    F(u, HY_KIND_STRING, NULL, NOLIM, 0, 0, "\"1\"", "the input column: a header name (H_A_per_m) or a 1-based index"),
    F(y, HY_KIND_STRING, NULL, NOLIM, 0, 0, "\"2\"", "the output column: a header name (B_T) or a 1-based index"),
    F(t, HY_KIND_STRING, NULL, NOLIM, 0, 0, NULL, "the time column, if any: a header name or a 1-based index"),
    F(u_scale, HY_KIND_NUMBER, NULL, NOLIM, 0, 0, "1", "factor applied to u as read (a unit: 1e3 for kA/m to A/m); not 0"),
    F(y_scale, HY_KIND_NUMBER, NULL, NOLIM, 0, 0, "1", "factor applied to y as read (1e-3 for mT to T); not 0"),
    F(t_scale, HY_KIND_NUMBER, NULL, NOLIM, 0, 0, "1", "factor applied to t as read; not 0"),
    F(split, HY_KIND_STRING, NULL, NOLIM, 0, 0, NULL,
      "a column whose value changes from one record to the next (loop): each run of rows with one value is a "
      "record, drawn as a separate piece"),
    F(record, HY_KIND_INTEGER, NULL, NONNEG, 0, 0, "0", "the record read, 1-based in file order (0: every record)"),
};
#undef SECT

#define SECT hy_decl_annotation
static const hy_scene_key_spec annotation_keys[] = {
    F(text, HY_KIND_STRING, NULL, NOLIM, 0, 0, NULL, "text drawn at (x, y)"),
    FQ("x", NULL, x, HY_KIND_NUMBER, NULL, NOLIM, 0, 0, NULL, "x position in data coordinates"),
    FQ("y", NULL, y, HY_KIND_NUMBER, NULL, NOLIM, 0, 0, NULL, "y position in data coordinates"),
    F(point_x, HY_KIND_NUMBER, NULL, NOLIM, 0, 0, NULL,
      "x of the point the text is about: a leader line joins them (with point_y; default: none)"),
    F(point_y, HY_KIND_NUMBER, NULL, NOLIM, 0, 0, NULL, "y of that point"),
};
#undef SECT

#define SECT hy_decl_output
static const hy_scene_key_spec output_keys[] = {
    F(name, HY_KIND_NAME, NULL, NOLIM, 0, 0, NULL,
      "base name of the output files (default: the scene file's name)"),
    F(formats, HY_KIND_ENUM_LIST, formats, NOLIM, 1, 0, "svg", "output formats written"),
    F(dir, HY_KIND_STRING, NULL, NOLIM, 0, 0, "\".\"",
      "output directory, relative to the scene file's directory and below it (-o beats it)"),
};
#undef SECT

#define SECT hy_decl_animation
static const hy_scene_key_spec animation_keys[] = {
    FQ("duration", "s", duration, HY_KIND_NUMBER, NULL, POS, 0, 0, "5", "length of the animation in seconds"),
    FQ("fps", "1/s", fps, HY_KIND_INTEGER, NULL, HY_SPEC_MIN | HY_SPEC_MAX, 1, 240, 0, 0, "30",
      "frames per second"),
    F(easing, HY_KIND_ENUM, easings, NOLIM, 0, 0, "smooth", "how the animated parameter moves"),
    F(quality, HY_KIND_ENUM, qualities, NOLIM, 0, 0, "720p30", "frame size and rate preset (the presets of hystviz animate --quality)"),
};
#undef SECT

#define SECT hy_decl_keyframe
static const hy_scene_key_spec keyframe_keys[] = {
    F(key, HY_KIND_STRING, NULL, NOLIM, 0, 0, NULL,
      "the numeric scene key animated, written as for --set: \"model.sigma0\", \"input.umin2\", \"series.g.gamma\""),
    F(times, HY_KIND_NUMBER_LIST, NULL, NONNEG, 1, 0, NULL,
      "times of the keys in seconds, strictly ascending"),
    F(values, HY_KIND_NUMBER_LIST, NULL, NOLIM, 1, 0, NULL,
      "the key's value at each time (as many as times); held before the first and after the last"),
    F(easing, HY_KIND_ENUM, easings, NOLIM, 0, 0, NULL,
      "how the value moves between two keys (default: the [animation] easing)"),
    F(log, HY_KIND_BOOL, NULL, NOLIM, 0, 0, "false",
      "interpolate log(value) (values > 0), e.g. for a time scale gamma"),
};
#undef SECT

#define SECT hy_decl_controls
static const hy_scene_key_spec controls_keys[] = {
    F(main, HY_KIND_STRING, NULL, NOLIM, 0, 0, NULL,
      "the numeric keys that matter most, written as for --set and separated by commas: \"model.sigma0, input.umin2\" "
      "(hystviz serve's presentation view shows these)"),
};
#undef SECT

#define SECT hy_decl_param
static const hy_scene_key_spec param_keys[] = {
    F(value, HY_KIND_NUMBER, NULL, NOLIM, 0, 0, NULL,
      "the parameter's value, which every key written `key = $NAME` takes (checked against each of them)"),
};
#undef SECT

#define SECT hy_decl_preset
static const hy_scene_key_spec preset_keys[] = {
    F(label, HY_KIND_STRING, NULL, NOLIM, 0, 0, NULL, "the preset's name on its button (default: the section's NAME)"),
    F(set, HY_KIND_STRING, NULL, NOLIM, 0, 0, "\"\"",
      "the values of the preset, written as for --set and separated by ';': "
      "\"model.sigma0=1; input.umin2=0.2; figure.zoom_x=0.94, 1.02\""),
};
#undef SECT

#define S(name, named, rep, keys, doc) { name, named, rep, keys, NKEYS(keys), doc }

/* [model]'s rows: the shared rows above, then each model's own rows (its
 * file's HY_MODEL_ROWS, hy_scene_model_rows.h) in the order of the model
 * table, marked with its kind; assembled once, on the first call below. */
#define ROWS_DECL(id, name) extern const hy_model_rows hy_model_rows_##id;
HY_MODEL_ROW_KINDS(ROWS_DECL)
#define ROWS_ENTRY(id, name) {name, &hy_model_rows_##id},
static const struct {
    const char *kind;
    const hy_model_rows *rows;
} model_rows[] = {HY_MODEL_ROW_KINDS(ROWS_ENTRY){NULL, NULL}};
static hy_scene_key_spec model_all[HY_SCENE_KEYS_MAX];
static pthread_once_t assembled = PTHREAD_ONCE_INIT;

static hy_scene_section_spec sections[] = {
    S("model", 0, 0, model_keys, "the hysteresis model and its parameters"),
    S("input", 0, 0, input_keys, "the periodic input u(t)"),
    S("compute", 0, 0, compute_keys, "what is integrated and how"),
    S("figure", 0, 0, figure_keys, "the axes: kind, labels, ranges, size, fonts"),
    S("forc", 0, 0, forc_keys, "the FORC protocol on the model, or a measured FORC file, and the FORC distribution "
      "drawn by [figure] kind = forc (docs/FORC.md)"),
    S("series", 1, 1, series_keys, "one curve per section, drawn in file order"),
    S("annotation", 1, 1, annotation_keys, "one text label per section"),
    S("data", 1, 1, data_keys, "measured samples read from a file (u, y and optionally t columns): drawn by a "
      "[series] data = measured, driving the model through [input] kind = data"),
    S("panel", 1, 1, panel_keys, "one panel per section, in file order: a figure of several scenes side by side"),
    S("output", 0, 0, output_keys, "where the figure is written"),
    S("controls", 0, 0, controls_keys, "how hystviz serve presents the scene's parameters"),
    S("param", 1, 1, param_keys, "a named value that several keys read (`gamma = $NAME`): they move together, "
      "set with --set param.NAME.value=..."),
    S("preset", 1, 1, preset_keys, "a named set of values hystviz serve switches to in one click (keys 1-9)"),
    S("animation", 0, 0, animation_keys, "frame timing of an animation"),
    S("keyframe", 1, 1, keyframe_keys, "one animated numeric key per section (hystviz animate SCENE.scene)"),
};

static void assemble(void)
{
    size_t n = 0;
    for (size_t i = 0; i < NKEYS(model_keys); i++)
        model_all[n++] = model_keys[i];
    for (size_t m = 0; model_rows[m].kind; m++)
        for (size_t i = 0; i < model_rows[m].rows->n; i++) {
            if (n == HY_SCENE_KEYS_MAX) { /* a table error: fails every test at once */
                fprintf(stderr, "hystviz: [model] has more than HY_SCENE_KEYS_MAX = %d keys (hy_scene_decl.h)\n",
                        HY_SCENE_KEYS_MAX);
                abort();
            }
            model_all[n] = model_rows[m].rows->rows[i];
            model_all[n++].model = model_rows[m].kind;
        }
    sections[0].keys = model_all; /* sections[0] is [model] */
    sections[0].nkeys = n;
}

const hy_scene_section_spec *hy_scene_schema(size_t *n)
{
    pthread_once(&assembled, assemble);
    if (n)
        *n = NKEYS(sections);
    return sections;
}

int hy_scene_schema_section(const char *name)
{
    pthread_once(&assembled, assemble);
    for (size_t i = 0; i < NKEYS(sections); i++)
        if (sections[i].name[0] == name[0] && strcmp(sections[i].name, name) == 0) /* first byte: a cheap filter */
            return (int)i;
    return -1;
}

int hy_scene_schema_key(int sec, const char *key)
{
    pthread_once(&assembled, assemble);
    if (sec < 0 || (size_t)sec >= NKEYS(sections))
        return -1;
    for (size_t j = 0; j < sections[sec].nkeys; j++)
        if (sections[sec].keys[j].name[0] == key[0] && strcmp(sections[sec].keys[j].name, key) == 0)
            return (int)j;
    return -1;
}

const char *hy_scene_kind_name(hy_scene_kind kind)
{
    switch (kind) {
    case HY_KIND_NUMBER: return "number";
    case HY_KIND_INTEGER: return "integer";
    case HY_KIND_BOOL: return "bool";
    case HY_KIND_ENUM: return "identifier";
    case HY_KIND_STRING: return "string";
    case HY_KIND_NAME: return "name";
    case HY_KIND_PATH: return "path";
    case HY_KIND_NUMBER_LIST: return "list of numbers";
    case HY_KIND_INTEGER_LIST: return "list of integers";
    case HY_KIND_ENUM_LIST: return "list of identifiers";
    case HY_KIND_LENGTH: return "length";
    case HY_KIND_LENGTH_PAIR: return "pair of lengths";
    case HY_KIND_COLOR: return "colour";
    case HY_KIND_PAIR: return "pair of numbers";
    case HY_KIND_LIMITS: return "limits";
    }
    return "value";
}

void hy_scene_range_text(const hy_scene_key_spec *k, char *buf, size_t n)
{
    int lo = (k->flags & HY_SPEC_MIN) != 0, hi = (k->flags & HY_SPEC_MAX) != 0;
    int lox = (k->flags & HY_SPEC_MIN_EXCL) != 0, hix = (k->flags & HY_SPEC_MAX_EXCL) != 0;
    if (lo && hi)
        snprintf(buf, n, "in %c%.15g, %.15g%c", lox ? '(' : '[', k->min, k->max, hix ? ')' : ']');
    else if (lo)
        snprintf(buf, n, "%s %.15g", lox ? ">" : ">=", k->min);
    else if (hi)
        snprintf(buf, n, "%s %.15g", hix ? "<" : "<=", k->max);
    else if (n)
        buf[0] = '\0';
}
