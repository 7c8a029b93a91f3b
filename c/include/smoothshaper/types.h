/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file types.h
 * @brief Scalar type, status codes and stage kinds shared by every smoothshaper module.
 *
 * Precision: the library is compiled once per precision from one source. Define
 * `SMS_USE_FLOAT` (the `smoothshaper_float` CMake target does it for you, also for its
 * consumers) to make ::sms_real a `float`; otherwise it is a `double`. Design quantities
 * (durations, frequencies, damping) are always `double`: only the signal path and the filter
 * state use ::sms_real. The float build's functions link under the suffix `_f32`
 * (precision.h), so code compiled for one precision does not link against the other library.
 */
#ifndef SMOOTHSHAPER_TYPES_H
#define SMOOTHSHAPER_TYPES_H

#include <stddef.h>
#include "smoothshaper/export.h"
#include "smoothshaper/precision.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifdef SMS_USE_FLOAT
typedef float sms_real;   /**< signal and state type (float build) */
#else
typedef double sms_real;  /**< signal and state type (double build) */
#endif

/**
 * @brief Largest input magnitude the per-sample paths are specified for.
 *
 * The largest internal sums (x - rest, the recursions' states, the notch's w) are the input
 * range times the stage's internal gain, and this bound leaves a factor of about 2^10 (float
 * 2^13) to the overflow threshold of ::sms_real: inputs and reset values with
 * |x| <= SMS_INPUT_MAX keep every output and state finite for stages whose internal gain is
 * below that factor (all undamped smoothers, notches and shapers away from zeta -> 1).
 * A configuration with a larger internal gain (a heavily damped harmonic smoother: about
 * e^{-sigma Ts}/sin(pi/N); a shaper with large correction taps) has a smaller finite range,
 * computed in closed form when it is built: sms_smoother_input_max(), sms_stage_input_max(),
 * sms_chain_input_max() (docs/numerics.md). Larger or non-finite inputs are not refused on the
 * per-sample path (it has no status): they can make outputs non-finite for a while (see each
 * family's header for how it recovers), and the state saved then still loads (save/load
 * accept whatever a run produces; tests/c/test_fuzz_api.c checks it). The Python wrappers and
 * the FMUs refuse inputs beyond the configuration's range before they reach the core.
 */
#ifdef SMS_USE_FLOAT
#define SMS_INPUT_MAX 3.0e35
#else
#define SMS_INPUT_MAX 1.0e305
#endif

/**
 * @brief Largest sample period [s] the generators (sms_generator_init(),
 * sms_multi_generator_init(), sms_bspline_init()) and the FMUs take: 2^-56 times the largest
 * double, rounded down to a power of two (2^967 = 1.25e291 s), in both builds (Ts, the times
 * derived from it and a state's values are doubles in both).
 *
 * The bound comes from the time arithmetic. A move's durations and a state's times are held to
 * 2^53 samples (the counts stay exact as doubles), so each is at most 2^53 Ts; a move adds up
 * to 5 of them (its ramps, cruise and the first sample's offset) and the FMU's clock adds
 * the start time to ticks Ts with ticks below 2^52. With 2^56 Ts no larger than the largest
 * double all of these sums are finite; a larger Ts makes 2^53 Ts itself overflow
 * (Ts = DBL_MAX), and a state check could no longer bound a duration. A larger Ts is refused
 * with ::SMS_ERR_SAMPLE_PERIOD_RANGE.
 */
#define SMS_TS_MAX 0x1p967

/**
 * @brief Result of every function that can fail. ::SMS_OK is 0, errors are negative and each
 * names the offending argument. On any error the object passed in is left untouched.
 */
typedef enum sms_status {
    SMS_OK = 0,                     /**< success */
    SMS_ERR_NULL = -1,              /**< a required pointer argument is NULL */
    SMS_ERR_SAMPLE_PERIOD = -2,     /**< Ts is NaN/Inf or <= 0 */
    SMS_ERR_DURATION = -3,          /**< T is NaN/Inf or <= 0 (a target's minimum_duration: NaN/Inf,
                                         < 0, beyond 2^50 samples, or not 0 where the
                                         profile cannot stretch a move) */
    SMS_ERR_DURATION_BELOW_TS = -4, /**< T < Ts (beyond the 1e-9 grid tolerance): shorter than
                                     one sample; see config.h for the one rule */
    SMS_ERR_SIGMA = -5,             /**< sigma is NaN/Inf or > 0 (an unstable mode) */
    SMS_ERR_WN = -6,                /**< natural frequency wn is NaN/Inf or <= 0 */
    SMS_ERR_ZETA = -7,              /**< damping ratio zeta is NaN/Inf or outside [0, 1)
                                         ([0, 0.25] for ::SMS_SMOOTH_ZV, ::SMS_SMOOTH_MZV,
                                         ::SMS_SMOOTH_EI) */
    SMS_ERR_MULTIPLE = -8,          /**< the multiple k is < 1 */
    SMS_ERR_EVEN_MULTIPLE = -9,     /**< k is even for a harmonic family: no zero lands on wn */
    SMS_ERR_ORDER = -10,            /**< order out of range (ZV^n n, chain length, B-spline degree) */
    SMS_ERR_BUFFER_TOO_SMALL = -11, /**< caller buffer shorter than the size query demands */
    SMS_ERR_KIND = -12,             /**< unknown ::sms_kind or ::sms_timing value */
    SMS_ERR_NOTCH_DAMPING = -13,    /**< notch: pole damping must exceed zero damping */
    SMS_ERR_TOLERANCE = -14,        /**< shaper vibration tolerance outside (0, 1) */
    SMS_ERR_TOO_LONG = -15,         /**< a length (samples) overflows size_t or the state format */
    SMS_ERR_ABOVE_NYQUIST = -16,    /**< the mode lies at or above the Nyquist frequency pi/Ts */
    SMS_ERR_LIMIT = -17,            /**< a kinematic limit or displacement is NaN/Inf or <= 0 */
    SMS_ERR_RECORD = -18,           /**< a measured record is too short, non-finite or not a decay */
    SMS_ERR_STATE = -19,            /**< a saved state vector does not match this object */
    SMS_ERR_BANDWIDTH = -20,        /**< notch bandwidth is NaN/Inf, <= 0 or too wide */
    SMS_ERR_SHAPER_DURATION = -21,  /**< generalised MZV duration outside (0, (order-1)/2) or
                                         giving a negative impulse */
    /* A saved state of another configuration (config.h, SMS_STATE_IDENTITY_COUNT): the first
     * field of its identity that differs from the object's. */
    SMS_ERR_STATE_FORMAT = -22,     /**< not a saved state, or another format version */
    SMS_ERR_STATE_PRECISION = -23,  /**< saved by the other precision (float/double) */
    SMS_ERR_STATE_KIND = -24,       /**< saved by another kind of stage or object */
    SMS_ERR_STATE_TS = -25,         /**< saved at another sample period Ts */
    SMS_ERR_STATE_TIMING = -26,     /**< saved with another timing */
    SMS_ERR_STATE_T = -27,          /**< saved with another duration T */
    SMS_ERR_STATE_SIGMA = -28,      /**< saved with another sigma */
    SMS_ERR_STATE_K = -29,          /**< saved with another multiple k */
    SMS_ERR_STATE_WN = -30,         /**< saved with another wn */
    SMS_ERR_STATE_ZETA = -31,       /**< saved with another zeta */
    SMS_ERR_STATE_ORDER = -32,      /**< saved with another order */
    SMS_ERR_STATE_TOLERANCE = -33,  /**< saved with another tolerance */
    SMS_ERR_STATE_NOTCH_POLE_ZETA = -34, /**< saved with another notch_pole_zeta */
    SMS_ERR_STATE_DURATION = -35,   /**< saved with another (GMZV, SI) duration, or for other
                                         user-defined impulses */
    SMS_ERR_STATE_VMAX = -36,       /**< saved with another vmax (generators) */
    SMS_ERR_STATE_AMAX = -37,       /**< saved with another amax (generators) */
    SMS_ERR_STATE_JMAX = -38,       /**< saved with another jmax (generators) */
    SMS_ERR_STATE_PROFILE = -39,    /**< saved with another profile (generator) */
    SMS_ERR_STATE_DEGREE = -40,     /**< saved with another degree (B-spline) */
    SMS_ERR_STATE_AXES = -41,       /**< saved with another number of axes */
    SMS_ERR_STATE_SYNC = -42,       /**< saved with another sync (multi-axis generator) */
    SMS_ERR_STATE_STAGES = -43,     /**< saved with another number of vibration stages on an
                                         axis (multi-axis generator) */
    SMS_ERR_COEFFS = -44,           /**< precomputed coefficients (coeffs.h) that no design
                                         writes: a length, tap or delay out of range, a
                                         non-finite value */
    SMS_ERR_RETUNE_BUSY = -45,      /**< a retune while the previous switch of the stage is
                                         still in progress (tunable.h) */
    SMS_ERR_TARGET_POSITION = -46,  /**< a target position is NaN/Inf */
    SMS_ERR_TARGET_VELOCITY = -47,  /**< a target velocity is NaN/Inf, beyond the velocity
                                         bounds, or not 0 where the profile plans to rest only */
    SMS_ERR_TARGET_ACCELERATION = -48, /**< a target acceleration is NaN/Inf, beyond the
                                         acceleration bounds, takes the velocity beyond its
                                         bounds before or after the target (v -+ a|a|/(2 jmax)),
                                         or is not 0 where the profile cannot hold one */
    SMS_ERR_INTERFACE = -49,        /**< unknown control interface (::sms_interface) */
    SMS_ERR_IMPULSE_AMPLITUDE = -50, /**< user-defined impulses: an amplitude is NaN/Inf, or
                                          they do not sum to > 0 */
    SMS_ERR_IMPULSE_TIME = -51,     /**< user-defined impulses: a time is NaN/Inf or < 0, or
                                         the times do not strictly increase */
    SMS_ERR_TARGET_SYNC = -52,      /**< a multi-axis target's per-axis synchronisation is not
                                         one the generator's mode takes (::sms_sync) */
    SMS_ERR_SAMPLE_PERIOD_RANGE = -55, /**< a generator's Ts is above ::SMS_TS_MAX: its tick and
                                           duration arithmetic (2^56 Ts) would overflow */
    SMS_ERR_POSITION_LIMIT = -56    /**< position limits of the generator (qmin, qmax of
                                         ::sms_generator_config): a target position outside
                                         [qmin, qmax], a start state outside or whose brake to
                                         rest would cross a limit, or a saved state of other
                                         position limits */
} sms_status;

/** @brief Stage families. Values are stable (the FMU enumeration and saved states use them). */
typedef enum sms_kind {
    SMS_RECTANGULAR = 0,      /**< moving average M, docs/filters.md */
    SMS_HARMONIC = 1,         /**< sinusoidal S, docs/filters.md */
    SMS_DAMPED_HARMONIC = 2,  /**< S_sigma, docs/filters.md */
    SMS_EXPONENTIAL = 3,      /**< M_sigma, docs/filters.md */
    SMS_SHAPER_ZV = 4,        /**< ZV input shaper, docs/filters.md */
    SMS_SHAPER_ZVD = 5,       /**< ZVD = ZV^2 */
    SMS_SHAPER_ZVDD = 6,      /**< ZVDD = ZV^3 */
    SMS_SHAPER_ZVN = 7,       /**< ZV^n, n = sms_stage_config::order */
    SMS_SHAPER_EI = 8,        /**< extra-insensitive (one hump) */
    SMS_SHAPER_EI2 = 9,       /**< two-hump extra-insensitive */
    SMS_SHAPER_MZV = 10,      /**< modified ZV as used by 3-D printer firmware */
    SMS_NOTCH_TUSTIN = 11,    /**< notch, Tustin with pre-warping at wn, docs/filters.md */
    SMS_NOTCH_MATCHED = 12,   /**< notch, pole-zero matched, docs/filters.md */
    SMS_SHAPER_EI3 = 13,      /**< three-hump extra-insensitive */
    SMS_SHAPER_GMZV = 14,     /**< generalised MZV: sms_stage_config::order impulses over
                                   sms_stage_config::duration damped periods */
    SMS_SMOOTH_ZV = 15,       /**< smooth ZV input smoother: a polynomial kernel with zero end
                                   taps for the mode wn, zeta (shaper.h) */
    SMS_SMOOTH_MZV = 16,      /**< smooth MZV input smoother */
    SMS_SMOOTH_EI = 17,       /**< smooth EI input smoother */
    SMS_SMOOTH_EI2 = 18,      /**< smooth two-hump EI input smoother */
    SMS_SMOOTH_ZVD_EI = 19,   /**< smooth ZVD-EI input smoother */
    SMS_SMOOTH_SI = 20,       /**< smooth SI input smoother */
    SMS_SHAPER_SI = 21,       /**< specified-insensitivity shaper: sms_stage_config::order
                                   impulses over sms_stage_config::duration damped periods,
                                   residual <= tolerance over the widest band */
    SMS_SHAPER_IMPULSES = 22  /**< user-defined impulses: sms_stage_config::amplitudes at
                                   sms_stage_config::times */
} sms_kind;

/** @brief Number of ::sms_kind values (0 .. SMS_KIND_COUNT - 1). */
#define SMS_KIND_COUNT 23

/**
 * @brief How a duration that is not a whole number of sample periods is realised.
 *
 * ::SMS_TIMING_EXACT (default) keeps the continuous design and corrects the end taps so that the
 * discrete zero sits exactly on the sampled continuous zero e^{s Ts} (see docs/exact-mode.md).
 * ::SMS_TIMING_PAPER reproduces the seeds: N = round(T/Ts) and the integer-N formulas.
 * ::SMS_TIMING_BOUNDED (rectangular and exponential smoothers only) pins the same zero with one
 * more tap, chosen so that no tap exceeds the continuous response's peak density times Ts:
 * what a stage that is both tuned to a mode and a kinematic bound needs
 * (docs/sampled-limits.md).
 * When T/Ts is an integer (to 1e-9 relative) all three give the same filter.
 */
typedef enum sms_timing {
    SMS_TIMING_EXACT = 0,   /**< the continuous design, zero pinned exactly (default) */
    SMS_TIMING_PAPER = 1,   /**< N = round(T/Ts) and the integer-N formulas of the papers */
    SMS_TIMING_BOUNDED = 2  /**< exact zero, no tap above the peak density (rectangular,
                                 exponential) */
} sms_timing;

/** @brief Human-readable one-line description of a status (static storage, never NULL).
 * @param status any value; one outside ::sms_status gives "unknown status"
 * @return a NUL-terminated string in static storage, never NULL
 */
SMS_API const char *sms_status_string(sms_status status);

/** @brief Name of a kind ("rectangular", "harmonic", ..., "notch_matched"), or NULL if unknown.
 * @param kind any value
 * @return the name in static storage (the Python and FMU spelling), or NULL when kind is not
 *         an ::sms_kind
 */
SMS_API const char *sms_kind_name(sms_kind kind);

/**
 * @name Deprecated names of the state functions
 * Every object now uses get_state/set_state, the names of the Python API and of FMI's
 * fmi2GetFMUstate/fmi2SetFMUstate; the old save/load names remain as aliases.
 * @{
 */
#define sms_smoother_save_state sms_smoother_get_state /**< deprecated: sms_smoother_get_state() */
#define sms_smoother_load_state sms_smoother_set_state /**< deprecated: sms_smoother_set_state() */
#define sms_shaper_save_state sms_shaper_get_state /**< deprecated: sms_shaper_get_state() */
#define sms_shaper_load_state sms_shaper_set_state /**< deprecated: sms_shaper_set_state() */
#define sms_notch_save_state sms_notch_get_state /**< deprecated: sms_notch_get_state() */
#define sms_notch_load_state sms_notch_set_state /**< deprecated: sms_notch_set_state() */
#define sms_stage_save_state sms_stage_get_state /**< deprecated: sms_stage_get_state() */
#define sms_stage_load_state sms_stage_set_state /**< deprecated: sms_stage_set_state() */
#define sms_chain_save_state sms_chain_get_state /**< deprecated: sms_chain_get_state() */
#define sms_chain_load_state sms_chain_set_state /**< deprecated: sms_chain_set_state() */
#define sms_generator_save_state sms_generator_get_state /**< deprecated: sms_generator_get_state() */
#define sms_generator_load_state sms_generator_set_state /**< deprecated: sms_generator_set_state() */
#define sms_bspline_save_state sms_bspline_get_state /**< deprecated: sms_bspline_get_state() */
#define sms_bspline_load_state sms_bspline_set_state /**< deprecated: sms_bspline_set_state() */
#define sms_multi_generator_save_state sms_multi_generator_get_state /**< deprecated: sms_multi_generator_get_state() */
#define sms_multi_generator_load_state sms_multi_generator_set_state /**< deprecated: sms_multi_generator_set_state() */
/** @} */

#ifdef __cplusplus
}
#endif
#endif
