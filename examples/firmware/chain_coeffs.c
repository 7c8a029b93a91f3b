/* SPDX-License-Identifier: Apache-2.0 */
/* Written by: smoothshaper design --stage harmonic:wn=100 --stage zv:wn=100,zeta=0.05 --Ts 0.001 --c-coeffs examples/firmware/chain_coeffs.c --c-name axis_x */
/* Precomputed coefficients (smoothshaper 0.1.0, coeffs.h) of the chain
 *   0: harmonic, T = 0.09424777960769379 s, exact timing
 *   1: zv shaper, wn = 100.0 rad/s, zeta = 0.05, exact timing
 * at Ts = 0.001 s; FIR length 127 samples. Both precisions: SMS_USE_FLOAT picks
 * the float values. On the target, with no design:
 *   extern const sms_stage_coeffs axis_x[];
 *   extern const size_t axis_x_stages;
 *   sms_chain_coeffs_memory_size(axis_x, axis_x_stages, &need);
 *   sms_chain_init_coeffs(&chain, stages, axis_x, axis_x_stages, memory, n_cells); */
#include "smoothshaper/coeffs.h"

extern const sms_stage_coeffs axis_x[2];
extern const size_t axis_x_stages;
const size_t axis_x_stages = 2u;

#ifdef SMS_USE_FLOAT
static const sms_shaper_tap axis_x_taps_1[3] = {{0u, 0.538930058f}, {31u, 0.251713127f},
    {32u, 0.20935683f}};
const sms_stage_coeffs axis_x[2] = {
    {SMS_HARMONIC,
     {5459283.0, 2.0, 4.0, 1.0, 0.001, 0.0, 0.094247779607693788, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0,
      0.0, 0.0},
     {.smoother = {95u, 94u, -0.000555504113f, 0.0333271623f, -3.69575204e-12f,
                   -1.42902401e-09f, 0.0166682079f, 0.0166676398f, -0.000137666502f, 2u,
                   {93u, 94u}, {2.15791879e-05f, 6.44292086e-05f}, 5.8529446570256082e+36}}},
    {SMS_SHAPER_ZV,
     {5459283.0, 2.0, 4.0, 4.0, 0.001, 0.0, 0.0, 0.0, 0.0, 100.0, 0.050000000000000003, 0.0,
      0.0, 0.0, 0.0},
     {.shaper = {33u, 3u, axis_x_taps_1}}}
};
#else
static const sms_shaper_tap axis_x_taps_1[3] = {{0u, 0.53893005073571409},
    {31u, 0.25171312252241551}, {32u, 0.20935682674187023}};
const sms_stage_coeffs axis_x[2] = {
    {SMS_HARMONIC,
     {5459283.0, 2.0, 8.0, 1.0, 0.001, 0.0, 0.094247779607693788, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0,
      0.0, 0.0},
     {.smoother = {95u, 94u, -0.00055550411713149717, 0.033327160836753619,
                   1.5576583214821307e-20, 9.0787125858147927e-19, 0.016668208028636888,
                   0.016667639509536543, -0.00013766650301246685, 2u, {93u, 94u},
                   {2.1579187882672847e-05, 6.4429209767951736e-05}, 3.092078837648601e+306}}},
    {SMS_SHAPER_ZV,
     {5459283.0, 2.0, 8.0, 4.0, 0.001, 0.0, 0.0, 0.0, 0.0, 100.0, 0.050000000000000003, 0.0,
      0.0, 0.0, 0.0},
     {.shaper = {33u, 3u, axis_x_taps_1}}}
};
#endif
