/* SPDX-License-Identifier: Apache-2.0 */
/* Harmonic (sinusoidal) smoother S (Biagiotti & Melchiorri 2011a, sec. 3.2).
 *
 * Continuous impulse response (pi/(2T)) sin(pi t/T) on [0, T); integer N: taps proportional
 * to sin(pi i/N), i = 0..N-1 (tap 0 is 0), S(z) = (1 - cos(pi/N))(z^-1 + z^-(N+1)) /
 * (1 - 2 cos(pi/N) z^-1 + z^-2). Zeros at odd multiples of pi/T beyond the first, so the
 * mode design T = k 3 pi/wn needs k odd (even k leaves ~2.9 % residual, docs/errata.md) and exact
 * timing pins w* = 3 pi k/T. The recursion runs on the complex pole e^{j pi/N} (a rotation,
 * better conditioned than the real second-order resonator, whose rounding grows like N^2). */
#include "filter/smoother_family.h"

void sms_harmonic_describe(sms_smoother_family *family)
{
    family->damped = 0;
    family->half_sine = 1;
    family->zero_turns = 3.0;
}
