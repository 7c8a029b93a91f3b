/* SPDX-License-Identifier: Apache-2.0 */
/* The README's chain stepped through a unit step, printing y[20] (0.060473): compiled for one
 * precision and linked against each library by precision_mix.cmake, which requires the mixed
 * links to fail (precision.h) and the matching ones to print the right value. */
#include <stdio.h>
#include "smoothshaper/smoothshaper.h"

int main(void)
{
    static sms_memory_cell memory[512];
    sms_stage_config cfg[2];
    sms_stage stages[2];
    sms_chain chain;
    sms_real x = 0;
    int n;
    sms_design_for_mode(SMS_HARMONIC, 100.0, 0.0, 1, &cfg[0]);
    sms_design_for_mode(SMS_SHAPER_ZV, 100.0, 0.05, 1, &cfg[1]);
    if (sms_chain_init(&chain, stages, cfg, 2, 1e-3, memory, 512) != SMS_OK)
        return 1;
    for (n = 0; n <= 20; n++) {
        x = 1;
        sms_chain_step(&chain, &x);
    }
    printf("y[20] = %.6f\n", (double)x);
    return 0;
}
