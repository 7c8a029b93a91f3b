/* SPDX-License-Identifier: Apache-2.0 */
/*
 * A minimal FMI 2.0 Co-Simulation importer: loads an FMU's binary (LoadLibrary on Windows,
 * dlopen elsewhere), sets real parameters, and runs one real input to one real output with
 * fmpy's timing: the parameters and u(t_0) set in initialization mode, y recorded after
 * initialization, then for k = 0 .. K-2: set u(t_k), doStep(t_k, t_(k+1) - t_k), record y.
 *
 * It exists to run the FMUs' win64 binary under wine without fmpy's TCP remoting (whose
 * client waits for a server that may never start, so a failure looked like a stall): built
 * with x86_64-w64-mingw32-gcc by tests/python/test_fmu_win64.py, and natively too, where its
 * output must equal fmpy's bit for bit (the check that this host imports as fmpy does).
 *
 * Usage: fmi2_host BINARY GUID INPUT OUTPUT U_VR Y_VR [VR=VALUE ...]
 *   INPUT: one "t u" pair per line; OUTPUT: y at each t, one per line (%.17g).
 * Exit status 0 on success; otherwise what failed is on stderr (with the FMU's log messages).
 */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef _WIN32
#define WIN32_LEAN_AND_MEAN
#include <windows.h>
#else
#include <dlfcn.h>
#endif

#include "fmi2Functions.h"

#define MAX_STEPS 1000000

typedef struct {
    fmi2InstantiateTYPE *instantiate;
    fmi2FreeInstanceTYPE *free_instance;
    fmi2SetupExperimentTYPE *setup_experiment;
    fmi2EnterInitializationModeTYPE *enter_init;
    fmi2ExitInitializationModeTYPE *exit_init;
    fmi2SetRealTYPE *set_real;
    fmi2GetRealTYPE *get_real;
    fmi2DoStepTYPE *do_step;
    fmi2TerminateTYPE *terminate;
} api;

static void logger(fmi2ComponentEnvironment env, fmi2String name, fmi2Status status,
                   fmi2String category, fmi2String message, ...)
{
    va_list args;
    (void)env;
    fprintf(stderr, "[%s] status %d, %s: ", name, (int)status, category);
    va_start(args, message);
    vfprintf(stderr, message, args);
    va_end(args);
    fputc('\n', stderr);
}

static void *symbol(void *lib, const char *name)
{
    void *sym;
#ifdef _WIN32
    FARPROC p = GetProcAddress((HMODULE)lib, name);
    memcpy(&sym, &p, sizeof sym);
#else
    sym = dlsym(lib, name);
#endif
    if (sym == NULL)
        fprintf(stderr, "fmi2_host: the binary does not export %s\n", name);
    return sym;
}

/* Each entry point through its FMI type (POSIX and Win32 both hand out object pointers that
 * hold the function's address). */
#define BIND(field, name) \
    do { void *s_ = symbol(lib, (name)); if (s_ == NULL) return 0; \
         memcpy(&f->field, &s_, sizeof f->field); } while (0)

static int bind_api(void *lib, api *f)
{
    BIND(instantiate, "fmi2Instantiate");
    BIND(free_instance, "fmi2FreeInstance");
    BIND(setup_experiment, "fmi2SetupExperiment");
    BIND(enter_init, "fmi2EnterInitializationMode");
    BIND(exit_init, "fmi2ExitInitializationMode");
    BIND(set_real, "fmi2SetReal");
    BIND(get_real, "fmi2GetReal");
    BIND(do_step, "fmi2DoStep");
    BIND(terminate, "fmi2Terminate");
    return 1;
}

static int fail(const char *what)
{
    fprintf(stderr, "fmi2_host: %s\n", what);
    return 1;
}

int main(int argc, char **argv)
{
    static double t[MAX_STEPS], u[MAX_STEPS];
    fmi2CallbackFunctions callbacks = { logger, calloc, free, NULL, NULL };
    fmi2ValueReference u_vr, y_vr;
    fmi2Component c;
    size_t n = 0, k;
    FILE *in, *out;
    double y;
    void *lib;
    api f;
    int i;

    if (argc < 7)
        return fail("usage: fmi2_host BINARY GUID INPUT OUTPUT U_VR Y_VR [VR=VALUE ...]");
#ifdef _WIN32
    lib = (void *)LoadLibraryA(argv[1]);
#else
    lib = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
#endif
    if (lib == NULL) {
        fprintf(stderr, "fmi2_host: cannot load %s\n", argv[1]);
        return 1;
    }
    if (!bind_api(lib, &f))
        return 1;
    in = fopen(argv[3], "r");
    if (in == NULL)
        return fail("cannot open the input file");
    while (n < MAX_STEPS && fscanf(in, "%lf %lf", &t[n], &u[n]) == 2)
        ++n;
    fclose(in);
    if (n < 2)
        return fail("the input file holds fewer than two points");
    u_vr = (fmi2ValueReference)strtoul(argv[5], NULL, 10);
    y_vr = (fmi2ValueReference)strtoul(argv[6], NULL, 10);

    c = f.instantiate("host", fmi2CoSimulation, argv[2], NULL, &callbacks, fmi2False, fmi2False);
    if (c == NULL)
        return fail("fmi2Instantiate returned NULL");
    if (f.setup_experiment(c, fmi2False, 0.0, t[0], fmi2True, t[n - 1]) > fmi2Warning
        || f.enter_init(c) > fmi2Warning)
        return fail("setting up the experiment failed");
    for (i = 7; i < argc; ++i) {
        char *eq = strchr(argv[i], '=');
        fmi2ValueReference vr;
        double v;
        if (eq == NULL)
            return fail("a parameter is not VR=VALUE");
        vr = (fmi2ValueReference)strtoul(argv[i], NULL, 10);
        v = strtod(eq + 1, NULL);
        if (f.set_real(c, &vr, 1, &v) > fmi2Warning) {
            fprintf(stderr, "fmi2_host: fmi2SetReal refused %s\n", argv[i]);
            return 1;
        }
    }
    if (f.set_real(c, &u_vr, 1, &u[0]) > fmi2Warning || f.exit_init(c) > fmi2Warning)
        return fail("initialization failed");
    out = fopen(argv[4], "w");
    if (out == NULL)
        return fail("cannot open the output file");
    if (f.get_real(c, &y_vr, 1, &y) > fmi2Warning)
        return fail("fmi2GetReal failed after initialization");
    fprintf(out, "%.17g\n", y);
    for (k = 0; k + 1 < n; ++k) {
        if (f.set_real(c, &u_vr, 1, &u[k]) > fmi2Warning
            || f.do_step(c, t[k], t[k + 1] - t[k], fmi2True) > fmi2Warning
            || f.get_real(c, &y_vr, 1, &y) > fmi2Warning) {
            fprintf(stderr, "fmi2_host: step %lu at t = %.17g failed\n", (unsigned long)k, t[k]);
            return 1;
        }
        fprintf(out, "%.17g\n", y);
    }
    if (fclose(out) != 0)
        return fail("writing the output file failed");
    f.terminate(c);
    f.free_instance(c);
    return 0;
}
