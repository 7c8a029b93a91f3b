/* SPDX-License-Identifier: Apache-2.0 */
/*
 * A fmi2DoStep of 1e12 s over a newly held input gives, bit for bit, the outputs and state of
 * ticking every sample (fmu_model_tick(), what the glue did before the closed forms), for
 * SmoothShaper chains at the state limit (a moving average of FMU_MAX_REALS - 64 samples) and
 * with a slowly decaying notch between two moving averages. The reference ticks until every
 * stage has absorbed the input, then the remaining ticks modulo the period of the absorbed
 * state (the moving averages' 2M: only their ring heads and copy ages move), so it stays short.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"
#include "fmu_instance.h"
#include "smoothshaper/smoothshaper.h"
#include "SmoothShaper_variables.h"
#include "fmu_test_callbacks.h"

#define TS 1e-3

static int failures;


typedef struct stage_spec {
    int kind;
    double T, wn, pole_zeta;
} stage_spec;

static fmi2Component make(const stage_spec *spec, int n)
{
    fmi2Component c = fmi2Instantiate("long", fmi2CoSimulation, FMU_MODEL_GUID, "", &callbacks,
                                      fmi2False, fmi2False);
    fmi2ValueReference ts = SS_VR_TS;
    fmi2Real Ts = TS;
    int k;
    fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0);
    fmi2EnterInitializationMode(c);
    fmi2SetReal(c, &ts, 1, &Ts);
    for (k = 0; k < SS_MAX_STAGES; ++k) {
        const fmi2ValueReference base = SS_STAGE_BASE + SS_STAGE_STRIDE * (unsigned)k;
        fmi2ValueReference kind = base + SS_FIELD_KIND;
        fmi2Integer code = k < n ? spec[k].kind : SS_KIND_NONE;
        fmi2SetInteger(c, &kind, 1, &code);
        if (k < n) {
            fmi2ValueReference vr[3] = { base + SS_FIELD_T, base + SS_FIELD_WN,
                                         base + SS_FIELD_NOTCH_POLE_ZETA };
            fmi2Real v[3];
            v[0] = spec[k].T;
            v[1] = spec[k].wn;
            v[2] = spec[k].pole_zeta;
            fmi2SetReal(c, vr, 3, v);
        }
    }
    if (fmi2ExitInitializationMode(c) != fmi2OK) {
        fprintf(stderr, "configuration refused\n");
        ++failures;
        fmi2FreeInstance(c);
        return NULL;
    }
    return c;
}

/* Outputs and the model's state vector of a and b agree bit for bit. */
static void compare(fmi2Component a, fmi2Component b, const char *what)
{
    const void *ma = ((fmu_instance *)a)->model, *mb = ((fmu_instance *)b)->model;
    size_t n = fmu_model_state_count(ma);
    double *sa = (double *)malloc(n * sizeof *sa), *sb = (double *)malloc(n * sizeof *sb);
    fmi2ValueReference y = SS_VR_Y;
    fmi2Real ya, yb;
    fmi2GetReal(a, &y, 1, &ya);
    fmi2GetReal(b, &y, 1, &yb);
    fmu_model_save_state(ma, sa);
    fmu_model_save_state(mb, sb);
    if (n != fmu_model_state_count(mb) || memcmp(&ya, &yb, sizeof ya) != 0
        || memcmp(sa, sb, n * sizeof *sa) != 0) {
        size_t i = 0;
        while (i < n && memcmp(&sa[i], &sb[i], sizeof sa[i]) == 0)
            ++i;
        fprintf(stderr, "%s: y %.17g vs %.17g; state differs at %lu of %lu\n", what, ya, yb,
                (unsigned long)i, (unsigned long)n);
        ++failures;
    } else {
        printf("%s: y = %.17g, %lu state values, all equal\n", what, ya, (unsigned long)n);
    }
    free(sa);
    free(sb);
}

/* A history of random inputs into both, a new input, then one step of 1e12 s in a and the
 * ticks it covers in b (reduced beyond `settled` by `period`). */
static void run(const stage_spec *spec, int n, unsigned long long settled,
                unsigned long long period, const char *what)
{
    fmi2Component a = make(spec, n), b = make(spec, n);
    fmi2ValueReference u = SS_VR_U;
    unsigned long long ticks, rest, i;
    double t = 0.0, h = 1e12, x;
    int k;
    if (a == NULL || b == NULL)
        return;
    srand(7);
    for (k = 0; k < 50; ++k) {
        x = (double)rand() / RAND_MAX - 0.5;
        fmi2SetReal(a, &u, 1, &x);
        fmi2SetReal(b, &u, 1, &x);
        fmi2DoStep(a, t, 7 * TS, fmi2True);
        fmi2DoStep(b, t, 7 * TS, fmi2True);
        t += 7 * TS;
    }
    x = 3.25;
    fmi2SetReal(a, &u, 1, &x);
    fmi2SetReal(b, &u, 1, &x);
    if (fmi2DoStep(a, t, h, fmi2True) != fmi2OK) {
        fprintf(stderr, "%s: the long step failed\n", what);
        ++failures;
    }
    ticks = ((fmu_instance *)a)->clock.ticks - 350u;
    rest = ticks > settled ? settled + (ticks - settled) % period : ticks;
    for (i = 0; i < rest; ++i)
        fmu_model_tick(((fmu_instance *)b)->model);
    {
        /* the glue's output variable is the model's y, which the ticks wrote */
        char label[200];
        snprintf(label, sizeof label, "%s (%llu ticks in one step, %llu ticked)", what, ticks, rest);
        compare(a, b, label);
    }
    fmi2FreeInstance(a);
    fmi2FreeInstance(b);
}

int main(void)
{
    const double M = (double)(FMU_MAX_REALS - 64u);
    /* a moving average at the state limit: absorbed within 2M + 2 ticks, period 2M */
    const stage_spec limit[1] = { { 0, M * TS, 0.0, 0.0 } };
    /* moving averages of 2^16 and 2^10 samples around a notch whose pole decays at
     * xi2 wn Ts = 0.003 per sample (about 1.7e5 samples to end its transient, 9.2e5 bound) */
    const stage_spec notch[3] = {
        { 0, 65536 * TS, 0.0, 0.0 }, { SMS_NOTCH_TUSTIN, 0.0, 10.0, 0.3 },
        { 0, 1024 * TS, 0.0, 0.0 } };
    run(limit, 1, (unsigned long long)(2.0 * M) + 4u, (unsigned long long)(2.0 * M),
        "moving average of FMU_MAX_REALS - 64");
    run(notch, 3, 131074ull + 1000000ull + 2050ull, 131072ull, "average, slow notch, average");
    return failures == 0 ? 0 : 1;
}
