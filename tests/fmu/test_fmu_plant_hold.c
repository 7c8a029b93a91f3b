/* SPDX-License-Identifier: Apache-2.0 */
/*
 * ElasticPlant long steps: a step of more than 65536 ticks advances the deviation from the rest
 * (u, 0) by Ad^(n-1) in closed form, then ticks once (elastic_plant_model.c). Against ticking
 * every sample (fmu_model_tick()) the scaled state and the output differ by at most the ticks'
 * own rounding, which grows at most linearly: |dz| <= 8 n eps (max |z| + |u|), for undamped
 * and damped modes; steps of up to 65536 ticks are the ticks bit for bit; and a step of 1e12 s
 * of a damped mode ends at rest (y = u to that rounding).
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fmi2Functions.h"
#include "fmu_instance.h"
#include "ElasticPlant_variables.h"
#include "fmu_test_callbacks.h"

#define TS 1e-3

static int failures;


/* A plant of mode wn [rad/s] and damping zeta (J_l = 1, k_t = wn^2, b_t = 2 zeta wn), moved
 * by a few random inputs, then given the input 2.5. */
static fmi2Component make(double wn, double zeta)
{
    fmi2Component c = fmi2Instantiate("plant", fmi2CoSimulation, FMU_MODEL_GUID, "", &callbacks,
                                      fmi2False, fmi2False);
    const fmi2ValueReference vr[4] = { EP_VR_TS, EP_VR_J_L, EP_VR_K_T, EP_VR_B_T };
    const fmi2ValueReference u = EP_VR_U;
    fmi2Real v[4], x;
    double t = 0.0;
    int k;
    v[0] = TS;
    v[1] = 1.0;
    v[2] = wn * wn;
    v[3] = 2.0 * zeta * wn;
    fmi2SetupExperiment(c, fmi2False, 0.0, 0.0, fmi2False, 0.0);
    fmi2EnterInitializationMode(c);
    fmi2SetReal(c, vr, 4, v);
    if (fmi2ExitInitializationMode(c) != fmi2OK) {
        ++failures;
        return c;
    }
    srand(3);
    for (k = 0; k < 20; ++k) {
        x = 4.0 * rand() / RAND_MAX - 2.0;
        fmi2SetReal(c, &u, 1, &x);
        fmi2DoStep(c, t, 13 * TS, fmi2True);
        t += 13 * TS;
    }
    x = 2.5;
    fmi2SetReal(c, &u, 1, &x);
    return c;
}

static void compare(double wn, double zeta, unsigned long n)
{
    fmi2Component a = make(wn, zeta), b = make(wn, zeta);
    double sa[3], sb[3], zmax = 0.0, bound, dz;
    unsigned long i;
    fmi2DoStep(a, 20 * 13 * TS, (double)n * TS, fmi2True);
    for (i = 0; i < n; ++i) {
        fmu_model_tick(((fmu_instance *)b)->model);
        fmu_model_save_state(((fmu_instance *)b)->model, sb);
        zmax = fmax(zmax, fmax(fabs(sb[1]), fabs(sb[2])));
    }
    fmu_model_save_state(((fmu_instance *)a)->model, sa);
    fmu_model_save_state(((fmu_instance *)b)->model, sb);
    /* saved state: y, then the scaled z */
    bound = 8.0 * (double)n * DBL_EPSILON * (zmax + 2.5);
    dz = fmax(fmax(fabs(sa[1] - sb[1]), fabs(sa[2] - sb[2])), fabs(sa[0] - sb[0]));
    if (n <= 65536u ? memcmp(sa, sb, sizeof sa) != 0 : !(dz <= bound)) {
        fprintf(stderr, "wn %g zeta %g n %lu: |dz| %.3g over %.3g\n", wn, zeta, n, dz, bound);
        ++failures;
    } else {
        printf("wn %g zeta %g n %lu: |dz| %.3g (bound %.3g)\n", wn, zeta, n, dz, bound);
    }
    fmi2FreeInstance(a);
    fmi2FreeInstance(b);
}

int main(void)
{
    const double zetas[4] = {0.0, 1e-3, 0.05, 0.7}, wns[2] = {31.4, 600.0};
    const unsigned long ns[3] = {65536u, 65537u, 400000u};
    int i, j, k;
    for (i = 0; i < 2; ++i)
        for (j = 0; j < 4; ++j)
            for (k = 0; k < 3; ++k)
                compare(wns[i], zetas[j], ns[k]);
    {
        /* a damped mode held for 1e12 s rests on the input */
        fmi2Component c = make(31.4, 0.05);
        fmi2ValueReference y = EP_VR_Y;
        fmi2Real out;
        fmi2DoStep(c, 20 * 13 * TS, 1e12, fmi2True);
        fmi2GetReal(c, &y, 1, &out);
        if (!(fabs(out - 2.5) <= 8.0 * DBL_EPSILON * 2.5)) {
            fprintf(stderr, "1e12 s: y = %.17g, not at rest on 2.5\n", out);
            ++failures;
        }
        fmi2FreeInstance(c);
    }
    return failures == 0 ? 0 : 1;
}
