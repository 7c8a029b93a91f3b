/* SPDX-License-Identifier: Apache-2.0 */
/* What a firmware application links for one axis filter (the README's chain: a harmonic
 * smoother and a ZV shaper on the mode 100 rad/s), three ways (FIRMWARE_PROBE):
 * 1 per-sample only: sms_chain_step on a chain built elsewhere;
 * 2 built from precomputed coefficients, then stepped: examples/firmware/axis_filter.c with
 *   its chain_coeffs.c (the firmware path, coeffs.h);
 * 3 designed on the target (sms_design_for_mode twice, sms_chain_init), then stepped.
 * Never run: cortex_m.cmake links each with --gc-sections, prints its code size, and fails if
 * 1 or 2 link a soft-float double routine or a libm function, or 2 exceeds 4 kB. */
#include "smoothshaper/smoothshaper.h"
#if FIRMWARE_PROBE == 2
#include "axis_filter.h"
#endif

/* The sample interrupt's input and output: volatile, so the loop is kept. */
static volatile sms_real input_sample, output_sample;

#if FIRMWARE_PROBE == 1
static sms_chain chain;

int main(void)
{
    for (;;) {
        sms_real x = input_sample;
        sms_chain_step(&chain, &x);
        output_sample = x;
    }
}
#elif FIRMWARE_PROBE == 2
int main(void)
{
    if (axis_filter_init() != 0)
        return 1;
    for (;;)
        output_sample = axis_filter_sample(input_sample);
}
#elif FIRMWARE_PROBE == 3
static volatile double mode_wn = 100.0, mode_zeta = 0.05, sample_period = 1e-3;
static sms_memory_cell memory[256];
static sms_stage stages[2];
static sms_chain chain;

int main(void)
{
    sms_stage_config cfg[2];
    if (sms_design_for_mode(SMS_HARMONIC, mode_wn, 0.0, 1, &cfg[0]) != SMS_OK
        || sms_design_for_mode(SMS_SHAPER_ZV, mode_wn, mode_zeta, 1, &cfg[1]) != SMS_OK
        || sms_chain_init(&chain, stages, cfg, 2, sample_period, memory, 256) != SMS_OK)
        return 1;
    for (;;) {
        sms_real x = input_sample;
        sms_chain_step(&chain, &x);
        output_sample = x;
    }
}
#else
#error "FIRMWARE_PROBE must be 1, 2 or 3"
#endif
