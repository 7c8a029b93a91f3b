/* SPDX-License-Identifier: Apache-2.0 */
/* Stages in series over one caller memory block, laid out stage after stage. */
#include <math.h>
#include "smoothshaper/coeffs.h"
#include "core/kind.h"

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

sms_status sms_chain_coeffs_memory_size(const sms_stage_coeffs *coeffs, size_t n, size_t *n_cells)
{
    size_t total = 0, i;
    if (coeffs == NULL || n_cells == NULL)
        return SMS_ERR_NULL;
    if (n == 0 || n > SMS_CHAIN_MAX_STAGES)
        return SMS_ERR_ORDER;
    for (i = 0; i < n; ++i) {
        size_t need;
        sms_status st = sms_stage_coeffs_memory_size(&coeffs[i], &need);
        if (st != SMS_OK)
            return st;
        if (need > (size_t)-1 - total)
            return SMS_ERR_TOO_LONG;
        total += need;
    }
    *n_cells = total;
    return SMS_OK;
}

sms_status sms_chain_init_coeffs(sms_chain *chain, sms_stage *stages,
                                 const sms_stage_coeffs *coeffs, size_t n,
                                 sms_memory_cell *memory, size_t n_cells)
{
    size_t total, offset = 0, i;
    sms_status st;
    if (chain == NULL || stages == NULL || coeffs == NULL)
        return SMS_ERR_NULL;
    st = sms_chain_coeffs_memory_size(coeffs, n, &total);
    if (st != SMS_OK)
        return st;
    if (memory == NULL)
        return SMS_ERR_NULL;
    if (n_cells < total)
        return SMS_ERR_BUFFER_TOO_SMALL;
    /* Every stage checked and the memory large enough: the inits below cannot fail. */
    for (i = 0; i < n; ++i) {
        size_t need;
        (void)sms_stage_coeffs_memory_size(&coeffs[i], &need);
        st = sms_stage_init_coeffs(&stages[i], &coeffs[i], memory + offset, need);
        if (st != SMS_OK)
            return st;
        offset += need;
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

/* ---- holding a constant input (chain.h, sms_chain_hold()) ---- */

/* Samples of a constant input after which a FIR stage has absorbed it, if its input is
 * constant from `offset` samples on (smoother: from its phase then; shaper: its length and
 * one more); 0 for a notch (no closed form: observed, sms_notch_is_settled()). */
static uint64_t fir_settle_after(const sms_stage *st, uint64_t offset)
{
    switch (sms_family_of(st->kind)) {
    case SMS_FAMILY_SMOOTHER: {
        sms_smoother probe = *st->u.smoother;   /* only the phase is read and moved */
        sms_smoother_advance(&probe, offset);
        return sms_smoother_settle_length(&probe);
    }
    case SMS_FAMILY_SHAPER: return (uint64_t)st->u.shaper->length + 1u;
    default: return 0u;
    }
}

/* Advance an absorbed FIR stage by n samples (its values no longer change: only the ring
 * head moves); a settled notch is a fixed point. */
static void advance_absorbed(sms_stage *st, uint64_t n)
{
    switch (sms_family_of(st->kind)) {
    case SMS_FAMILY_SMOOTHER: sms_smoother_advance(st->u.smoother, n); break;
    case SMS_FAMILY_SHAPER: {
        sms_shaper *f = st->u.shaper;
        f->head = (size_t)((f->head + n % f->history_len) % f->history_len);
        break;
    }
    default: break;
    }
}

/* n >= fir_settle_after(st, 0) samples of x in closed form (the absorbed state one sample
 * before the end, then one real sample); the last output. */
static sms_real fir_settle(sms_stage *st, sms_real x, uint64_t n)
{
    if (sms_family_of(st->kind) == SMS_FAMILY_SMOOTHER)
        return sms_smoother_settle(st->u.smoother, x, n);
    {
        sms_shaper *f = st->u.shaper;
        size_t i;
        for (i = 0; i < f->history_len; ++i)
            f->history[i] = x;
        advance_absorbed(st, n - 1u);
        sms_shaper_process(f, &x, &x, 1u);
        return x;
    }
}

/* Stages first..n_stages-1, all FIR, their input x constant from now on: if every one has
 * absorbed it within n - 1 samples (each from the sample its input turns constant), put them
 * in closed form and return 1 with the last output in *y; else 0, nothing touched. */
static int settle_tail(sms_chain *chain, size_t first, sms_real x, uint64_t n, sms_real *y)
{
    uint64_t t = 0;
    size_t i;
    for (i = first; i < chain->n_stages; ++i) {
        uint64_t need;
        if (sms_family_of(chain->stages[i].kind) == SMS_FAMILY_NOTCH)
            return 0;
        need = fir_settle_after(&chain->stages[i], t);
        if (need > n - t)
            return 0;
        t += need;
    }
    for (i = first; i < chain->n_stages; ++i)
        x = fir_settle(&chain->stages[i], x, n);
    *y = x;
    return 1;
}

#define HOLD_BLOCK 256u

void sms_chain_hold(sms_chain *chain, sms_real x, uint64_t n, sms_real *y)
{
    sms_real buf[HOLD_BLOCK], in = x;           /* in: the constant input of stage `live` */
    uint64_t done = 0, since = 0, need = 0;     /* since: when stage live's input turned constant */
    uint64_t frozen_at[SMS_CHAIN_MAX_STAGES];
    sms_real last[SMS_CHAIN_MAX_STAGES];       /* each stage's last output */
    size_t live = 0, i;
    if (n == 0u)
        return;
    if (chain->n_stages == 0u) {
        *y = x;
        return;
    }
    need = fir_settle_after(&chain->stages[0], 0);
    while (live < chain->n_stages) {
        const uint64_t left = n - done;
        size_t b;
        /* the stages from live on see a constant input now: in closed form if they all
         * absorb it in time (tried when live moves: later it only gets harder) */
        if (done == since && settle_tail(chain, live, in, left, y))
            break;
        b = left < HOLD_BLOCK ? (size_t)left : HOLD_BLOCK;
        for (i = 0; i < b; ++i)
            buf[i] = in;
        for (i = live; i < chain->n_stages; ++i) {
            sms_stage_process(&chain->stages[i], buf, buf, b);
            last[i] = buf[b - 1u];
        }
        done += b;
        *y = buf[b - 1u];
        if (done == n)
            break;
        /* Freeze the stages that have absorbed their constant input: from now on their
         * output is their last one, and only their phase moves (advanced at the end). */
        while (live < chain->n_stages) {
            sms_stage *st = &chain->stages[live];
            const int notch = sms_family_of(st->kind) == SMS_FAMILY_NOTCH;
            if (notch && !sms_notch_is_settled(st->u.notch, in)) {
                /* A guard, never reached in the tests: a transient still running at twice the
                 * notch's bound (a rounding cycle in the normal range) is ended there, at its
                 * rest, rather than filtered for ever. */
                if (!((double)(done - since) >= 2.0 * sms_notch_settle_bound(st->u.notch)))
                    break;
                st->u.notch->w1 = st->u.notch->w2 = (sms_real)0;
                last[live] = in;
            } else if (!notch && done - since < need) {
                break;
            }
            frozen_at[live] = done;
            in = last[live];
            since = done;
            ++live;
            if (live < chain->n_stages)
                need = fir_settle_after(&chain->stages[live], 0);
        }
    }
    if (live == chain->n_stages)
        *y = in;
    for (i = 0; i < live; ++i)
        advance_absorbed(&chain->stages[i], n - frozen_at[i]);
}

sms_status sms_chain_hold_cost(const sms_stage_config *configs, size_t n, double Ts, double *samples)
{
    double t = 0.0, total = 0.0;
    size_t i;
    if (configs == NULL || samples == NULL)
        return SMS_ERR_NULL;
    if (n == 0 || n > SMS_CHAIN_MAX_STAGES)
        return SMS_ERR_ORDER;
    for (i = 0; i < n; ++i) {
        double settle, weight = 1.0;
        size_t reals;
        sms_status st = sms_stage_buffer_size(&configs[i], Ts, &reals);
        if (st != SMS_OK)
            return st;
        switch (sms_family_of(configs[i].kind)) {
        case SMS_FAMILY_SMOOTHER: settle = 2.0 * (double)reals + 2.0; break;
        case SMS_FAMILY_SHAPER: {
            /* a sample of an input smoother (one tap per sample of its window) costs its
             * taps over SMS_SHAPER_MAX_TAPS stage-samples */
            size_t taps = 0;
            (void)sms_shaper_tap_count(&configs[i], Ts, &taps);
            settle = (double)reals + 1.0;
            weight = taps > SMS_SHAPER_MAX_TAPS ? (double)taps / SMS_SHAPER_MAX_TAPS : 1.0;
            break;
        }
        default: {
            sms_notch probe;
            (void)sms_notch_init(&probe, &configs[i], Ts);   /* valid: sized above */
            settle = sms_notch_settle_bound(&probe);
            break;
        }
        }
        t += settle;        /* stage i has absorbed a new input by then, at the latest */
        total += t * weight;   /* and it is filtered until then */
    }
    *samples = total;
    return SMS_OK;
}

double sms_chain_settle_bound(const sms_chain *chain)
{
    double total = 0.0;
    size_t i;
    for (i = 0; i < chain->n_stages; ++i) {
        const sms_stage *st = &chain->stages[i];
        switch (sms_family_of(st->kind)) {
        case SMS_FAMILY_SMOOTHER: total += 2.0 * (double)st->u.smoother->window + 2.0; break;
        case SMS_FAMILY_SHAPER: total += (double)st->u.shaper->length + 1.0; break;
        default: total += sms_notch_settle_bound(st->u.notch); break;
        }
    }
    return total;
}

void sms_chain_advance(sms_chain *chain, uint64_t n)
{
    size_t i;
    for (i = 0; i < chain->n_stages; ++i)
        advance_absorbed(&chain->stages[i], n);
}

sms_real sms_chain_settle(sms_chain *chain, sms_real x, uint64_t n)
{
    size_t i;
    for (i = 0; i < chain->n_stages; ++i) {
        sms_stage *st = &chain->stages[i];
        if (sms_family_of(st->kind) == SMS_FAMILY_NOTCH) {
            sms_notch *f = st->u.notch;   /* settled: the fixed point, then one sample */
            f->x1 = f->x2 = x;
            f->w1 = f->w2 = (sms_real)0;
            sms_notch_process(f, &x, &x, 1u);
        } else {
            x = fir_settle(st, x, n);
        }
    }
    return x;
}
