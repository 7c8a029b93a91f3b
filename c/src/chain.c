/* Stages in series over one caller memory block, laid out stage after stage. */
#include "smoothshaper/chain.h"

/* Validate every config and size its stage (need[i] cells); the total into *n_cells. */
static sms_status size_stages(const sms_stage_config *configs, size_t n, double Ts,
                              size_t need[SMS_CHAIN_MAX_STAGES], size_t *n_cells)
{
    size_t total = 0, i;
    if (n == 0 || n > SMS_CHAIN_MAX_STAGES)
        return SMS_ERR_ORDER;
    for (i = 0; i < n; ++i) {
        sms_status st = sms_stage_memory_size(&configs[i], Ts, &need[i]);
        if (st != SMS_OK)
            return st;
        if (need[i] > (size_t)-1 - total)
            return SMS_ERR_TOO_LONG;
        total += need[i];
    }
    *n_cells = total;
    return SMS_OK;
}

sms_status sms_chain_memory_size(const sms_stage_config *configs, size_t n, double Ts, size_t *n_cells)
{
    size_t need[SMS_CHAIN_MAX_STAGES];
    if (configs == NULL || n_cells == NULL)
        return SMS_ERR_NULL;
    return size_stages(configs, n, Ts, need, n_cells);
}

sms_status sms_chain_init(sms_chain *chain, sms_stage *stages, const sms_stage_config *configs,
                          size_t n, double Ts, sms_memory_cell *memory, size_t n_cells)
{
    size_t need[SMS_CHAIN_MAX_STAGES], total, offset = 0, i;
    sms_status st;
    if (chain == NULL || stages == NULL || configs == NULL)
        return SMS_ERR_NULL;
    st = size_stages(configs, n, Ts, need, &total);
    if (st != SMS_OK)
        return st;
    if (memory == NULL)
        return SMS_ERR_NULL;
    if (n_cells < total)
        return SMS_ERR_BUFFER_TOO_SMALL;
    /* Every config is valid and the memory is large enough: the inits below cannot fail. */
    for (i = 0; i < n; ++i) {
        st = sms_stage_init(&stages[i], &configs[i], Ts, memory + offset, need[i]);
        if (st != SMS_OK)
            return st;
        offset += need[i];
    }
    chain->stages = stages;
    chain->n_stages = n;
    chain->memory = memory;
    chain->memory_len = total;
    return SMS_OK;
}

void sms_chain_reset(sms_chain *chain, sms_real rest)
{
    size_t i;
    for (i = 0; i < chain->n_stages; ++i)
        sms_stage_reset(&chain->stages[i], rest);
}

void sms_chain_process(sms_chain *chain, const sms_real *in, sms_real *out, size_t n)
{
    size_t i;
    if (n == 0 || chain->n_stages == 0)
        return;
    sms_stage_process(&chain->stages[0], in, out, n);
    for (i = 1; i < chain->n_stages; ++i)
        sms_stage_process(&chain->stages[i], out, out, n);
}

size_t sms_chain_length(const sms_chain *chain)
{
    size_t i, total = 0, fir_stages = 0;
    for (i = 0; i < chain->n_stages; ++i) {
        size_t len = sms_stage_length(&chain->stages[i]);
        if (len > 0) {
            total += len;
            ++fir_stages;
        }
    }
    return fir_stages > 0 ? total - (fir_stages - 1) : 0;
}

size_t sms_chain_state_count(const sms_chain *chain)
{
    size_t i, total = 0;
    for (i = 0; i < chain->n_stages; ++i)
        total += sms_stage_state_count(&chain->stages[i]);
    return total;
}

void sms_chain_get_state(const sms_chain *chain, double *dst)
{
    size_t i;
    for (i = 0; i < chain->n_stages; ++i) {
        sms_stage_get_state(&chain->stages[i], dst);
        dst += sms_stage_state_count(&chain->stages[i]);
    }
}

sms_status sms_chain_set_state(sms_chain *chain, const double *src, size_t n)
{
    size_t i, offset = 0;
    if (chain == NULL || src == NULL)
        return SMS_ERR_NULL;
    if (n != sms_chain_state_count(chain)) {
        /* A state of another configuration has another length, often: name the field of the
         * first stage whose identity differs (the stages before it match, and so their
         * lengths). */
        for (i = 0; i < chain->n_stages && offset + SMS_STATE_IDENTITY_COUNT <= n; ++i) {
            size_t count = sms_stage_state_count(&chain->stages[i]);
            sms_status st = sms_stage_check_state(&chain->stages[i], src + offset,
                                                  n - offset < count ? n - offset : count);
            if (st <= SMS_ERR_STATE_FORMAT)
                return st;
            offset += count;
        }
        return SMS_ERR_STATE;
    }
    /* Check every stage before writing any, so a bad vector leaves the whole chain as it was. */
    for (i = 0; i < chain->n_stages; ++i) {
        size_t count = sms_stage_state_count(&chain->stages[i]);
        sms_status st = sms_stage_check_state(&chain->stages[i], src + offset, count);
        if (st != SMS_OK)
            return st;
        offset += count;
    }
    for (i = 0; i < chain->n_stages; ++i) {
        size_t count = sms_stage_state_count(&chain->stages[i]);
        sms_status st = sms_stage_set_state(&chain->stages[i], src, count);
        if (st != SMS_OK)
            return st;
        src += count;
    }
    return SMS_OK;
}

void sms_chain_rebind(sms_chain *chain, sms_stage *stages, sms_memory_cell *memory)
{
    size_t i, offset = 0;
    chain->stages = stages;
    chain->memory = memory;
    for (i = 0; i < chain->n_stages; ++i) {
        sms_stage_rebind(&stages[i], memory + offset);
        offset += sms_stage_memory_len(&stages[i]);
    }
}
