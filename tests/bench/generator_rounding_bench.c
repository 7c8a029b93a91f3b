/* SPDX-License-Identifier: Apache-2.0 */
/* Rounding campaign of the online generator (docs/sampled-limits.md, "What rounding adds"):
 * the random cases of tests/c/generator_campaign.h, half with Ts on the phase grid; prints the
 * worst reported |v|/vmax - 1, |a|/amax - 1, |j|/jmax - 1 in units of u (the unit roundoff of
 * the build) and the worst backward difference |d^i q|/Ts^i beyond the positions' rounding
 * 2^i 16 u S / Ts^i (S the largest |q| or target so far), relative to its limit, minus 1
 * (<= 0: within it), with and without a mode, and the case that gave each.
 *
 * usage: generator_rounding_bench_double [cases [seed]]  (cases default 20000, two draws
 * each: about a minute per precision). Built by CMake (tests/bench), never run by ctest. */
#include <stdio.h>
#include <stdlib.h>
#include "generator_campaign.h"

#ifdef SMS_USE_FLOAT
#define U 5.9604644775390625e-8
#define PRECISION "float"
#else
#define U 1.1102230246251565e-16
#define PRECISION "double"
#endif

static unsigned long long rng = 88172645463325252ull;
static double urand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) / 9007199254740992.0;
}

static sms_real ring[1 << 20];

int main(int argc, char **argv)
{
    static const char *const name[6] = {"|v|/vmax - 1 [u]", "|a|/amax - 1 [u]",
                                        "|j|/jmax - 1 [u]", "dq/Ts beyond, rel - 1",
                                        "d2q/Ts^2 beyond, rel - 1", "d3q/Ts^3 beyond, rel - 1"};
    static char where[2][6][200];
    double worst[2][6];
    long n = argc > 1 ? atol(argv[1]) : 20000, t, cases[2] = {0, 0};
    int i, m;
    if (argc > 2)
        rng = strtoull(argv[2], NULL, 10) | 1u;
    for (m = 0; m < 2; ++m)
        for (i = 0; i < 6; ++i)
            worst[m][i] = -1e300;
    for (t = 0; t < 2 * n; ++t) {
        campaign_case k;
        double reported[4], beyond[4], x[6];
        campaign_draw(&k, urand, t % 2 == 1);
        if (!campaign_run(&k, urand, U, ring, sizeof ring / sizeof ring[0], reported, beyond,
                          NULL, NULL))
            continue;
        m = k.config.wn > 0.0;
        ++cases[m];
        for (i = 1; i < 4; ++i) {
            x[i - 1] = (reported[i] - 1.0) / U;
            x[i + 2] = beyond[i] - 1.0;
        }
        for (i = 0; i < 6; ++i)
            if (x[i] > worst[m][i]) {
                worst[m][i] = x[i];
                snprintf(where[m][i], sizeof where[m][i],
                         "profile %d wn %.6g vmax %.6g amax %.6g jmax %.6g Ts %.6g style %d",
                         (int)k.config.profile, k.config.wn, k.config.vmax, k.config.amax,
                         k.config.jmax, k.Ts, k.style);
            }
    }
    for (m = 0; m < 2; ++m) {
        printf("%s, %s: %ld cases\n", PRECISION, m ? "with a mode" : "no mode", cases[m]);
        for (i = 0; i < 6; ++i)
            printf("  %-26s %+10.3g   %s\n", name[i], worst[m][i], where[m][i]);
    }
    return 0;
}
