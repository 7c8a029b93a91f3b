/* SPDX-License-Identifier: Apache-2.0 */
/* Consumer of an installed smoothshaper: a unit step through a rectangular stage of
 * N = T/Ts = 8 taps must give the ramp min(n+1, N)/N, in the precision the package says. */
#include <float.h>
#include <stdio.h>
#include <smoothshaper/smoothshaper.h>
/* the area headers are installed beside it and agree with it */
#include <smoothshaper/core.h>
#include <smoothshaper/filter.h>
#include <smoothshaper/identify.h>
#include <smoothshaper/motion.h>

#define N_TAPS 8
#define N_SAMPLES 20

static int check_real_size(void)
{
#ifdef CONSUMER_EXPECT_REAL_SIZE
    /* The float package must hand SMS_USE_FLOAT to its consumers (target or Cflags). */
    if (sizeof(sms_real) != CONSUMER_EXPECT_REAL_SIZE) {
        printf("sizeof(sms_real) = %u, expected %u\n", (unsigned)sizeof(sms_real),
               (unsigned)CONSUMER_EXPECT_REAL_SIZE);
        return 1;
    }
#endif
    return 0;
}

int main(void)
{
    const double Ts = 1e-3;
    /* Each output sums at most N_TAPS terms of size 1/N_TAPS: |error| <= N_TAPS eps. */
    const double tol = 2.0 * N_TAPS * (sizeof(sms_real) == sizeof(float) ? FLT_EPSILON : DBL_EPSILON);
    sms_stage_config config = sms_stage_config_default(SMS_RECTANGULAR);
    sms_memory_cell memory[64];
    size_t n_cells = 0;
    sms_stage stage;
    sms_status status;
    int n, failures = check_real_size();

    config.T = N_TAPS * Ts;
    status = sms_stage_memory_size(&config, Ts, &n_cells);
    if (status != SMS_OK || n_cells > sizeof memory / sizeof memory[0]) {
        printf("memory size query: %s, %u cells\n", sms_status_string(status), (unsigned)n_cells);
        return 1;
    }
    /* A bad sample period is refused by name. */
    status = sms_stage_init(&stage, &config, -Ts, memory, n_cells);
    if (status != SMS_ERR_SAMPLE_PERIOD) {
        printf("init with Ts < 0 returned %s\n", sms_status_string(status));
        return 1;
    }
    status = sms_stage_init(&stage, &config, Ts, memory, n_cells);
    if (status != SMS_OK) {
        printf("init: %s\n", sms_status_string(status));
        return 1;
    }
    if (sms_stage_length(&stage) != N_TAPS) {
        printf("length %u, expected %d\n", (unsigned)sms_stage_length(&stage), N_TAPS);
        failures++;
    }
    for (n = 0; n < N_SAMPLES; n++) {
        sms_real x = 1;
        double expected = (double)(n + 1 < N_TAPS ? n + 1 : N_TAPS) / N_TAPS, err;
        sms_stage_step(&stage, &x);
        err = (double)x - expected;
        if (err > tol || err < -tol) {
            printf("y[%d] = %.17g, expected %.17g (tol %.3g)\n", n, (double)x, expected, tol);
            failures++;
        }
    }
    printf("%s consumer (%s): %s\n", sizeof(sms_real) == sizeof(float) ? "float" : "double",
           sms_kind_name(SMS_RECTANGULAR), failures ? "FAILED" : "step gives the ramp");
    return failures ? 1 : 0;
}
