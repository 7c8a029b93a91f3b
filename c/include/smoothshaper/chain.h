/**
 * @file chain.h
 * @brief Stages in series: y = H_{n-1}( ... H_1(H_0(x))).
 *
 * Memory: the caller owns the ::sms_chain, an array of n ::sms_stage and one buffer of
 * sms_chain_buffer_size() reals shared by all stages (laid out stage after stage).
 */
#ifndef SMOOTHSHAPER_CHAIN_H
#define SMOOTHSHAPER_CHAIN_H

#include "smoothshaper/stage.h"

#ifdef __cplusplus
extern "C" {
#endif

/** @brief Most stages in one chain. */
#define SMS_CHAIN_MAX_STAGES 16

typedef struct sms_chain {
    sms_stage *stages;
    size_t n_stages;
    sms_real *buffer;
    size_t buffer_len;
} sms_chain;

/** @brief Reals needed by a chain of these n configs (sum of the stages' needs).
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_ORDER (n = 0 or > ::SMS_CHAIN_MAX_STAGES),
 *         ::SMS_ERR_TOO_LONG, or the first failing config's status. */
SMS_API sms_status sms_chain_buffer_size(const sms_stage_config *configs, size_t n, double Ts,
                                         size_t *n_reals);
/** @brief Validate every config, then build all stages at rest at 0. On error nothing is
 * touched (chain, stages and buffer keep their contents). */
SMS_API sms_status sms_chain_init(sms_chain *chain, sms_stage *stages, const sms_stage_config *configs,
                                  size_t n, double Ts, sms_real *buffer, size_t n_reals);
SMS_API void sms_chain_reset(sms_chain *chain, sms_real rest);
SMS_API void sms_chain_step(sms_chain *chain, sms_real *x);
/** @brief Filter n samples through all stages; in == out allowed. */
SMS_API void sms_chain_process(sms_chain *chain, const sms_real *in, sms_real *out, size_t n);
/** @brief Sum of the stages' impulse-response lengths minus (stages - 1): the chain's FIR
 * length in samples (IIR notches count 0). */
SMS_API size_t sms_chain_length(const sms_chain *chain);
SMS_API size_t sms_chain_state_count(const sms_chain *chain);
SMS_API void sms_chain_get_state(const sms_chain *chain, double *dst);
SMS_API sms_status sms_chain_set_state(sms_chain *chain, const double *src, size_t n);
/** @brief After copying chain, stages and buffer elsewhere, point the copy at its own memory. */
SMS_API void sms_chain_rebind(sms_chain *chain, sms_stage *stages, sms_real *buffer);

#ifdef __cplusplus
}
#endif
#endif
