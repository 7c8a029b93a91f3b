/* SPDX-License-Identifier: Apache-2.0 */
/*
 * What each FMI call costs for the largest states an FMU accepts: one model linked in-process
 * (SmoothShaper, or TrajectoryGenerator / MultiAxisGenerator with FMU_TEST_TRAJECTORY /
 * FMU_TEST_MULTI_AXIS), configured to allocate about N reals of delay line for N up to
 * FMU_MAX_REALS (the per-instance limit, fmu_model.h), and every call that touches the whole
 * state timed once per round (CPU time, median of the rounds):
 *   fmi2ExitInitializationMode (plan, allocate, build at rest), fmi2GetFMUstate (new and reused
 *   state), fmi2SetFMUstate, fmi2SerializeFMUstate, fmi2DeSerializeFMUstate, fmi2FreeFMUstate,
 *   fmi2DoStep of one sample, fmi2DoStep over a newly held input of about the longest length
 *   that is still filtered sample by sample (medium_ticks()), fmi2DoStep of 1e9 s over a newly held input (the model's closed
 *   forms after a bounded number of ticks, fmu_model_hold()), fmi2Reset, fmi2FreeInstance;
 * printed in ms and in ns per byte of the serialised state, with the slowest call per size.
 * The limit is chosen from these figures: the slowest call at N = FMU_MAX_REALS must stay well
 * under the 100 ms the fuzz test (test_fmu_fuzz.c) allows any call.
 * The last size, twice the limit, shows the refusal (its time and, on stderr, its message).
 * Usage: bench_fmu_state_size_<Model> [--quick] [log2 of the largest N, default: the limit's]
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "fmi2Functions.h"
#include "fmu_model.h"
#if defined(FMU_TEST_TRAJECTORY)
#include "TrajectoryGenerator_variables.h"
#elif defined(FMU_TEST_MULTI_AXIS)
#include "MultiAxisGenerator_variables.h"
#else
#include "SmoothShaper_variables.h"
#endif
#include "../bench/cpu_time.h"
#include "fmu_test_callbacks.h"

#define ROUNDS 5
#define TS 1e-3

/* Parameters that make the model allocate about n reals (sample period TS); the input to move. */
#if defined(FMU_TEST_TRAJECTORY)
static const char *config_name = "zero-damping tail (4 rings of 2 pi/wn)";
/* the longest step after a new target that still steps: the stage's last 2M + 2 samples
 * (M = N/4) while the move still runs inside them */
static double medium_ticks(double n) { return n / 2.0; }
static const fmi2ValueReference input_vr = TG_VR_TARGET;
static void configure(fmi2Component c, double n)
{
    const fmi2ValueReference vr[6] = { TG_VR_TS, TG_VR_VMAX, TG_VR_AMAX, TG_VR_JMAX, TG_VR_WN,
                                       TG_VR_ZETA };
    const fmi2Real v[6] = { TS, 1.0, 10.0, 100.0, 2.0 * 3.14159265358979323846 / (n / 4.0 * TS),
                            0.0 };
    fmi2SetReal(c, vr, 6, v);
}
#elif defined(FMU_TEST_MULTI_AXIS)
static const char *config_name = "8 axes, 3 rectangular stages each (4 signals per stage)";
/* the longest step after a new target that is still filtered: just under the largest chain's
 * settle bound (3 stages of M = N/96 to N/99 each, 2M + 2 per stage), stepped in blocks */
static double medium_ticks(double n) { return n / 16.5; }
static const fmi2ValueReference input_vr = MA_VR_TARGET(0);
static void configure(fmi2Component c, double n)
{
    const double per_line = n / (4.0 * MA_MAX_AXES * MA_MAX_STAGES);
    fmi2ValueReference ivr[2] = { MA_VR_AXES, MA_VR_SYNC }, ts = MA_VR_TS;
    fmi2Integer iv[2] = { MA_MAX_AXES, 0 };
    fmi2Real Ts = TS;
    int i, k;
    fmi2SetInteger(c, ivr, 2, iv);
    fmi2SetReal(c, &ts, 1, &Ts);
    for (i = 0; i < MA_MAX_AXES; ++i) {
        fmi2ValueReference vr[3] = { MA_VR_VMAX(i), MA_VR_AMAX(i), MA_VR_JMAX(i) };
        fmi2Real v[3] = { 1.0, 10.0, 100.0 };
        fmi2SetReal(c, vr, 3, v);
        for (k = 0; k < MA_MAX_STAGES; ++k) {
            /* stage k, field g, axis i: MA_STAGE_BASE + 100 (MA_STAGE_STRIDE k + g) + i */
            fmi2ValueReference base = (fmi2ValueReference)(MA_STAGE_BASE + 100 * MA_STAGE_STRIDE * k
                                                           + i);
            fmi2ValueReference kv = base + 100 * MA_STAGE_KIND;
            fmi2ValueReference rv[2] = { base + 100 * MA_STAGE_WN, base + 100 * MA_STAGE_ZETA };
            fmi2Integer kind = 0;   /* rectangular: one period of the mode */
            fmi2Real mode[2];
            mode[0] = 2.0 * 3.14159265358979323846 / (per_line * TS) * (1.0 + 0.01 * k);
            mode[1] = 0.0;
            fmi2SetInteger(c, &kv, 1, &kind);
            fmi2SetReal(c, rv, 2, mode);
        }
    }
}
#else
static const char *config_name = "moving average (rectangular) of N samples";
/* the longest step after a new input that is still filtered: a stage absorbs within 2N + 2 */
static double medium_ticks(double n) { return 2.0 * n - 3.0; }
static const fmi2ValueReference input_vr = SS_VR_U;
static void configure(fmi2Component c, double n)
{
    fmi2ValueReference kinds[SS_MAX_STAGES], ts = SS_VR_TS, vr_T = SS_STAGE_BASE + SS_FIELD_T;
    fmi2Integer codes[SS_MAX_STAGES];
    fmi2Real Ts = TS, T = n * TS;
    int k;
    for (k = 0; k < SS_MAX_STAGES; ++k) {
        kinds[k] = SS_STAGE_BASE + SS_STAGE_STRIDE * (unsigned)k + SS_FIELD_KIND;
        codes[k] = k == 0 ? 0 : SS_KIND_NONE;
    }
    fmi2SetInteger(c, kinds, SS_MAX_STAGES, codes);
    fmi2SetReal(c, &ts, 1, &Ts);
    fmi2SetReal(c, &vr_T, 1, &T);
}
#endif

enum { C_EXIT, C_STEP, C_MEDIUM, C_ABSORB, C_GET_NEW, C_GET, C_SET, C_SERIALIZE, C_DESERIALIZE, C_FREE_STATE,
       C_RESET, C_FREE, N_CALLS };
static const char *const call_names[N_CALLS] = {
    "ExitInitializationMode", "DoStep(Ts)", "DoStep(longest filtered)", "DoStep(1e9 s), new input", "GetFMUstate (new)",
    "GetFMUstate (reuse)", "SetFMUstate", "SerializeFMUstate", "DeSerializeFMUstate",
    "FreeFMUstate", "Reset", "FreeInstance" };

#define TIME(slot, call) do { double t0_ = cpu_seconds(); ok = ok && (call) == fmi2OK; \
    cost[slot][r] = cpu_seconds() - t0_; } while (0)

/* One round per r: a fresh instance of about n reals through every call. 0, or 1 if refused. */
static int measure(double n, double cost[N_CALLS][ROUNDS], size_t *bytes)
{
    int r, ok = 1;
    for (r = 0; r < ROUNDS && ok; ++r) {
        fmi2Component c = fmi2Instantiate("bench", fmi2CoSimulation, FMU_MODEL_GUID, "",
                                          &callbacks, fmi2False, fmi2False);
        fmi2FMUstate state = NULL, copy = NULL;
        fmi2Real u = 1.0;
        unsigned char *blob;
        double t;
        if (c == NULL || fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0) != fmi2OK
            || fmi2EnterInitializationMode(c) != fmi2OK)
            return 1;
        configure(c, n);
        TIME(C_EXIT, fmi2ExitInitializationMode(c));
        if (!ok) {
            fmi2FreeInstance(c);
            return 1;
        }
        TIME(C_STEP, fmi2DoStep(c, 0.0, TS, fmi2True));
        t = TS;
        fmi2SetReal(c, &input_vr, 1, &u);
        /* about the longest step that is still filtered (a stage of N reals absorbs a new input
         * in up to 2 N ticks), then the closed forms */
        TIME(C_MEDIUM, fmi2DoStep(c, t, medium_ticks(n) * TS, fmi2True));
        t += medium_ticks(n) * TS;
        u = -1.0;
        fmi2SetReal(c, &input_vr, 1, &u);
        TIME(C_ABSORB, fmi2DoStep(c, t, 1e9, fmi2True));
        t += 1e9;
        TIME(C_GET_NEW, fmi2GetFMUstate(c, &state));
        TIME(C_GET, fmi2GetFMUstate(c, &state));
        TIME(C_SET, fmi2SetFMUstate(c, state));
        ok = ok && fmi2SerializedFMUstateSize(c, state, bytes) == fmi2OK;
        blob = (unsigned char *)malloc(*bytes);
        ok = ok && blob != NULL;
        TIME(C_SERIALIZE, fmi2SerializeFMUstate(c, state, (fmi2Byte *)blob, *bytes));
        TIME(C_DESERIALIZE, fmi2DeSerializeFMUstate(c, (fmi2Byte *)blob, *bytes, &copy));
        free(blob);
        ok = ok && fmi2SetFMUstate(c, copy) == fmi2OK;
        TIME(C_FREE_STATE, fmi2FreeFMUstate(c, &copy));
        fmi2FreeFMUstate(c, &state);
        TIME(C_RESET, fmi2Reset(c));
        fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0);
        fmi2EnterInitializationMode(c);
        configure(c, n);
        ok = ok && fmi2ExitInitializationMode(c) == fmi2OK;
        {
            double t0 = cpu_seconds();
            fmi2FreeInstance(c);
            cost[C_FREE][r] = cpu_seconds() - t0;
        }
        (void)t;
    }
    return ok ? 0 : 2;
}

int main(int argc, char **argv)
{
    const int quick = argc > 1 && strcmp(argv[1], "--quick") == 0;
    const int last_arg = argc > 1 + quick ? atoi(argv[1 + quick]) : 0;
    int top = last_arg > 0 ? last_arg : (int)(log2((double)FMU_MAX_REALS) + 0.5), e, k;
    int first = quick ? 10 : 16;
    if (quick && last_arg == 0)
        top = 12;
    setvbuf(stdout, NULL, _IOLBF, 0);
    printf("%s, %s, Ts = %g s; per-instance limit FMU_MAX_REALS = %lu reals\n",
           FMU_MODEL_IDENTIFIER, config_name, TS, (unsigned long)FMU_MAX_REALS);
    printf("CPU time per call, median of %d rounds: ms (ns per byte of serialised state)\n",
           ROUNDS);
    for (e = first; e <= top + 1; e += e < top - 2 ? 2 : 1) {   /* top + 1: refused */
        double cost[N_CALLS][ROUNDS], worst = 0.0;
        size_t bytes = 0;
        int st = measure(ldexp(1.0, e), cost, &bytes);
        printf("N = 2^%d reals: ", e);
        if (st == 1) {
            printf("refused by fmi2ExitInitializationMode in %.3f ms (beyond the limit)\n",
                   1e3 * cost[C_EXIT][0]);
            continue;
        }
        if (st != 0) {
            printf("a call failed\n");
            return 1;
        }
        printf("%lu bytes serialised\n", (unsigned long)bytes);
        for (k = 0; k < N_CALLS; ++k) {
            double m = median(cost[k], ROUNDS);
            if (m > worst)
                worst = m;
            printf("  %-28s %9.3f ms (%6.3f ns/B)\n", call_names[k], 1e3 * m,
                   1e9 * m / (double)bytes);
        }
        printf("  slowest call                   %7.3f ms\n", 1e3 * worst);
    }
    return 0;
}
