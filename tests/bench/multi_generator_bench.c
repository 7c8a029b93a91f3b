/* SPDX-License-Identifier: Apache-2.0 */
/* Prints the multi-axis generator's cost for 1, 3 and 6 axes (phase-synchronised): ns per
 * sample while moving (no re-plan), and the cost of one re-plan from rest and blended
 * mid-motion (a new target seen during the cruise), each measured on copies of one saved
 * generator: the time of a step that re-plans minus that of the same step without a new
 * target. Figures only; nothing is asserted. --quick: a smoke run with fewer repetitions. */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <string.h>
#include "smoothshaper/smoothshaper.h"
#include "cpu_time.h"

/* Median-free but robust enough: the least of 5 rounds of m steps on copies of *from, each
 * copy stepped once with targets[c % n_targets] (ns per step). */
static double copy_step(const sms_multi_generator *from, sms_real targets[][SMS_MULTI_MAX_AXES],
                        size_t n_targets, long m, volatile sms_real *sink)
{
    double best = 1e300;
    int round;
    for (round = 0; round < 5; ++round) {
        sms_multi_generator g;
        sms_real out[4 * SMS_MULTI_MAX_AXES];
        double t0 = cpu_seconds(), t;
        long c;
        for (c = 0; c < m; ++c) {
            memcpy(&g, from, sizeof g);
            sms_multi_generator_step(&g, targets[(size_t)c % n_targets], out);
            *sink += out[0];
        }
        t = (cpu_seconds() - t0) / (double)m * 1e9;
        if (t < best)
            best = t;
    }
    return best;
}

int main(int argc, char **argv)
{
    const int quick = argc > 1 && strcmp(argv[1], "--quick") == 0;
    const size_t axes_list[] = {1, 3, 6};
    size_t a;
    printf("multi-axis generator (%s), Ts = 1e-4 s\n", sizeof(sms_real) == 4 ? "float" : "double");
    printf("axes  ns/sample (no re-plan)  us/re-plan from rest  us/re-plan blended\n");
    for (a = 0; a < sizeof axes_list / sizeof axes_list[0]; ++a) {
        size_t n_axes = axes_list[a], i, c;
        sms_multi_generator_config cfg;
        sms_multi_generator g, rest, cruise;
        sms_real hold[1][SMS_MULTI_MAX_AXES], start[1][SMS_MULTI_MAX_AXES];
        sms_real fresh[16][SMS_MULTI_MAX_AXES], out[4 * SMS_MULTI_MAX_AXES];
        volatile sms_real sink = 0;
        double base_rest, base_cruise, per_sample, t0;
        long k, n = quick ? 100000 : 2000000, m = quick ? 1000 : 20000;
        memset(&cfg, 0, sizeof cfg);
        cfg.n_axes = n_axes;
        cfg.sync = SMS_SYNC_PHASE;
        for (i = 0; i < n_axes; ++i) {
            cfg.vmax[i] = 1.0 + (double)i;
            cfg.amax[i] = 10.0 + 3.0 * (double)i;
            cfg.jmax[i] = 100.0 + 50.0 * (double)i;
            start[0][i] = (sms_real)(1000.0 * (1.0 + (double)i)); /* one long move */
            hold[0][i] = 0;
            for (c = 0; c < 16; ++c) /* new targets: other directions and lengths */
                fresh[c][i] = (sms_real)(((c + i) % 3 == 0 ? -1.0 : 1.0) *
                                         (0.3 + 0.37 * (double)((c * 7 + i * 3) % 11)));
        }
        if (sms_multi_generator_init(&g, &cfg, 1e-4, NULL, 0, NULL, 0, NULL) != SMS_OK)
            return 1;
        t0 = cpu_seconds();
        for (k = 0; k < n; ++k) {
            sms_multi_generator_step(&g, start[0], out);
            sink += out[0];
        }
        per_sample = (cpu_seconds() - t0) / (double)n * 1e9;

        /* at rest at 0; cruising towards the long move's target (the first transition done) */
        sms_multi_generator_reset(&g, NULL);
        memcpy(&rest, &g, sizeof g);
        for (k = 0; k < 30000; ++k)
            sms_multi_generator_step(&g, start[0], out);
        memcpy(&cruise, &g, sizeof g);
        base_rest = copy_step(&rest, hold, 1, m, &sink);
        base_cruise = copy_step(&cruise, start, 1, m, &sink);
        printf("%4zu  %24.1f  %20.2f  %18.2f\n", n_axes, per_sample,
               (copy_step(&rest, fresh, 16, m, &sink) - base_rest) * 1e-3,
               (copy_step(&cruise, fresh, 16, m, &sink) - base_cruise) * 1e-3);
    }
    return 0;
}
