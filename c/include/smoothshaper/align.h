/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file align.h
 * @brief The lag of a stage or chain, and the fractional delay that pads chains to a common
 * lag or centres a planned trajectory (docs/align.md).
 *
 * **Lag.** A stage with unit DC gain maps a constant-speed input x[n] = x0 + v n to
 * x0 + v (n - D) once its transient is over: it delays the motion by its DC group delay D,
 * the centroid of its impulse response, D = sum_i i h[i] for FIR stages (smoothers: of the
 * taps of docs/exact-mode.md; shapers: of their sparse taps), D = (d2 - d0)/(1 + a1 + a2) for a
 * notch (notch.h's realisation; the DC group delay of 1 + D(z)/A(z)). A chain's lag is the sum
 * of its stages' (the derivative of a product at z = 1). Computed in double from the realised
 * design: O(L) for a smoother (its taps one by one), O(taps) for a shaper, O(1) for a notch;
 * not for the per-sample path.
 *
 * **Fractional delay** ::sms_delay: y[n] = x[n-m] + f (x[n-m-1] - x[n-m]) for a delay of
 * d = m + f samples, m = floor(d), 0 <= f < 1: linear interpolation between two samples, with
 * unit DC gain and lag exactly d, so a constant-speed input comes out delayed by exactly d
 * samples (to rounding), a constant input exactly unchanged, and f = 0 is a pure delay (the
 * samples themselves). It is the 2-tap FIR (1 - f) z^-m + f z^-(m+1): |H| falls from 1 at DC
 * to |1 - 2 f| at the Nyquist frequency (a zero there for f = 1/2), which smooths a trajectory
 * by less than a sample. Memory: m + 2 reals of caller buffer. O(1) per sample, no libm, float
 * and double.
 */
#ifndef SMOOTHSHAPER_ALIGN_H
#define SMOOTHSHAPER_ALIGN_H

#include <stdint.h>
#include "smoothshaper/chain.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * @brief The lag D [samples] of a stage of this config at Ts (see above).
 * @return ::SMS_OK, ::SMS_ERR_NULL, or the config's status.
 * @param config the stage description (config.h for ranges)
 * @param Ts     sample period [s], finite, > 0
 * @param lag    receives D [samples], >= 0
 */
SMS_API sms_status sms_stage_config_lag(const sms_stage_config *config, double Ts, double *lag);
/** @brief The lag of a chain of these configs: the sum of the stages' [samples].
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_ORDER (n > ::SMS_CHAIN_MAX_STAGES), or the first
 *         failing config's status; n = 0 gives 0.
 * @param configs n stage descriptions
 * @param n       stages, 0 .. ::SMS_CHAIN_MAX_STAGES
 * @param Ts      sample period [s], finite, > 0
 * @param lag     receives the sum [samples], >= 0
 */
SMS_API sms_status sms_chain_config_lag(const sms_stage_config *configs, size_t n, double Ts,
                                        double *lag);
/** @brief The lag of a built stage [samples], from the configuration and Ts it was built with
 * (its identity, config.h); for user-defined impulses, whose identity holds a checksum, from
 * the stage's taps (the same design: sms_stage_config_lag() of its config, to the rounding of
 * the taps to ::sms_real).
 * @param stage  a built stage (read only)
 * @return D [samples], >= 0
 */
SMS_API double sms_stage_lag(const sms_stage *stage);
/** @brief The lag of a built chain [samples] (0 for no stages).
 * @param chain  a built chain (read only)
 * @return the sum of its stages' lags [samples], >= 0
 */
SMS_API double sms_chain_lag(const sms_chain *chain);

/** @brief Largest delay a ::sms_delay takes [samples] (2^40: its indices stay exact doubles in
 * a saved state). */
#define SMS_DELAY_MAX_SAMPLES 1099511627776.0

/** @brief A fractional delay. Fields are public for inspection; change them only through the
 * functions below. */
typedef struct sms_delay {
    size_t whole;        /**< m = floor(d) */
    sms_real fraction;   /**< f = d - m, in [0, 1) */
    double samples;      /**< d */
    sms_real *ring;      /**< caller buffer: the last m + 2 inputs */
    size_t len;          /**< m + 2 */
    size_t head;         /**< slot the next input is written to */
} sms_delay;

/** @brief Reals of buffer a delay of d samples needs (floor(d) + 2).
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_DURATION (d NaN, negative or above
 *         ::SMS_DELAY_MAX_SAMPLES).
 * @param samples the delay d [samples], finite, in [0, ::SMS_DELAY_MAX_SAMPLES]
 * @param n_reals receives floor(d) + 2
 */
SMS_API sms_status sms_delay_buffer_size(double samples, size_t *n_reals);
/** @brief Build a delay of d samples at rest at 0.
 * @return as sms_delay_buffer_size(), ::SMS_ERR_NULL (d or buffer NULL),
 *         ::SMS_ERR_BUFFER_TOO_SMALL. Nothing is written on error.
 * @param d       instance to fill; untouched on error
 * @param samples the delay [samples], as sms_delay_buffer_size()
 * @param buffer  the ring, kept by d
 * @param n_reals reals in buffer, >= floor(samples) + 2
 */
SMS_API sms_status sms_delay_init(sms_delay *d, double samples, sms_real *buffer,
                                  size_t n_reals);
/** @brief Rest at rest: as if the input had been rest forever. O(m).
 * @param d      the delay, built by sms_delay_init()
 * @param rest   finite
 */
SMS_API void sms_delay_reset(sms_delay *d, sms_real rest);
/** @brief One sample in place.
 * @param d      the delay, built by sms_delay_init()
 * @param x      in: the input x[n]; out: the output y[n]
 */
SMS_API void sms_delay_step(sms_delay *d, sms_real *x);
/** @brief n samples; in == out allowed, other overlaps not; the same as n steps.
 * @param d      the delay, built by sms_delay_init()
 * @param in     n inputs
 * @param out    n outputs; may be in itself
 * @param n      number of samples, any
 */
SMS_API void sms_delay_process(sms_delay *d, const sms_real *in, sms_real *out, size_t n);
/** @brief Samples of a constant input after which the delay holds only it (m + 2).
 * @param d      the delay (read only)
 * @return m + 2
 */
SMS_API uint64_t sms_delay_settle_length(const sms_delay *d);
/** @brief The state after n >= sms_delay_settle_length() samples of the constant x, in O(m):
 * the ring filled with x, the head advanced by n; returns the last output (x).
 * @param d      the delay, built by sms_delay_init()
 * @param x      the held input
 * @param n      samples, >= sms_delay_settle_length()
 * @return the last output, x
 */
SMS_API sms_real sms_delay_settle(sms_delay *d, sms_real x, uint64_t n);
/** @brief Advance the head by n samples, keeping the values (exactly n samples of an absorbed
 * input). O(1).
 * @param d      the delay, built by sms_delay_init()
 * @param n      samples, any
 */
SMS_API void sms_delay_advance(sms_delay *d, uint64_t n);
/** @brief Doubles of a saved state: 3 + m + 2 (d, m + 2, head, the ring in slot order).
 * @param d      the delay (read only)
 * @return 3 + m + 2
 */
SMS_API size_t sms_delay_state_count(const sms_delay *d);
/** @brief Write the state, sms_delay_state_count() doubles.
 * @param d    the delay (read only)
 * @param dst  sms_delay_state_count() doubles */
SMS_API void sms_delay_get_state(const sms_delay *d, double *dst);
/** @brief Would sms_delay_set_state() accept it? ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_STATE
 * (another delay, n, or a head out of range). Writes nothing.
 * @param d      the delay (read only)
 * @param src    the saved state
 * @param n      its length in doubles
 * @return ::SMS_OK, ::SMS_ERR_NULL or ::SMS_ERR_STATE
 */
SMS_API sms_status sms_delay_check_state(const sms_delay *d, const double *src, size_t n);
/** @brief Restore a saved state of a delay of the same d; nothing written on error.
 * @param d      the delay, built by sms_delay_init(); untouched on error
 * @param src    the saved state
 * @param n      its length in doubles, sms_delay_state_count()
 * @return as sms_delay_check_state()
 */
SMS_API sms_status sms_delay_set_state(sms_delay *d, const double *src, size_t n);

#ifdef __cplusplus
}
#endif
#endif
