/* SPDX-License-Identifier: Apache-2.0 */
/* Rectangular smoother M (moving average), docs/filters.md.
 *
 * Continuous impulse response 1/T on [0, T); integer N: taps 1/N at delays 0..N-1,
 * M(z) = (1/N)(1 - z^-N)/(1 - z^-1). Zeros at w = 2 pi k/T for every k >= 1, so exact timing
 * pins w* = 2 pi k/T. The recursion is the running sum (pole 1). */
#include "filter/smoother_family.h"

void sms_rectangular_describe(sms_smoother_family *family)
{
    family->damped = 0;
    family->half_sine = 0;
    family->zero_turns = 2.0;
}
