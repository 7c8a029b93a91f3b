/* SPDX-License-Identifier: Apache-2.0 */
/* The multi-axis generator's alignment (multi_generator.h, config.align): each axis's lag, the
 * common lag, and the fractional delays that pad every axis's q, v, a, j to it, with what the
 * generator's step, hold, reset, state and rebinding do with them. */
#include <math.h>
#include "trajectory/multi_parts.h"

/* Reals per cell of caller memory (a cell holds a double). */
#define REALS_PER_CELL (sizeof(sms_memory_cell) / sizeof(sms_real))

sms_status sms_multi_align_lags(const sms_multi_generator_config *c, double Ts, double *axis_lag,
                                double *common)
{
    size_t i;
    double most = 0.0;
    for (i = 0; i < c->n_axes; ++i) {
        sms_status st = sms_chain_config_lag(c->stages[i], c->n_stages[i], Ts, &axis_lag[i]);
        if (st != SMS_OK)
            return st;
        if (axis_lag[i] > most)
            most = axis_lag[i];
    }
    *common = most;
    return SMS_OK;
}

/* The delay of axis i: common - axis_lag[i], never negative (rounding). */
static double pad(double common, double axis)
{
    return common > axis ? common - axis : 0.0;
}

sms_status sms_multi_align_cells(const sms_multi_generator_config *c, double Ts, size_t *cells)
{
    double lags[SMS_MULTI_MAX_AXES], common;
    size_t i, total = 0;
    sms_status st;
    *cells = 0;
    if (!c->align)
        return SMS_OK;
    st = sms_multi_align_lags(c, Ts, lags, &common);
    if (st != SMS_OK)
        return st;
    for (i = 0; i < c->n_axes; ++i) {
        size_t reals;
        st = sms_delay_buffer_size(pad(common, lags[i]), &reals);
        if (st != SMS_OK)
            return SMS_ERR_TOO_LONG;
        total += SMS_MULTI_SIGNALS * ((reals + REALS_PER_CELL - 1u) / REALS_PER_CELL);
    }
    *cells = total;
    return SMS_OK;
}

void sms_multi_align_init(sms_multi_generator *g, const sms_multi_generator_config *c,
                          double Ts, sms_memory_cell *memory)
{
    size_t i, m;
    g->aligned = c->align != 0;
    for (i = 0; i < SMS_MULTI_MAX_AXES; ++i)
        g->axis_lag[i] = 0.0;
    (void)sms_multi_align_lags(c, Ts, g->axis_lag, &g->lag);   /* validated by the size query */
    for (i = 0; i < SMS_MULTI_MAX_AXES; ++i)
        for (m = 0; m < SMS_MULTI_SIGNALS; ++m) {
            sms_delay *d = &g->delay[i][m];
            size_t reals = 0;
            d->ring = NULL;
            d->len = 0;
            if (!g->aligned || i >= c->n_axes)
                continue;
            (void)sms_delay_buffer_size(pad(g->lag, g->axis_lag[i]), &reals);
            (void)sms_delay_init(d, pad(g->lag, g->axis_lag[i]), &memory->r, reals);
            memory += (reals + REALS_PER_CELL - 1u) / REALS_PER_CELL;
        }
}

void sms_multi_align_rebind(sms_multi_generator *g, sms_memory_cell *memory)
{
    size_t i, m;
    if (!g->aligned)
        return;
    for (i = 0; i < g->n_axes; ++i)
        for (m = 0; m < SMS_MULTI_SIGNALS; ++m) {
            g->delay[i][m].ring = &memory->r;
            memory += (g->delay[i][m].len + REALS_PER_CELL - 1u) / REALS_PER_CELL;
        }
}

double sms_multi_generator_lag(const sms_multi_generator *g)
{
    return g->lag * g->Ts;
}

void sms_multi_align_reset(sms_multi_generator *g, const sms_real *position)
{
    size_t i;
    if (!g->aligned)
        return;
    for (i = 0; i < g->n_axes; ++i) {
        sms_delay_reset(&g->delay[i][0], position != NULL ? position[i] : 0);
        sms_delay_reset(&g->delay[i][1], 0);
        sms_delay_reset(&g->delay[i][2], 0);
        sms_delay_reset(&g->delay[i][3], 0);
    }
}

void sms_multi_align_process(sms_multi_generator *g, size_t axis, size_t signal, sms_real *x,
                             size_t n)
{
    if (g->aligned)
        sms_delay_process(&g->delay[axis][signal], x, x, n);
}

void sms_multi_align_step(sms_multi_generator *g, sms_real *out)
{
    size_t i, m;
    if (!g->aligned)
        return;
    for (i = 0; i < g->n_axes; ++i)
        for (m = 0; m < SMS_MULTI_SIGNALS; ++m)
            sms_delay_step(&g->delay[i][m], &out[4 * i + m]);
}

uint64_t sms_multi_align_settle_length(const sms_multi_generator *g)
{
    uint64_t most = 0;
    size_t i;
    if (!g->aligned)
        return 0;
    for (i = 0; i < g->n_axes; ++i)
        if (sms_delay_settle_length(&g->delay[i][0]) > most)
            most = sms_delay_settle_length(&g->delay[i][0]);
    return most;
}

void sms_multi_align_settle(sms_multi_generator *g, const sms_real *x, uint64_t n)
{
    size_t i, m;
    if (!g->aligned)
        return;
    for (i = 0; i < g->n_axes; ++i)
        for (m = 0; m < SMS_MULTI_SIGNALS; ++m)
            (void)sms_delay_settle(&g->delay[i][m], x[4 * i + m], n);
}

void sms_multi_align_advance(sms_multi_generator *g, uint64_t n)
{
    size_t i, m;
    if (!g->aligned)
        return;
    for (i = 0; i < g->n_axes; ++i)
        for (m = 0; m < SMS_MULTI_SIGNALS; ++m)
            sms_delay_advance(&g->delay[i][m], n);
}

size_t sms_multi_align_state_count(const sms_multi_generator *g)
{
    size_t i, m, total = 0;
    if (!g->aligned)
        return 0;
    for (i = 0; i < g->n_axes; ++i)
        for (m = 0; m < SMS_MULTI_SIGNALS; ++m)
            total += sms_delay_state_count(&g->delay[i][m]);
    return total;
}

void sms_multi_align_get_state(const sms_multi_generator *g, double *dst)
{
    size_t i, m;
    if (!g->aligned)
        return;
    for (i = 0; i < g->n_axes; ++i)
        for (m = 0; m < SMS_MULTI_SIGNALS; ++m) {
            sms_delay_get_state(&g->delay[i][m], dst);
            dst += sms_delay_state_count(&g->delay[i][m]);
        }
}

double sms_multi_signal_range(const sms_multi_generator *g, size_t i, size_t m)
{
    const sms_chain *c = &g->chain[i][m];
    switch (m) {
    case 0: return sms_chain_input_max(c);
    case 1: return (double)g->vmax[i] * (1.0 + SMS_LIMIT_RTOL);
    case 2: return (double)g->amax[i] * (1.0 + SMS_LIMIT_RTOL);
    default: return (double)g->jmax[i] * (1.0 + SMS_LIMIT_RTOL);
    }
}

double sms_multi_generator_output_range(const sms_multi_generator *g, size_t axis,
                                        size_t signal)
{
    const sms_chain *c;
    double product = 1.0;
    size_t k;
    if (g == NULL || axis >= g->n_axes || signal >= SMS_MULTI_SIGNALS)
        return 0.0;
    c = &g->chain[axis][signal];
    if (c->n_stages == 0)
        return sms_multi_signal_range(g, axis, signal);
    for (k = 0; k < c->n_stages; ++k)
        product *= sms_stage_gain_bound(&c->stages[k]);
    return (1.0 + 2.0 * product) * sms_multi_signal_range(g, axis, signal) * (1.0 + 0x1p-20);
}

sms_status sms_multi_align_check_state(const sms_multi_generator *g, const double *src)
{
    size_t i, m, k;
    if (!g->aligned)
        return SMS_OK;
    for (i = 0; i < g->n_axes; ++i)
        for (m = 0; m < SMS_MULTI_SIGNALS; ++m) {
            const size_t count = sms_delay_state_count(&g->delay[i][m]);
            /* the ring (after the delay's samples, length and head: sms_delay_get_state)
             * holds the chain's outputs, within what the chain can output */
            const double bound = sms_multi_generator_output_range(g, i, m);
            if (sms_delay_check_state(&g->delay[i][m], src, count) != SMS_OK)
                return SMS_ERR_STATE;
            for (k = 3; k < count; ++k)
                if (!(fabs(src[k]) <= bound))
                    return SMS_ERR_STATE;
            src += count;
        }
    return SMS_OK;
}

void sms_multi_align_set_state(sms_multi_generator *g, const double *src)
{
    size_t i, m;
    if (!g->aligned)
        return;
    for (i = 0; i < g->n_axes; ++i)
        for (m = 0; m < SMS_MULTI_SIGNALS; ++m) {
            const size_t count = sms_delay_state_count(&g->delay[i][m]);
            (void)sms_delay_set_state(&g->delay[i][m], src, count);
            src += count;
        }
}
