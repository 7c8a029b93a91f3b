/* SPDX-License-Identifier: Apache-2.0 */
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

/** @brief Stages in series, built by sms_chain_init(). Fields are public for inspection. */
typedef struct sms_chain {
    sms_stage *stages;         /**< caller array of n_stages stages, first applied first */
    size_t n_stages;           /**< 1 .. ::SMS_CHAIN_MAX_STAGES */
    sms_memory_cell *memory;   /**< the stages' memory, stage after stage */
    size_t memory_len;         /**< cells of it in use */
} sms_chain;

/** @brief Cells of memory a chain of these n configs needs (the sum of
 * sms_stage_memory_size() over the stages).
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_ORDER (n = 0 or > ::SMS_CHAIN_MAX_STAGES),
 *         ::SMS_ERR_TOO_LONG (the sum overflows size_t), or the first failing config's status.
 * @param configs  n stage descriptions, first applied first (config.h for ranges)
 * @param n        stages, 1 .. ::SMS_CHAIN_MAX_STAGES
 * @param Ts       sample period [s], finite and > 0
 * @param n_cells  receives the number of ::sms_memory_cell
 */
SMS_API sms_status sms_chain_memory_size(const sms_stage_config *configs, size_t n, double Ts,
                                         size_t *n_cells);
/** @brief Validate every config, then build all stages at rest at 0.
 * @param stages  caller array of n stages
 * @param memory  caller memory of n_cells >= sms_chain_memory_size() cells
 * @return ::SMS_OK, ::SMS_ERR_NULL (chain, stages, configs or memory NULL), the statuses of
 *         sms_chain_memory_size(), ::SMS_ERR_BUFFER_TOO_SMALL. On error nothing is touched
 *         (chain, stages and memory keep their contents).
 * @param chain   instance to fill; untouched on error
 * @param configs  n stage descriptions, first applied first (config.h for ranges)
 * @param n        stages, 1 .. ::SMS_CHAIN_MAX_STAGES
 * @param Ts       sample period [s], finite and > 0
 * @param n_cells length of memory in cells
 */
SMS_API sms_status sms_chain_init(sms_chain *chain, sms_stage *stages, const sms_stage_config *configs,
                                  size_t n, double Ts, sms_memory_cell *memory, size_t n_cells);
/** @brief Put every stage at rest at `rest`: as if the input had been `rest` forever, so the
 * next outputs equal `rest` until the input changes.
 * @param chain  the chain
 * @param rest   finite, |rest| <= sms_chain_input_max() */
SMS_API void sms_chain_reset(sms_chain *chain, sms_real rest);
/** @brief Filter one sample in place through every stage in order; O(1) per smoother and
 * notch, O(taps) per shaper, no libm.
 * @param chain  the chain
 * @param x      in: the input x[n], |x| <= sms_chain_input_max(); out: the output y[n] */
SMS_API void sms_chain_step(sms_chain *chain, sms_real *x);
/** @brief Filter n samples through all stages; in == out allowed.
 * @param chain  the chain, built by sms_chain_init() or sms_chain_init_coeffs()
 * @param in     n inputs, |x| <= sms_chain_input_max()
 * @param out    n outputs; may be in itself
 * @param n      number of samples, any
 */
SMS_API void sms_chain_process(sms_chain *chain, const sms_real *in, sms_real *out, size_t n);
/** @brief Sum of the stages' impulse-response lengths minus (stages - 1): the chain's FIR
 * length in samples (IIR notches count 0).
 * @param chain  the chain (read only)
 * @return the length [samples]
 */
SMS_API size_t sms_chain_length(const sms_chain *chain);
/**
 * @brief The chain's finite input range: inputs and reset values with |x| at most this keep
 * every stage's output and state finite. All stages rest at the same value and map x - rest
 * to y - rest through their taps, so stage i sees at most R_i |x|, R_0 = 1,
 * R_i = 1 + 2 G_0 ... G_{i-1} with G_j = sms_stage_gain_bound(); the bound is
 * min_i L_i / R_i, at most ::SMS_INPUT_MAX, L_i the stage's range before that cap (the
 * REAL_MAX-over-gain figure of sms_stage_input_max()). O(stages).
 * @param chain  the chain (read only)
 * @return the largest |input|, in (0, ::SMS_INPUT_MAX]
 */
SMS_API double sms_chain_input_max(const sms_chain *chain);
/**
 * @brief sms_chain_input_max() of the chain sms_chain_init() would build from these n configs
 * at Ts, bit for bit, without building it: stage i's uncapped range (sms_stage_config_range()
 * before the cap) over R_i = 1 + 2 G_0 ... G_{i-1}, capped at ::SMS_INPUT_MAX. O(stages), plus
 * each shaper's taps.
 * @param configs    n stage configurations, first applied first
 * @param n          stages, 1 .. ::SMS_CHAIN_MAX_STAGES
 * @param Ts         sample period [s], finite, > 0
 * @param input_max  receives the range, in (0, ::SMS_INPUT_MAX]; untouched on error
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_ORDER (n = 0 or > ::SMS_CHAIN_MAX_STAGES), or the
 *         first failing config's status
 */
SMS_API sms_status sms_chain_config_input_max(const sms_stage_config *configs, size_t n,
                                              double Ts, double *input_max);
/**
 * @brief Filter n samples of the constant input x: the state and the last output (into *y)
 * are those of n calls of sms_chain_step() with x, bit for bit, at a cost bounded whatever n.
 *
 * Each stage absorbs a constant input in a bounded number of samples, after which its values
 * stop changing and only its phase moves: a smoother once both its restarted copies began
 * under the input (sms_smoother_settle_length(), at most 2M + 2 samples), a shaper once its
 * delay line holds only the input (L + 1), a notch once its transient has ended exactly
 * (sms_notch_is_settled(), about sms_notch_settle_bound() samples). Stage i sees a constant
 * input once stage i - 1 has absorbed its own. The stages are filtered in blocks until they
 * have absorbed (from then on only their phase is advanced, in O(1)); stages that are all FIR
 * and absorb within the remaining samples are put straight into their absorbed state at the
 * end (sms_smoother_settle(): O(M) writes, no filtering). So the cost is at most the
 * filtering of each stage i for T_i samples, T_i = B_0 + ... + B_i with B_j the bounds above
 * (sms_chain_hold_cost() sums them from the configs), plus O(memory); a chain of FIR stages
 * held longer than T costs only its memory writes (about 1 ns per real), whatever n.
 * @param n  samples (0: nothing changes, *y untouched)
 * @param x  finite, |x| <= sms_chain_input_max()
 * @param chain  the chain, built by sms_chain_init() or sms_chain_init_coeffs()
 * @param y      receives the last output (untouched when n = 0)
 */
SMS_API void sms_chain_hold(sms_chain *chain, sms_real x, uint64_t n, sms_real *y);
/**
 * @brief Worst-case filtering work of sms_chain_hold() for a chain of these configs: the sum
 * over the stages of T_i = B_0 + ... + B_i samples, B_j = 2 M_j + 2 for a smoother (M_j its ring
 * length), L_j + 1 for a shaper, sms_notch_settle_bound() for a notch (HUGE_VAL when its poles
 * do not decay); an input smoother's T_i counts its taps / ::SMS_SHAPER_MAX_TAPS times (every
 * sample of its window is a tap). Multiply by the cost of a stage-sample (about 1.5 to 4 ns,
 * x86-64) for a time. O(stages).
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_ORDER (n = 0 or > ::SMS_CHAIN_MAX_STAGES), or the
 *         first failing config's status.
 * @param configs  n stage descriptions, first applied first (config.h for ranges)
 * @param n        stages, 1 .. ::SMS_CHAIN_MAX_STAGES
 * @param Ts       sample period [s], finite and > 0
 * @param samples  receives the work in stage-samples (HUGE_VAL with a notch that does not decay)
 */
SMS_API sms_status sms_chain_hold_cost(const sms_stage_config *configs, size_t n, double Ts,
                                       double *samples);
/**
 * @brief Samples of a constant input after which the chain has absorbed it from any state:
 * the sum over the stages of 2 M + 2 (smoother), L + 1 (shaper) and sms_notch_settle_bound()
 * (notch: an estimate for the largest state). For a chain without a notch it also bounds how
 * many of the latest inputs its state depends on: the stages' states are the same after that
 * many samples whatever they held before (with a notch, the same to rounding). O(stages).
 * @param chain  the chain (read only)
 * @return the sample count (HUGE_VAL with a notch that does not decay)
 */
SMS_API double sms_chain_settle_bound(const sms_chain *chain);
/** @brief Advance every stage's phase (ring heads) by n samples, keeping
 * their values: exactly n samples of an absorbed input; on any other state the phase of n
 * samples later with stale values, which the next sms_chain_settle_bound() samples of a FIR
 * chain replace entirely. O(stages).
 * @param chain  the chain, built by sms_chain_init() or sms_chain_init_coeffs()
 * @param n      samples, any
 */
SMS_API void sms_chain_advance(sms_chain *chain, uint64_t n);
/** @brief The state and last output after n samples whose last sms_chain_settle_bound() (or
 * more) were the constant x: every stage put into its absorbed state (sms_smoother_settle(),
 * shapers' delay lines filled, notches at their fixed point), phase advanced by n, whatever
 * the earlier inputs; bit for bit n samples (for a notch, as far as its bound holds). O(memory).
 * @param n  >= 2 and > sms_chain_settle_bound()
 * @param chain  the chain, built by sms_chain_init() or sms_chain_init_coeffs()
 * @param x      the held input, finite, |x| <= sms_chain_input_max()
 * @return the output of the last sample
 */
SMS_API sms_real sms_chain_settle(sms_chain *chain, sms_real x, uint64_t n);
/** @brief Doubles of the chain's saved state: the sum of sms_stage_state_count() over its
 * stages.
 * @param chain  the chain (read only)
 * @return the count */
SMS_API size_t sms_chain_state_count(const sms_chain *chain);
/** @brief Write the state: each stage's sms_stage_get_state() one after the other.
 * @param chain  the chain (read only)
 * @param dst    sms_chain_state_count() doubles */
SMS_API void sms_chain_get_state(const sms_chain *chain, double *dst);
/** @brief Restore a state written by sms_chain_get_state() (the stages' states one after the
 * other, each starting with its configuration identity, config.h). Checks every stage before
 * writing any: on error nothing changes.
 * @return ::SMS_OK, ::SMS_ERR_NULL; ::SMS_ERR_STATE_FORMAT .. ::SMS_ERR_STATE_DURATION naming the
 * first field that differs in the first stage saved by another configuration (also when the
 * lengths differ); ::SMS_ERR_STATE if n or a value does not fit.
 * @param chain  the chain, built by sms_chain_init() or sms_chain_init_coeffs(); untouched on error
 * @param src    the saved state
 * @param n      its length in doubles, sms_chain_state_count()
 */
SMS_API sms_status sms_chain_set_state(sms_chain *chain, const double *src, size_t n);
/** @brief Is src a state a run of the chain with every input and rest value |x| <= x_max could
 * reach? Each stage's part as sms_stage_check_state_range() with the range stage i sees,
 * (1 + 2 G_0 ... G_{i-1}) x_max (sms_chain_input_max()). Writes nothing.
 * @param x_max  the largest |input| of the run, at most sms_chain_input_max()
 * @return ::SMS_OK, ::SMS_ERR_NULL, a stage's identity status, or ::SMS_ERR_STATE.
 * @param chain  the chain (read only)
 * @param src    the saved state
 * @param n      its length in doubles
 */
SMS_API sms_status sms_chain_check_state_range(const sms_chain *chain, const double *src,
                                               size_t n, double x_max);
/** @brief After copying chain, stages and memory elsewhere, point the copy at its own stages
 * and memory.
 * @param chain   the copied chain
 * @param stages  the copy of its stage array
 * @param memory  the copy of its memory block
 */
SMS_API void sms_chain_rebind(sms_chain *chain, sms_stage *stages, sms_memory_cell *memory);

#ifdef __cplusplus
}
#endif
#endif
