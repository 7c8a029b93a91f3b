/**
 * @file shaper.h
 * @brief Input shapers: ZV^n (ZV, ZVD, ZVDD, ...), EI, two-hump EI, MZV (SPEC 3.5).
 * OWNER: C shapers work package (struct fields may change).
 */
#ifndef SMOOTHSHAPER_SHAPER_H
#define SMOOTHSHAPER_SHAPER_H

#include "smoothshaper/config.h"

#ifdef __cplusplus
extern "C" {
#endif

/** @brief Most non-zero taps of a discrete shaper (ZV^8 split over neighbouring samples). */
#define SMS_SHAPER_MAX_TAPS 24

typedef struct sms_shaper {
    sms_kind kind;
    size_t length;                        /**< impulse response length L [samples] */
    size_t n_taps;
    size_t tap_delay[SMS_SHAPER_MAX_TAPS];
    sms_real tap_gain[SMS_SHAPER_MAX_TAPS];
    sms_real rest;
    sms_real *history;
    size_t history_len;
    size_t head;
} sms_shaper;

SMS_API sms_status sms_shaper_buffer_size(const sms_stage_config *config, double Ts, size_t *n_reals);
SMS_API sms_status sms_shaper_init(sms_shaper *f, const sms_stage_config *config, double Ts,
                                   sms_real *buffer, size_t n_reals);
SMS_API void sms_shaper_reset(sms_shaper *f, sms_real rest);
SMS_API void sms_shaper_step(sms_shaper *f, sms_real *x);
SMS_API void sms_shaper_process(sms_shaper *f, const sms_real *in, sms_real *out, size_t n);
SMS_API size_t sms_shaper_state_count(const sms_shaper *f);
SMS_API void sms_shaper_save_state(const sms_shaper *f, double *dst);
/** @brief Restore a saved state; validates first and writes nothing on error (::SMS_ERR_STATE). */
SMS_API sms_status sms_shaper_load_state(sms_shaper *f, const double *src, size_t n);
/** @brief The validation of sms_shaper_load_state() alone: writes nothing. */
SMS_API sms_status sms_shaper_check_state(const sms_shaper *f, const double *src, size_t n);
/** @brief The continuous design: amplitudes (sum 1) and times [s]; *count receives how many. */
SMS_API sms_status sms_shaper_impulses(const sms_stage_config *config, double *amplitudes,
                                       double *times, size_t capacity, size_t *count);
SMS_API sms_status sms_shaper_taps(const sms_stage_config *config, double Ts, double *taps, size_t n_taps);

#ifdef __cplusplus
}
#endif
#endif
