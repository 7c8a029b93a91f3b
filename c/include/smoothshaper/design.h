/**
 * @file design.h
 * @brief Design from a vibration mode (SPEC 4.2) and mode identification (SPEC 4.3).
 * OWNER: C shapers work package.
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
 * Other fields take sms_stage_config_default() values; timing is ::SMS_TIMING_EXACT.
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_KIND, ::SMS_ERR_WN, ::SMS_ERR_ZETA,
 *         ::SMS_ERR_MULTIPLE (k < 1, or k != 1 for shapers/notches), ::SMS_ERR_EVEN_MULTIPLE.
 */
SMS_API sms_status sms_design_for_mode(sms_kind kind, double wn, double zeta, unsigned k,
                                       sms_stage_config *config);

/** @brief An identified mode. */
typedef struct sms_mode {
    double wn, zeta, wd, sigma;
} sms_mode;

/**
 * @brief Mode from two successive peaks (t1, p1), (t2, p2) of a free decay (SPEC 4.3):
 * T0 = t2 - t1, sigma = ln(p2/p1)/T0, wd = 2 pi / T0.
 * @return ::SMS_ERR_RECORD unless t2 > t1, p1 > p2 > 0 (same sign, decaying) and all finite.
 */
SMS_API sms_status sms_identify_from_peaks(double t1, double p1, double t2, double p2, sms_mode *mode);

/**
 * @brief Mode from a sampled free decay x[0..n-1] at period Ts (about its final value), by a
 * least-squares fit over the whole record. Needs n >= 8 and at least one visible oscillation.
 */
SMS_API sms_status sms_identify_from_record(const double *x, size_t n, double Ts, sms_mode *mode);

#ifdef __cplusplus
}
#endif
#endif
