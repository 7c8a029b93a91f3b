/* SPDX-License-Identifier: Apache-2.0 */
/* Damped harmonic smoother S_sigma (Biagiotti et al. 2020, eq. 10, 14, 17).
 *
 * Continuous impulse response c e^{sigma t} sin(pi t/T) on [0, T); integer N, r = e^{sigma Ts}:
 * S_sigma(z) = K (z^-1 + r^N z^-(N+1)) / (1 - 2 r cos(pi/N) z^-1 + r^2 z^-2),
 * K = (1 - 2 r cos(pi/N) + r^2)/(1 + r^N). Zeros at s = sigma + j(2m+1) pi/T; the mode
 * design sigma = -zeta wn, T = k 3 pi/wd (k odd) puts one on the mode, and exact timing pins
 * s* = sigma + j 3 pi k/T. The recursion runs on the complex pole r e^{j pi/N}. */
#include "filter/smoother_family.h"

void sms_damped_harmonic_describe(sms_smoother_family *family)
{
    family->damped = 1;
    family->half_sine = 1;
    family->zero_turns = 3.0;
}
