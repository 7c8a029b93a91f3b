/* SPDX-License-Identifier: Apache-2.0 */
/*
 * Random sequences of FMI 2.0 calls against SmoothShaper, or TrajectoryGenerator when built with
 * FMU_TEST_TRAJECTORY, or ServoDrive with FMU_TEST_SERVO_DRIVE (each linked in-process, so
 * ASan/UBSan see everything): wrong orders, NULL pointers, bad value references, NaN and out-of-range
 * parameters, FMU states and corrupted serialised states. A shadow of the FMI state machine
 * predicts which state-changing calls must succeed; every call must return fmi2OK or fmi2Error
 * (the only statuses this FMU uses) and never crash or leak.
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"
#if defined(FMU_TEST_TRAJECTORY)
#include "TrajectoryGenerator_variables.h"
#define VR_OUTPUT TG_VR_Q
#elif defined(FMU_TEST_SERVO_DRIVE)
#include "ServoDrive_variables.h"
#define VR_OUTPUT SV_VR_Q_L
#else
#include "SmoothShaper_variables.h"
#define VR_OUTPUT SS_VR_Y
#endif

static int failures = 0;
static unsigned long n_logged = 0;
static char last_message[1024];
static unsigned long n_steps_ok = 0, n_restored = 0;

#define CHECK(cond) do { if (!(cond)) { ++failures; \
    fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); } } while (0)

static void logger(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                   fmi2String category, fmi2String message, ...)
{
    char buf[1024];
    va_list ap;
    (void)env;
    (void)status;
    CHECK(name != NULL && category != NULL && message != NULL);
    va_start(ap, message);
    vsnprintf(buf, sizeof buf, message, ap);   /* the message must be a safe printf format */
    va_end(ap);
    memcpy(last_message, buf, sizeof buf);
    ++n_logged;
}

static unsigned long rng_state = 12345u;
static unsigned rnd(unsigned n)
{
    rng_state = rng_state * 6364136223846793005ul + 1442695040888963407ul;
    return (unsigned)((rng_state >> 33) % n);
}

static const fmi2CallbackFunctions callbacks = { logger, calloc, free, NULL, NULL };

typedef enum { S_INSTANTIATED, S_INIT, S_STEP, S_TERMINATED } shadow;

static double random_real(void)
{
    static const double pool[] = { 0.0, 1.0, -1.0, 0.001, 0.0123, 100.0, 0.3, 1e300, -5.0, 0.5 };
    switch (rnd(8)) {
    case 0: return NAN;
    case 1: return INFINITY;
    default: return pool[rnd(sizeof pool / sizeof pool[0])];
    }
}

static fmi2ValueReference random_vr(void)
{
    static const fmi2ValueReference pool[] = {
#if defined(FMU_TEST_TRAJECTORY)
        TG_VR_TARGET, TG_VR_Q, TG_VR_V, TG_VR_A, TG_VR_J, TG_VR_TS, TG_VR_VMAX, TG_VR_AMAX,
        TG_VR_JMAX, TG_VR_PROFILE, TG_VR_WN, TG_VR_ZETA, 5, 9, 17, 100000
#elif defined(FMU_TEST_SERVO_DRIVE)
        /* inputs, outputs, the plant, each controller's parameters, gaps and beyond the end */
        SV_VR_Q_REF, SV_VR_TAU_LOAD, SV_VR_Q_M, SV_VR_TAU_M, SV_VR_TS, SV_VR_CONTROLLER,
        SV_VR_JM, SV_VR_KEL, SV_VR_DEL, SV_VR_PID_WCV, SV_VR_PID_WCP, SV_VR_TDO_TF,
        SV_VR_NOTCH_AT, SV_VR_NOTCH_WN, SV_VR_PLACE_ZETA0, SV_VR_OBSERVER_REAL1, SV_VR_LQ_Q4,
        SV_VR_LQ_R, SV_VR_KALMAN_ENCODER_NOISE, SV_VR_WF, 7, 18, SV_VR_END, 100000
#else
        SS_VR_U, VR_OUTPUT, SS_VR_TS, 3, 99, 100000,
        SS_STAGE_BASE + SS_FIELD_KIND, SS_STAGE_BASE + SS_FIELD_T, SS_STAGE_BASE + SS_FIELD_ZETA,
        SS_STAGE_BASE + SS_FIELD_WN, SS_STAGE_BASE + SS_FIELD_ORDER,
        SS_STAGE_BASE + SS_STAGE_STRIDE + SS_FIELD_KIND, SS_STAGE_BASE + SS_STAGE_STRIDE + SS_FIELD_T,
        SS_STAGE_BASE + SS_STAGE_STRIDE * 7 + SS_FIELD_NOTCH_POLE_ZETA,
        SS_STAGE_BASE + SS_STAGE_STRIDE * 8 + SS_FIELD_KIND, SS_STAGE_BASE + SS_FIELD_COUNT
#endif
    };
    return pool[rnd(sizeof pool / sizeof pool[0])];
}

#define MAX_STATES 4

static void run_sequence(unsigned length)
{
    fmi2Component c = fmi2Instantiate("seq%s", fmi2CoSimulation, FMU_MODEL_GUID, NULL, &callbacks,
                                      fmi2False, rnd(2) ? fmi2True : fmi2False);
    fmi2FMUstate states[MAX_STATES] = { NULL, NULL, NULL, NULL };
    shadow slot_phase[MAX_STATES];
    double slot_time[MAX_STATES];
    shadow s = S_INSTANTIATED;
    double t = 0.0;
    unsigned i, k;
    CHECK(c != NULL);
    if (c == NULL)
        return;
    for (i = 0; i < length; ++i) {
        fmi2Status st = fmi2OK;
        fmi2ValueReference vr = random_vr(), vrs[2];
        fmi2Real r = random_real(), rs[2], out[2];
        fmi2Integer n = (fmi2Integer)rnd(16) - 2, iout;
        fmi2FMUstate *slot = &states[rnd(MAX_STATES)];
        switch (rnd(22)) {
        case 0: st = fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0);
            CHECK((st == fmi2OK) == (s == S_INSTANTIATED)); t = 0.0; break;
        case 1: st = fmi2EnterInitializationMode(c);
            CHECK((st == fmi2OK) == (s == S_INSTANTIATED));
            if (st == fmi2OK) s = S_INIT;
            break;
        case 2: case 3: st = fmi2ExitInitializationMode(c);
            CHECK(st == fmi2Error || s == S_INIT);   /* may fail on invalid parameters */
            if (st == fmi2OK) { s = S_STEP; t = 0.0; }
            break;
        case 4: case 5: case 6: st = fmi2DoStep(c, t, rnd(4) ? 0.00037 * (1 + rnd(30)) : r, fmi2True);
            CHECK(st == fmi2Error || s == S_STEP);
            if (st == fmi2Warning) /* a step done, with a warning (a dropped target) */
                st = fmi2OK;
            if (st == fmi2OK) {
                fmi2Real now = 0.0;
                ++n_steps_ok;
                CHECK(fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &now) == fmi2OK);
                t = now;
            }
            break;
        case 7: st = fmi2Terminate(c); CHECK((st == fmi2OK) == (s == S_STEP));
            if (st == fmi2OK) s = S_TERMINATED;
            break;
        case 8: st = fmi2Reset(c); CHECK(st == fmi2OK); s = S_INSTANTIATED; t = 0.0; break;
        case 9: case 10: vrs[0] = vr; vrs[1] = random_vr(); rs[0] = r; rs[1] = random_real();
            st = fmi2SetReal(c, rnd(8) ? vrs : NULL, rnd(3), rnd(8) ? rs : NULL);
            break;
        case 11: st = fmi2SetInteger(c, &vr, 1, &n); break;
        case 12: vrs[0] = vr; vrs[1] = VR_OUTPUT;
            st = fmi2GetReal(c, vrs, rnd(3), rnd(8) ? out : NULL);
            CHECK(st == fmi2Error || s != S_INSTANTIATED);
            break;
        case 13: st = fmi2GetInteger(c, &vr, 1, &iout); break;
        case 14: st = fmi2GetFMUstate(c, rnd(10) ? slot : NULL);
            if (st == fmi2OK) { slot_phase[slot - states] = s; slot_time[slot - states] = t; }
            break;
        case 15: st = fmi2SetFMUstate(c, *slot);
            CHECK((st == fmi2OK) == (*slot != NULL));
            if (st == fmi2OK) { s = slot_phase[slot - states]; t = slot_time[slot - states]; }
            break;
        case 16: st = fmi2FreeFMUstate(c, rnd(10) ? slot : NULL); break;
        case 17: if (*slot != NULL) {
                size_t size = 0;
                unsigned char *blob;
                fmi2FMUstate back = NULL;
                CHECK(fmi2SerializedFMUstateSize(c, *slot, &size) == fmi2OK);
                blob = (unsigned char *)malloc(size + 1);
                CHECK(fmi2SerializeFMUstate(c, *slot, (fmi2Byte *)blob, size) == fmi2OK);
                CHECK(fmi2SerializeFMUstate(c, *slot, (fmi2Byte *)blob, size + 1) == fmi2Error);
                if (rnd(2)) {   /* corrupt or truncate: must be refused */
                    if (rnd(2)) blob[rnd((unsigned)size)] ^= (unsigned char)(1u << rnd(8));
                    else size = rnd((unsigned)size);
                    CHECK(fmi2DeSerializeFMUstate(c, (fmi2Byte *)blob, size, &back) == fmi2Error);
                    CHECK(back == NULL);
                } else {
                    if (fmi2DeSerializeFMUstate(c, (fmi2Byte *)blob, size, &back) != fmi2OK) {
                        ++failures;
                        fprintf(stderr, "intact state refused: %s\n", last_message);
                    }
                    ++n_restored;
                    CHECK(fmi2FreeFMUstate(c, &back) == fmi2OK);
                }
                free(blob);
            }
            break;
        case 18: st = fmi2SetDebugLogging(c, rnd(2) ? fmi2True : fmi2False, rnd(3), NULL); break;
        case 19: { const char *cats[] = { "logCalls", rnd(2) ? "logStatusError" : "nope%n", NULL };
            st = fmi2SetDebugLogging(c, fmi2True, 1 + rnd(3), cats); } break;
        case 20: st = fmi2SetRealInputDerivatives(c, &vr, 1, &n, &r); CHECK(st == fmi2Error); break;
        default: st = fmi2CancelStep(c); CHECK(st == fmi2Error);
            CHECK(fmi2GetDirectionalDerivative(c, &vr, 1, &vr, 1, &r, out) == fmi2Error);
            CHECK(fmi2SetTime(c, 0.0) == fmi2Error);
            break;
        }
        CHECK(st == fmi2OK || st == fmi2Error);
    }
    for (k = 0; k < MAX_STATES; ++k)
        CHECK(fmi2FreeFMUstate(c, &states[k]) == fmi2OK);
    fmi2FreeInstance(c);
}

static void null_and_foreign_calls(void)
{
    fmi2Real r = 0.0;
    fmi2ValueReference vr = 0;
    fmi2FMUstate state = NULL;
    CHECK(fmi2Instantiate("x", fmi2CoSimulation, "{wrong}", NULL, &callbacks, 0, 1) == NULL);
    CHECK(fmi2Instantiate("x", fmi2ModelExchange, FMU_MODEL_GUID, NULL, &callbacks, 0, 1) == NULL);
    CHECK(fmi2Instantiate(NULL, fmi2CoSimulation, FMU_MODEL_GUID, NULL, &callbacks, 0, 1) == NULL);
    CHECK(fmi2Instantiate("x", fmi2CoSimulation, NULL, NULL, &callbacks, 0, 1) == NULL);
    CHECK(fmi2Instantiate("x", fmi2CoSimulation, FMU_MODEL_GUID, NULL, NULL, 0, 1) == NULL);
    CHECK(fmi2SetupExperiment(NULL, 0, 0, 0, 0, 0) == fmi2Error);
    CHECK(fmi2EnterInitializationMode(NULL) == fmi2Error);
    CHECK(fmi2DoStep(NULL, 0, 1, 0) == fmi2Error);
    CHECK(fmi2SetReal(NULL, &vr, 1, &r) == fmi2Error);
    CHECK(fmi2GetReal(NULL, &vr, 1, &r) == fmi2Error);
    CHECK(fmi2GetFMUstate(NULL, &state) == fmi2Error);
    CHECK(fmi2Reset(NULL) == fmi2Error);
    CHECK(fmi2SetDebugLogging(NULL, 1, 0, NULL) == fmi2Error);
    fmi2FreeInstance(NULL);
    CHECK(strcmp(fmi2GetVersion(), "2.0") == 0);
    CHECK(strcmp(fmi2GetTypesPlatform(), "default") == 0);
}

int main(void)
{
    unsigned seq;
    null_and_foreign_calls();
    for (seq = 0; seq < 300; ++seq)
        run_sequence(40 + rnd(200));
    CHECK(n_steps_ok > 300 && n_restored > 50);   /* the sequences reached the interesting states */
    printf("call sequences: %d failures, %lu successful steps, %lu states deserialised, %lu log "
           "messages\n", failures, n_steps_ok, n_restored, n_logged);

    return failures == 0 ? 0 : 1;
}
