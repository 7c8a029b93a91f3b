/* SPDX-License-Identifier: Apache-2.0 */
/* Internal: the input smoothers' kernels and taps (input_smoother.c; documented in shaper.h). */
#ifndef SMS_INPUT_SMOOTHER_H
#define SMS_INPUT_SMOOTHER_H

#include "smoothshaper/shaper.h"

/* 1 for SMS_SMOOTH_ZV .. SMS_SMOOTH_SI. */
int sms_is_input_smoother(sms_kind kind);

/* 1 for the kinds whose kernel depends on zeta (SMS_SMOOTH_ZV, SMS_SMOOTH_MZV, SMS_SMOOTH_EI). */
int sms_input_smoother_reads_zeta(sms_kind kind);

/* The kernel of a validated config: q[0..degree] (at most 11 entries; P(u) = sum q_k u^k with
 * int_{-1/2}^{1/2} P = 1) and its duration T [s]; returns the degree. */
unsigned sms_input_smoother_kernel(const sms_stage_config *config, double *q, double *T);

/* Taps of a validated config at Ts: SMS_OK and the length L (every sample of the window), or
 * SMS_ERR_TOO_LONG, SMS_ERR_ABOVE_NYQUIST (the kernel spans fewer than 4 samples). */
sms_status sms_input_smoother_length(const sms_stage_config *config, double Ts, size_t *length);

/* H_c(s) = int_0^T g(tau) e^{-s tau} dtau of a validated config. */
void sms_input_smoother_transfer(const sms_stage_config *config, double s_re, double s_im,
                                 double *h_re, double *h_im);

/* The lag [samples] a validated config's taps have at Ts: int g(tau) tau dtau / Ts, the
 * centroid the correction pins. */
double sms_input_smoother_lag(const sms_stage_config *config, double Ts);

/* Write the L taps (delays 0..L-1) into taps and/or dense, and the sum of |g_k| over the gains
 * rounded to sms_real (as a built stage holds them) into abs_sum (any may be NULL); 0 (nothing
 * written) if the correction is not a number. */
int sms_input_smoother_taps(const sms_stage_config *config, double Ts, size_t length,
                            sms_shaper_tap *taps, double *dense, double *abs_sum);

#endif
