/* SPDX-License-Identifier: Apache-2.0 */
/* The README's C example as a complete program: a harmonic smoother and a ZV shaper, both
 * placed on the mode wn = 100 rad/s, filter a unit step sampled at 1 kHz. Built and run by
 * ctest (test "example_chain_step"), which also checks what it prints. */
#include <stdio.h>
#include "smoothshaper/smoothshaper.h"

int main(void)
{
    const double Ts = 1e-3;                   /* sample period [s] */
    sms_stage_config cfg[2];
    sms_stage stages[2];
    sms_chain chain;
    static sms_memory_cell memory[512];       /* caller-owned: stages, taps, delay lines */
    size_t need, n;
    sms_real x = 0;
    sms_status st;

    /* A harmonic smoother and a ZV shaper, both placed on the mode wn = 100 rad/s. */
    sms_design_for_mode(SMS_HARMONIC, 100.0, 0.0, 1, &cfg[0]);
    sms_design_for_mode(SMS_SHAPER_ZV, 100.0, 0.05, 1, &cfg[1]);
    sms_chain_memory_size(cfg, 2, Ts, &need); /* size query: how many cells the chain needs */
    if (need > 512)
        return 1;
    st = sms_chain_init(&chain, stages, cfg, 2, Ts, memory, 512);
    if (st != SMS_OK) {                       /* every status names the bad argument */
        fprintf(stderr, "sms_chain_init: %s\n", sms_status_string(st));
        return 1;
    }
    printf("memory: %zu bytes, FIR length: %zu samples\n", need * sizeof memory[0],
           sms_chain_length(&chain));
    for (n = 0; n < 140; n++) {
        x = 1.0;                              /* a unit step, one sample at a time */
        sms_chain_step(&chain, &x);           /* in place: x is now the output */
        if (n % 20 == 0 || n == 139)
            printf("y[%3zu] = %.6f\n", n, (double)x);
    }
    printf("at rest on 1 exactly: %s\n", x == 1.0 ? "yes" : "no");
    return 0;
}
