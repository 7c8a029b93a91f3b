/* SPDX-License-Identifier: Apache-2.0 */
/* Exponential (damped rectangular) smoother M_sigma (docs/filters.md; Béarée 2014).
 *
 * Continuous impulse response sigma e^{sigma t}/(e^{sigma T} - 1) on [0, T); integer N,
 * r = e^{sigma Ts}: taps r^i / sum, i = 0..N-1, recursive form (1 - r^N z^-N)/(1 - r z^-1)
 * times the gain. Zeros at s = sigma + j 2 pi k/T for every k >= 1 (the mode design
 * sigma = -zeta wn, T = k Td); exact timing pins s* = sigma + j 2 pi k/T. With sigma = 0 it is
 * the rectangular smoother. */
#include "filter/smoother_family.h"

void sms_exponential_describe(sms_smoother_family *family)
{
    family->damped = 1;
    family->half_sine = 0;
    family->zero_turns = 2.0;
}
