/* SPDX-License-Identifier: MIT */
/* hy_jiles.h: the Jiles-Atherton model of ferromagnetic hysteresis (Jiles and
 * Atherton, J. Magn. Magn. Mater. 61 (1986) 48), integrated in H by GSL, in
 * one of two variants (hy_jiles.variant).
 *
 * HY_JILES_JA1986 (the default):
 *     H_e = H + α M,           M_an = Ms L(H_e / a),   L(x) = coth x - 1/x,
 *     M = M_irr + M_rev,       M_rev = c (M_an - M_irr),
 *     dM_irr/dH_e = (M_an - M_irr) / (k δ),   δ = sign(dH/dt),
 * which with M_an - M_irr = (M_an - M)/(1 - c) gives
 *     χ_e = dM/dH_e = (M_an - M)/(k δ) + c dM_an/dH_e,   dM/dH = χ_e / (1 - α χ_e),
 * the irreversible term set to 0 while (M_an - M) δ < 0 (the usual guard
 * against a negative susceptibility just after a reversal), and B = μ0 (H + M).
 *
 * HY_JILES_JTD1992, the total-M form of Jiles, Thoelke and Devine (IEEE
 * Trans. Magn. 28 (1992) 27), the one most identification codes fit with:
 *     dM/dH = δ_M (M_an - M) / ((1 + c)(δ k - α (M_an - M))) + c/(1 + c) dM_an/dH_e,
 * δ_M = 1 where (M_an - M) δ > 0, else 0 (the same guard), no mean-field
 * factor on the reversible term.  The two agree where c = 0 (any α).
 *
 * μ0 is CODATA 2018's 1.25663706212e-6 N/A², not 4π·1e-7 (5.5e-10 relative).
 *
 * The model is rate-independent, so it is integrated in H: each monotone
 * stretch of the input is one initial value problem (GSL odeiv2 rk8pd by
 * default, or the stepper j->stepper names, the implicit ones with a
 * finite-difference Jacobian; local tolerance 1e-13, on M/Ms and
 * ∫ (H + M) dH), restarted at every
 * reversal; the switch of the guard inside a stretch is located (regula falsi
 * on single steps) and the integration restarted there, so no step straddles
 * the kink of dM/dH.  L is evaluated near 0 by its series in Lambert's
 * continued-fraction form x/(3 + x²/(5 + x²/(7 + ...))), without the
 * cancellation of coth x - 1/x.
 *
 *     hy_jiles j;
 *     hy_jiles_init(&j, 1.6e6, 1100, 400, 0.2, 1.6e-3, &err);  // Ms a k c α
 *     hy_jiles_state s;
 *     hy_jiles_state_init(&j, &s, 0.0);                       // H = 0, M = 0
 *     hy_jiles_apply(&j, &s, 5000, NULL, &err);                // s.M, hy_jiles_b(&s)
 *
 * The GSL error handler must be off (gsl_set_error_handler_off) in programs
 * that call this.  Nothing here allocates beyond one call.
 */
#ifndef HY_JILES_H
#define HY_JILES_H

#include <stddef.h>
#include "hy_input.h"
#include "hy_rateind.h"

#ifdef __cplusplus
extern "C" {
#endif

#define HY_MU0 1.25663706212e-6 /* vacuum permeability, N/A² (CODATA 2018) */
#define HY_JILES_RTOL 1e-13     /* the stepper's default local tolerance (hy_jiles.rtol) */
#define HY_JILES_MAX_STEPS 1000000 /* default step budget of a state (hy_jiles.max_steps): about 1 s */
#define HY_JILES_HMAX 1e4       /* |H| <= HY_JILES_HMAX max(Ms, a, k): hy_jiles_input_check */
#define HY_JILES_STEP_K 4.0     /* a stretch of length L takes at least about L/(4k) steps */

enum { HY_JILES_JA1986 = 0, HY_JILES_JTD1992 = 1 };

/* The variants' names in the order of their values, NULL-terminated (the
 * scene key model.ja_variant lists them from here). */
extern const char *const hy_jiles_variant_names[];

typedef struct hy_jiles {
    double ms;      /* saturation magnetisation Ms (A/m), > 0                  */
    double a;       /* shape of the anhysteretic (A/m), > 0                    */
    double k;       /* pinning (A/m), > 0                                       */
    double c;       /* reversibility, 0 <= c < 1                               */
    double alpha;   /* mean-field coupling, >= 0, α Ms / (3a) < 1              */
    double m0;      /* initial magnetisation M (A/m), |m0| < Ms (default 0)    */
    double rtol;    /* local tolerance of the stepper (default 1e-13)          */
    const char *stepper; /* GSL stepper, a name of hy_ode_stepper_names()
                            (NULL: rk8pd, the default; `hystviz report` runs
                            each against rk8pd at 1e-13)                     */
    int variant;    /* HY_JILES_JA1986 (0, default) or HY_JILES_JTD1992        */
    unsigned long max_steps; /* steps (accepted, rejected and those locating a
                            guard switch) a state may take from
                            hy_jiles_state_init on; 0: HY_JILES_MAX_STEPS    */
    const hy_cancel *cancel; /* asked every 64 steps of a stretch (NULL, as
                            hy_jiles_init sets it: never; hy_cancel.h)     */
} hy_jiles;

/* Langevin function L(x) = coth x - 1/x, accurate for every x (odd, L(0) = 0). */
double hy_langevin(double x);
/* L'(x) = 1/x² - 1/sinh² x, accurate for every x (L'(0) = 1/3). */
double hy_langevin_d(double x);

/* Fills j (m0 = 0, rtol = 1e-13, variant 1986, default step budget) and validates it
 * (j must not be NULL: HY_EINVAL; j is written only when valid). */
int hy_jiles_init(hy_jiles *j, double ms, double a, double k, double c, double alpha, hy_error *err);
/* HY_OK, or HY_EINVAL with a message naming the parameter: Ms, a, k > 0,
 * c in [0, 1), alpha >= 0 with alpha Ms/(3a) < 1 (else the anhysteretic curve
 * is not single-valued: spontaneous magnetisation), |m0| < Ms, rtol in
 * [1e-15, 1e-2], all finite; stepper NULL or a known name; variant known.
 * j must not be NULL (HY_EINVAL). */
int hy_jiles_validate(const hy_jiles *j, hy_error *err);

/* HY_OK when an input reaching |H| = hmax and travelling `travel` A/m (the
 * sum of |ΔH| over its stretches, e.g. a period's variation; 0: not checked)
 * is within what the model integrates, else HY_EINVAL with a message that
 * blames the input's scale (not alpha or k):
 * - |H| <= HY_JILES_HMAX max(Ms, a, k), 10^4 times its largest field scale,
 *   far into saturation (M_an within 1e-4 of Ms or closer);
 * - travel / (HY_JILES_STEP_K k) <= the step budget: where the irreversible
 *   term acts, (M_an - M)/k pulls M onto M_an at rate 1/k, so the explicit
 *   stepper's stable step is a few k (measured: 1 to 4 k, saturation included)
 *   and the travel needs at least this many steps.
 * j must not be NULL (HY_EINVAL). */
int hy_jiles_input_check(const hy_jiles *j, double hmax, double travel, hy_error *err);

typedef struct hy_jiles_state {
    double H;       /* present field (A/m)                                      */
    double M;       /* present magnetisation (A/m)                              */
    double hb;      /* ∫ (H + M) dH along the path so far (∫ B dH = μ0 hb)      */
    unsigned long steps; /* steps taken since hy_jiles_state_init (the budget's count) */
} hy_jiles_state;

typedef struct hy_jiles_stats {
    unsigned long steps, fails, nfev, switches, stretches;
} hy_jiles_stats;

/* The state M = j->m0 at field H0 (j or s NULL: nothing done). */
void hy_jiles_state_init(const hy_jiles *j, hy_jiles_state *s, double H0);
/* B = μ0 (H + M) of a state, in tesla (s NULL: NaN). */
double hy_jiles_b(const hy_jiles_state *s);

/* Moves the field monotonically from s->H to H (any direction; δ is its
 * sign).  stats (may be NULL) is added to.  HY_EINVAL when the trajectory
 * reaches a vanishing denominator, 1 - α χ_e <= 1e-9 (1986) or
 * (k - α |M_an - M|)/k <= 1e-9 (1992) (no physical solution from there:
 * alpha too large for this k, e.g. from |M_an - M| > k/α; the message names
 * alpha, k, H and M; a trial stage that probes such a state only shrinks the
 * step), when H is not finite or beyond hy_jiles_input_check's bound on
 * |H| (checked first: the message names the field's scale), or when the
 * state's steps pass the step budget (j->max_steps, counted in s->steps: a
 * stiff stretch; the message says "step budget" and gives the stretch's
 * length against k);
 * HY_ENUM when GSL fails (message gives H and the reason).  On error s is
 * left at the last good step.  j and s must not be NULL (HY_EINVAL). */
int hy_jiles_apply(const hy_jiles *j, hy_jiles_state *s, double H, hy_jiles_stats *stats, hy_error *err);

/* dM/dH of the variant j->variant at field H, magnetisation M (A/m), moving
 * up (delta > 0) or down (delta < 0), with the guard δ_M = [(M_an - M) δ > 0];
 * NaN where the denominator vanishes (no physical solution there), and for j
 * NULL. */
double hy_jiles_dmdh(const hy_jiles *j, double H, double M, int delta);

/* M and B (either may be NULL) at ascending times t[0..n-1] for an input of
 * hy_input.h read as H(t) in A/m, from M = j->m0 at H = u(0); every extremum
 * of the input between samples is a restart.  stats (may be NULL) is added to.
 * j and in (with pieces) must not be NULL, nor t when n > 0 (HY_EINVAL). */
int hy_jiles_drive(const hy_jiles *j, const hy_input *in, const double *t, size_t n, double *M, double *B,
                   hy_jiles_stats *stats, hy_error *err);

/* Features of the major loop for the symmetric drive ±hmax (cycled from the
 * demagnetised state until M at +hmax changes by < 1e-12 Ms per cycle), read
 * on the descending branch. */
typedef struct hy_jiles_loop {
    double hc;      /* coercive field: B = 0 (A/m, > 0)                          */
    double hci;     /* intrinsic coercive field: M = 0 (A/m, > 0)                */
    double br;      /* remanence B at H = 0 (T)                                  */
    double mr;      /* remanent magnetisation M at H = 0 (A/m)                   */
    double bmax;    /* B at H = hmax (T)                                          */
    int cycles;     /* cycles driven                                             */
} hy_jiles_loop;
/* HY_EINVAL for hmax <= 0 or a model error, HY_ENUM when the cycle does not
 * settle in 100 periods or a root is not bracketed; j and out must not be
 * NULL (HY_EINVAL). */
int hy_jiles_major_loop(const hy_jiles *j, double hmax, hy_jiles_loop *out, hy_error *err);

/* The steady minor loop of a bimodal input (hy_rateind.h), the input read as
 * H in A/m and the output as B: periods are driven from M = m0 at u(0) until
 * M at u_min,1 changes by < 1e-11 Ms per period (HY_ENUM after 400); the loop
 * does not close exactly (no return-point memory): y_close != y_start.  j, in
 * and out must not be NULL (HY_EINVAL). */
int hy_jiles_minor_loop(const hy_jiles *j, const hy_input *in, hy_minor_loop *out, hy_error *err);

#ifdef __cplusplus
}
#endif

#endif
