/* SPDX-License-Identifier: Apache-2.0 */
/* How long sizing and validating a filter takes, as a function of its length (printed, never
 * asserted): every size query and every refusal is O(1), so the times below must not grow with
 * T/Ts. Run: build/release/tests/refusal_bench_double */
#include <math.h>
#include <stdio.h>
#include "smoothshaper/smoothshaper.h"
#include "cpu_time.h"

/* Mean time of one sms_chain_memory_size call over `reps` calls. */
static double size_time(const sms_stage_config *c, size_t n, double Ts, size_t *need,
                        sms_status *st)
{
    const int reps = 1000;
    double t0 = cpu_seconds();
    int r;
    for (r = 0; r < reps; ++r)
        *st = sms_chain_memory_size(c, n, Ts, need);
    return (cpu_seconds() - t0) / reps;
}

int main(void)
{
    static const sms_kind kinds[] = { SMS_RECTANGULAR, SMS_HARMONIC, SMS_DAMPED_HARMONIC,
                                      SMS_EXPONENTIAL };
    const double Ts = 1e-6;
    double nu;
    size_t need, k;
    sms_status st;
    printf("size query of one smoother (exact timing), mean of 1000 calls\n");
    printf("%-18s %12s %12s %12s %12s\n", "T/Ts", "rectangular", "harmonic", "damped harm.",
           "exponential");
    for (nu = 1e3; nu <= 1e15; nu *= 1e3) {
        printf("%-18.10g", nu * (1.0 + 3.7e-7));
        for (k = 0; k < 4; ++k) {
            sms_stage_config c = sms_stage_config_default(kinds[k]);
            c.T = nu * (1.0 + 3.7e-7) * Ts;
            c.sigma = -0.5;
            printf(" %9.3f us", 1e6 * size_time(&c, 1, Ts, &need, &st));
        }
        printf("\n");
    }
    printf("\nstages for a mode wn = 100 rad/s, zeta = 0.99999999999, Ts = 1 ms\n");
    for (k = 0; k < 4; ++k) {
        sms_stage_config c;
        double t;
        sms_design_for_mode(kinds[k], 100.0, 0.99999999999, 1u, &c);
        t = size_time(&c, 1, 1e-3, &need, &st);
        printf("  %-16s status %3d, %10lu cells, %8.3f us\n", sms_kind_name(kinds[k]), (int)st,
               (unsigned long)need, 1e6 * t);
    }
    {
        sms_stage_config chain[4];
        double t;
        for (k = 0; k < 4; ++k) {
            chain[k] = sms_stage_config_default(kinds[k]);
            chain[k].T = 1e3 + 0.5e-6 * (double)k; /* 1e9 samples each */
            chain[k].sigma = -1e-3;
        }
        t = size_time(chain, 4, Ts, &need, &st);
        printf("\nchain of 4 smoothers of 1e9 samples each: %.3f us (status %d, %lu cells)\n",
               1e6 * t, (int)st, (unsigned long)need);
    }
    return 0;
}
