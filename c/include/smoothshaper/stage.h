/**
 * @file stage.h
 * @brief One stage of any family behind one interface: the building block of a chain.
 *
 * Memory: the caller owns the ::sms_stage and a buffer of sms_stage_buffer_size() reals
 * (the delay line). Nothing is allocated. A stage keeps a pointer to its buffer; if you copy
 * a stage together with its buffer elsewhere, call sms_stage_rebind() on the copy.
 *
 * Every stage has unit DC gain and realises y[n] = sum_i h[i] x[n-i], i = 0..L-1, with h the
 * family's taps (see the family headers), except the notch, which is the IIR biquad of notch.h.
 */
#ifndef SMOOTHSHAPER_STAGE_H
#define SMOOTHSHAPER_STAGE_H

#include "smoothshaper/config.h"
#include "smoothshaper/smoother.h"
#include "smoothshaper/shaper.h"
#include "smoothshaper/notch.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct sms_stage {
    sms_kind kind;
    union {
        sms_smoother smoother;
        sms_shaper shaper;
        sms_notch notch;
    } u;
} sms_stage;

/** @brief Number of ::sms_real the stage needs as its buffer (0 for a notch).
 * @return ::SMS_OK, ::SMS_ERR_NULL, or the config's validation status. */
SMS_API sms_status sms_stage_buffer_size(const sms_stage_config *config, double Ts, size_t *n_reals);

/**
 * @brief Validate and build a stage at rest at 0.
 * @param stage    instance to fill; untouched on error
 * @param config   the stage description (see config.h for ranges)
 * @param Ts       sample period [s], finite and > 0
 * @param buffer   caller memory of at least sms_stage_buffer_size() reals (may be NULL if 0)
 * @param n_reals  length of buffer
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_BUFFER_TOO_SMALL or a config status.
 */
SMS_API sms_status sms_stage_init(sms_stage *stage, const sms_stage_config *config, double Ts,
                                  sms_real *buffer, size_t n_reals);
/** @brief Put the stage at rest at `rest`: as if its input had been `rest` forever. */
SMS_API void sms_stage_reset(sms_stage *stage, sms_real rest);
/** @brief Filter one sample in place. */
SMS_API void sms_stage_step(sms_stage *stage, sms_real *x);
/** @brief Filter n samples; in == out is allowed (in place), other overlaps are not. */
SMS_API void sms_stage_process(sms_stage *stage, const sms_real *in, sms_real *out, size_t n);
/** @brief Impulse-response length L in samples (notch: 0, it is IIR). */
SMS_API size_t sms_stage_length(const sms_stage *stage);
/** @brief Number of doubles sms_stage_get_state() writes. */
SMS_API size_t sms_stage_state_count(const sms_stage *stage);
/** @brief Write the dynamic state (delay line, recursion state, indices) as doubles. */
SMS_API void sms_stage_get_state(const sms_stage *stage, double *dst);
/** @brief Restore a state written by sms_stage_get_state() of an identically configured stage.
 * @return ::SMS_OK, ::SMS_ERR_NULL, or ::SMS_ERR_STATE if n or any index does not fit. */
SMS_API sms_status sms_stage_set_state(sms_stage *stage, const double *src, size_t n);
/** @brief Would sms_stage_set_state() accept this vector? Writes nothing. */
SMS_API sms_status sms_stage_check_state(const sms_stage *stage, const double *src, size_t n);
/** @brief Reals of the caller buffer this stage uses (its delay line; 0 for a notch). */
SMS_API size_t sms_stage_buffer_len(const sms_stage *stage);
/** @brief Point a (copied) stage at a buffer holding the same contents as its original's. */
SMS_API void sms_stage_rebind(sms_stage *stage, sms_real *buffer);

#ifdef __cplusplus
}
#endif
#endif
