/* SPDX-License-Identifier: Apache-2.0 */
/* Internal: each family's half of the firmware path (coeffs.h): make its coefficients from a
 * config (host side, the design) and check coefficients before a stage is laid out from them
 * (target side: integer and sms_real tests only, no double arithmetic). */
#ifndef SMS_COEFFS_CHECK_INTERNAL_H
#define SMS_COEFFS_CHECK_INTERNAL_H

#include "smoothshaper/coeffs.h"

sms_status sms_smoother_coeffs_make(const sms_stage_config *config, double Ts,
                                    sms_stage_coeffs *coeffs);
/* A shaper's taps are written into taps (n_taps entries): ::SMS_ERR_BUFFER_TOO_SMALL if fewer
 * than it has. */
sms_status sms_shaper_coeffs_make(const sms_stage_config *config, double Ts,
                                  sms_stage_coeffs *coeffs, sms_shaper_tap *taps, size_t n_taps);
sms_status sms_notch_coeffs_make(const sms_stage_config *config, double Ts,
                                 sms_stage_coeffs *coeffs);

sms_status sms_smoother_coeffs_check(const sms_stage_coeffs *coeffs);
sms_status sms_shaper_coeffs_check(const sms_stage_coeffs *coeffs);
sms_status sms_notch_coeffs_check(const sms_stage_coeffs *coeffs);

#endif
