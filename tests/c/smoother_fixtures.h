/* SPDX-License-Identifier: Apache-2.0 */
/* Helpers shared by the smoother tests and the drift benchmark. */
#ifndef SMS_TEST_SMOOTHER_FIXTURES_H
#define SMS_TEST_SMOOTHER_FIXTURES_H

#include "smoothshaper/smoothshaper.h"

static inline sms_stage_config smoother(sms_kind kind, double T, double sigma, unsigned k,
                                        sms_timing timing)
{
    sms_stage_config c = sms_stage_config_default(kind);
    c.T = T;
    c.sigma = sigma;
    c.k = k;
    c.timing = timing;
    return c;
}

/* Families whose impulse response carries sin(pi t/T): zeros at odd multiples of pi/T. */
static inline int is_harmonic(sms_kind kind)
{
    return kind == SMS_HARMONIC || kind == SMS_DAMPED_HARMONIC;
}

/* xorshift64: deterministic uniform numbers in [0, 1), 53 bits, from *state (non-zero). */
static inline double xorshift_uniform(unsigned long long *state)
{
    *state ^= *state << 13;
    *state ^= *state >> 7;
    *state ^= *state << 17;
    return (double)(*state >> 11) / 9007199254740992.0;
}

#endif
