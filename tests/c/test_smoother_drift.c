/* SPDX-License-Identifier: Apache-2.0 */
/* Drift (docs/numerics.md): 1e7 samples of 1e3 + uniform noise through every recursive smoother.
 * The error against the direct convolution with the taps over the last 1e4 samples must be
 * no larger than over the 1e4 after the first 1e4 (within 2x): rounding does not accumulate with run
 * length. (tests/bench/drift_bench.c prints the figures for up to 1e9 samples.) */
#include <float.h>
#include "check.h"
#include "compensated_sum.h"
#include "smoother_fixtures.h"

#ifdef SMS_USE_FLOAT
#define REAL_EPS FLT_EPSILON
#else
#define REAL_EPS DBL_EPSILON
#endif

/* 1e7 samples; the sanitizer build, 10 to 20 times slower per sample, runs the first 1e6 of
 * the same campaign (tests/CMakeLists.txt): its errors of memory and arithmetic show there as
 * well, and the release build measures the drift over the full length. */
#ifdef SMS_TEST_DRIFT_RUN
#define RUN SMS_TEST_DRIFT_RUN
#else
#define RUN 10000000u
#endif
#define WINDOW 10000u
#define MAX_LEN 2100

static sms_real ring[MAX_LEN];
static double taps[MAX_LEN], recent[MAX_LEN];

static unsigned long long rng = 88172645463325252ull;
static double noise(void)
{
    return 2.0 * xorshift_uniform(&rng) - 1.0; /* [-1, 1) */
}

static void run_case(sms_kind kind, double T, double sigma)
{
    const double Ts = 1e-3;
    sms_stage_config c = sms_stage_config_default(kind);
    sms_smoother f;
    double early = 0.0, late = 0.0, floor_err;
    size_t L, n, head = 0, i;
    c.T = T;
    c.sigma = sigma;
    CHECK_STATUS(sms_smoother_init(&f, &c, Ts, ring, MAX_LEN), SMS_OK);
    L = f.length;
    CHECK_STATUS(sms_smoother_taps(&c, Ts, taps, MAX_LEN), SMS_OK);
    for (i = 0; i < L; ++i)
        recent[i] = 0.0;
    for (n = 0; n < RUN; ++n) {
        sms_real x = (sms_real)(1e3 + noise());
        recent[head] = (double)x;
        sms_smoother_step(&f, &x);
        if ((n >= WINDOW && n < 2 * WINDOW) || n >= RUN - WINDOW) {
            /* y[n] = sum_i h[i] x[n-i]; x[n-i] is at head - i (mod L). */
            compensated_sum y = { 0.0, 0.0 }; /* its own rounding stays below the engine's */
            double e;
            size_t idx = head;
            for (i = 0; i < L; ++i) {
                compensated_add_product(&y, taps[i], recent[idx]);
                idx = idx == 0 ? L - 1 : idx - 1;
            }
            e = fabs(((double)x - y.sum) - y.err);
            if (n < 2 * WINDOW && e > early)
                early = e;
            if (n >= RUN - WINDOW && e > late)
                late = e;
        }
        head = head + 1 == L ? 0 : head + 1;
    }
    /* Errors are a few ulps of the output: compare against at least 2 ulps of 1e3 (2^9 eps
     * each), so that 1 ulp early and 2 ulps late is not taken for drift. */
    floor_err = 1024.0 * REAL_EPS;
    printf("%-16s L = %4zu: max |error| samples 1e4..2e4 = %.3g, last 1e4 of %.0e = %.3g "
           "(relative %.3g)\n", sms_kind_name(kind), L, early, (double)RUN, late, late / 1e3);
    CHECK(late <= 2.0 * (early > floor_err ? early : floor_err));
    CHECK(late <= SMS_TEST_REL_TOL * 1e3);
}

int main(void)
{
    run_case(SMS_RECTANGULAR, 0.1003, 0.0);
    run_case(SMS_HARMONIC, 0.1, 0.0);
    run_case(SMS_DAMPED_HARMONIC, 0.0987, -15.6539);
    run_case(SMS_EXPONENTIAL, 0.1, -3.0);
    run_case(SMS_RECTANGULAR, 2.0, 0.0);
    run_case(SMS_HARMONIC, 2.0476, 0.0);
    run_case(SMS_DAMPED_HARMONIC, 2.0, -1.0);
    run_case(SMS_EXPONENTIAL, 2.0313, -0.5);
    return check_summary("test_smoother_drift");
}
