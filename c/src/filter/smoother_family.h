/* SPDX-License-Identifier: Apache-2.0 */
/* Internal: what distinguishes one FIR smoother family from another, and the four families'
 * descriptions (rectangular.c, harmonic.c, damped_harmonic.c, exponential.c). Below the
 * design (smoother_design.h), which reads them: a family's file needs nothing else. */
#ifndef SMS_SMOOTHER_FAMILY_INTERNAL_H
#define SMS_SMOOTHER_FAMILY_INTERNAL_H

/* What distinguishes one smoother family from another. */
typedef struct sms_smoother_family {
    int damped;        /* uses config->sigma (else sigma = 0 and the field is ignored) */
    int half_sine;     /* impulse response carries sin(pi t/T): k must be odd, tap 0 is 0 */
    double zero_turns; /* pinned zero at w* = k * zero_turns * pi / T (2 or 3) */
} sms_smoother_family;

void sms_rectangular_describe(sms_smoother_family *family);
void sms_harmonic_describe(sms_smoother_family *family);
void sms_damped_harmonic_describe(sms_smoother_family *family);
void sms_exponential_describe(sms_smoother_family *family);

#endif
