/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file coeffs.h
 * @brief Precomputed stage coefficients: design on a host, load on a target with no double
 * arithmetic and no libm (the firmware path).
 *
 * Licensed under the Apache License 2.0 (LICENSE): free to compile into closed firmware.
 *
 * sms_stage_init() designs each stage from its ::sms_stage_config: in double, with sin, cos,
 * exp and a small least-squares solve. On a microcontroller without a double-precision FPU
 * that pulls in the soft-float double routines and libm (about 30 kB of code on a
 * Cortex-M4F for two designs and a chain). The design's result is a handful of numbers: a
 * smoother's pole, gain and direct taps, a shaper's taps, a notch's four coefficients. An
 * ::sms_stage_coeffs holds them in ::sms_real, exactly as the instance uses them:
 * - host: sms_stage_coeffs_make() (or `smoothshaper.coeffs` in Python, or the command line's
 *   `design --c-coeffs` and `calibrate --c-coeffs`, which write them as C source) designs
 *   them from a config, computed by the library of the target's precision;
 * - target: sms_stage_init_coeffs() / sms_chain_init_coeffs() build the stages from them,
 *   with integer and ::sms_real operations only (copies, checks, the reset).
 * A stage built from coefficients is the stage sms_stage_init() builds from the config they
 * were made from, bit for bit (same outputs, same saved states: the configuration identity
 * travels with the coefficients).
 *
 * Measured on a Cortex-M4F (float, -Os, docs/firmware.md): a harmonic smoother and a ZV
 * shaper initialised from coefficients and stepped take well under 4 kB of code; the
 * portability test fails if that path links a soft-double or libm function.
 */
#ifndef SMOOTHSHAPER_COEFFS_H
#define SMOOTHSHAPER_COEFFS_H

#include "smoothshaper/chain.h"

#ifdef __cplusplus
extern "C" {
#endif

/** @brief A smoother's realised constants (smoother.h: the recursion and its direct taps). */
typedef struct sms_smoother_coeffs {
    size_t length;                     /**< impulse response length L, M or M + 1 */
    size_t window;                     /**< M >= 1: taps from the recursion, ring length */
    sms_real pole_m1_re;               /**< Re q - 1, q the recursion's pole */
    sms_real pole_im;                  /**< Im q (0 for a real pole) */
    sms_real pole_lo_re;               /**< what the rounding lost of Re q */
    sms_real pole_lo_im;               /**< what the rounding lost of Im q */
    sms_real gain;                     /**< c, weight of the newest input */
    sms_real tail_re;                  /**< Re of -c q^M, the weight of x[n-M] */
    sms_real tail_im;                  /**< Im of -c q^M */
    size_t n_corrections;              /**< direct taps, 0 or 2 */
    size_t correction_delay[SMS_SMOOTHER_MAX_CORRECTIONS]; /**< {M-1, M} or {0, M} */
    sms_real correction_gain[SMS_SMOOTHER_MAX_CORRECTIONS]; /**< the direct taps' gains d_j */
    double input_limit;                /**< sms_smoother_input_max() before its cap */
} sms_smoother_coeffs;

/** @brief A shaper's taps (shaper.h): y[n] = sum_k g_k x[n - d_k]. */
typedef struct sms_shaper_coeffs {
    size_t length;                     /**< L = last delay + 1 */
    size_t n_taps;                     /**< 1 .. ::SMS_SHAPER_MAX_TAPS; an input smoother's
                                            5 .. ::SMS_INPUT_SMOOTHER_MAX_LENGTH, = length */
    const sms_shaper_tap *taps;        /**< n_taps taps, delays strictly increasing (an input
                                            smoother's are 0 .. length-1) */
} sms_shaper_coeffs;

/** @brief A notch's coefficients (notch.h):
 * H = 1 + (1 - z^-1)(d0 - d2 z^-1)/(1 + a1 z^-1 + a2 z^-2). */
typedef struct sms_notch_coeffs {
    sms_real d0;   /**< b0 - 1 */
    sms_real d2;   /**< b2 - a2 */
    sms_real a1;   /**< denominator coefficient of z^-1 */
    sms_real a2;   /**< denominator coefficient of z^-2 */
} sms_notch_coeffs;

/** @brief Everything a target needs to build one stage without designing it. */
typedef struct sms_stage_coeffs {
    sms_kind kind;                     /**< the family, selects the member of u */
    /** The configuration identity (config.h: the config and Ts they were made from), which
     * saved states are checked against; copied, never computed, on the target. */
    double identity[SMS_STATE_IDENTITY_COUNT];
    /** @brief The family's constants. */
    union {
        sms_smoother_coeffs smoother;  /**< kind ::SMS_RECTANGULAR .. ::SMS_EXPONENTIAL */
        sms_shaper_coeffs shaper;      /**< the shaper and input smoother kinds */
        sms_notch_coeffs notch;        /**< ::SMS_NOTCH_TUSTIN, ::SMS_NOTCH_MATCHED */
    } u;
} sms_stage_coeffs;

/**
 * @brief Host side: design a stage and write its coefficients (double and libm, as
 * sms_stage_init()).
 * @param config  the stage (config.h for ranges)
 * @param Ts      sample period [s], finite, > 0
 * @param coeffs  receives the coefficients; untouched on error
 * @param taps    a shaper's or input smoother's taps go here (coeffs->u.shaper.taps points
 *                at it): at least sms_shaper_tap_count() entries (::SMS_SHAPER_MAX_TAPS for
 *                any shaper; an input smoother has one per sample of its window); may be NULL
 *                for smoothers and notches
 * @param n_taps  length of taps
 * @return ::SMS_OK, ::SMS_ERR_NULL (config or coeffs; taps for a shaper),
 *         ::SMS_ERR_BUFFER_TOO_SMALL (n_taps below the shaper's tap count), or the config's
 *         status (as sms_stage_init()).
 */
SMS_API sms_status sms_stage_coeffs_make(const sms_stage_config *config, double Ts,
                                         sms_stage_coeffs *coeffs, sms_shaper_tap *taps,
                                         size_t n_taps);

/**
 * @brief Target side: check coefficients and report the memory a stage built from them needs
 * (as sms_stage_memory_size() for their config). No double arithmetic, no libm; O(taps).
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_KIND (not a known kind), ::SMS_ERR_COEFFS (not
 *         what sms_stage_coeffs_make() writes: a length, window, tap count, delay or direct
 *         tap out of its range, a non-finite coefficient, a NULL tap table),
 *         ::SMS_ERR_TOO_LONG (the size overflows size_t).
 * @param coeffs   coefficients made by sms_stage_coeffs_make() of this precision
 * @param n_cells  receives the number of ::sms_memory_cell
 */
SMS_API sms_status sms_stage_coeffs_memory_size(const sms_stage_coeffs *coeffs, size_t *n_cells);

/**
 * @brief Target side: build a stage at rest at 0 from coefficients. No double arithmetic, no
 * libm: the stage is the one sms_stage_init() builds from the config they were made from.
 * @param memory   at least sms_stage_coeffs_memory_size() cells; the stage keeps it (a
 *                 shaper's taps are copied into it: coeffs may live in flash or go away)
 * @return the statuses of sms_stage_coeffs_memory_size(), ::SMS_ERR_NULL (stage or memory),
 *         ::SMS_ERR_BUFFER_TOO_SMALL. Nothing is written on error.
 * @param stage    instance to fill; untouched on error
 * @param coeffs   coefficients made by sms_stage_coeffs_make() of this precision
 * @param n_cells  length of memory in cells
 */
SMS_API sms_status sms_stage_init_coeffs(sms_stage *stage, const sms_stage_coeffs *coeffs,
                                         sms_memory_cell *memory, size_t n_cells);

/** @brief Target side: cells of memory a chain of these n stages needs (their sum).
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_ORDER (n = 0 or > ::SMS_CHAIN_MAX_STAGES),
 *         ::SMS_ERR_TOO_LONG, or the first failing stage's status.
 * @param coeffs   n stages' coefficients, first applied first
 * @param n        stages, 1 .. ::SMS_CHAIN_MAX_STAGES
 * @param n_cells  receives the number of ::sms_memory_cell
 */
SMS_API sms_status sms_chain_coeffs_memory_size(const sms_stage_coeffs *coeffs, size_t n,
                                                size_t *n_cells);

/** @brief Target side: check every stage's coefficients, then build the chain at rest at 0
 * (as sms_chain_init() for their configs). No double arithmetic, no libm.
 * @return ::SMS_OK, ::SMS_ERR_NULL (chain, stages, coeffs or memory), the statuses of
 *         sms_chain_coeffs_memory_size(), ::SMS_ERR_BUFFER_TOO_SMALL. On error nothing is
 *         touched.
 * @param chain    instance to fill; untouched on error
 * @param stages   caller array of n stages
 * @param coeffs   n stages' coefficients, first applied first
 * @param n        stages, 1 .. ::SMS_CHAIN_MAX_STAGES
 * @param memory   caller memory of n_cells >= sms_chain_coeffs_memory_size() cells; kept
 * @param n_cells  length of memory in cells
 */
SMS_API sms_status sms_chain_init_coeffs(sms_chain *chain, sms_stage *stages,
                                         const sms_stage_coeffs *coeffs, size_t n,
                                         sms_memory_cell *memory, size_t n_cells);

/** @brief A smoother from coefficients (coeffs->kind a smoother kind); buffer of at least
 * coeffs->u.smoother.window reals. As sms_smoother_init(), without the design.
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_KIND, ::SMS_ERR_COEFFS,
 *         ::SMS_ERR_BUFFER_TOO_SMALL.
 * @param f        instance to fill; untouched on error
 * @param coeffs   a smoother's coefficients
 * @param buffer   the ring, kept by f
 * @param n_reals  reals in buffer, >= coeffs->u.smoother.window
 */
SMS_API sms_status sms_smoother_init_coeffs(sms_smoother *f, const sms_stage_coeffs *coeffs,
                                            sms_real *buffer, size_t n_reals);
/** @brief A shaper from coefficients: its taps are copied into taps (n_taps >= their count),
 * buffer of at least coeffs->u.shaper.length reals. As sms_shaper_init(), without the design.
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_KIND, ::SMS_ERR_COEFFS,
 *         ::SMS_ERR_BUFFER_TOO_SMALL.
 * @param f        instance to fill; untouched on error
 * @param coeffs   a shaper's or input smoother's coefficients
 * @param taps     the tap table, kept by f
 * @param n_taps   entries in taps, >= coeffs->u.shaper.n_taps
 * @param buffer   the delay line, kept by f
 * @param n_reals  reals in buffer, >= coeffs->u.shaper.length
 */
SMS_API sms_status sms_shaper_init_coeffs(sms_shaper *f, const sms_stage_coeffs *coeffs,
                                          sms_shaper_tap *taps, size_t n_taps, sms_real *buffer,
                                          size_t n_reals);
/** @brief A notch from coefficients. As sms_notch_init(), without the design.
 * @return ::SMS_OK, ::SMS_ERR_NULL, ::SMS_ERR_KIND, ::SMS_ERR_COEFFS.
 * @param f        instance to fill; untouched on error
 * @param coeffs   a notch's coefficients
 */
SMS_API sms_status sms_notch_init_coeffs(sms_notch *f, const sms_stage_coeffs *coeffs);

#ifdef __cplusplus
}
#endif
#endif
