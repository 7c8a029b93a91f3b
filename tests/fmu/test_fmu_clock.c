/* SPDX-License-Identifier: Apache-2.0 */
/*
 * Tick accounting against a host that accumulates its clock (t += h, h = Ts = 1 ms), as simple
 * masters and fmpy's SSP runner do. That clock drifts from k*h: at step 334,586 the step ends at
 * 334.58599999899997 (1e-6 ticks early) and after 1e9 steps it is 18.5 ticks ahead. Every step of
 * h = Ts must still compute exactly one tick.
 *
 * The probe: a 2-sample moving average (taps 1/2, 1/2) fed u = k before step k. After step k,
 * y = (k + (k - 1))/2 exactly; a lost tick leaves y at the previous value, a doubled tick gives
 * (k + k)/2. The host clock is accumulated over all 1e9 steps (cheap); the FMU runs the first
 * 400,000 steps contiguously (through step 334,586) and fresh instances run windows of steps
 * starting at the accumulated clock of steps 1e7, 1e8 and 1e9 - 4000. With the environment
 * variable SMS_FMU_CLOCK_FULL=1 one instance runs all 1e9 steps contiguously (about a minute).
 * Steps of up to 1e12 s (1e15 ticks) leave a clock whose serialised state loads again: the
 * tick count floor(h/Ts) of one long step is off by a few ulp of h/Ts, so the time since the
 * last tick may fall slightly outside [0, Ts) and the reader must allow that rounding; a step
 * that would end beyond the largest double is refused.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"
#include "smoothshaper/types.h"
#include "SmoothShaper_variables.h"
#include "fmu_test_callbacks.h"
#include "fmu_test_probe.h"

/* Steps k = first .. first + n - 1 with the host clock starting at *t (advanced t += h).
 * Returns the number of steps whose output shows a lost or doubled tick. */
static long run(fmi2Component c, long first, long n, double *t)
{
    const fmi2ValueReference vr_u = SS_VR_U, vr_y = SS_VR_Y;
    long bad = 0, i;
    for (i = 0; i < n; ++i) {
        /* inputs modulo 2^20 keep (k + k - 1)/2 exact and distinguish neighbours */
        double k = (double)((first + i) % 1048576L), prev = k == 0.0 ? 1048575.0 : k - 1.0, y;
        if (i == 0)
            prev = k;   /* the instance rests at u = k before its first step */
        fmi2SetReal(c, &vr_u, 1, &k);
        if (fmi2DoStep(c, *t, h, fmi2True) != fmi2OK)
            return n;
        *t += h;
        fmi2GetReal(c, &vr_y, 1, &y);
        if (y != 0.5 * (k + prev)) {
            if (bad < 5)
                fprintf(stderr, "step %ld (t = %.17g): y = %.17g, expected %.17g\n", first + i, *t,
                        y, 0.5 * (k + prev));
            ++bad;
        }
    }
    return bad;
}

static long window(long first, long n, double t0)
{
    double t = t0;
    long bad;
    fmi2Component c = probe_instance("clock", t0, (double)(first % 1048576L));
    if (c == NULL) {
        fprintf(stderr, "could not set up the probe\n");
        return 1;
    }
    bad = run(c, first, n, &t);
    fmi2FreeInstance(c);
    printf("steps %ld .. %ld (host t from %.17g): %ld lost or doubled ticks\n", first,
           first + n - 1, t0, bad);
    return bad;
}

/* After steps of 1 s .. 1e12 s over new inputs, every serialised state loads again. Returns the
 * number of states refused. */
static long long_steps_reload(void)
{
    const fmi2ValueReference vr_u = SS_VR_U;
    static const double lengths[] = { 1.0, 1e6, 1e9, 1e11 / 3.0, 1e12 };
    fmi2Component c = probe_instance("clock", 0.0, 0.0);
    double t = 0.0, u;
    long bad = 0;
    size_t i;
    if (c == NULL)
        return 1;
    for (i = 0; i < sizeof lengths / sizeof lengths[0]; ++i) {
        fmi2FMUstate s = NULL, back = NULL;
        size_t size = 0;
        unsigned char *blob;
        u = (double)(i + 1);
        if (fmi2SetReal(c, &vr_u, 1, &u) != fmi2OK || fmi2DoStep(c, t, lengths[i], fmi2True) != fmi2OK
            || fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &t) != fmi2OK
            || fmi2GetFMUstate(c, &s) != fmi2OK || fmi2SerializedFMUstateSize(c, s, &size) != fmi2OK
            || (blob = (unsigned char *)malloc(size)) == NULL) {
            fmi2FreeInstance(c);
            return bad + 1;
        }
        if (fmi2SerializeFMUstate(c, s, (fmi2Byte *)blob, size) != fmi2OK
            || fmi2DeSerializeFMUstate(c, (fmi2Byte *)blob, size, &back) != fmi2OK
            || fmi2SetFMUstate(c, back) != fmi2OK) {
            fprintf(stderr, "FAILED: the state after a step of %.17g s does not load\n",
                    lengths[i]);
            ++bad;
        }
        free(blob);
        fmi2FreeFMUstate(c, &back);
        fmi2FreeFMUstate(c, &s);
    }
    fmi2FreeInstance(c);
    return bad;
}

/* With the largest Ts (SMS_TS_MAX = 2^967, 1.25e291 s: ticks below FMU_MAX_TICK_INDEX then
 * span at most 5e306 s) and a start time 7e305 s below the largest double, a step of 2e305 s
 * and then one of 4e306 s would end beyond the largest double: the second is refused (its end
 * time would be inf, and no saved state could hold that clock), and the state after the first
 * loads again. Returns the number of failed checks. */
static long step_beyond_the_largest_double(void)
{
    const fmi2ValueReference vr_ts = SS_VR_TS, vr_T = SS_STAGE_BASE + SS_FIELD_T;
    const fmi2ValueReference vr_kind1 = SS_STAGE_BASE + SS_STAGE_STRIDE + SS_FIELD_KIND;
    const fmi2Integer none = SS_KIND_NONE;   /* stage 0 a moving average of 2 Ts, no stage 1 */
    const double Ts = SMS_TS_MAX, T = 2.0 * SMS_TS_MAX, t0 = 1.79e308, h1 = 2e305, h2 = 4e306;
    fmi2Component c = fmi2Instantiate("clock", fmi2CoSimulation, FMU_MODEL_GUID, "", &callbacks,
                                      fmi2False, fmi2False);
    fmi2FMUstate s = NULL, back = NULL;
    unsigned char blob[4096];
    size_t size = 0;
    long bad = 0;
    if (c == NULL || fmi2SetupExperiment(c, fmi2False, 0.0, t0, fmi2False, 0.0) != fmi2OK
        || fmi2EnterInitializationMode(c) != fmi2OK
        || fmi2SetInteger(c, &vr_kind1, 1, &none) != fmi2OK
        || fmi2SetReal(c, &vr_ts, 1, &Ts) != fmi2OK
        || fmi2SetReal(c, &vr_T, 1, &T) != fmi2OK || fmi2ExitInitializationMode(c) != fmi2OK
        || fmi2DoStep(c, t0, h1, fmi2True) != fmi2OK) {
        fmi2FreeInstance(c);
        return 1;
    }
    bad += fmi2DoStep(c, t0 + h1, h2, fmi2True) != fmi2Error;
    bad += fmi2GetFMUstate(c, &s) != fmi2OK || fmi2SerializedFMUstateSize(c, s, &size) != fmi2OK
           || size > sizeof blob || fmi2SerializeFMUstate(c, s, (fmi2Byte *)blob, size) != fmi2OK
           || fmi2DeSerializeFMUstate(c, (fmi2Byte *)blob, size, &back) != fmi2OK;
    if (bad != 0)
        fprintf(stderr, "FAILED: a step ending beyond the largest double was taken, or the state "
                "before it does not load\n");
    fmi2FreeFMUstate(c, &back);
    fmi2FreeFMUstate(c, &s);
    fmi2FreeInstance(c);
    return bad;
}

int main(void)
{
    const long total = 1000000000L, windows[] = { 10000000L, 100000000L, 1000000000L - 4000 };
    const char *full = getenv("SMS_FMU_CLOCK_FULL");
    long bad = 0, step, unloadable = long_steps_reload() + step_beyond_the_largest_double();
    size_t w = 0;
    double t = 0.0;
    if (full != NULL && strcmp(full, "1") == 0)
        return window(0, total, 0.0) != 0;
    bad += window(0, 400000, 0.0);   /* includes step 334,586 */
    for (step = 0; step < total && w < sizeof windows / sizeof windows[0]; ++step) {
        if (step == windows[w])
            bad += window(windows[w++], 4000, t);
        t += h;   /* the host's accumulated clock */
    }
    printf("host clock at step %ld: %.17g (k*h = %.17g)\n", step, t, (double)step * h);
    if (bad != 0 || unloadable != 0) {
        fprintf(stderr, "FAILED: %ld steps lost or doubled a tick, %ld states after long steps "
                "do not load\n", bad, unloadable);
        return 1;
    }
    return 0;
}
