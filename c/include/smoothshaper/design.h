/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file design.h
 * @brief Design from a vibration mode and mode identification (docs/design.md).
 */
#ifndef SMOOTHSHAPER_DESIGN_H
#define SMOOTHSHAPER_DESIGN_H

#include "smoothshaper/config.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * @brief Fill a config of `kind` that cancels the mode (wn [rad/s], zeta in [0,1)).
 *
 * wd = wn sqrt(1 - zeta^2), Td = 2 pi / wd, sigma = -zeta wn.
 * - rectangular: T = k 2 pi / wd (zeros on the imaginary axis: cancels wd exactly only if zeta = 0)
 * - harmonic: T = k 3 pi / wd, k odd (same remark)
 * - damped harmonic: sigma = -zeta wn, T = k 3 pi / wd, k odd
 * - exponential: sigma = -zeta wn, T = k Td
 * - shapers and notches: wn, zeta copied (k must be 1)
 * The config's k is set to k (exact timing pins the zero k 2 pi/T or k 3 pi/T, which is then
 * wd). Other fields take sms_stage_config_default() values; timing is ::SMS_TIMING_EXACT.
 * Why k must be odd for the harmonic families: their zeros sit at sigma +- j (2m+1) pi/T; with
 * T = k 3 pi/wd the zero index is wd T/pi = 3k, an odd number only when k is odd. An even k
 * puts wd between two zeros (about 2.9 % residual for k = 2, docs/errata.md).
 * - input smoothers: wn, zeta copied (k must be 1; their own zeta range is checked by init)
 * Checks in order: config NULL, kind (::SMS_SHAPER_IMPULSES has no mode: ::SMS_ERR_KIND), wn,
 * zeta, k < 1, k even (harmonic families), k != 1 (shapers, notches). *config is untouched on
 * error.
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_KIND, ::SMS_ERR_WN, ::SMS_ERR_ZETA,
 *         ::SMS_ERR_MULTIPLE (k < 1, or k != 1 for shapers/notches), ::SMS_ERR_EVEN_MULTIPLE.
 * @param kind   any stage kind but ::SMS_SHAPER_IMPULSES
 * @param wn     natural frequency [rad/s], finite, > 0
 * @param zeta   damping ratio, finite, in [0, 1)
 * @param k      multiple, >= 1; odd for the harmonic families; 1 for shapers, notches and
 *               input smoothers
 * @param config receives the config
 */
SMS_API sms_status sms_design_for_mode(sms_kind kind, double wn, double zeta, unsigned k,
                                       sms_stage_config *config);

/** @brief An identified mode. */
typedef struct sms_mode {
    double wn;      /**< natural frequency [rad/s], > 0 */
    double zeta;    /**< damping ratio, in [0, 1) */
    double wd;      /**< damped frequency wn sqrt(1 - zeta^2) [rad/s] */
    double sigma;   /**< decay rate -zeta wn [1/s], <= 0 */
} sms_mode;

/**
 * @brief Mode from two successive peaks (t1, p1), (t2, p2) of a free decay about its final
 * value (Biagiotti et al. 2020, eq. 16): T0 = t2 - t1, sigma = ln(p2/p1)/T0, wd = 2 pi / T0,
 * wn = sqrt(sigma^2 + wd^2), zeta = -sigma/wn. Two maxima or two minima (troughs) both work.
 * @param t1,t2 peak times [s], finite, t2 > t1 (one damped period apart)
 * @param p1,p2 peak values, finite, same sign, 0 < |p2| < |p1| (decaying)
 * @return ::SMS_OK, ::SMS_ERR_NULL (mode), ::SMS_ERR_RECORD (any condition above violated);
 *         *mode is untouched on error.
 * @param mode  receives the mode
 */
SMS_API sms_status sms_identify_from_peaks(double t1, double p1, double t2, double p2, sms_mode *mode);

/**
 * @brief Mode from a sampled free decay x[0..n-1] at period Ts, by a least-squares fit of
 * x[k] = c + e^{sigma t_k}(A cos(wd t_k) + B sin(wd t_k)), t_k = k Ts, over the whole record
 * (c absorbs an unknown final value / offset).
 *
 * Method: start values from AR(2)-with-constant least-squares fits
 * x[k] = a1 x[k-d] + a2 x[k-2d] + c at lags d = 1, 2, 4, ... (n >= 4d); the two starts with
 * the least squared error are refined by Levenberg-Marquardt on all five parameters and the
 * better fit wins. For white noise this is the maximum-likelihood estimate:
 * tests/c/test_identify.c measures it at the Cramer-Rao bound (worst of 20 noise draws within
 * 3 standard deviations). Cost: O(n) exp/cos/sin per iteration (about 0.2 s for n = 2e5);
 * design-time only (uses libm).
 * @param x   record, all finite; n >= 8
 * @param Ts  sample period [s], finite, > 0
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_SAMPLE_PERIOD, ::SMS_ERR_RECORD (n < 8, a
 *         non-finite sample, no oscillating fit, sigma >= 0 (not a decay), wd at or above
 *         pi/Ts, or less than one period wd (n-1) Ts < 2 pi in the record); *mode is untouched
 *         on error.
 * @param n   samples in x
 * @param mode receives the mode
 */
SMS_API sms_status sms_identify_from_record(const double *x, size_t n, double Ts, sms_mode *mode);

#ifdef __cplusplus
}
#endif
#endif
