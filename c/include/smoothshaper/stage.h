/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file stage.h
 * @brief One stage of any family behind one interface: the building block of a chain.
 *
 * Memory: the caller owns a small ::sms_stage (the kind and a pointer) and one block of
 * sms_stage_memory_size() ::sms_memory_cell. Nothing is allocated. The block holds, in this
 * order, each part starting on a cell boundary:
 * | family      | instance            | table                                 | delay line |
 * |-------------|---------------------|---------------------------------------|------------|
 * | smoothers   | ::sms_smoother      | -                                     | M reals (sms_smoother_buffer_size()) |
 * | shapers     | ::sms_shaper        | n_taps ::sms_shaper_tap (sms_shaper_tap_count()) | L reals (sms_shaper_buffer_size()) |
 * | notches     | ::sms_notch         | -                                     | -          |
 * so a stage costs what its family needs (a notch no more than its biquad, a shaper no more
 * than its own taps). A stage points into its block; if you copy a stage together with its
 * block elsewhere, call sms_stage_rebind() on the copy.
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

/**
 * @brief Unit of caller memory for stages and chains: aligned for every object a stage puts
 * in it (its instance, tap table and delay line). Memory from malloc() is always suitable
 * (allocate cells * sizeof(sms_memory_cell) bytes); static memory is an array of this type.
 */
typedef union sms_memory_cell {
    double d;      /**< as a double (design constants, identities) */
    sms_real r;    /**< as a signal value (delay lines, states) */
    size_t z;      /**< as an index */
    void *p;       /**< as a pointer */
} sms_memory_cell;

/** @brief One stage: its kind and its instance, which lives in the stage's memory block. */
typedef struct sms_stage {
    sms_kind kind;                 /**< the family, selects the member of u */
    /** @brief The instance, in the stage's memory block. */
    union {
        sms_smoother *smoother;    /**< ::SMS_RECTANGULAR .. ::SMS_EXPONENTIAL */
        sms_shaper *shaper;        /**< shapers and input smoothers */
        sms_notch *notch;          /**< ::SMS_NOTCH_TUSTIN, ::SMS_NOTCH_MATCHED */
    } u;
} sms_stage;

/**
 * @brief Cells of memory a stage of this config needs (instance, tap table, delay line; see
 * the table above). O(1) for every family (the smoothers' sizes are closed forms).
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_TOO_LONG (the size overflows size_t), or the
 *         config's validation status.
 * @param config   the stage description (see config.h for ranges)
 * @param Ts       sample period [s], finite and > 0
 * @param n_cells  receives the number of ::sms_memory_cell
 */
SMS_API sms_status sms_stage_memory_size(const sms_stage_config *config, double Ts, size_t *n_cells);

/** @brief Reals in the stage's delay line (M for a smoother, L for a shaper, 0 for a notch):
 * part of sms_stage_memory_size(), for reporting and limits; init needs the memory size.
 * @return ::SMS_OK, ::SMS_ERR_NULL, or the config's validation status.
 * @param config   the stage description (see config.h for ranges)
 * @param Ts       sample period [s], finite and > 0
 * @param n_reals  receives the number of reals
 */
SMS_API sms_status sms_stage_buffer_size(const sms_stage_config *config, double Ts, size_t *n_reals);

/**
 * @brief Validate and build a stage at rest at 0.
 * @param stage    instance to fill; untouched on error
 * @param config   the stage description (see config.h for ranges)
 * @param Ts       sample period [s], finite and > 0
 * @param memory   caller memory of at least sms_stage_memory_size() cells; the stage keeps it
 * @param n_cells  length of memory in cells
 * @return ::SMS_OK, ::SMS_ERR_NULL (stage, config or memory NULL), ::SMS_ERR_BUFFER_TOO_SMALL
 *         (n_cells below the size query) or a config status. Nothing is written on error.
 */
SMS_API sms_status sms_stage_init(sms_stage *stage, const sms_stage_config *config, double Ts,
                                  sms_memory_cell *memory, size_t n_cells);
/** @brief Put the stage at rest at `rest`: as if its input had been `rest` forever.
 * @param stage  the stage, built by sms_stage_init() or sms_stage_init_coeffs()
 * @param rest   finite, |rest| <= sms_stage_input_max()
 */
SMS_API void sms_stage_reset(sms_stage *stage, sms_real rest);
/** @brief Filter one sample in place.
 * @param stage  the stage, built by sms_stage_init() or sms_stage_init_coeffs()
 * @param x      in: the input x[n], |x| <= sms_stage_input_max(); out: the output y[n]
 */
SMS_API void sms_stage_step(sms_stage *stage, sms_real *x);
/** @brief Filter n samples; in == out is allowed (in place), other overlaps are not.
 * @param stage  the stage, built by sms_stage_init() or sms_stage_init_coeffs()
 * @param in     n inputs, |x| <= sms_stage_input_max()
 * @param out    n outputs; may be in itself
 * @param n      number of samples, any
 */
SMS_API void sms_stage_process(sms_stage *stage, const sms_real *in, sms_real *out, size_t n);
/**
 * @brief The stage's finite input range: inputs and reset values with |x| at most this keep
 * every output and state finite: min(::SMS_INPUT_MAX, L) with L = REAL_MAX over the stage's
 * internal gain. Smoothers: sms_smoother_input_max(); shapers: L = REAL_MAX / (2 sum |g_k|);
 * notches: L = REAL_MAX (an overflow restarts the notch, notch.h). O(1).
 * @param stage  the stage (read only)
 * @return the largest |input|, in (0, ::SMS_INPUT_MAX]
 */
SMS_API double sms_stage_input_max(const sms_stage *stage);
/**
 * @brief The stage's input limit before the cap at ::SMS_INPUT_MAX: the L of
 * sms_stage_input_max() (REAL_MAX over the internal gain; REAL_MAX for a notch). Inputs and
 * rest values with |x| <= L keep every sum of the stage finite. A chain's range divides each
 * stage's L by the bound R_i its inputs grow by before capping (sms_chain_input_max()): the
 * capped figure divided by R_i >= 3 would put every chain of two stages or more below
 * ::SMS_INPUT_MAX / 3 for no reason. O(1).
 * @param stage  the stage (read only)
 * @return L, in [sms_stage_input_max(), REAL_MAX]
 */
SMS_API double sms_stage_input_limit(const sms_stage *stage);
/**
 * @brief An upper bound G on the l1 norm of the stage's impulse response (its largest gain
 * from input to output in the time domain): |y - rest| <= G max |x - rest|. Smoothers:
 * 1 + 2 (|d_0| + |d_1|) (the base taps are non-negative and sum with the direct taps to 1);
 * shapers: sum |g_k|; notches: 1 + (|d0| + |d2|) E, E a closed-form bound on the l1 norm of
 * (1 - z^-1)/A(z) from the poles (a bound, not the norm: about 3 to 5 for ordinary notches,
 * HUGE_VAL if a pole rounds onto the unit circle). O(1).
 * @param stage  the stage (read only)
 * @return G >= 1 (HUGE_VAL for a notch whose pole rounds onto the unit circle)
 */
SMS_API double sms_stage_gain_bound(const sms_stage *stage);
/**
 * @brief sms_stage_input_max() and sms_stage_gain_bound() of the stage sms_stage_init() would
 * build from config at Ts, bit for bit, without building it (no memory): the design's
 * constants rounded to ::sms_real as the stage holds them. Smoothers: the design's input limit
 * and 1 + 2 (|d_0| + |d_1|); shapers and input smoothers: REAL_MAX / (2 sum |g_k|) and
 * sum |g_k|; notches: REAL_MAX and the closed-form l1 bound. For checking a configuration
 * before it replaces a running one (a retune that narrows the range). O(1) for smoothers and
 * notches, O(taps) for shapers (an input smoother: two passes over its window).
 * @param config      the stage (config.h for ranges)
 * @param Ts          sample period [s], finite, > 0
 * @param input_max   receives the input range, in (0, ::SMS_INPUT_MAX]; untouched on error
 * @param gain_bound  receives the gain bound G, at least 1 up to the rounding of the taps
 *                    (HUGE_VAL for a notch whose pole rounds onto the unit circle); untouched
 *                    on error
 * @return ::SMS_OK, ::SMS_ERR_NULL, or the config's status (as sms_stage_config_validate())
 */
SMS_API sms_status sms_stage_config_range(const sms_stage_config *config, double Ts,
                                          double *input_max, double *gain_bound);
/**
 * @brief sms_stage_input_limit() and sms_stage_gain_bound() of the stage sms_stage_init() would
 * build from config at Ts, bit for bit, without building it: sms_stage_config_range() before
 * its cap at ::SMS_INPUT_MAX (the same closed forms of the design's constants rounded to
 * ::sms_real). For the range of a chain that a retune leads to
 * (sms_tunable_chain_retune_input_max()), which caps only after dividing by each stage's R_i.
 * O(1) for smoothers and notches, O(taps) for shapers.
 * @param config      the stage (config.h for ranges)
 * @param Ts          sample period [s], finite, > 0
 * @param limit       receives L, in [the capped range, REAL_MAX]; untouched on error
 * @param gain_bound  receives the gain bound G, as sms_stage_config_range(); untouched on error
 * @return ::SMS_OK, ::SMS_ERR_NULL, or the config's status (as sms_stage_config_validate())
 */
SMS_API sms_status sms_stage_config_limit(const sms_stage_config *config, double Ts,
                                          double *limit, double *gain_bound);
/** @brief Impulse-response length L in samples (notch: 0, it is IIR).
 * @param stage  the stage (read only)
 * @return L [samples], 0 for a notch
 */
SMS_API size_t sms_stage_length(const sms_stage *stage);
/** @brief Number of doubles sms_stage_get_state() writes.
 * @param stage  the stage (read only)
 * @return the count, ::SMS_STATE_IDENTITY_COUNT plus the family's dynamic state
 */
SMS_API size_t sms_stage_state_count(const sms_stage *stage);
/** @brief Write the state: the configuration identity (config.h), then the delay line,
 * recursion state and indices, sms_stage_state_count() doubles.
 * @param stage  the stage (read only)
 * @param dst    sms_stage_state_count() doubles
 */
SMS_API void sms_stage_get_state(const sms_stage *stage, double *dst);
/** @brief Restore a state written by sms_stage_get_state() of an identically configured stage.
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_STATE_FORMAT .. ::SMS_ERR_STATE_DURATION (saved
 * by another configuration: the status names the first field of the identity that differs,
 * config.h), or ::SMS_ERR_STATE if n or any index does not fit.
 * @param stage  the stage, built by sms_stage_init() or sms_stage_init_coeffs(); untouched on error
 * @param src    the saved state
 * @param n      its length in doubles, sms_stage_state_count()
 */
SMS_API sms_status sms_stage_set_state(sms_stage *stage, const double *src, size_t n);
/** @brief Would sms_stage_set_state() accept this vector? Writes nothing.
 * @param stage  the stage (read only)
 * @param src    the saved state
 * @param n      its length in doubles
 * @return what sms_stage_set_state() would return
 */
SMS_API sms_status sms_stage_check_state(const sms_stage *stage, const double *src, size_t n);
/** @brief Is src a state a run with every input and rest value |x| <= x_max could reach? What
 * sms_stage_check_state() accepts, with every value finite and within what such inputs leave
 * in it (sms_smoother_check_state_range(), sms_shaper_check_state_range(),
 * sms_notch_check_state_range()). For loading states that come from outside. Writes nothing.
 * @param x_max  the largest |input| of the run, at most sms_stage_input_max()
 * @param stage  the stage (read only)
 * @param src    the saved state
 * @param n      its length in doubles
 * @return ::SMS_OK, what sms_stage_check_state() returns, or ::SMS_ERR_STATE
 */
SMS_API sms_status sms_stage_check_state_range(const sms_stage *stage, const double *src,
                                               size_t n, double x_max);
/** @brief Cells of memory this stage uses (= sms_stage_memory_size() of its config).
 * @param stage  the stage (read only)
 * @return the number of cells
 */
SMS_API size_t sms_stage_memory_len(const sms_stage *stage);
/** @brief Point a stage copied together with its memory (cell for cell) at the copy.
 * @param stage  the copied stage
 * @param memory the copy of its memory block
 */
SMS_API void sms_stage_rebind(sms_stage *stage, sms_memory_cell *memory);

#ifdef __cplusplus
}
#endif
#endif
