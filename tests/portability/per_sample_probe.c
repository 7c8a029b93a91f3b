/* SPDX-License-Identifier: Apache-2.0 */
/* Takes the address of every per-sample function (step, process, reset) of one group
 * (PROBE_GROUP) and nothing else, so that a --gc-sections link keeps exactly the code those
 * functions can reach. Never run: check_no_libm.cmake and cortex_m.cmake inspect which libm
 * symbols the linked program still needs.
 * Groups: 1 filters (stage, chain and the families behind them), 2 B-spline, 3 generator,
 * 4 the firmware path: a chain built from precomputed coefficients (coeffs.h), then stepped. */
#include <smoothshaper/smoothshaper.h>

/* void (*)(void) is C's generic function pointer; the addresses are only stored, never called. */
typedef void (*probe_fn)(void);
#define PROBE(f) ((probe_fn)(f))

static const probe_fn runtime_functions[] = {
#if PROBE_GROUP == 1
    PROBE(sms_stage_step), PROBE(sms_stage_process), PROBE(sms_stage_reset),
    PROBE(sms_chain_step), PROBE(sms_chain_process), PROBE(sms_chain_reset),
    PROBE(sms_smoother_step), PROBE(sms_smoother_process), PROBE(sms_smoother_reset),
    PROBE(sms_shaper_step), PROBE(sms_shaper_process), PROBE(sms_shaper_reset),
    PROBE(sms_notch_step), PROBE(sms_notch_process), PROBE(sms_notch_reset)
#elif PROBE_GROUP == 2
    PROBE(sms_bspline_step), PROBE(sms_bspline_reset)
#elif PROBE_GROUP == 3
    PROBE(sms_generator_step), PROBE(sms_generator_reset)
#elif PROBE_GROUP == 4
    PROBE(sms_chain_coeffs_memory_size), PROBE(sms_chain_init_coeffs),
    PROBE(sms_stage_coeffs_memory_size), PROBE(sms_stage_init_coeffs),
    PROBE(sms_smoother_init_coeffs), PROBE(sms_shaper_init_coeffs), PROBE(sms_notch_init_coeffs),
    PROBE(sms_chain_step), PROBE(sms_chain_process), PROBE(sms_chain_reset)
#else
#error "PROBE_GROUP must be 1, 2, 3 or 4"
#endif
};

/* Volatile stores: the optimiser cannot drop the table, so every address is linked in. */
static volatile probe_fn probe_sink;

int main(void)
{
    size_t i;
    for (i = 0; i < sizeof runtime_functions / sizeof runtime_functions[0]; i++) {
        probe_sink = runtime_functions[i];
    }
    return 0;
}
