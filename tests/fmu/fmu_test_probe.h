/* SPDX-License-Identifier: Apache-2.0 */
/*
 * The tick probe of the clock tests (test_fmu_clock.c, test_fmu_start_time.c): a SmoothShaper
 * instance whose only stage is the 2-sample moving average M(T = 2 Ts), Ts = h = 1 ms, so that
 * fed u = k before step k its output after step k is (k + (k - 1))/2 exactly and a lost or a
 * doubled tick shows in it. Include after fmu_test_callbacks.h.
 */
#ifndef SMS_TESTS_FMU_TEST_PROBE_H
#define SMS_TESTS_FMU_TEST_PROBE_H

#include "fmi2Functions.h"
#include "SmoothShaper_variables.h"

static const double h = 1e-3;   /* = Ts */

/* The probe named name, at rest at u0, its clock starting at t0; NULL if a call failed. */
static fmi2Component probe_instance(fmi2String name, double t0, double u0)
{
    const fmi2ValueReference vr_ts = SS_VR_TS, vr_u = SS_VR_U;
    const fmi2ValueReference vr_T = SS_STAGE_BASE + SS_FIELD_T;
    fmi2ValueReference kinds[SS_MAX_STAGES];
    fmi2Integer codes[SS_MAX_STAGES];
    const double T = 2 * h;
    int k;
    fmi2Component c = fmi2Instantiate(name, fmi2CoSimulation, FMU_MODEL_GUID, "", &callbacks,
                                      fmi2False, fmi2False);
    if (c == NULL)
        return NULL;
    for (k = 0; k < SS_MAX_STAGES; ++k) {
        kinds[k] = SS_STAGE_BASE + SS_STAGE_STRIDE * (unsigned)k + SS_FIELD_KIND;
        codes[k] = k == 0 ? 0 : SS_KIND_NONE;   /* stage 0 rectangular, the others none */
    }
    if (fmi2SetupExperiment(c, fmi2False, 0.0, t0, fmi2False, 0.0) != fmi2OK
        || fmi2EnterInitializationMode(c) != fmi2OK
        || fmi2SetInteger(c, kinds, SS_MAX_STAGES, codes) != fmi2OK
        || fmi2SetReal(c, &vr_ts, 1, &h) != fmi2OK || fmi2SetReal(c, &vr_T, 1, &T) != fmi2OK
        || fmi2SetReal(c, &vr_u, 1, &u0) != fmi2OK || fmi2ExitInitializationMode(c) != fmi2OK) {
        fmi2FreeInstance(c);
        return NULL;
    }
    return c;
}

#endif
