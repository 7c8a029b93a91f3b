/*
 * Seeded random FMI 2.0 call sequences against SmoothShaper, or TrajectoryGenerator when built
 * with FMU_TEST_TRAJECTORY, linked in-process (the sanitizer build runs them under ASan and
 * UBSan). Unlike test_fmu_call_sequence.c, which walks the state machine with a few fixed
 * values, the parameters here are drawn so that about half of the initialisations succeed
 * (random stage chains / limits, with NULL, NaN, Inf, huge, subnormal and negative values
 * mixed in), and every call is checked for:
 * - no crash, and no call longer than 100 ms;
 * - an fmi2Error leaves the instance unchanged (its serialised state is byte for byte the
 *   same before and after the failing call);
 * - no fmi2OK with a non-finite output (fmi2GetReal after every successful step);
 * - every FMU state saved loads again (fmi2SetFMUstate, and serialise -> deserialise -> set).
 * Usage: test_fmu_fuzz_<Model> [sequences [seed [huge]]]; default 1000 sequences (seconds).
 * Steps are up to 2000 ticks long; "huge" adds steps of up to 1e12 s. The long campaign:
 * build/sanitize/fmu/test_fmu_fuzz_SmoothShaper 100000 (tests/README.md).
 */
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "fmi2Functions.h"
#ifdef FMU_TEST_TRAJECTORY
#include "TrajectoryGenerator_variables.h"
#else
#include "SmoothShaper_variables.h"
#endif

#define CALL_LIMIT_S 0.1
#define MAX_SLOTS 3

static unsigned long failures, n_calls, n_errors, n_steps, n_inits, n_restores, n_slow;
static double slowest;
static unsigned long long rng;
static char last_message[1024];
static int huge_steps;   /* third argument "huge": steps of up to 1e12 s (O(1) over held input) */

#define CHECK(cond) do { if (!(cond)) { ++failures; \
    fprintf(stderr, "%s:%d: check failed: %s (last message: %s)\n", __FILE__, __LINE__, #cond, \
            last_message); } } while (0)

static void logger(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                   fmi2String category, fmi2String message, ...)
{
    va_list ap;
    (void)env;
    (void)name;
    (void)status;
    (void)category;
    va_start(ap, message);
    vsnprintf(last_message, sizeof last_message, message, ap);
    va_end(ap);
}

static const fmi2CallbackFunctions callbacks = { logger, calloc, free, NULL, NULL };

static unsigned long long next64(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return rng;
}

static unsigned pick(unsigned n)
{
    return (unsigned)(next64() % n);
}

static double uniform(void)
{
    return (double)(next64() >> 11) * (1.0 / 9007199254740992.0);
}

/* A plausible value 10^[lo, hi], or (one time in five) an edge of double. */
static double any_real(double lo, double hi);

/* Sample periods: 1e-4 s and up (plus the edges), because both FMUs allocate the delay lines a
 * configuration needs (no cap but memory), and 1e-9 s with a 1 s mode is 1e9 samples: accepted
 * sizes must stay small for the 100 ms bound to be about the FMU's own work. */
static double any_real(double lo, double hi)
{
    static const double edge[] = { 0.0, -1.0, NAN, INFINITY, -INFINITY, DBL_MAX, -DBL_MAX,
                                   1e300, -1e300, 4.9e-324, 1e-300, 1e306, 0.99999999999 };
    if (pick(5) == 0)
        return edge[pick(sizeof edge / sizeof edge[0])];
    return pow(10.0, lo + (hi - lo) * uniform());
}

/* Damping ratios: near 1 a mode designs delay lines of 1e7+ samples, which the FMUs accept and
 * allocate (no cap but memory): kept to invalid edges and plausible values. */
static double any_zeta(void)
{
    static const double edge[] = { -1.0, 1.0, 1.5, NAN, INFINITY, -0.0, 1e300 };
    if (pick(3))
        return 0.1 * uniform();
    return pick(4) ? pow(10.0, -12.0 + 11.5 * uniform()) : edge[pick(7)];
}

static double seconds(void)
{
    return (double)clock() / CLOCKS_PER_SEC;
}

/* The instance's serialised state (a fingerprint of everything it holds), or size 0. */
static size_t fingerprint(fmi2Component c, unsigned char **blob)
{
    fmi2FMUstate s = NULL;
    size_t size = 0;
    *blob = NULL;
    if (fmi2GetFMUstate(c, &s) != fmi2OK)
        return 0;
    if (fmi2SerializedFMUstateSize(c, s, &size) == fmi2OK) {
        *blob = (unsigned char *)malloc(size);
        if (*blob == NULL || fmi2SerializeFMUstate(c, s, (fmi2Byte *)*blob, size) != fmi2OK)
            size = 0;
    }
    fmi2FreeFMUstate(c, &s);
    return size;
}

#ifdef FMU_TEST_TRAJECTORY
static const fmi2ValueReference outputs[] = { TG_VR_Q, TG_VR_V, TG_VR_A, TG_VR_J };
#define INPUT_VR TG_VR_TARGET
#define TS_VR TG_VR_TS

static void random_parameters(fmi2Component c)
{
    fmi2ValueReference vr[6] = { TG_VR_TS, TG_VR_VMAX, TG_VR_AMAX, TG_VR_JMAX, TG_VR_WN,
                                 TG_VR_ZETA };
    fmi2Real v[6];
    fmi2Integer profile = (fmi2Integer)pick(4) - (pick(8) == 0 ? 2 : 0);
    fmi2ValueReference pvr = TG_VR_PROFILE;
    v[0] = pick(6) ? pow(10.0, -4.0 + 2.0 * uniform()) : any_real(-4, 2);
    /* T2 ~ vmax/amax and T3 ~ amax/jmax at most ~10 s in the plausible draws: the FMU
     * allocates the tail the limits need, so accepted sizes stay small here */
    v[1] = any_real(-2, 2);
    v[2] = v[1] * any_real(-1, 2);
    v[3] = v[2] * any_real(-1, 2);
    v[4] = any_real(0, 3);
    v[5] = pick(2) ? 0.0 : any_zeta();
    fmi2SetReal(c, vr, 6, v);
    fmi2SetInteger(c, &pvr, 1, &profile);
}
#else
static const fmi2ValueReference outputs[] = { SS_VR_Y };
#define INPUT_VR SS_VR_U
#define TS_VR SS_VR_TS

static void random_parameters(fmi2Component c)
{
    fmi2ValueReference ts = SS_VR_TS;
    double Ts = pick(6) ? pow(10.0, -4.0 + 2.0 * uniform()) : any_real(-4, 2);
    unsigned k, n_active = pick(4);
    fmi2SetReal(c, &ts, 1, &Ts);
    for (k = 0; k < SS_MAX_STAGES; ++k) {
        fmi2ValueReference base = SS_STAGE_BASE + SS_STAGE_STRIDE * k;
        fmi2ValueReference ivr[5] = { base + SS_FIELD_KIND, base + SS_FIELD_DESIGN,
                                      base + SS_FIELD_TIMING, base + SS_FIELD_K,
                                      base + SS_FIELD_ORDER };
        fmi2ValueReference rvr[7] = { base + SS_FIELD_T, base + SS_FIELD_SIGMA, base + SS_FIELD_WN,
                                      base + SS_FIELD_ZETA, base + SS_FIELD_TOLERANCE,
                                      base + SS_FIELD_NOTCH_POLE_ZETA, base + SS_FIELD_DURATION };
        fmi2Integer iv[5];
        fmi2Real rv[7];
        iv[0] = k < n_active ? (fmi2Integer)pick(SS_KIND_COUNT) : SS_KIND_NONE;
        if (pick(30) == 0)
            iv[0] = (fmi2Integer)pick(40) - 5;
        iv[1] = (fmi2Integer)(pick(10) == 0 ? pick(4) : pick(2));
        iv[2] = (fmi2Integer)(pick(10) == 0 ? pick(4) : pick(2));
        iv[3] = pick(4) ? 1 : (fmi2Integer)pick(6) - 1;
        iv[4] = pick(3) ? 1 : (fmi2Integer)pick(12) - 1;
        /* delay lines up to ~2e4 samples per stage (the FMUs allocate what a chain needs, so
         * accepted sizes stay small here); the edges of double are refused in O(1) */
        rv[0] = Ts * (pick(3) ? 2.0 + 200.0 * uniform() : any_real(-3, 4.3));
        rv[1] = pick(2) ? 0.0 : -any_real(-2, 3);
        rv[2] = any_real(0, 3);
        rv[3] = any_zeta();
        rv[4] = any_real(-300, 0);
        rv[5] = any_real(-1, 1);
        rv[6] = any_real(-1, 0.4);
        fmi2SetInteger(c, ivr, 5, iv);
        fmi2SetReal(c, rvr, 7, rv);
    }
}
#endif

#define N_OUTPUTS (sizeof outputs / sizeof outputs[0])

/* After a successful step or initialisation every output must be finite. */
static void outputs_finite(fmi2Component c)
{
    fmi2Real y[4];
    size_t i;
    CHECK(fmi2GetReal(c, outputs, N_OUTPUTS, y) == fmi2OK);
    for (i = 0; i < N_OUTPUTS; ++i)
        CHECK(isfinite(y[i]));
}

static fmi2Real any_input(void)
{
    switch (pick(6)) {
    case 0: return any_real(-5, 308) * (pick(2) ? 1.0 : -1.0);
    case 1: return pick(2) ? 1e305 : -1e305;
    default: return 10.0 * uniform() - 5.0;
    }
}

static void run_sequence(unsigned length)
{
    fmi2Component c = fmi2Instantiate("fuzz", fmi2CoSimulation, FMU_MODEL_GUID, NULL,
                                      &callbacks, fmi2False, fmi2False);
    fmi2FMUstate slots[MAX_SLOTS] = { NULL, NULL, NULL };
    double t = 0.0;
    unsigned i;
    CHECK(c != NULL);
    if (c == NULL)
        return;
    for (i = 0; i < length; ++i) {
        unsigned char *before = NULL, *after = NULL;
        size_t n_before = 0, n_after;
        unsigned op = pick(20);
        fmi2Status st = fmi2OK;
        double t0, dt;
        int compare = pick(8) == 0;
        fmi2FMUstate *slot = &slots[pick(MAX_SLOTS)];
        fmi2ValueReference vr = INPUT_VR;
        fmi2Real value;
        if (compare)
            n_before = fingerprint(c, &before);
        t0 = seconds();
        switch (op) {
        case 0: st = fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0); t = 0.0; break;
        case 1: st = fmi2EnterInitializationMode(c); break;
        case 2: random_parameters(c); st = fmi2OK; compare = 0; break;
        case 3: case 4: st = fmi2ExitInitializationMode(c);
            if (st == fmi2OK) { ++n_inits; t = 0.0; outputs_finite(c); }
            break;
        case 5: case 6: case 7: case 8: {
            /* Up to 2000 ticks (the model's own Ts), sometimes arbitrary sizes that the FMU
             * must refuse; steps of any length over a held input with huge_steps. */
            fmi2ValueReference tsr = TS_VR;
            double h, Ts = 0.0;
            if (fmi2GetReal(c, &tsr, 1, &Ts) != fmi2OK || !(Ts > 0.0))
                Ts = 1e-3;
            h = Ts * (double)(1 + pick(pick(10) ? 20 : 2000));
            if (pick(10) == 0)
                h = huge_steps ? any_real(-9, 12) : -any_real(-9, 1);
            st = fmi2DoStep(c, pick(20) ? t : t + any_real(-6, 6), h, fmi2True);
            if (st == fmi2OK) {
                fmi2Real now = 0.0;
                ++n_steps;
                CHECK(fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &now) == fmi2OK);
                t = now;
                outputs_finite(c);
            }
            break;
        }
        case 9: case 10: value = any_input();
            st = fmi2SetReal(c, pick(20) ? &vr : NULL, 1, pick(20) ? &value : NULL); break;
        case 11: random_parameters(c); compare = 0; break;
        case 12: st = fmi2GetFMUstate(c, pick(20) ? slot : NULL); break;
        case 13: if (*slot != NULL) {
                st = fmi2SetFMUstate(c, *slot);
                CHECK(st == fmi2OK);   /* every state saved loads again */
                ++n_restores;
                if (st == fmi2OK) { fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &t); }
            }
            break;
        case 14: if (*slot != NULL) {   /* serialise, deserialise, load */
                size_t size = 0;
                unsigned char *blob;
                fmi2FMUstate back = NULL;
                CHECK(fmi2SerializedFMUstateSize(c, *slot, &size) == fmi2OK);
                blob = (unsigned char *)malloc(size ? size : 1);
                CHECK(fmi2SerializeFMUstate(c, *slot, (fmi2Byte *)blob, size) == fmi2OK);
                st = fmi2DeSerializeFMUstate(c, (fmi2Byte *)blob, size, &back);
                CHECK(st == fmi2OK);
                if (st == fmi2OK) {
                    CHECK(fmi2SetFMUstate(c, back) == fmi2OK);
                    fmi2GetRealStatus(c, fmi2LastSuccessfulTime, &t);
                    ++n_restores;
                }
                fmi2FreeFMUstate(c, &back);
                free(blob);
            }
            break;
        case 15: st = fmi2FreeFMUstate(c, slot); break;
        case 16: st = fmi2Terminate(c); break;
        case 17: if (pick(4) == 0) { st = fmi2Reset(c); t = 0.0; } break;
        case 18: { fmi2Real y[4];
            size_t k, ny = pick(8) ? N_OUTPUTS : 0;
            st = fmi2GetReal(c, outputs, ny, pick(20) ? y : NULL);
            for (k = 0; st == fmi2OK && k < ny; ++k)
                CHECK(isfinite(y[k]));
            break; }
        default: { fmi2ValueReference ts = TS_VR;
            value = pick(2) ? any_real(-4, 2) : 1e-3;   /* as random_parameters: see there */
            st = fmi2SetReal(c, &ts, 1, &value);
            break; }
        }
        dt = seconds() - t0;
        ++n_calls;
        if (dt > slowest) slowest = dt;
        if (dt > CALL_LIMIT_S) {
            ++n_slow;
            fprintf(stderr, "call %u took %.3f s\n", op, dt);
        }
        CHECK(st == fmi2OK || st == fmi2Error);
        if (st == fmi2Error) {
            ++n_errors;
            if (compare && n_before > 0) {
                n_after = fingerprint(c, &after);
                CHECK(n_after == n_before && memcmp(before, after, n_before) == 0);
            }
        }
        free(before);
        free(after);
    }
    {
        unsigned k;
        for (k = 0; k < MAX_SLOTS; ++k)
            CHECK(fmi2FreeFMUstate(c, &slots[k]) == fmi2OK);
    }
    fmi2FreeInstance(c);
}

int main(int argc, char **argv)
{
    unsigned long n = argc > 1 ? strtoul(argv[1], NULL, 10) : 1000ul, s;
    rng = 0x2545F4914F6CDD1Dull ^ (argc > 2 ? strtoull(argv[2], NULL, 10) : 1ull);
    huge_steps = argc > 3 && strcmp(argv[3], "huge") == 0;
    for (s = 0; s < n; ++s)
        run_sequence(20 + pick(120));
    CHECK(n_slow == 0);
    CHECK(n < 200 || (n_inits > n / 4 && n_steps > n && n_restores > n / 4));
    printf("fmu_fuzz %s: %lu sequences, %lu calls (%lu errors), %lu initialisations, %lu steps, "
           "%lu states restored, %lu calls over %.0f ms (slowest %.3f ms), %lu failures\n",
           FMU_MODEL_IDENTIFIER, n, n_calls, n_errors, n_inits, n_steps, n_restores, n_slow,
           1e3 * CALL_LIMIT_S, 1e3 * slowest, failures);
    return failures == 0 ? 0 : 1;
}
