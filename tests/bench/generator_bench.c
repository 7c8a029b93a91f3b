/* SPDX-License-Identifier: Apache-2.0 */
/* Prints the generator's cost: ns per sample on a long move (no re-plan) for each profile,
 * with and without a mode, the re-plan cost (a target that moves every sample, minus the
 * steady cost), the re-plan cost of each kind of target (a moving one, the velocity
 * interface), each with symmetric and with asymmetric limits, and the kinematic design time. Figures only; nothing is asserted. */
#define _POSIX_C_SOURCE 199309L
#include <stdio.h>
#include "smoothshaper/smoothshaper.h"
#include "cpu_time.h"

static sms_real table[100000];

static volatile sms_real sink = 0;

/* ns per step of a staircase whose target moves by `wiggle` every sample (0: one long move) */
static double per_step(sms_generator *g, long n, double wiggle)
{
    sms_real out[4];
    double t0;
    long k;
    sms_generator_reset(g, 0);
    t0 = cpu_seconds();
    for (k = 0; k < n; ++k) {
        sms_generator_step(g, (sms_real)(1e3 + wiggle * (double)(k % 64)), out);
        sink += out[0];
    }
    return (cpu_seconds() - t0) / (double)n * 1e9;
}

/* ns per step when every sample brings a new target of one kind (polynomial profile, no
 * stage): 0 a position target at rest (a staircase), 1 a moving position target (a conveyor
 * at 100 units/s, its position wiggled every sample), 2 the velocity interface (a velocity
 * that changes every sample), 3 the same target held (no re-plan: the steady cost). */
static double per_step_kind(sms_generator *g, long n, int kind)
{
    sms_real out[4];
    sms_target t;
    double t0, Ts = 1e-4;
    long k;
    sms_generator_reset(g, 0);
    t.interface = kind == 2 ? SMS_INTERFACE_VELOCITY : SMS_INTERFACE_POSITION;
    t.acceleration = 0;
    t.minimum_duration = 0;
    t0 = cpu_seconds();
    for (k = 0; k < n; ++k) {
        double w = kind == 3 ? 0.0 : (double)(k % 64);
        t.position = (sms_real)(kind == 1 ? 100.0 * Ts * (double)k + 1e-2 * w : 1e3 + w);
        t.velocity = (sms_real)(kind == 1 ? 100.0 : kind == 2 ? 100.0 + w : 0.0);
        sms_generator_step_target(g, &t, out);
        sink += out[0];
    }
    return (cpu_seconds() - t0) / (double)n * 1e9;
}

int main(void)
{
    static const struct {
        const char *name;
        sms_profile profile;
        double wn, zeta;
    } cases[] = {
        {"polynomial", SMS_PROFILE_POLYNOMIAL, 0.0, 0.0},
        {"trigonometric", SMS_PROFILE_TRIGONOMETRIC, 0.0, 0.0},
        {"polynomial, mode 40 rad/s", SMS_PROFILE_POLYNOMIAL, 40.0, 0.0},
        {"trigonometric, mode 40 rad/s", SMS_PROFILE_TRIGONOMETRIC, 40.0, 0.0},
        {"damped, mode 40 rad/s", SMS_PROFILE_DAMPED, 40.0, 0.05},
    };
    double Ts = 1e-4, t0, design_ns;
    size_t i, need;
    long k;
    printf("generator [%s], Ts = %g s\n", sizeof(sms_real) == 4 ? "float" : "double", Ts);
    for (i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        sms_generator g;
        sms_generator_config c;
        double steady, replan;
        c.vmax = 250.0; c.amax = 5000.0; c.jmax = 200000.0;
        c.profile = cases[i].profile; c.wn = cases[i].wn; c.zeta = cases[i].zeta;
        c.vmin = c.amin = 0.0; /* symmetric */
        c.qmin = c.qmax = 0.0; /* no position limits */
        if (sms_generator_buffer_size(&c, Ts, &need) != SMS_OK || need > 100000 ||
            sms_generator_init(&g, &c, Ts, table, need) != SMS_OK)
            return 1;
        steady = per_step(&g, 5000000, 0.0);
        replan = per_step(&g, 1000000, 1.0) - steady;
        printf("  %-30s per sample %.2f ns, a re-plan %.1f ns (stage %lu samples)\n",
               cases[i].name, steady, replan, (unsigned long)g.stage_length);
    }
    {
        static const char *kinds[] = {"position target at rest", "moving position target",
                                      "velocity interface"};
        sms_generator g;
        sms_generator_config c;
        double steady;
        int kind;
        c.vmax = 250.0; c.amax = 5000.0; c.jmax = 200000.0;
        c.profile = SMS_PROFILE_POLYNOMIAL; c.wn = 0.0; c.zeta = 0.0;
        int asym;
        for (asym = 0; asym < 2; ++asym) {
            /* symmetric, then asymmetric limits (vmin = -vmax/2, amin = -amax/4: the same
             * targets, which stay within both; the moving target's 100 units/s forward) */
            c.vmin = asym ? -125.0 : 0.0;
            c.amin = asym ? -1250.0 : 0.0;
            c.qmin = c.qmax = 0.0; /* no position limits */
            if (sms_generator_buffer_size(&c, Ts, &need) != SMS_OK || need > 100000 ||
                sms_generator_init(&g, &c, Ts, table, need) != SMS_OK)
                return 1;
            steady = per_step_kind(&g, 2000000, 3);
            printf("  a new target every sample (polynomial%s), per sample minus the held one's "
                   "%.2f ns:\n", asym ? ", vmin = -vmax/2, amin = -amax/4" : "", steady);
            for (kind = 0; kind < 3; ++kind)
                printf("    %-28s a re-plan %.1f ns\n", kinds[kind],
                       per_step_kind(&g, 500000, kind) - steady);
        }
    }
    {
        double L[3] = {250.0, 5000.0, 200000.0}, T[3];
        size_t cnt;
        long m = 200000;
        t0 = cpu_seconds();
        for (k = 0; k < m; ++k) {
            L[0] = 250.0 + (double)(k % 100);
            sms_kinematic_design(0.4 + 1e-3 * (double)(k % 1000), L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 0.0, T, 3, &cnt);
            sink += (sms_real)T[0];
        }
        design_ns = (cpu_seconds() - t0) / (double)m * 1e9;
    }
    printf("  kinematic design n=3 (short moves): %.1f ns per design\n", design_ns);
    return sink == 12345.0;
}
