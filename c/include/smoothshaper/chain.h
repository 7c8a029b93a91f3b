/**
 * @file chain.h
 * @brief Stages in series: y = H_{n-1}( ... H_1(H_0(x))).
 *
 * Memory: the caller owns the ::sms_chain, an array of n ::sms_stage and one block of
 * sms_chain_memory_size() ::sms_memory_cell shared by all stages, laid out stage after stage
 * (each stage's part as stage.h describes: instance, tap table, delay line).
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
    sms_memory_cell *memory;   /**< the stages' memory, stage after stage */
    size_t memory_len;         /**< cells of it in use */
} sms_chain;

/** @brief Cells of memory a chain of these n configs needs (the sum of
 * sms_stage_memory_size() over the stages).
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_ORDER (n = 0 or > ::SMS_CHAIN_MAX_STAGES),
 *         ::SMS_ERR_TOO_LONG (the sum overflows size_t), or the first failing config's status. */
SMS_API sms_status sms_chain_memory_size(const sms_stage_config *configs, size_t n, double Ts,
                                         size_t *n_cells);
/** @brief Validate every config, then build all stages at rest at 0.
 * @param stages  caller array of n stages
 * @param memory  caller memory of n_cells >= sms_chain_memory_size() cells
 * @return ::SMS_OK, ::SMS_ERR_NULL (chain, stages, configs or memory NULL), the statuses of
 *         sms_chain_memory_size(), ::SMS_ERR_BUFFER_TOO_SMALL. On error nothing is touched
 *         (chain, stages and memory keep their contents). */
SMS_API sms_status sms_chain_init(sms_chain *chain, sms_stage *stages, const sms_stage_config *configs,
                                  size_t n, double Ts, sms_memory_cell *memory, size_t n_cells);
SMS_API void sms_chain_reset(sms_chain *chain, sms_real rest);
SMS_API void sms_chain_step(sms_chain *chain, sms_real *x);
/** @brief Filter n samples through all stages; in == out allowed. */
SMS_API void sms_chain_process(sms_chain *chain, const sms_real *in, sms_real *out, size_t n);
/** @brief Sum of the stages' impulse-response lengths minus (stages - 1): the chain's FIR
 * length in samples (IIR notches count 0). */
SMS_API size_t sms_chain_length(const sms_chain *chain);
/**
 * @brief The chain's finite input range: inputs and reset values with |x| at most this keep
 * every stage's output and state finite. All stages rest at the same value and map x - rest
 * to y - rest through their taps, so stage i sees at most R_i |x|, R_0 = 1,
 * R_i = 1 + 2 G_0 ... G_{i-1} with G_j = sms_stage_gain_bound(); the bound is
 * min_i L_i / R_i, at most ::SMS_INPUT_MAX, L_i the stage's range before that cap (the
 * REAL_MAX-over-gain figure of sms_stage_input_max()). O(stages).
 */
SMS_API double sms_chain_input_max(const sms_chain *chain);
SMS_API size_t sms_chain_state_count(const sms_chain *chain);
SMS_API void sms_chain_get_state(const sms_chain *chain, double *dst);
/** @brief Restore a state written by sms_chain_get_state() (the stages' states one after the
 * other, each starting with its configuration identity, config.h). Checks every stage before
 * writing any: on error nothing changes.
 * @return ::SMS_OK, ::SMS_ERR_NULL; ::SMS_ERR_STATE_FORMAT .. ::SMS_ERR_STATE_DURATION naming the
 * first field that differs in the first stage saved by another configuration (also when the
 * lengths differ); ::SMS_ERR_STATE if n or a value does not fit. */
SMS_API sms_status sms_chain_set_state(sms_chain *chain, const double *src, size_t n);
/** @brief After copying chain, stages and memory elsewhere, point the copy at its own stages
 * and memory. */
SMS_API void sms_chain_rebind(sms_chain *chain, sms_stage *stages, sms_memory_cell *memory);

#ifdef __cplusplus
}
#endif
#endif
