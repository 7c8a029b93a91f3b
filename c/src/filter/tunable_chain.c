/* SPDX-License-Identifier: Apache-2.0 */
/* Retunable stages in series over one caller memory block, stage after stage. When no stage
 * is switching, the active filters are an ordinary chain (sms_chain over their descriptors),
 * which the long-hold closed forms and the input range use as they are. */
#include "filter/tunable_internal.h"

sms_status sms_tunable_chain_memory_size(const size_t *slot_cells, size_t n, size_t *n_cells)
{
    size_t total = 0, i;
    if (slot_cells == NULL || n_cells == NULL)
        return SMS_ERR_NULL;
    if (n == 0 || n > SMS_CHAIN_MAX_STAGES)
        return SMS_ERR_ORDER;
    for (i = 0; i < n; ++i) {
        size_t need;
        sms_status st = sms_tunable_memory_size(slot_cells[i], &need);
        if (st != SMS_OK)
            return st;
        if (need > (size_t)-1 - total)
            return SMS_ERR_TOO_LONG;
        total += need;
    }
    *n_cells = total;
    return SMS_OK;
}

sms_status sms_tunable_chain_init(sms_tunable_chain *chain, sms_tunable *stages,
                                  const sms_stage_config *configs, const size_t *slot_cells,
                                  size_t n, double Ts, sms_memory_cell *memory, size_t n_cells)
{
    size_t total, offset = 0, i;
    sms_status st;
    if (chain == NULL || stages == NULL || configs == NULL || slot_cells == NULL)
        return SMS_ERR_NULL;
    st = sms_tunable_chain_memory_size(slot_cells, n, &total);
    if (st != SMS_OK)
        return st;
    for (i = 0; i < n; ++i) {
        st = sms_tunable_fits(&configs[i], Ts, slot_cells[i]);
        if (st != SMS_OK)
            return st;
    }
    if (memory == NULL)
        return SMS_ERR_NULL;
    if (n_cells < total)
        return SMS_ERR_BUFFER_TOO_SMALL;
    /* every config valid and fitting: the inits below cannot fail */
    for (i = 0; i < n; ++i) {
        st = sms_tunable_init(&stages[i], &configs[i], Ts, slot_cells[i], memory + offset,
                              2u * slot_cells[i]);
        if (st != SMS_OK)
            return st;
        offset += 2u * slot_cells[i];
    }
    chain->stages = stages;
    chain->n_stages = n;
    chain->memory = memory;
    chain->memory_len = total;
    return SMS_OK;
}

sms_status sms_tunable_chain_retune(sms_tunable_chain *chain, size_t i,
                                    const sms_stage_config *config)
{
    if (chain == NULL || config == NULL)
        return SMS_ERR_NULL;
    if (i >= chain->n_stages)
        return SMS_ERR_ORDER;
    return sms_tunable_retune(&chain->stages[i], config);
}

void sms_tunable_chain_reset(sms_tunable_chain *chain, sms_real rest)
{
    size_t i;
    for (i = 0; i < chain->n_stages; ++i)
        sms_tunable_reset(&chain->stages[i], rest);
}

void sms_tunable_chain_process(sms_tunable_chain *chain, const sms_real *in, sms_real *out,
                               size_t n)
{
    size_t i;
    if (n == 0 || chain->n_stages == 0)
        return;
    sms_tunable_process(&chain->stages[0], in, out, n);
    for (i = 1; i < chain->n_stages; ++i)
        sms_tunable_process(&chain->stages[i], out, out, n);
}

void sms_tunable_chain_step(sms_tunable_chain *chain, sms_real *x)
{
    sms_tunable_chain_process(chain, x, x, 1);
}

int sms_tunable_chain_switching(const sms_tunable_chain *chain)
{
    size_t i;
    for (i = 0; i < chain->n_stages; ++i)
        if (chain->stages[i].switching)
            return 1;
    return 0;
}

/* The active filters as an ordinary chain (descriptors copied; they point at the same
 * instances). */
static sms_chain active_view(const sms_tunable_chain *chain, sms_stage *view)
{
    sms_chain c;
    size_t i;
    for (i = 0; i < chain->n_stages; ++i)
        view[i] = *sms_tunable_active(&chain->stages[i]);
    c.stages = view;
    c.n_stages = chain->n_stages;
    c.memory = chain->memory;
    c.memory_len = 0;
    return c;
}

size_t sms_tunable_chain_length(const sms_tunable_chain *chain)
{
    sms_stage view[SMS_CHAIN_MAX_STAGES];
    const sms_chain c = active_view(chain, view);
    return sms_chain_length(&c);
}

double sms_tunable_chain_input_max(const sms_tunable_chain *chain)
{
    sms_stage view[SMS_CHAIN_MAX_STAGES];
    double bound = SMS_INPUT_MAX, product = 1.0;
    size_t i;
    if (!sms_tunable_chain_switching(chain)) {
        const sms_chain c = active_view(chain, view);
        return sms_chain_input_max(&c);
    }
    /* as sms_chain_input_max(), with each stage's limit (before the cap, which the bound's
     * start applies) and gain over both its filters */
    for (i = 0; i < chain->n_stages; ++i) {
        const double range = i == 0 ? 1.0 : 1.0 + 2.0 * product;
        const double limit = sms_tunable_input_limit(&chain->stages[i]) / range;
        if (limit < bound)
            bound = limit;
        product *= sms_tunable_gain_bound(&chain->stages[i]);
    }
    return bound;
}

double sms_tunable_chain_retune_input_max(const sms_tunable_chain *chain, const int *retuned,
                                          const double *input_max, const double *gain_bound)
{
    double bound = SMS_INPUT_MAX, product = 1.0;
    size_t i;
    /* as the switching case of sms_tunable_chain_input_max(), each stage over every phase to
     * come: its limit (uncapped: the bound starts at SMS_INPUT_MAX, which caps the result
     * once) the smallest and its gain the largest of now, of the switch from its active filter
     * to the new one (sms_tunable_gain_bound() of that switch) and after it */
    for (i = 0; i < chain->n_stages; ++i) {
        const sms_tunable *t = &chain->stages[i];
        const double range = i == 0 ? 1.0 : 1.0 + 2.0 * product;
        double limit = sms_tunable_input_limit(t), gain = sms_tunable_gain_bound(t);
        if (retuned[i]) {
            const double next = 1.0 + 2.0 * gain_bound[i]
                                + 2.0 * sms_stage_gain_bound(sms_tunable_active(t));
            if (input_max[i] < limit)
                limit = input_max[i];
            if (next > gain)
                gain = next;
        }
        if (limit / range < bound)
            bound = limit / range;
        product *= gain;
    }
    return bound;
}

void sms_tunable_chain_hold(sms_tunable_chain *chain, sms_real x, uint64_t n, sms_real *y)
{
    sms_real v = x;
    if (n == 0)
        return;
    /* a switch in progress ends within its fade; the chain's closed forms take the rest but
     * the last sample, which is stepped so that every stage records its last input */
    while (n > 1u && sms_tunable_chain_switching(chain)) {
        v = x;
        sms_tunable_chain_step(chain, &v);
        --n;
    }
    if (n > 1u) {
        sms_stage view[SMS_CHAIN_MAX_STAGES];
        sms_chain c = active_view(chain, view);
        sms_chain_hold(&c, x, n - 1u, &v);
    }
    v = x;
    sms_tunable_chain_step(chain, &v);
    *y = v;
}

size_t sms_tunable_chain_state_count(const sms_tunable_chain *chain)
{
    size_t i, total = 0;
    for (i = 0; i < chain->n_stages; ++i)
        total += sms_tunable_state_count(&chain->stages[i]);
    return total;
}

void sms_tunable_chain_get_state(const sms_tunable_chain *chain, double *dst)
{
    size_t i;
    for (i = 0; i < chain->n_stages; ++i) {
        sms_tunable_get_state(&chain->stages[i], dst);
        dst += sms_tunable_state_count(&chain->stages[i]);
    }
}

sms_status sms_tunable_chain_set_state(sms_tunable_chain *chain, const double *src, size_t n)
{
    size_t i, offset = 0;
    if (chain == NULL || src == NULL)
        return SMS_ERR_NULL;
    /* every part checked before any is written; each part's length as the saving stage had
     * it (a stage switching now may have saved no switch, and the other way round) */
    for (i = 0; i < chain->n_stages; ++i) {
        const size_t count = sms_tunable_saved_state_count(&chain->stages[i], src + offset,
                                                           n - offset);
        sms_status st;
        if (count == 0 || count > n - offset)
            return SMS_ERR_STATE;
        st = sms_tunable_check_state(&chain->stages[i], src + offset, count);
        if (st != SMS_OK)
            return st;
        offset += count;
    }
    if (offset != n)
        return SMS_ERR_STATE;
    offset = 0;
    for (i = 0; i < chain->n_stages; ++i) {
        const size_t count = sms_tunable_saved_state_count(&chain->stages[i], src + offset,
                                                           n - offset);
        (void)sms_tunable_set_state(&chain->stages[i], src + offset, count);
        offset += count;
    }
    return SMS_OK;
}

void sms_tunable_chain_rebind(sms_tunable_chain *chain, sms_tunable *stages,
                              sms_memory_cell *memory)
{
    size_t i, offset = 0;
    chain->stages = stages;
    chain->memory = memory;
    for (i = 0; i < chain->n_stages; ++i) {
        sms_tunable_rebind(&stages[i], memory + offset);
        offset += (size_t)stages[i].n_slots * stages[i].slot_cells;
    }
}
