/* SPDX-License-Identifier: Apache-2.0 */
/* The online generator's rounding campaign (docs/sampled-limits.md, "What rounding adds"),
 * shared by tests/c/test_generator.c (a few hundred cases, asserted) and
 * tests/bench/generator_rounding_bench.c (tens of thousands, printed).
 *
 * A case: vmax 1e-2..1e2, amax/vmax 0.1..1e3, jmax/amax 0.1..1e5 (log-uniform), any profile;
 * Ts from 1e-3 to 100 jerk phases (at most 3000 samples per vmax/amax), or on a grid where
 * every phase boundary of a move from rest is a sample (Ts = (amax/jmax)/R, vmax/amax = M
 * samples); a mode on the damped profile and on 30 % of the others; targets (style): 0 steps
 * every 1..5 samples, 1 every 1..200, 2 tiny steps among jumps, 3 a single move, 4 one
 * retarget mid-motion. */
#ifndef SMS_TEST_GENERATOR_CAMPAIGN_H
#define SMS_TEST_GENERATOR_CAMPAIGN_H

#include <math.h>
#include <string.h>
#include "smoothshaper/smoothshaper.h"

typedef double (*campaign_uniform)(void); /* uniform in [0, 1) */

typedef struct campaign_case {
    sms_generator_config config;
    double Ts, scale; /* targets within +-2 scale */
    int style;
    long samples;
} campaign_case;

static double campaign_log_uniform(campaign_uniform u, double lo, double hi)
{
    return exp(log(lo) + u() * (log(hi) - log(lo)));
}

/* Draw a case (grid: Ts on the phase grid). */
static void campaign_draw(campaign_case *k, campaign_uniform u, int grid)
{
    double v = campaign_log_uniform(u, 1e-2, 1e2), a = v * campaign_log_uniform(u, 1e-1, 1e3);
    double j = a * campaign_log_uniform(u, 1e-1, 1e5), Ts;
    int profile = (int)(u() * 3.0);
    memset(k, 0, sizeof *k);
    k->style = (int)(u() * 5.0);
    k->samples = k->style <= 2 ? 4000 : 8000;
    if (!grid) {
        Ts = a / j * campaign_log_uniform(u, 1e-3, 1e2);
        if (v / a / Ts > 3000.0)
            Ts = v / a / 3000.0;
    } else {
        double R = floor(campaign_log_uniform(u, 1.0, 2000.0));
        double M = R + floor(campaign_log_uniform(u, 1.0, 5000.0));
        Ts = a / j / R;
        v = a * M * Ts;
        k->samples = 4 * (long)(M + R) + 200 > 20000 ? 20000 : 4 * (long)(M + R) + 200;
    }
    k->Ts = Ts;
    k->config.vmax = v;
    k->config.amax = a;
    k->config.jmax = j;
    k->config.profile = (sms_profile)profile;
    if (profile == SMS_PROFILE_DAMPED || u() < 0.3) {
        k->config.wn = campaign_log_uniform(u, 5.0, 300.0);
        if (k->config.wn * Ts > 2.5)
            k->config.wn = 2.5 / Ts * (0.1 + 0.9 * u());
        k->config.zeta = profile == SMS_PROFILE_POLYNOMIAL ? 0.0 : 0.2 * u();
        k->config.vmin = k->config.amin = 0.0; /* symmetric */
        k->config.qmin = k->config.qmax = 0.0; /* no position limits */
    }
    k->scale = v * campaign_log_uniform(u, 1e-3, grid ? 3.0 : 1.0);
}

/* Called after every sample of campaign_run() with the generator (e.g. to save its state). */
typedef void (*campaign_observer)(const sms_generator *g, void *context);

/* Run a case from rest at 0 with the ring (ring_len reals); for i = 1..3: reported[i] the
 * largest |out[i]|/L_i, beyond[i] the largest (|d^i q| - 2^i 16 unit S)/Ts^i/L_i (S the largest
 * |q| or target so far, unit the build's unit roundoff); observe (if not NULL) after every
 * sample. Returns 0 when the generator does not take the case (its stage needs more than
 * ring_len reals). */
static int campaign_run(const campaign_case *k, campaign_uniform u, double unit, sms_real *ring,
                        size_t ring_len, double reported[4], double beyond[4],
                        campaign_observer observe, void *context)
{
    sms_generator g;
    sms_real out[4];
    size_t need = 0;
    double L[4], prev[3] = {0, 0, 0}, S = 0.0, target = 0.0;
    long m, next = 0, retarget = -1;
    int i;
    if (sms_generator_buffer_size(&k->config, k->Ts, &need) != SMS_OK || need > ring_len ||
        sms_generator_init(&g, &k->config, k->Ts, ring, need) != SMS_OK)
        return 0;
    L[1] = k->config.vmax;
    L[2] = k->config.amax;
    L[3] = k->config.jmax;
    for (i = 0; i < 4; ++i)
        reported[i] = beyond[i] = 0.0;
    if (k->style == 3)
        target = k->scale * campaign_log_uniform(u, 1e-4, 1.0) * (u() < 0.5 ? -1.0 : 1.0);
    if (k->style == 4) {
        target = k->scale * (u() - 0.5) * 4.0;
        retarget = (long)(u() * (double)k->samples * 0.5);
    }
    for (m = 0; m < k->samples; ++m) {
        double q, e[4];
        if (k->style <= 2 && m == next) {
            if (k->style == 2 && u() < 0.3)
                target += (u() - 0.5) * 1e-6 * k->scale;
            else
                target = (u() - 0.5) * 4.0 * k->scale;
            next = m + 1 + (long)(u() * (k->style == 0 ? 5.0 : 200.0));
        }
        if (m == retarget)
            target = (u() - 0.5) * 4.0 * k->scale;
        sms_generator_step(&g, (sms_real)target, out);
        if (observe != NULL)
            observe(&g, context);
        q = (double)out[0];
        S = fabs(q) > S ? fabs(q) : S;
        S = fabs(target) > S ? fabs(target) : S;
        e[1] = q - prev[0];
        e[2] = q - 2.0 * prev[0] + prev[1];
        e[3] = q - 3.0 * prev[0] + 3.0 * prev[1] - prev[2];
        for (i = 1; i < 4; ++i) {
            double r = fabs((double)out[i]) / L[i];
            double d = (fabs(e[i]) - ldexp(16.0 * unit * S, i)) / pow(k->Ts, (double)i) / L[i];
            reported[i] = r > reported[i] ? r : reported[i];
            beyond[i] = d > beyond[i] ? d : beyond[i];
        }
        prev[2] = prev[1];
        prev[1] = prev[0];
        prev[0] = q;
    }
    return 1;
}

#endif
