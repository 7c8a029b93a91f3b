/* SPDX-License-Identifier: Apache-2.0 */
/*
 * The FMU's per-step cost next to the modelica Reference-FMUs' Feedthrough, measured by one
 * raw C host the same way for both: each FMU's binary is loaded from its unpacked folder with
 * dlopen (as an importer does), and one step is set(input) + doStep(t, 1 ms) + get(output),
 * one value each, through the function pointers. Also: SmoothShaper's chain stepped directly
 * (sms_chain_step, the same chain: the default
 * rectangular 10 ms + ZV at 100 rad/s, Ts = 1 ms), and the fixed cost of DeSerializeFMUstate
 * (+ FreeFMUstate) of a small state, for FMI 2.0 and FMI 3.0. CPU time, median of interleaved
 * rounds (tests/bench/cpu_time.h).
 *
 * Usage: bench_fmu_feedthrough [--quick | --state-load] [FEEDTHROUGH2_DIR [FEEDTHROUGH3_DIR]]
 * --state-load: only the DeSerializeFMUstate rounds, each figure also as a machine-readable
 * line "state_load<TAB>fmi2|fmi3<TAB>model<TAB>us" (read by python -m smoothshaper.bench).
 * The Feedthrough folders are the Reference-FMUs' unpacked FMUs, built with their own CMake:
 *   cmake -S Reference-FMUs -B build2 -DFMI_VERSION=2 -DCMAKE_BUILD_TYPE=Release
 *   cmake --build build2 --target Feedthrough       (-> build2/temp/Feedthrough)
 * and the same with -DFMI_VERSION=3 into build3. Without them only SmoothShaper's figures
 * print. SmoothShaper's unpacked FMUs come from this build (SMS_FMU2_DIR, SMS_FMU3_DIR); the
 * environment variable SMS_BENCH_FMU2_DIR names another unpacked FMI 2.0 SmoothShaper instead
 * (another build, to compare).
 */
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"
#include "fmi3Functions.h"
#include "smoothshaper/smoothshaper.h"
#include "../bench/cpu_time.h"

#define ROUNDS 7
static const double Ts = 1e-3;

/* A symbol as a function pointer (POSIX: dlsym's object pointer holds a function's address). */
#define LOAD(lib, name, field, ok) \
    do { void *sym_ = dlsym((lib), (name)); \
         if (sym_ == NULL) (ok) = 0; else memcpy(&(field), &sym_, sizeof(field)); } while (0)

/* The value of the first of the attributes `names` (NULL-terminated) in the folder's
 * modelDescription.xml. */
static int read_attribute(const char *dir, const char *const *names, char *value, size_t len)
{
    char path[4096], key[64], *at = NULL, *end;
    static char xml[1 << 20];
    size_t n;
    FILE *f;
    snprintf(path, sizeof path, "%s/modelDescription.xml", dir);
    f = fopen(path, "rb");
    if (f == NULL)
        return 0;
    n = fread(xml, 1, sizeof xml - 1, f);
    fclose(f);
    xml[n] = '\0';
    for (; *names != NULL && at == NULL; ++names) {
        snprintf(key, sizeof key, " %s=\"", *names);
        at = strstr(xml, key);
    }
    if (at == NULL)
        return 0;
    at = strchr(at, '"') + 1;
    end = strchr(at, '"');
    if (end == NULL || (size_t)(end - at) >= len)
        return 0;
    memcpy(value, at, (size_t)(end - at));
    value[end - at] = '\0';
    return 1;
}

/* <dir>/binaries/<platform>/<modelIdentifier>.so, and the instantiation token. */
static void *open_binary(const char *dir, const char *platform, char *token, size_t len)
{
    static const char *const tokens[] = { "guid", "instantiationToken", NULL };
    static const char *const ids[] = { "modelIdentifier", NULL };
    char path[4096], id[256];
    void *lib;
    if (!read_attribute(dir, tokens, token, len) || !read_attribute(dir, ids, id, sizeof id)) {
        fprintf(stderr, "bench_fmu_feedthrough: no modelDescription.xml in %s\n", dir);
        return NULL;
    }
    snprintf(path, sizeof path, "%s/binaries/%s/%s.so", dir, platform, id);
    lib = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (lib == NULL)
        fprintf(stderr, "bench_fmu_feedthrough: cannot load %s: %s\n", path, dlerror());
    return lib;
}

/* ---------------------------------------------------------------- FMI 2.0 */

typedef struct fmi2_api {
    fmi2InstantiateTYPE *instantiate;
    fmi2SetupExperimentTYPE *setup;
    fmi2EnterInitializationModeTYPE *enter;
    fmi2ExitInitializationModeTYPE *exit_init;
    fmi2SetRealTYPE *set_real;
    fmi2GetRealTYPE *get_real;
    fmi2DoStepTYPE *do_step;
    fmi2GetFMUstateTYPE *get_state;
    fmi2SerializedFMUstateSizeTYPE *state_size;
    fmi2SerializeFMUstateTYPE *serialize;
    fmi2DeSerializeFMUstateTYPE *deserialize;
    fmi2FreeFMUstateTYPE *free_state;
    fmi2FreeInstanceTYPE *free_instance;
    char token[128];
} fmi2_api;

static void logger2(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                    fmi2String category, fmi2String message, ...)
{
    (void)env; (void)status; (void)category;
    fprintf(stderr, "[%s] %s\n", name, message);
}

static const fmi2CallbackFunctions callbacks2 = { logger2, calloc, free, NULL, NULL };

static int load2(const char *dir, fmi2_api *a)
{
    void *lib = open_binary(dir, "linux64", a->token, sizeof a->token);
    int ok = lib != NULL;
    if (!ok)
        return 0;
    LOAD(lib, "fmi2Instantiate", a->instantiate, ok);
    LOAD(lib, "fmi2SetupExperiment", a->setup, ok);
    LOAD(lib, "fmi2EnterInitializationMode", a->enter, ok);
    LOAD(lib, "fmi2ExitInitializationMode", a->exit_init, ok);
    LOAD(lib, "fmi2SetReal", a->set_real, ok);
    LOAD(lib, "fmi2GetReal", a->get_real, ok);
    LOAD(lib, "fmi2DoStep", a->do_step, ok);
    LOAD(lib, "fmi2GetFMUstate", a->get_state, ok);
    LOAD(lib, "fmi2SerializedFMUstateSize", a->state_size, ok);
    LOAD(lib, "fmi2SerializeFMUstate", a->serialize, ok);
    LOAD(lib, "fmi2DeSerializeFMUstate", a->deserialize, ok);
    LOAD(lib, "fmi2FreeFMUstate", a->free_state, ok);
    LOAD(lib, "fmi2FreeInstance", a->free_instance, ok);
    return ok;
}

/* An instance at its parameters' start values, initialised. */
static fmi2Component start2(const fmi2_api *a)
{
    fmi2Component c = a->instantiate("bench", fmi2CoSimulation, a->token, "", &callbacks2,
                                     fmi2False, fmi2False);
    if (c == NULL || a->setup(c, fmi2False, 0.0, 0.0, fmi2False, 0.0) != fmi2OK
        || a->enter(c) != fmi2OK)
        return NULL;
    return a->exit_init(c) == fmi2OK ? c : NULL;
}

/* ns per step of set + doStep + get (inputs changing every step, so every tick computes). */
static double steps2(const fmi2_api *a, fmi2Component c, fmi2ValueReference in,
                     fmi2ValueReference out, long n, double *t, double *sink)
{
    double t0 = cpu_seconds(), y = 0.0;
    long i;
    for (i = 0; i < n; ++i) {
        const double u = (double)(i & 1023);
        a->set_real(c, &in, 1, &u);
        a->do_step(c, *t, Ts, fmi2True);
        a->get_real(c, &out, 1, &y);
        *sink += y;
        *t += Ts;
    }
    return (cpu_seconds() - t0) / (double)n * 1e9;
}

/* us per DeSerializeFMUstate + FreeFMUstate of the instance's state. */
static double deserialize2(const fmi2_api *a, fmi2Component c, long n)
{
    fmi2FMUstate s = NULL, back = NULL;
    size_t size = 0;
    unsigned char *blob;
    double t0;
    long i;
    if (a->get_state(c, &s) != fmi2OK || a->state_size(c, s, &size) != fmi2OK)
        return -1.0;
    blob = (unsigned char *)malloc(size);
    if (blob == NULL || a->serialize(c, s, (fmi2Byte *)blob, size) != fmi2OK)
        return -1.0;
    t0 = cpu_seconds();
    for (i = 0; i < n; ++i) {
        a->deserialize(c, (fmi2Byte *)blob, size, &back);
        a->free_state(c, &back);
    }
    t0 = (cpu_seconds() - t0) / (double)n * 1e6;
    free(blob);
    a->free_state(c, &s);
    return t0;
}

/* ---------------------------------------------------------------- FMI 3.0 */

typedef struct fmi3_api {
    fmi3InstantiateCoSimulationTYPE *instantiate;
    fmi3EnterInitializationModeTYPE *enter;
    fmi3ExitInitializationModeTYPE *exit_init;
    fmi3SetFloat64TYPE *set_real;
    fmi3GetFloat64TYPE *get_real;
    fmi3DoStepTYPE *do_step;
    fmi3GetFMUStateTYPE *get_state;
    fmi3SerializedFMUStateSizeTYPE *state_size;
    fmi3SerializeFMUStateTYPE *serialize;
    fmi3DeserializeFMUStateTYPE *deserialize;
    fmi3FreeFMUStateTYPE *free_state;
    fmi3FreeInstanceTYPE *free_instance;
    char token[128];
} fmi3_api;

static void logger3(fmi3InstanceEnvironment env, fmi3Status status, fmi3String category,
                    fmi3String message)
{
    (void)env; (void)status; (void)category;
    fprintf(stderr, "[fmi3] %s\n", message);
}

static int load3(const char *dir, fmi3_api *a)
{
    void *lib = open_binary(dir, "x86_64-linux", a->token, sizeof a->token);
    int ok = lib != NULL;
    if (!ok)
        return 0;
    LOAD(lib, "fmi3InstantiateCoSimulation", a->instantiate, ok);
    LOAD(lib, "fmi3EnterInitializationMode", a->enter, ok);
    LOAD(lib, "fmi3ExitInitializationMode", a->exit_init, ok);
    LOAD(lib, "fmi3SetFloat64", a->set_real, ok);
    LOAD(lib, "fmi3GetFloat64", a->get_real, ok);
    LOAD(lib, "fmi3DoStep", a->do_step, ok);
    LOAD(lib, "fmi3GetFMUState", a->get_state, ok);
    LOAD(lib, "fmi3SerializedFMUStateSize", a->state_size, ok);
    LOAD(lib, "fmi3SerializeFMUState", a->serialize, ok);
    LOAD(lib, "fmi3DeserializeFMUState", a->deserialize, ok);
    LOAD(lib, "fmi3FreeFMUState", a->free_state, ok);
    LOAD(lib, "fmi3FreeInstance", a->free_instance, ok);
    return ok;
}

static fmi3Instance start3(const fmi3_api *a)
{
    fmi3Instance c = a->instantiate("bench", a->token, "", fmi3False, fmi3False, fmi3False,
                                    fmi3False, NULL, 0, NULL, logger3, NULL);
    if (c == NULL || a->enter(c, fmi3False, 0.0, 0.0, fmi3False, 0.0) != fmi3OK)
        return NULL;
    return a->exit_init(c) == fmi3OK ? c : NULL;
}

static double steps3(const fmi3_api *a, fmi3Instance c, fmi3ValueReference in,
                     fmi3ValueReference out, long n, double *t, double *sink)
{
    double t0 = cpu_seconds(), y = 0.0, last;
    fmi3Boolean event, terminate, early;
    long i;
    for (i = 0; i < n; ++i) {
        const double u = (double)(i & 1023);
        a->set_real(c, &in, 1, &u, 1);
        a->do_step(c, *t, Ts, fmi3True, &event, &terminate, &early, &last);
        a->get_real(c, &out, 1, &y, 1);
        *sink += y;
        *t += Ts;
    }
    return (cpu_seconds() - t0) / (double)n * 1e9;
}

static double deserialize3(const fmi3_api *a, fmi3Instance c, long n)
{
    fmi3FMUState s = NULL, back = NULL;
    size_t size = 0;
    unsigned char *blob;
    double t0;
    long i;
    if (a->get_state(c, &s) != fmi3OK || a->state_size(c, s, &size) != fmi3OK)
        return -1.0;
    blob = (unsigned char *)malloc(size);
    if (blob == NULL || a->serialize(c, s, blob, size) != fmi3OK)
        return -1.0;
    t0 = cpu_seconds();
    for (i = 0; i < n; ++i) {
        a->deserialize(c, blob, size, &back);
        a->free_state(c, &back);
    }
    t0 = (cpu_seconds() - t0) / (double)n * 1e6;
    free(blob);
    a->free_state(c, &s);
    return t0;
}

/* ---------------------------------------------------------------- the chain alone */

static double chain_steps(long n, double *sink)
{
    sms_stage_config cfg[2];
    sms_chain chain;
    sms_stage stages[2];
    sms_memory_cell *memory;
    size_t need = 0;
    double t0;
    long i;
    cfg[0] = sms_stage_config_default(SMS_RECTANGULAR);
    cfg[0].T = 0.01;
    cfg[1] = sms_stage_config_default(SMS_SHAPER_ZV);
    cfg[1].wn = 100.0;
    cfg[1].zeta = 0.0;
    if (sms_chain_memory_size(cfg, 2, Ts, &need) != SMS_OK)
        return -1.0;
    memory = (sms_memory_cell *)calloc(need, sizeof *memory);
    if (memory == NULL || sms_chain_init(&chain, stages, cfg, 2, Ts, memory, need) != SMS_OK)
        return -1.0;
    t0 = cpu_seconds();
    for (i = 0; i < n; ++i) {
        sms_real x = (sms_real)(i & 1023);
        sms_chain_step(&chain, &x);
        *sink += (double)x;
    }
    t0 = (cpu_seconds() - t0) / (double)n * 1e9;
    free(memory);
    return t0;
}

int main(int argc, char **argv)
{
    int quick = 0, state_load = 0, a = 1, r, have2 = 0, have3 = 0;
    const char *ft2 = NULL, *ft3 = NULL;
    long n, nd;
    double sink = 0.0;
    fmi2_api ss2, ft2_api;
    fmi3_api ss3, ft3_api;
    if (argc > 1 && strcmp(argv[1], "--quick") == 0) {
        quick = 1;
        a = 2;
    } else if (argc > 1 && strcmp(argv[1], "--state-load") == 0) {
        state_load = 1;
        a = 2;
    }
    if (a < argc)
        ft2 = argv[a++];
    if (a < argc)
        ft3 = argv[a];
    n = quick ? 20000 : 2000000;
    nd = quick ? 200 : 20000;
    if (!load2(getenv("SMS_BENCH_FMU2_DIR") ? getenv("SMS_BENCH_FMU2_DIR") : SMS_FMU2_DIR, &ss2)
        || !load3(SMS_FMU3_DIR, &ss3)) {
        fprintf(stderr, "bench_fmu_feedthrough: cannot load SmoothShaper from %s / %s\n",
                SMS_FMU2_DIR, SMS_FMU3_DIR);
        return 1;
    }
    have2 = ft2 != NULL && load2(ft2, &ft2_api);
    have3 = ft3 != NULL && load3(ft3, &ft3_api);
    {
        /* SmoothShaper at its defaults (rectangular 10 ms + ZV at 100 rad/s, Ts = 1 ms) u (0)
         * -> y (1); Feedthrough's Float64_continuous_input (7) -> _output (8). */
        fmi2Component s2 = start2(&ss2), f2 = have2 ? start2(&ft2_api) : NULL;
        fmi3Instance s3 = start3(&ss3), f3 = have3 ? start3(&ft3_api) : NULL;
        double ss2_ns[ROUNDS], ft2_ns[ROUNDS], ss3_ns[ROUNDS], ft3_ns[ROUNDS], chain_ns[ROUNDS];
        double ss2_de[ROUNDS], ft2_de[ROUNDS], ss3_de[ROUNDS], ft3_de[ROUNDS];
        double ts2 = 0.0, tf2 = 0.0, ts3 = 0.0, tf3 = 0.0, ch, f, ratio;
        if (s2 == NULL || s3 == NULL || (have2 && f2 == NULL) || (have3 && f3 == NULL)) {
            fprintf(stderr, "bench_fmu_feedthrough: an instance could not be set up\n");
            return 1;
        }
        if (state_load) {
            for (r = 0; r < ROUNDS; ++r) {
                ss2_de[r] = deserialize2(&ss2, s2, nd);
                ss3_de[r] = deserialize3(&ss3, s3, nd);
                ft2_de[r] = have2 ? deserialize2(&ft2_api, f2, nd) : 0.0;
                ft3_de[r] = have3 ? deserialize3(&ft3_api, f3, nd) : 0.0;
            }
            printf("DeSerializeFMUstate + FreeFMUstate of the instance's state (median of %d "
                   "rounds of %ld)\n", ROUNDS, nd);
            printf("state_load\tfmi2\tSmoothShaper\t%.4f\n", median(ss2_de, ROUNDS));
            printf("state_load\tfmi3\tSmoothShaper\t%.4f\n", median(ss3_de, ROUNDS));
            if (have2)
                printf("state_load\tfmi2\tFeedthrough\t%.4f\n", median(ft2_de, ROUNDS));
            if (have3)
                printf("state_load\tfmi3\tFeedthrough\t%.4f\n", median(ft3_de, ROUNDS));
            ss2.free_instance(s2);
            ss3.free_instance(s3);
            if (have2)
                ft2_api.free_instance(f2);
            if (have3)
                ft3_api.free_instance(f3);
            return 0;
        }
        for (r = 0; r < ROUNDS; ++r) {
            ss2_ns[r] = steps2(&ss2, s2, 0, 1, n, &ts2, &sink);
            ss3_ns[r] = steps3(&ss3, s3, 0, 1, n, &ts3, &sink);
            ft2_ns[r] = have2 ? steps2(&ft2_api, f2, 7, 8, n, &tf2, &sink) : 0.0;
            ft3_ns[r] = have3 ? steps3(&ft3_api, f3, 7, 8, n, &tf3, &sink) : 0.0;
            chain_ns[r] = chain_steps(n, &sink);
            ss2_de[r] = deserialize2(&ss2, s2, nd);
            ss3_de[r] = deserialize3(&ss3, s3, nd);
            ft2_de[r] = have2 ? deserialize2(&ft2_api, f2, nd) : 0.0;
            ft3_de[r] = have3 ? deserialize3(&ft3_api, f3, nd) : 0.0;
        }
        ch = median(chain_ns, ROUNDS);
        printf("One step: set(input) + doStep(t, 1 ms) + get(output), one value each, through "
               "dlopen'd function pointers (median of %d rounds of %ld steps, CPU time)\n",
               ROUNDS, n);
        printf("  %-44s %9s %9s\n", "", "FMI 2.0", "FMI 3.0");
        printf("  %-44s %7.1f ns %7.1f ns\n", "SmoothShaper (rectangular 10 ms + ZV)",
               median(ss2_ns, ROUNDS), median(ss3_ns, ROUNDS));
        if (have2 || have3)
            printf("  %-44s %7.1f ns %7.1f ns\n", "Reference-FMUs Feedthrough",
                   median(ft2_ns, ROUNDS), median(ft3_ns, ROUNDS));
        printf("  %-44s %7.1f ns\n", "sms_chain_step, the same chain", ch);
        if (have2) {
            f = median(ft2_ns, ROUNDS);
            ratio = median(ss2_ns, ROUNDS) / (ch + f);
            printf("  SmoothShaper / (chain + Feedthrough), FMI 2.0:   %.2f  (%.1f ns beyond the "
                   "chain, Feedthrough %.1f)\n", ratio, median(ss2_ns, ROUNDS) - ch, f);
        }
        if (have3) {
            f = median(ft3_ns, ROUNDS);
            ratio = median(ss3_ns, ROUNDS) / (ch + f);
            printf("  SmoothShaper / (chain + Feedthrough), FMI 3.0:   %.2f  (%.1f ns beyond the "
                   "chain, Feedthrough %.1f)\n", ratio, median(ss3_ns, ROUNDS) - ch, f);
        }
        printf("\nDeSerializeFMUstate + FreeFMUstate of the instance's state (median of %d "
               "rounds of %ld)\n", ROUNDS, nd);
        printf("  %-44s %7.3f us %7.3f us\n", "SmoothShaper (its default chain)",
               median(ss2_de, ROUNDS), median(ss3_de, ROUNDS));
        if (have2 || have3)
            printf("  %-44s %7.3f us %7.3f us\n", "Reference-FMUs Feedthrough",
                   median(ft2_de, ROUNDS), median(ft3_de, ROUNDS));
        ss2.free_instance(s2);
        ss3.free_instance(s3);
        if (have2)
            ft2_api.free_instance(f2);
        if (have3)
            ft3_api.free_instance(f3);
    }
    return sink == 0.5 ? 2 : 0;   /* keeps the loops */
}
