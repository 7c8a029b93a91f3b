/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file config.h
 * @brief ::sms_stage_config, the plain description of one stage of any family.
 *
 * A config is data only: fill it by hand (start from sms_stage_config_default()), or let
 * sms_design_for_mode() fill it for a vibration mode. Each family reads only its own fields.
 */
#ifndef SMOOTHSHAPER_CONFIG_H
#define SMOOTHSHAPER_CONFIG_H

#include "smoothshaper/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * @brief Doubles of configuration identity at the start of every saved stage state
 * (sms_smoother_get_state(), sms_shaper_get_state(), sms_notch_get_state(), and so of
 * sms_stage_get_state() and each stage's part of sms_chain_get_state()), in this order:
 * ::SMS_STATE_TAG, ::SMS_STATE_VERSION, sizeof(::sms_real) of the build, kind, Ts, timing, T,
 * sigma, k, wn, zeta, order, tolerance, notch_pole_zeta, duration, the fields a kind does not
 * read being 0. Loading a state compares them with the object's own (exact equality) and
 * refuses, writing nothing, with the status naming the first field that differs
 * (::SMS_ERR_STATE_FORMAT, ::SMS_ERR_STATE_PRECISION, ::SMS_ERR_STATE_KIND, ::SMS_ERR_STATE_TS,
 * ::SMS_ERR_STATE_TIMING ... ::SMS_ERR_STATE_DURATION).
 */
#define SMS_STATE_IDENTITY_COUNT 15
/**
 * @brief Doubles of the head every saved state starts with, whatever the object: ::SMS_STATE_TAG,
 * ::SMS_STATE_VERSION, sizeof(::sms_real), kind, Ts. The kind is an ::sms_kind for a stage, or
 * ::SMS_STATE_KIND_GENERATOR, ::SMS_STATE_KIND_BSPLINE, ::SMS_STATE_KIND_MULTI_GENERATOR; the
 * object's own configuration fields follow (trajectory.h, multi_generator.h), so a state loaded
 * into another kind of object is refused with ::SMS_ERR_STATE_KIND.
 */
#define SMS_STATE_IDENTITY_HEAD 5
/** @brief First double of a saved state ("SMS" read as a 24-bit integer). */
#define SMS_STATE_TAG 5459283.0
/** @brief Format version of saved states (2: a smoother saves its run of equal inputs, and its
 * ring holds the inputs themselves). */
#define SMS_STATE_VERSION 2.0
/** @brief Kind field of a saved ::sms_generator state (beyond every ::sms_kind). */
#define SMS_STATE_KIND_GENERATOR 100.0
/** @brief Kind field of a saved ::sms_bspline state. */
#define SMS_STATE_KIND_BSPLINE 101.0
/** @brief Kind field of a saved ::sms_multi_generator state. */
#define SMS_STATE_KIND_MULTI_GENERATOR 102.0

/** @brief Most ZV^n order accepted (ZV^n has n+1 impulses). */
#define SMS_SHAPER_MAX_ORDER 8

/** @brief Most impulses of a continuous shaper design (ZV^n with n = ::SMS_SHAPER_MAX_ORDER),
 * and of a user-defined one (::SMS_SHAPER_IMPULSES: sms_stage_config::amplitudes). */
#define SMS_SHAPER_MAX_IMPULSES (SMS_SHAPER_MAX_ORDER + 1)

/**
 * @brief Everything that defines one stage.
 *
 * | field            | used by                                  | valid range |
 * |------------------|------------------------------------------|-------------|
 * | kind             | all                                      | an ::sms_kind |
 * | timing           | smoothers, shapers                       | an ::sms_timing |
 * | T                | rectangular, harmonic, damped harmonic, exponential | finite, >= Ts [s] (1) |
 * | sigma            | damped harmonic, exponential             | finite, <= 0 [1/s] |
 * | k                | smoothers: which zero exact timing pins  | >= 1; odd for (damped) harmonic |
 * | wn               | shapers, notches                         | finite, > 0, below pi/Ts [rad/s] |
 * | zeta             | shapers, notches (zero damping xi1)      | [0, 1) |
 * | order            | ::SMS_SHAPER_ZVN: n of ZV^n              | 1 .. ::SMS_SHAPER_MAX_ORDER |
 * |                  | ::SMS_SHAPER_GMZV: number of impulses    | 3 .. ::SMS_SHAPER_MAX_IMPULSES |
 * |                  | ::SMS_SHAPER_SI: number of impulses      | 3, 5, 7 or 9 |
 * |                  | ::SMS_SHAPER_IMPULSES: number of impulses | 1 .. ::SMS_SHAPER_MAX_IMPULSES |
 * | tolerance        | ::SMS_SHAPER_EI, ::SMS_SHAPER_EI2, ::SMS_SHAPER_EI3, ::SMS_SHAPER_SI | (0, 1), e.g. 0.05 |
 * | duration         | ::SMS_SHAPER_GMZV: span in damped periods Td | (0, (order-1)/2), no negative impulse; 0.75 = MZV |
 * |                  | ::SMS_SHAPER_SI: span in damped periods Td | [(order-1)/4, (order-1)/2]; (order-1)/2 = EI, EI3 |
 * | notch_pole_zeta  | notches (pole damping xi2)               | finite, > zeta |
 * | amplitudes       | ::SMS_SHAPER_IMPULSES: the first order entries | finite, sum > 0 (normalised to 1) |
 * | times            | ::SMS_SHAPER_IMPULSES: the first order entries [s] | finite, >= 0, strictly increasing |
 *
 * The input smoothers ::SMS_SMOOTH_ZV .. ::SMS_SMOOTH_SI read wn (their design frequency) and,
 * ::SMS_SMOOTH_ZV, ::SMS_SMOOTH_MZV and ::SMS_SMOOTH_EI only, zeta in [0, 0.25] (shaper.h).
 * ::SMS_SHAPER_IMPULSES reads neither wn nor zeta.
 *
 * (1) One rule for short durations, everywhere (smoothers, B-splines, the Python reference and
 * the FMUs): T/Ts below 1 is refused with ::SMS_ERR_DURATION_BELOW_TS, except within the
 * sample-grid tolerance (T/Ts >= 1 - 1e-9), which is one sample. There is no pass-through for
 * tiny T. The harmonic families need two samples (T/Ts >= 2 - 2e-9): one sample of
 * sin(pi t/T) is its zero.
 *
 * The pinned zero of a smoother (exact timing) is s = sigma + j*k*2*pi/T for rectangular and
 * exponential, s = sigma + j*k*3*pi/T for harmonic and damped harmonic (sigma = 0 when the
 * family has none).
 */
typedef struct sms_stage_config {
    sms_kind kind;            /**< the family */
    sms_timing timing;        /**< how an off-grid duration is realised */
    double T;                 /**< smoother duration [s], finite, >= Ts (1) */
    double sigma;             /**< decay rate of the damped smoothers [1/s], finite, <= 0 */
    unsigned k;               /**< which zero exact timing pins, >= 1 (odd for harmonic ones) */
    double wn;                /**< mode natural frequency [rad/s], finite, 0 < wn < pi/Ts */
    double zeta;              /**< mode damping ratio, [0, 1) ([0, 0.25] smooth ZV/MZV/EI) */
    unsigned order;           /**< ZV^n n, or the number of impulses (GMZV, SI, impulses) */
    double tolerance;         /**< residual vibration tolerance V of EI, EI2, EI3, SI, (0, 1) */
    double notch_pole_zeta;   /**< notch pole damping xi2, finite, > zeta, <= 1e6 */
    double duration;          /**< GMZV or SI span in damped periods Td */
    double amplitudes[SMS_SHAPER_MAX_IMPULSES]; /**< user impulses: the first order amplitudes */
    double times[SMS_SHAPER_MAX_IMPULSES];      /**< user impulses: the first order times [s] */
} sms_stage_config;

/**
 * @brief A config of the given kind with every field at a documented default:
 * timing ::SMS_TIMING_EXACT, T = 0 (must be set for smoothers), sigma = 0, k = 1, wn = 0
 * (must be set for shapers and notches), zeta = 0, order = 1 (3 for ::SMS_SHAPER_GMZV and
 * ::SMS_SHAPER_SI, 0 for ::SMS_SHAPER_IMPULSES: its impulses must be set), tolerance = 0.05,
 * notch_pole_zeta = 0.7, duration = 0.75,
 * amplitudes and times all 0. The kind is stored as given (validated only by init).
 * @param kind the family; any value is stored, init validates it
 * @return the filled config (by value)
 */
SMS_API sms_stage_config sms_stage_config_default(sms_kind kind);

/**
 * @brief Validate a config for sample period Ts without building anything.
 * @return ::SMS_OK or the status init would return (first offending field wins, in the
 *         table order above).
 * @param config the stage description; NULL gives ::SMS_ERR_NULL
 * @param Ts     sample period [s], finite and > 0
 */
SMS_API sms_status sms_stage_config_validate(const sms_stage_config *config, double Ts);

#ifdef __cplusplus
}
#endif
#endif
