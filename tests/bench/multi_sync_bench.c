/* SPDX-License-Identifier: Apache-2.0 */
/* Prints the cost of the multi-axis generator's per-axis plan modes (Time, TimeIfNecessary,
 * None) for 1, 3 and 6 axes: ns per sample while moving (no re-plan), and us per re-plan from a
 * moving state to random target states (half of them moving), measured on copies of one
 * generator: the time of a step that re-plans minus that of the same step without a new
 * target. Figures only; nothing is asserted. --quick: a smoke run with fewer repetitions. */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <string.h>
#include "smoothshaper/smoothshaper.h"
#include "cpu_time.h"

#define N_TARGETS 64

static uint64_t seed = 0x9E3779B97F4A7C15ull;
static double uniform(void)
{
    seed ^= seed << 13;
    seed ^= seed >> 7;
    seed ^= seed << 17;
    return (double)(seed >> 11) / 9007199254740992.0;
}

/* The least of 5 rounds of m steps on copies of *from, copy c stepped once with
 * targets[c % N_TARGETS] (ns per step). */
static double copy_step(const sms_multi_generator *from, const sms_multi_target *targets,
                        long m, volatile sms_real *sink)
{
    double best = 1e300;
    int round;
    for (round = 0; round < 5; ++round) {
        static sms_multi_generator g;
        sms_real out[4 * SMS_MULTI_MAX_AXES];
        double t0 = cpu_seconds(), t;
        long c;
        for (c = 0; c < m; ++c) {
            memcpy(&g, from, sizeof g);
            sms_multi_generator_step_target(&g, &targets[c % N_TARGETS], out);
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
    const char *names[] = {"time", "time_if_necessary", "none"};
    size_t a;
    int mode;
    printf("multi-axis generator, per-axis plan modes (%s), Ts = 1e-3 s\n",
           sizeof(sms_real) == 4 ? "float" : "double");
    printf("mode               axes  ns/sample (moving)  us/re-plan (any state to any state)\n");
    for (mode = 0; mode < 3; ++mode)
        for (a = 0; a < sizeof axes_list / sizeof axes_list[0]; ++a) {
            static sms_multi_generator g, moving;
            static sms_multi_target same[N_TARGETS], fresh[N_TARGETS];
            sms_multi_generator_config cfg;
            sms_multi_target first;
            sms_real q[SMS_MULTI_MAX_AXES] = {0}, v[SMS_MULTI_MAX_AXES] = {0},
                     acc[SMS_MULTI_MAX_AXES] = {0}, out[4 * SMS_MULTI_MAX_AXES];
            volatile sms_real sink = 0;
            size_t n_axes = axes_list[a], i, c, bad;
            long k, n = quick ? 20000 : 400000, m = quick ? 500 : 20000;
            double t0, per_sample, base, replan;
            memset(&cfg, 0, sizeof cfg);
            memset(&first, 0, sizeof first);
            cfg.n_axes = n_axes;
            cfg.sync = (sms_sync)(SMS_SYNC_TIME + mode);
            for (i = 0; i < n_axes; ++i) {
                cfg.vmax[i] = 1.0 + (double)i;
                cfg.amax[i] = 10.0 + 3.0 * (double)i;
                cfg.jmax[i] = 100.0 + 50.0 * (double)i;
                first.position[i] = (sms_real)(1000.0 * (1.0 + (double)i)); /* a long move */
            }
            if (sms_multi_generator_init(&g, &cfg, 1e-3, NULL, 0, NULL, 0, &bad) != SMS_OK ||
                sms_multi_generator_start(&g, q, v, acc, &first, &bad) != SMS_OK)
                return 1;
            t0 = cpu_seconds();
            for (k = 0; k < n; ++k) {
                sms_multi_generator_step_target(&g, &first, out);
                sink += out[0];
            }
            per_sample = (cpu_seconds() - t0) / (double)n * 1e9;
            /* re-plans from a state mid-transition towards random targets near it */
            memset(&g, 0, sizeof g);
            (void)sms_multi_generator_init(&g, &cfg, 1e-3, NULL, 0, NULL, 0, &bad);
            for (i = 0; i < n_axes; ++i) {
                v[i] = (sms_real)(0.5 * cfg.vmax[i]);
                acc[i] = (sms_real)(0.3 * cfg.amax[i]);
            }
            (void)sms_multi_generator_start(&g, q, v, acc, &first, &bad);
            for (k = 0; k < 5; ++k)
                sms_multi_generator_step_target(&g, &first, out);
            moving = g;
            for (c = 0; c < N_TARGETS; ++c) {
                same[c] = first;
                memset(&fresh[c], 0, sizeof fresh[c]);
                for (i = 0; i < n_axes; ++i) {
                    fresh[c].position[i] = (sms_real)(out[4 * i] + (uniform() - 0.5) * 2.0);
                    if (c % 2 == 1) {
                        fresh[c].velocity[i] = (sms_real)((uniform() - 0.5) * cfg.vmax[i]);
                        fresh[c].acceleration[i] = 0;
                    }
                }
            }
            base = copy_step(&moving, same, m, &sink);
            replan = copy_step(&moving, fresh, m, &sink) - base;
            printf("%-18s %4zu  %18.1f  %8.2f\n", names[mode], n_axes, per_sample,
                   replan * 1e-3);
            (void)sink;
        }
    return 0;
}
