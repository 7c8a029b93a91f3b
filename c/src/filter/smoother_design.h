/* SPDX-License-Identifier: Apache-2.0 */
/* Internal: design of the four FIR smoothers (taps and recursive constants), in double.
 *
 * Every smoother's continuous impulse response on [0, T) is Re or Im of e^{(sigma + j*omega) t}
 * with omega = 0 (rectangular, exponential) or pi/T (harmonic families), so one design routine
 * serves all four; each family's source only says which of these it is (sms_*_describe). */
#ifndef SMS_SMOOTHER_DESIGN_INTERNAL_H
#define SMS_SMOOTHER_DESIGN_INTERNAL_H

#include "smoothshaper/config.h"
#include "filter/smoother_family.h"

/* Direct taps of exact timing: the correction on N0-1 and the corrected fractional tap N0. */
#define SMS_SMOOTHER_CORRECTION_TAPS 2

/* The designed filter: h[i] = Re/Im(gain * pole^i) for i < window, plus corrections. */
typedef struct sms_smoother_design {
    sms_smoother_family family;
    double decay;          /* sigma * Ts: log of the per-sample decay (0 when undamped) */
    double nu;             /* T'/Ts of the sampled response: N (integer, paper) or T/Ts (exact) */
    size_t length;         /* L: taps of the impulse response */
    size_t window;         /* M: taps 0..M-1 come from the recursion (M = N or N0) */
    double pole_m1_re, pole_im; /* q - 1: q = e^{sigma Ts} e^{j pi/nu} (half sine) or e^{sigma Ts} */
    double pole_m1_lo_re, pole_lo_im; /* what those doubles miss of q (double-double): the
                                       * pole to ~2^-100, so q^i stays accurate over long windows */
    double gain;           /* c = 1/sum(base taps): weight of the newest input */
    double tail_re, tail_im; /* -c q^M: weight of x[n-M], which truncates the response */
    size_t n_corrections;  /* 0 or 2 */
    size_t correction_delay[SMS_SMOOTHER_CORRECTION_TAPS];
    double correction_gain[SMS_SMOOTHER_CORRECTION_TAPS];
    double input_limit;    /* |x|, |rest| below it keep every sum finite (uncapped) */
} sms_smoother_design;

/* Validate config for Ts (in the order of the table in config.h) and design the filter.
 * Writes *design only on SMS_OK. */
sms_status sms_smoother_design_make(const sms_stage_config *config, double Ts,
                                    sms_smoother_design *design);

/* Tap i (0 <= i < design->length) of the designed filter, normalised, in double. */
double sms_smoother_design_tap(const sms_smoother_design *design, size_t i);

#endif
