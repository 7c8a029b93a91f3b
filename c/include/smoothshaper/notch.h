/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file notch.h
 * @brief Notch filter as one biquad (docs/filters.md): Tustin with pre-warping at wn, or pole-zero
 * matched.
 *
 * Continuous notch G(s) = (s^2 + 2 xi1 wn s + wn^2)/(s^2 + 2 xi2 wn s + wn^2), with
 * xi1 = sms_stage_config::zeta in [0, 1) (zero damping) and xi2 = sms_stage_config::notch_pole_zeta
 * (pole damping, xi1 < xi2 <= 1e6; xi2 >= 1 gives two real poles). Discrete transfer function
 * H(z) = (b0 + b1 z^-1 + b2 z^-2)/(1 + a1 z^-1 + a2 z^-2):
 * - ::SMS_NOTCH_TUSTIN: s = (wn / tan(wn Ts/2)) (z-1)/(z+1); with t = tan(wn Ts/2):
 *   b = [1 + 2 xi1 t + t^2, 2(t^2 - 1), 1 - 2 xi1 t + t^2] / a0,
 *   a = [1, 2(t^2 - 1), 1 - 2 xi2 t + t^2] / a0,  a0 = 1 + 2 xi2 t + t^2.
 *   Gain 1 at DC and exactly the continuous G(j wn) = xi1/xi2 at wn (0 when xi1 = 0).
 * - ::SMS_NOTCH_MATCHED: zeros exp(s Ts) of the numerator roots s = wn(-xi1 +- j sqrt(1-xi1^2))
 *   (exactly the sampled mode poles when (wn, xi1) is the mode), poles exp(s Ts) of the
 *   denominator roots (real when xi2 >= 1), gain such that H(1) = 1.
 * Both need wn < pi/Ts. Work per sample O(1), no buffer (sms_stage_buffer_size() gives 0).
 *
 * Realisation, exact at DC in any precision: H = 1 + D/A with D = B - A, and since D(1) = 0,
 * D(z) = (1 - z^-1)(d0 - d2 z^-1), d0 = b0 - 1, d2 = b2 - a2. Difference equations:
 *   w[n] = d0 (x[n] - x[n-1]) + d2 (x[n-2] - x[n-1]) - a1 w[n-1] - a2 w[n-2],  y[n] = x[n] + w[n].
 * A constant input gives differences of exactly 0, so w decays to 0 and the output equals the
 * input exactly after the transient, whatever the rounding of d0, d2, a1, a2 (a direct-form
 * biquad in float would miss unit DC gain by ~4 eps/(wn Ts)^2, e.g. 3e-5 at wn Ts = 0.05).
 *
 * The transient ends exactly: when w and the previous w are both below TINY in magnitude
 * (the smallest normal ::sms_real over its machine epsilon: 1.0e-292 in double, 9.9e-32 in
 * float), both are set to +0. Under a constant input that state is a fixed point (the input
 * differences are exactly 0), so a held input is absorbed after finitely many samples, about
 * ln(|w|/TINY) over the decay rate of the slowest pole (sms_notch_settle_bound()), never
 * cycling in the subnormals; the outputs differ from the plain recursion by less than TINY.
 * So the notch acts on swings of the input well above TINY: a signal whose differences are
 * themselves near TINY (1e-292 units in double, 1e-31 in float) passes unfiltered.
 *
 * Non-finite input: such a sample is passed to the output unchanged and does not enter the
 * state (the filter continues as if it had not been there). If the output is non-finite while
 * the input is finite (overflow, or a non-finite state loaded by sms_notch_set_state()), the
 * filter restarts at rest at that input and outputs it. The IIR state is never poisoned.
 */
#ifndef SMOOTHSHAPER_NOTCH_H
#define SMOOTHSHAPER_NOTCH_H

#include "smoothshaper/config.h"

#ifdef __cplusplus
extern "C" {
#endif

/** @brief Largest accepted pole damping xi2 (beyond it a real pole rounds onto z = 1). */
#define SMS_NOTCH_MAX_POLE_ZETA 1e6

/** @brief Instance of one notch. Fields are public for inspection only. */
typedef struct sms_notch {
    sms_kind kind;                /**< ::SMS_NOTCH_TUSTIN or ::SMS_NOTCH_MATCHED */
    /* w = d0 (x - x1) + d2 (x2 - x1) - a1 w1 - a2 w2; y = x + w */
    sms_real d0;                  /**< d0 = b0 - 1, weight of x - x1 */
    sms_real d2;                  /**< d2 = b2 - a2, weight of x2 - x1 */
    sms_real a1;                  /**< denominator coefficient of z^-1 */
    sms_real a2;                  /**< denominator coefficient of z^-2 */
    sms_real x1;                  /**< the previous input x[n-1] */
    sms_real x2;                  /**< the input before it, x[n-2] */
    sms_real w1;                  /**< the previous w = y - x */
    sms_real w2;                  /**< the w before it */
    sms_real rest;                /**< operating point set by the last reset */
    double identity[SMS_STATE_IDENTITY_COUNT]; /**< config and Ts it was built for (config.h) */
} sms_notch;

/**
 * @brief Validate and build a notch at rest at 0.
 * @return ::SMS_OK; ::SMS_ERR_NULL (f or config NULL); else the first failing check in this
 *         order: ::SMS_ERR_SAMPLE_PERIOD (Ts NaN/Inf or <= 0), ::SMS_ERR_KIND (not a notch
 *         kind), ::SMS_ERR_WN (NaN/Inf or <= 0), ::SMS_ERR_ABOVE_NYQUIST (wn >= pi/Ts),
 *         ::SMS_ERR_ZETA (outside [0,1)), ::SMS_ERR_NOTCH_DAMPING (notch_pole_zeta NaN/Inf,
 *         <= zeta or > ::SMS_NOTCH_MAX_POLE_ZETA). timing, T, sigma, k, order, tolerance
 *         are not read. f is untouched on error.
 * @param f      instance to fill; untouched on error
 * @param config a notch config (::SMS_NOTCH_TUSTIN or ::SMS_NOTCH_MATCHED); wn, zeta,
 *               notch_pole_zeta are read
 * @param Ts     sample period [s], finite, > 0
 */
SMS_API sms_status sms_notch_init(sms_notch *f, const sms_stage_config *config, double Ts);
/** @brief Rest at `rest`: as if the input had been `rest` forever.
 * @param f     the notch, built by sms_notch_init() or sms_notch_init_coeffs()
 * @param rest  finite; the next outputs equal rest until the input changes
 */
SMS_API void sms_notch_reset(sms_notch *f, sms_real rest);
/** @brief One sample in place (see the difference equations above).
 * @param f     the notch, built by sms_notch_init() or sms_notch_init_coeffs()
 * @param x     in: the input x[n] (non-finite: passed through, see above); out: y[n]
 */
SMS_API void sms_notch_step(sms_notch *f, sms_real *x);
/** @brief n samples; in == out allowed. Same result as n calls of step.
 * @param f     the notch, built by sms_notch_init() or sms_notch_init_coeffs()
 * @param in    n inputs
 * @param out   n outputs; may be in itself
 * @param n     number of samples, any
 */
SMS_API void sms_notch_process(sms_notch *f, const sms_real *in, sms_real *out, size_t n);
/**
 * @brief An estimate of the samples of a constant input after which the notch has absorbed it
 * from any finite state (w = 0 exactly, sms_notch_is_settled()): 2 ln(R)/s + 4, s = -ln rho
 * the decay rate of the slowest pole rho = max |z_p| of 1 + a1 z^-1 + a2 z^-2 (from the
 * coefficients in use), R = REAL_MAX/TINY (ln R = 1382 in double, 160 in float); the factor 2
 * covers the (n + 1) rho^n of two close poles and rounding. E.g. Tustin, xi2 = 0.7,
 * wn Ts = 0.01: s = 0.007, about 395,000 samples. HUGE_VAL when a pole rounds onto the unit
 * circle (s <= 0: no decay). For sizing the work of a long hold (sms_chain_hold()); O(1).
 * @param f     the notch (read only)
 * @return the sample estimate (>= 4), or HUGE_VAL when a pole does not decay
 */
SMS_API double sms_notch_settle_bound(const sms_notch *f);
/** @brief 1 when the notch rests at the constant input x: x1 = x2 = x and w1 = w2 = +0, a
 * fixed point of the recursion (every further sample of x outputs x + 0); else 0. O(1).
 * @param f     the notch (read only)
 * @param x     the held input
 * @return 1 or 0
 */
SMS_API int sms_notch_is_settled(const sms_notch *f, sms_real x);
/** @brief Doubles in a saved state: ::SMS_STATE_IDENTITY_COUNT + 6 (the configuration identity
 * of config.h, then kind, x1, x2, w1, w2, rest).
 * @param f     the notch (read only)
 * @return ::SMS_STATE_IDENTITY_COUNT + 6
 */
SMS_API size_t sms_notch_state_count(const sms_notch *f);
/** @brief Write sms_notch_state_count() doubles to dst.
 * @param f     the notch (read only)
 * @param dst   sms_notch_state_count() doubles
 */
SMS_API void sms_notch_get_state(const sms_notch *f, double *dst);
/** @brief Restore a saved state; validates first and writes nothing on error (::SMS_ERR_STATE:
 * wrong n or kind; ::SMS_ERR_NULL).
 * @param f     the notch, built by sms_notch_init() or sms_notch_init_coeffs(); untouched on error
 * @param src   the saved state
 * @param n     its length in doubles, sms_notch_state_count()
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_STATE_FORMAT .. ::SMS_ERR_STATE_DURATION (saved by
 *         another configuration: the first field of the identity that differs, config.h), or
 *         ::SMS_ERR_STATE (wrong n or kind, a value outside the range of ::sms_real)
 */
SMS_API sms_status sms_notch_set_state(sms_notch *f, const double *src, size_t n);
/** @brief The validation of sms_notch_set_state() alone: writes nothing.
 * @param f     the notch (read only)
 * @param src   the saved state
 * @param n     its length in doubles
 * @return what sms_notch_set_state() would return
 */
SMS_API sms_status sms_notch_check_state(const sms_notch *f, const double *src, size_t n);
/** @brief Is src a state a run with every input and rest value |x| <= x_max could reach? What
 * sms_notch_check_state() accepts, with the last inputs and the rest finite and within x_max and
 * the recursion's w1, w2 finite and within w_max (sms_stage_check_state_range() passes
 * 2 x_max (G - 1), G = sms_stage_gain_bound(): the l1 bound of (1 - z^-1)(d0 - d2 z^-1)/A).
 * Writes nothing.
 * @return ::SMS_OK, what sms_notch_check_state() returns, or ::SMS_ERR_STATE.
 * @param f     the notch (read only)
 * @param src   the saved state
 * @param n     its length in doubles
 * @param x_max the largest |input| of the run, finite, >= 0
 * @param w_max the largest |w| the run can reach, finite, >= 0
 */
SMS_API sms_status sms_notch_check_state_range(const sms_notch *f, const double *src, size_t n,
                                               double x_max, double w_max);
/**
 * @brief Pole damping xi2 such that the continuous notch (zero damping xi1 = zeta, centre wn)
 * has the given -3 dB bandwidth B [rad/s] (distance between the two frequencies where
 * |G(jw)|^2 = 1/2).
 *
 * |G(jw)|^2 = 1/2  <=>  (wn^2 - w^2)^2 = 4 wn^2 w^2 (xi2^2 - 2 xi1^2); its two positive roots are
 * w = wn (sqrt(c^2 + 1) +- c), c = sqrt(xi2^2 - 2 xi1^2), so B = 2 wn c exactly and
 * xi2 = sqrt(B^2/(4 wn^2) + 2 xi1^2) (> xi1 for any B > 0; >= 1 for wide notches).
 * @param wn        centre [rad/s], finite, > 0
 * @param zeta      zero damping xi1, [0, 1)
 * @param bandwidth B [rad/s], finite, > 0, and giving xi2 <= ::SMS_NOTCH_MAX_POLE_ZETA
 * @param pole_zeta receives xi2
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_WN, ::SMS_ERR_ZETA, ::SMS_ERR_BANDWIDTH.
 */
SMS_API sms_status sms_notch_pole_zeta_from_bandwidth(double wn, double zeta, double bandwidth,
                                                      double *pole_zeta);

#ifdef __cplusplus
}
#endif
#endif
