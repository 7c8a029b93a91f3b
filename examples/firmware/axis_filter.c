/* SPDX-License-Identifier: Apache-2.0 */
/* The firmware side of axis_filter.h: static memory, the chain built from the coefficients
 * of chain_coeffs.c (regenerate them with the command in its first line), one call of
 * sms_chain_step per sample. */
#include "smoothshaper/coeffs.h"
#include "axis_filter.h"

extern const sms_stage_coeffs axis_x[];
extern const size_t axis_x_stages;

#define AXIS_CELLS 256          /* sms_chain_coeffs_memory_size() of this chain: 205 (double) */
#define AXIS_MAX_STAGES 4

static sms_memory_cell memory[AXIS_CELLS];
static sms_stage stages[AXIS_MAX_STAGES];
static sms_chain chain;

int axis_filter_init(void)
{
    size_t need;
    if (axis_x_stages > AXIS_MAX_STAGES
        || sms_chain_coeffs_memory_size(axis_x, axis_x_stages, &need) != SMS_OK
        || need > AXIS_CELLS)
        return -1;
    return sms_chain_init_coeffs(&chain, stages, axis_x, axis_x_stages, memory, AXIS_CELLS)
           == SMS_OK ? 0 : -1;
}

sms_real axis_filter_sample(sms_real x)
{
    sms_chain_step(&chain, &x);
    return x;
}
