/* Prints the multi-axis generator's cost for 1, 3 and 6 axes (phase-synchronised): ns per
 * sample while moving or at rest (no re-plan), and the cost of a re-plan (from rest and
 * blended mid-motion) as the extra time of the samples that carry one. Figures only. */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include <string.h>
#include <time.h>
#include "smoothshaper/smoothshaper.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int main(void)
{
    const size_t axes_list[] = {1, 3, 6};
    size_t a;
    printf("multi-axis generator (%s), Ts = 1e-4 s\n", sizeof(sms_real) == 4 ? "float" : "double");
    printf("axes  ns/sample (no re-plan)  us/re-plan from rest  us/re-plan blended\n");
    for (a = 0; a < sizeof axes_list / sizeof axes_list[0]; ++a) {
        size_t n_axes = axes_list[a], i;
        sms_multi_generator_config c;
        sms_multi_generator g;
        sms_real target[SMS_MULTI_MAX_AXES], out[4 * SMS_MULTI_MAX_AXES];
        volatile sms_real sink = 0;
        double t0, per_sample, rest_replan, blend_replan;
        long k, n = 4000000, m = 20000;
        memset(&c, 0, sizeof c);
        c.n_axes = n_axes;
        c.sync = SMS_SYNC_PHASE;
        for (i = 0; i < n_axes; ++i) {
            c.vmax[i] = 1.0 + (double)i;
            c.amax[i] = 10.0 + 3.0 * (double)i;
            c.jmax[i] = 100.0 + 50.0 * (double)i;
            target[i] = (sms_real)(1000.0 * (1.0 + (double)i)); /* one long move */
        }
        if (sms_multi_generator_init(&g, &c, 1e-4, NULL, 0, NULL, 0, NULL) != SMS_OK)
            return 1;
        t0 = now();
        for (k = 0; k < n; ++k) {
            sms_multi_generator_step(&g, target, out);
            sink += out[0];
        }
        per_sample = (now() - t0) / (double)n * 1e9;

        /* from rest: reset, one step with a new target (the re-plan), repeated */
        t0 = now();
        for (k = 0; k < m; ++k) {
            sms_multi_generator_reset(&g, NULL);
            for (i = 0; i < n_axes; ++i)
                target[i] = (sms_real)(0.5 + 0.001 * (double)(k % 97) + 0.1 * (double)i);
            sms_multi_generator_step(&g, target, out);
            sink += out[0];
        }
        rest_replan = (now() - t0) / (double)m * 1e6 - per_sample * 1e-3;

        /* blended: a new target every 2000 samples while cruising (one re-plan each) */
        sms_multi_generator_reset(&g, NULL);
        t0 = now();
        for (k = 0; k < 2000L * 200; ++k) {
            if (k % 2000 == 0)
                for (i = 0; i < n_axes; ++i)
                    target[i] = (sms_real)((k / 2000) % 2 ? -1.0 : 1.0) * (sms_real)(1.0 + i);
            sms_multi_generator_step(&g, target, out);
            sink += out[0];
        }
        blend_replan = ((now() - t0) * 1e9 - per_sample * 2000.0 * 200.0) / 200.0 * 1e-3;
        printf("%4zu  %24.1f  %20.2f  %18.2f\n", n_axes, per_sample, rest_replan, blend_replan);
    }
    return 0;
}
