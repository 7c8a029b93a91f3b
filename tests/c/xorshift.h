/* SPDX-License-Identifier: Apache-2.0 */
/*
 * xorshift64 (Marsaglia, "Xorshift RNGs", 2003): the seeded, portable random stream of the
 * randomised C tests, so a failing case replays the same on every platform.
 */
#ifndef SMS_TESTS_XORSHIFT_H
#define SMS_TESTS_XORSHIFT_H

#include <stdint.h>

/** @return the next number of the stream *s (non-zero seed), uniform in [0, 1). */
static double xorshift_uniform(uint64_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    return (double)(*s >> 11) / 9007199254740992.0;
}

#endif
