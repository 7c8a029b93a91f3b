/* SPDX-License-Identifier: Apache-2.0 */
/*
 * One tick per step of h = Ts from any start time. An importer's clock is either t0 + k h
 * (fmpy: each step from t_k = t0 + k h to t_k+1, of length t_k+1 - t_k) or accumulated,
 * t += h (steps of exactly h). Far from 0 the first gives steps that are not h: near 1.7e9 s
 * one ulp of t is 2.4e-7 s and the step lengths alternate between 0.99993 and 1.00017 ms; near
 * 1e12 s they are multiples of 1.2e-4 s (0.977 or 1.099 ms). The tick slack must therefore
 * scale with |t|: a tick is in the step if it lies within the rounding of the importer's times.
 *
 * The probe (as in test_fmu_clock.c): a 2-sample moving average fed u = k before step k, so
 * after step k y = k - 1/2 exactly; a step without a tick leaves the previous output (a lost
 * tick), one with two ticks gives k (a doubled tick). For every start time (fixed ones: -1e3, -1, 0, 1e6, 1.7e9 + 0.1234, 1e12, and a seeded
 * draw from -1e3 to 1e12, log-uniform in |t0|) and both clock styles it runs 1e4 steps, counts
 * the lost and doubled ticks, and compares every output bit for bit with the run from t0 = 0.
 * Argument: the number of drawn start times (default 40).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"
#include "SmoothShaper_variables.h"
#include "fmu_test_callbacks.h"

#define STEPS 10000
static const double h = 1e-3;   /* = Ts */

static fmi2Component probe(double t0)
{
    const fmi2ValueReference vr_ts = SS_VR_TS, vr_T = SS_STAGE_BASE + SS_FIELD_T;
    fmi2ValueReference kinds[SS_MAX_STAGES];
    fmi2Integer codes[SS_MAX_STAGES];
    const double T = 2 * h;
    int k;
    fmi2Component c = fmi2Instantiate("start", fmi2CoSimulation, FMU_MODEL_GUID, "", &callbacks,
                                      fmi2False, fmi2False);
    if (c == NULL)
        return NULL;
    for (k = 0; k < SS_MAX_STAGES; ++k) {
        kinds[k] = SS_STAGE_BASE + SS_STAGE_STRIDE * (unsigned)k + SS_FIELD_KIND;
        codes[k] = k == 0 ? 0 : SS_KIND_NONE;   /* stage 0 rectangular M(2 Ts) */
    }
    if (fmi2SetupExperiment(c, fmi2False, 0.0, t0, fmi2False, 0.0) != fmi2OK
        || fmi2EnterInitializationMode(c) != fmi2OK
        || fmi2SetInteger(c, kinds, SS_MAX_STAGES, codes) != fmi2OK
        || fmi2SetReal(c, &vr_ts, 1, &h) != fmi2OK || fmi2SetReal(c, &vr_T, 1, &T) != fmi2OK
        || fmi2ExitInitializationMode(c) != fmi2OK) {
        fmi2FreeInstance(c);
        return NULL;
    }
    return c;
}

/* STEPS steps from t0 with the clock style (0: t0 + k h, 1: t += h); the outputs into y.
 * Counts lost and doubled ticks; returns -1 if a call failed. */
static int run(double t0, int accumulate, double *y, long *lost, long *doubled)
{
    const fmi2ValueReference vr_u = SS_VR_U, vr_y = SS_VR_Y;
    fmi2Component c = probe(t0);
    double t = t0;
    long k;
    if (c == NULL)
        return -1;
    for (k = 1; k <= STEPS; ++k) {
        const double u = (double)k;
        const double next = accumulate ? t + h : t0 + (double)k * h;
        if (fmi2SetReal(c, &vr_u, 1, &u) != fmi2OK
            || fmi2DoStep(c, t, accumulate ? h : next - t, fmi2True) != fmi2OK
            || fmi2GetReal(c, &vr_y, 1, &y[k - 1]) != fmi2OK) {
            fmi2FreeInstance(c);
            return -1;
        }
        t = next;
        if (y[k - 1] == (k == 1 ? 0.0 : y[k - 2]))   /* no tick: the output held */
            ++*lost;
        else if (y[k - 1] == u)                     /* two or more ticks under u */
            ++*doubled;
    }
    fmi2FreeInstance(c);
    return 0;
}

static unsigned long long rng = 88172645463325252ull;
static double uniform(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) * (1.0 / 9007199254740992.0);
}

int main(int argc, char **argv)
{
    static const double fixed[] = { -1e3, -1.0, 0.0, 1e6, 1.7e9 + 0.1234, 1e12 };
    const long draws = argc > 1 ? strtol(argv[1], NULL, 10) : 40;
    const long n_fixed = (long)(sizeof fixed / sizeof fixed[0]);
    static double ref[STEPS], y[STEPS];
    long lost_total = 0, doubled_total = 0, unequal_total = 0, i;
    int style;
    long l0 = 0, d0 = 0;
    if (run(0.0, 0, ref, &l0, &d0) != 0 || l0 != 0 || d0 != 0) {
        fprintf(stderr, "FAILED: the run from t0 = 0 itself loses or doubles ticks\n");
        return 1;
    }
    for (i = 0; i < n_fixed + draws; ++i) {
        double t0 = fixed[i < n_fixed ? i : 0];
        if (i >= n_fixed)   /* |t0| log-uniform in [1e-3, 1e12], negative ones down to -1e3 */
            t0 = uniform() < 0.2 ? -pow(10.0, -3.0 + 6.0 * uniform())
                                 : pow(10.0, -3.0 + 15.0 * uniform());
        for (style = 0; style < 2; ++style) {
            long lost = 0, doubled = 0, unequal = 0, k;
            if (run(t0, style, y, &lost, &doubled) != 0) {
                fprintf(stderr, "FAILED: a call failed from t0 = %.17g\n", t0);
                return 1;
            }
            for (k = 0; k < STEPS; ++k)
                unequal += memcmp(&y[k], &ref[k], sizeof y[k]) != 0;
            if (lost + doubled + unequal != 0 || i < n_fixed)
                printf("t0 = %-24.17g %-9s %5ld lost, %5ld doubled, %5ld of %d outputs differ "
                       "from t0 = 0\n", t0, style ? "t += h" : "t0 + k h", lost, doubled, unequal,
                       STEPS);
            lost_total += lost;
            doubled_total += doubled;
            unequal_total += unequal;
        }
    }
    printf("%ld start times x 2 clock styles x %d steps: %ld ticks lost, %ld doubled, %ld "
           "outputs differ from the start at 0\n", n_fixed + draws, STEPS, lost_total,
           doubled_total, unequal_total);
    return lost_total + doubled_total + unequal_total != 0;
}
