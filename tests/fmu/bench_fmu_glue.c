/* SPDX-License-Identifier: Apache-2.0 */
/*
 * What the FMI glue costs on top of the filters (SmoothShaper linked in-process, CPU time,
 * median of interleaved rounds):
 * - fmi2SetReal(u) and fmi2GetReal(y), one value per call (no formatting on this path);
 * - fmi2DoStep(t, Ts) with no stage (the glue alone: state machine, identity, tick count, one
 *   trivial tick), and with a moving average next to sms_chain_step on the same chain;
 * - fmi2GetFMUstate / fmi2SetFMUstate / fmi2SerializeFMUstate / fmi2DeSerializeFMUstate for
 *   chains of 10, 1000 and 100000 delay-line samples (cost and bytes proportional to the chain);
 *   deserialised by the instance itself (its own configuration: its built filters are copied)
 *   and by a new instance (no filters yet: the state's are designed and built);
 * - fmi2DoStep(t, 1e9 s) over a newly held input (absorbed in a few chain lengths, then skipped).
 * Usage: bench_fmu_glue [--quick]
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "fmi2Functions.h"
#include "SmoothShaper_variables.h"
#include "smoothshaper/smoothshaper.h"
#include "../bench/cpu_time.h"
#include "fmu_test_callbacks.h"

#define ROUNDS 7

static const double Ts = 1e-3;

/* An instance with stage 0 a moving average of T (T = 0: no stage at all), at rest at 0. */
static fmi2Component instance(double T)
{
    const fmi2ValueReference vr_ts = SS_VR_TS, vr_T = SS_STAGE_BASE + SS_FIELD_T;
    fmi2ValueReference kinds[SS_MAX_STAGES];
    fmi2Integer codes[SS_MAX_STAGES];
    int k;
    fmi2Component c = fmi2Instantiate("bench", fmi2CoSimulation, FMU_MODEL_GUID, "", &callbacks,
                                      fmi2False, fmi2False);
    for (k = 0; k < SS_MAX_STAGES; ++k) {
        kinds[k] = SS_STAGE_BASE + SS_STAGE_STRIDE * (unsigned)k + SS_FIELD_KIND;
        codes[k] = k == 0 && T > 0.0 ? 0 : SS_KIND_NONE;
    }
    if (c == NULL || fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0) != fmi2OK
        || fmi2EnterInitializationMode(c) != fmi2OK
        || fmi2SetInteger(c, kinds, SS_MAX_STAGES, codes) != fmi2OK
        || fmi2SetReal(c, &vr_ts, 1, &Ts) != fmi2OK
        || (T > 0.0 && fmi2SetReal(c, &vr_T, 1, &T) != fmi2OK)
        || fmi2ExitInitializationMode(c) != fmi2OK) {
        fprintf(stderr, "bench_fmu_glue: could not set up an instance (T = %g)\n", T);
        exit(1);
    }
    return c;
}

int main(int argc, char **argv)
{
    const int quick = argc > 1 && strcmp(argv[1], "--quick") == 0;
    const long n = quick ? 20000 : 2000000;
    const fmi2ValueReference vr_u = SS_VR_U, vr_y = SS_VR_Y;
    double set_ns[ROUNDS], get_ns[ROUNDS], step0_ns[ROUNDS], step_ns[ROUNDS], chain_ns[ROUNDS];
    double t0, y = 0.0, sink = 0.0, t;
    static const double sizes[] = { 10, 1000, 100000 };
    fmi2Component empty = instance(0.0), ma = instance(10.3 * Ts);
    sms_stage_config cfg = sms_stage_config_default(SMS_RECTANGULAR);
    sms_chain chain;
    sms_stage stage;
    sms_memory_cell *buffer;
    sms_real x;
    size_t need = 0;
    long i;
    int r, s;

    cfg.T = 10.3 * Ts;
    sms_chain_memory_size(&cfg, 1, Ts, &need);
    buffer = (sms_memory_cell *)calloc(need, sizeof *buffer);
    if (buffer == NULL || sms_chain_init(&chain, &stage, &cfg, 1, Ts, buffer, need) != SMS_OK)
        return 1;

    for (r = 0; r < ROUNDS; ++r) {   /* interleaved rounds, CPU time */
        double u;
        t0 = cpu_seconds();
        for (i = 0; i < n; ++i) {
            u = (double)(i & 1023);
            fmi2SetReal(empty, &vr_u, 1, &u);
        }
        set_ns[r] = (cpu_seconds() - t0) / (double)n * 1e9;
        t0 = cpu_seconds();
        for (i = 0; i < n; ++i) {
            fmi2GetReal(empty, &vr_y, 1, &y);
            sink += y;
        }
        get_ns[r] = (cpu_seconds() - t0) / (double)n * 1e9;
        t = (double)r * (double)n * Ts;
        t0 = cpu_seconds();
        for (i = 0; i < n; ++i) {   /* a new input every step: every tick is computed */
            u = (double)(i & 1023);
            fmi2SetReal(empty, &vr_u, 1, &u);
            fmi2DoStep(empty, t, Ts, fmi2True);
            t += Ts;
        }
        step0_ns[r] = (cpu_seconds() - t0) / (double)n * 1e9 - set_ns[r];
        t = (double)r * (double)n * Ts;
        t0 = cpu_seconds();
        for (i = 0; i < n; ++i) {
            u = (double)(i & 1023);
            fmi2SetReal(ma, &vr_u, 1, &u);
            fmi2DoStep(ma, t, Ts, fmi2True);
            t += Ts;
        }
        step_ns[r] = (cpu_seconds() - t0) / (double)n * 1e9 - set_ns[r];
        t0 = cpu_seconds();
        for (i = 0; i < n; ++i) {
            x = (sms_real)(i & 1023);
            sms_chain_step(&chain, &x);
            sink += (double)x;
        }
        chain_ns[r] = (cpu_seconds() - t0) / (double)n * 1e9;
    }
    printf("FMI glue per call (median of %d rounds of %ld calls, CPU time)\n", ROUNDS, n);
    printf("  fmi2SetReal (1 value)                 %7.1f ns\n", median(set_ns, ROUNDS));
    printf("  fmi2GetReal (1 value)                 %7.1f ns\n", median(get_ns, ROUNDS));
    printf("  fmi2DoStep(t, Ts), no stage           %7.1f ns  (glue overhead incl. a trivial tick)\n",
           median(step0_ns, ROUNDS));
    printf("  fmi2DoStep(t, Ts), M(10.3 Ts)         %7.1f ns\n", median(step_ns, ROUNDS));
    printf("  sms_chain_step, same M(10.3 Ts)       %7.1f ns\n", median(chain_ns, ROUNDS));
    printf("  doStep overhead beyond the filter     %7.1f ns\n",
           median(step_ns, ROUNDS) - median(chain_ns, ROUNDS));
    fmi2FreeInstance(empty);
    fmi2FreeInstance(ma);
    free(buffer);

    printf("\nFMU state of a moving average of N samples (median of %d)\n", ROUNDS);
    printf("  %8s %9s %9s %15s %16s %16s %10s %19s\n", "N", "get [us]", "set [us]",
           "serialize [us]", "deserialize [us]", "  (new instance)", "bytes", "doStep(1e9 s) [us]");
    for (s = 0; s < 3; ++s) {
        fmi2Component c = instance(sizes[s] * Ts);
        fmi2Component fresh = fmi2Instantiate("bench", fmi2CoSimulation, FMU_MODEL_GUID, "",
                                              &callbacks, fmi2False, fmi2False);
        fmi2FMUstate state = NULL, back = NULL;
        double get_us[ROUNDS], set_us[ROUNDS], ser_us[ROUNDS], des_us[ROUNDS], fresh_us[ROUNDS];
        double huge_us[ROUNDS], u = 1.0;
        size_t bytes = 0;
        unsigned char *blob;
        int reps = quick ? 3 : (sizes[s] > 5000 ? 20 : 2000), k;
        t = 0.0;
        fmi2GetFMUstate(c, &state);
        fmi2SerializedFMUstateSize(c, state, &bytes);
        blob = (unsigned char *)malloc(bytes);
        for (r = 0; r < ROUNDS; ++r) {
            t0 = cpu_seconds();
            for (k = 0; k < reps; ++k)
                fmi2GetFMUstate(c, &state);
            get_us[r] = (cpu_seconds() - t0) / reps * 1e6;
            t0 = cpu_seconds();
            for (k = 0; k < reps; ++k)
                fmi2SetFMUstate(c, state);
            set_us[r] = (cpu_seconds() - t0) / reps * 1e6;
            t0 = cpu_seconds();
            for (k = 0; k < reps; ++k)
                fmi2SerializeFMUstate(c, state, (fmi2Byte *)blob, bytes);
            ser_us[r] = (cpu_seconds() - t0) / reps * 1e6;
            des_us[r] = 0.0;
            fresh_us[r] = 0.0;
            for (k = 0; k < reps; ++k) {
                t0 = cpu_seconds();
                if (fmi2DeSerializeFMUstate(c, (fmi2Byte *)blob, bytes, &back) != fmi2OK)
                    return 1;
                des_us[r] += cpu_seconds() - t0;
                fmi2FreeFMUstate(c, &back);
                t0 = cpu_seconds();
                if (fmi2DeSerializeFMUstate(fresh, (fmi2Byte *)blob, bytes, &back) != fmi2OK)
                    return 1;
                fresh_us[r] += cpu_seconds() - t0;
                fmi2FreeFMUstate(fresh, &back);
            }
            des_us[r] *= 1e6 / reps;
            fresh_us[r] *= 1e6 / reps;
            u = -u;   /* a new held input, then one step of 1e9 s (1e12 ticks) */
            fmi2SetReal(c, &vr_u, 1, &u);
            t0 = cpu_seconds();
            if (fmi2DoStep(c, t, 1e9, fmi2True) != fmi2OK)
                return 1;
            huge_us[r] = (cpu_seconds() - t0) * 1e6;
            t += 1e9;
        }
        printf("  %8.0f %9.2f %9.2f %15.2f %16.2f %16.2f %10lu %19.0f\n", sizes[s],
               median(get_us, ROUNDS), median(set_us, ROUNDS), median(ser_us, ROUNDS),
               median(des_us, ROUNDS), median(fresh_us, ROUNDS), (unsigned long)bytes,
               median(huge_us, ROUNDS));
        free(blob);
        fmi2FreeFMUstate(c, &state);
        fmi2FreeInstance(c);
        fmi2FreeInstance(fresh);
    }
    return sink == 0.5 ? 2 : 0;   /* keeps the loops */
}
