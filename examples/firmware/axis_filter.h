/* SPDX-License-Identifier: Apache-2.0 */
/* One axis's command filter in firmware: the README's chain (a harmonic smoother and a ZV
 * shaper on the mode wn = 100 rad/s, zeta = 0.05, at Ts = 1 ms), built from precomputed
 * coefficients (chain_coeffs.c): no design on the target, no double arithmetic, no libm. */
#ifndef AXIS_FILTER_H
#define AXIS_FILTER_H

#include "smoothshaper/core.h"

/** Build the filter at rest at 0. Returns 0, or -1 if the coefficients do not fit the static
 * memory (they were made for another chain). Call once, before the sample interrupt runs. */
int axis_filter_init(void);

/** One sample, from the sample interrupt: the filtered command for the command x. */
sms_real axis_filter_sample(sms_real x);

#endif
