/* SPDX-License-Identifier: Apache-2.0 */
/* Internal: continuous shaper designs (amplitudes and times), see shaper_designs.c. */
#ifndef SMS_SHAPER_DESIGNS_H
#define SMS_SHAPER_DESIGNS_H

#include "smoothshaper/shaper.h"

/* ZV^n order of a shaper kind (order field for ZVN), 0 for EI, EI2, EI3, MZV, GMZV. */
unsigned sms_shaper_zv_order(const sms_stage_config *config);

/* Undamped generalised MZV: amplitudes (least squares, not yet normalised) and times in damped
 * periods for n impulses over `duration` periods; 0 if (n, duration) is out of range or an
 * amplitude is negative. */
int sms_gmzv_undamped(unsigned n, double duration, double *amp, double *units);

/* Undamped SI shaper (shaper_si.c): n (odd, 3..SMS_SHAPER_MAX_IMPULSES) impulses over
 * `duration` damped periods in [(n-1)/4, (n-1)/2] for tolerance V in (0, 1): amplitudes (sum 1,
 * none negative), times in damped periods and, if insensitivity is not NULL, the relative
 * width I of the band of |H| <= V; 0 if (n, duration, V) is out of range. */
int sms_si_undamped(unsigned n, double duration, double V, double *amp, double *units,
                    double *insensitivity);

/* Fill amp[] (sum 1) and time[] [s] (increasing, time[0] = 0) for a validated config; returns
 * the number of impulses (<= SMS_SHAPER_MAX_IMPULSES). */
size_t sms_shaper_design(const sms_stage_config *config, double *amp, double *time);

/* Sum of |g_k| over the taps sms_shaper_init() would build (gains rounded to sms_real, summed
 * in tap order, as a built shaper's sms_stage_gain_bound()), without a tap table: O(taps), an
 * input smoother's two passes over its window. Statuses as sms_shaper_coeffs_make();
 * *abs_sum written only on SMS_OK. */
sms_status sms_shaper_abs_gain(const sms_stage_config *config, double Ts, double *abs_sum);

/* Both sizes of a shaper from one design: delay-line length L and number of taps (the two
 * public size queries, for callers that need both). Statuses as sms_shaper_buffer_size(). */
sms_status sms_shaper_sizes(const sms_stage_config *config, double Ts, size_t *n_reals,
                            size_t *n_taps);

/* The realised taps' centroid sum_k d_k g_k / sum_k g_k [samples] (lag.c); the config's status
 * otherwise. */
sms_status sms_shaper_lag(const sms_stage_config *config, double Ts, double *lag);

#endif
