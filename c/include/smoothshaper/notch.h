/**
 * @file notch.h
 * @brief Notch filter as one biquad (SPEC 3.6): Tustin with pre-warping at wn, or pole-zero
 * matched. OWNER: C shapers work package (struct fields may change).
 */
#ifndef SMOOTHSHAPER_NOTCH_H
#define SMOOTHSHAPER_NOTCH_H

#include "smoothshaper/config.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sms_notch {
    sms_kind kind;
    sms_real b0, b1, b2, a1, a2;  /**< y = b0 x + b1 x1 + b2 x2 - a1 y1 - a2 y2 */
    sms_real x1, x2, y1, y2;
    sms_real rest;
} sms_notch;

SMS_API sms_status sms_notch_init(sms_notch *f, const sms_stage_config *config, double Ts);
SMS_API void sms_notch_reset(sms_notch *f, sms_real rest);
SMS_API void sms_notch_step(sms_notch *f, sms_real *x);
SMS_API void sms_notch_process(sms_notch *f, const sms_real *in, sms_real *out, size_t n);
SMS_API size_t sms_notch_state_count(const sms_notch *f);
SMS_API void sms_notch_save_state(const sms_notch *f, double *dst);
/** @brief Restore a saved state; validates first and writes nothing on error (::SMS_ERR_STATE). */
SMS_API sms_status sms_notch_load_state(sms_notch *f, const double *src, size_t n);
/** @brief The validation of sms_notch_load_state() alone: writes nothing. */
SMS_API sms_status sms_notch_check_state(const sms_notch *f, const double *src, size_t n);
/** @brief Pole damping xi2 such that the notch (zero damping xi1 = zeta, centre wn) has the
 * given -3 dB bandwidth [rad/s] (distance between the two -3 dB frequencies). */
SMS_API sms_status sms_notch_pole_zeta_from_bandwidth(double wn, double zeta, double bandwidth,
                                                      double *pole_zeta);

#ifdef __cplusplus
}
#endif
#endif
