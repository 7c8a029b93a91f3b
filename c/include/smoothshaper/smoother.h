/**
 * @file smoother.h
 * @brief FIR smoothers in O(1) recursive form: rectangular, harmonic, damped harmonic and
 * exponential (SPEC 3.1-3.4). OWNER: C smoothers work package (struct fields may change).
 */
#ifndef SMOOTHSHAPER_SMOOTHER_H
#define SMOOTHSHAPER_SMOOTHER_H

#include "smoothshaper/config.h"

#ifdef __cplusplus
extern "C" {
#endif

/** @brief Most numerator taps of the recursive form (head, tail and exact-timing corrections). */
#define SMS_SMOOTHER_MAX_TAPS 10

/** @brief Instance of one smoother. Fields are public for inspection; change them only
 * through the functions below. */
typedef struct sms_smoother {
    sms_kind kind;
    size_t length;                          /**< impulse response length L [samples] */
    size_t n_taps;                          /**< numerator taps used */
    size_t tap_delay[SMS_SMOOTHER_MAX_TAPS];
    sms_real tap_gain[SMS_SMOOTHER_MAX_TAPS];
    sms_real a1, a2;                        /**< denominator 1 - a1 z^-1 - a2 z^-2 */
    sms_real y1[2], y2[2];                  /**< past outputs of the two restarted copies */
    size_t age[2];                          /**< samples since each copy restarted */
    sms_real rest;                          /**< operating point set by reset */
    sms_real *history;                      /**< caller buffer: past inputs (ring) */
    size_t history_len;
    size_t head;
} sms_smoother;

SMS_API sms_status sms_smoother_buffer_size(const sms_stage_config *config, double Ts, size_t *n_reals);
SMS_API sms_status sms_smoother_init(sms_smoother *f, const sms_stage_config *config, double Ts,
                                     sms_real *buffer, size_t n_reals);
SMS_API void sms_smoother_reset(sms_smoother *f, sms_real rest);
SMS_API void sms_smoother_step(sms_smoother *f, sms_real *x);
SMS_API void sms_smoother_process(sms_smoother *f, const sms_real *in, sms_real *out, size_t n);
SMS_API size_t sms_smoother_state_count(const sms_smoother *f);
SMS_API void sms_smoother_save_state(const sms_smoother *f, double *dst);
/** @brief Restore a saved state; validates first and writes nothing on error (::SMS_ERR_STATE). */
SMS_API sms_status sms_smoother_load_state(sms_smoother *f, const double *src, size_t n);
/** @brief The validation of sms_smoother_load_state() alone: writes nothing. */
SMS_API sms_status sms_smoother_check_state(const sms_smoother *f, const double *src, size_t n);
/** @brief Write the L impulse-response taps (normalised, DC gain 1) into taps[0..L-1]. */
SMS_API sms_status sms_smoother_taps(const sms_stage_config *config, double Ts, double *taps, size_t n_taps);

#ifdef __cplusplus
}
#endif
#endif
