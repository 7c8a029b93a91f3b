/* Prints the generator's cost: ns per sample at rest/cruise (no re-plan), ns per sample when
 * the target changes every Nc samples (one re-plan each), the re-plan cost as the difference,
 * and the kinematic design time. Figures only; nothing is asserted. */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <time.h>
#include "smoothshaper/smoothshaper.h"

static sms_real table[100000];

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int main(void)
{
    sms_generator g;
    sms_generator_config c;
    sms_real out[4];
    volatile sms_real sink = 0;
    double Ts = 1e-4, t0, per_sample, per_replan_sample, design_ns;
    size_t need, replans = 0;
    long k, n = 20000000;
    c.vmax = 250.0; c.amax = 5000.0; c.jmax = 200000.0;
    c.profile = SMS_PROFILE_POLYNOMIAL; c.wn = 0.0; c.zeta = 0.0;
    if (sms_generator_buffer_size(&c, Ts, &need) != SMS_OK || need > 100000)
        return 1;
    sms_generator_init(&g, &c, Ts, table, need);

    /* one long move then rest: no re-plans after the first */
    t0 = now();
    for (k = 0; k < n; ++k) {
        sms_generator_step(&g, (sms_real)1e6, out);
        sink += out[0];
    }
    per_sample = (now() - t0) / (double)n * 1e9;

    /* re-plan cost: force "change allowed" before every step (fields are public), once with
     * a target that moves every step (a re-plan each step), once with a fixed one (none) */
    {
        double base, with;
        long m = 5000000;
        sms_generator_reset(&g, 0);
        t0 = now();
        for (k = 0; k < m; ++k) {
            g.age = g.n_tail;
            sms_generator_step(&g, (sms_real)1e3, out);
            sink += out[0];
        }
        base = (now() - t0) / (double)m * 1e9;
        sms_generator_reset(&g, 0);
        t0 = now();
        for (k = 0; k < m; ++k) {
            g.age = g.n_tail;
            sms_generator_step(&g, (sms_real)(1e3 + (double)(k % 64)), out);
            replans += g.age == 0 || g.seg_pos == 0;
            sink += out[0];
        }
        with = (now() - t0) / (double)m * 1e9;
        per_replan_sample = with - base;
        printf("  (re-plans counted: %lu of %ld steps)\n", (unsigned long)replans, m);
    }
    {
        double L[3] = {250.0, 5000.0, 200000.0}, T[3];
        size_t cnt;
        long m = 200000;
        t0 = now();
        for (k = 0; k < m; ++k) {
            L[0] = 250.0 + (double)(k % 100);
            sms_kinematic_design(0.4 + 1e-3 * (double)(k % 1000), L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 0.0, T, 3, &cnt);
            sink += (sms_real)T[0];
        }
        design_ns = (now() - t0) / (double)m * 1e9;
    }
    printf("generator [%s], Nc = %lu samples\n", sizeof(sms_real) == 4 ? "float" : "double",
           (unsigned long)g.n_tail);
    printf("  per sample, no re-plan:             %.2f ns\n", per_sample);
    printf("  re-plan cost (extra per step):      %.2f ns per re-plan\n", per_replan_sample);
    printf("  kinematic design n=3 (short moves): %.1f ns per design\n", design_ns);
    return sink == 12345.0;
}
