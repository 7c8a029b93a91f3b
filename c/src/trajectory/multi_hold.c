/* SPDX-License-Identifier: Apache-2.0 */
/* n samples of the multi-axis generator under held targets at a cost bounded whatever n: the
 * profile in closed form between the samples where a move changes, the stages absorbed or
 * jumped to their last window (sms_multi_generator_hold(), multi_generator.h). */
#include <stdint.h>
#include "trajectory/multi_parts.h"

/* Samples until a group's move changes other than by its index: a pending target is planned
 * (or dropped) on that sample (multi_step.c: when not moving at once; while moving once the
 * move time reaches the end of the first transition, or at the arrival if the target came
 * during the stop). UINT64_MAX when nothing is pending. */
static uint64_t group_event(const sms_multi_generator *g, const sms_multi_move *m)
{
    sms_real tr;
    uint64_t lo, hi;
    if (!m->pending)
        return UINT64_MAX;
    if (!m->active)
        return 1u;
    hi = (uint64_t)(m->k_end - m->k);   /* the arrival sample: planned from rest there */
    tr = m->seen > m->T1 ? m->seen : m->T1;
    if (tr > m->T1 + m->tau || sms_multi_group_bounded(g, (size_t)(m - g->move),
                                                       g->sync == SMS_SYNC_PHASE ? g->n_axes : 1u))
        return hi; /* planned from rest at the arrival (position limits: no blend) */
    /* the first sample whose move time reaches T1 (multi_step.c's blend test): t = off + k Ts
     * grows with k. A target seen at a sample that the step already counted in the stop
     * while seen <= T1 + tau (a rounding apart) blends on the next one, as there */
    lo = 1u;
    while (lo < hi) {
        const uint64_t mid = lo + (hi - lo) / 2u;
        const sms_real t = m->off + (sms_real)(size_t)(m->k + mid) * g->Ts_signal;
        if (t >= m->T1)
            hi = mid;
        else
            lo = mid + 1u;
    }
    return lo;
}

/* n samples of the profile alone with the held targets, in closed form between the samples on
 * which a move changes (new targets, plans, drops: at most two per group), out the last
 * sample's. Each move's sample is a function of its index (multi_step.c). */
static void hold_profile(sms_multi_generator *g, const sms_real *target, uint64_t n, sms_real *out)
{
    const size_t groups = g->sync == SMS_SYNC_PHASE ? 1u : g->n_axes;
    size_t i;
    if (SMS_SYNC_PER_AXIS_PLANS(g->sync)) {
        /* the first sample takes the target (and re-plans if it is new); then nothing is
         * pending and every plan's sample is closed form in its index */
        sms_multi_target t;
        sms_multi_sync_rest_target(g, target, &t);
        sms_multi_sync_step_profile(g, &t, out);
        /* a re-plan that waits (position limits: for a state from which it stays inside)
         * is tried sample by sample; it is planned by the running plans' end at the latest */
        for (--n; n > 0u && g->plan_pending; --n)
            sms_multi_sync_step_held(g, out);
        if (n > 0u) {
            sms_multi_sync_skip(g, n - 1u);
            sms_multi_sync_step_held(g, out);
        }
        return;
    }
    while (n > 0u) {
        uint64_t e = UINT64_MAX;
        int fresh = 0;
        for (i = 0; i < g->n_axes; ++i)
            if (sms_multi_takes_position(g, i, target[i]) && target[i] != g->target[i])
                fresh = 1;
        if (!fresh)
            for (i = 0; i < groups; ++i) {
                const uint64_t ev = group_event(g, &g->move[i]);
                if (ev < e)
                    e = ev;
            }
        else
            e = 1u;
        if (e > n)
            e = n;
        for (i = 0; i < groups; ++i) {   /* e - 1 samples of index only */
            sms_multi_move *m = &g->move[i];
            if (m->active) {
                if (e - 1u >= (uint64_t)(m->k_end - m->k)) {
                    m->k = m->k_end;
                    m->active = 0;
                } else {
                    m->k += (size_t)(e - 1u);
                }
            }
        }
        sms_multi_step_profile(g, target, out);
        n -= e;
    }
}

/* At rest: no move running, none pending, every target planned. */
static int profile_at_rest(const sms_multi_generator *g, const sms_real *target)
{
    const size_t groups = g->sync == SMS_SYNC_PHASE ? 1u : g->n_axes;
    size_t i;
    if (SMS_SYNC_PER_AXIS_PLANS(g->sync)) {
        sms_multi_target t;
        sms_multi_sync_rest_target(g, target, &t);
        return !sms_multi_sync_fresh(g, &t) && !sms_multi_sync_busy(g);
    }
    for (i = 0; i < g->n_axes; ++i)
        if (sms_multi_takes_position(g, i, target[i]) && target[i] != g->target[i])
            return 0;
    for (i = 0; i < groups; ++i)
        if (g->move[i].active || g->move[i].pending)
            return 0;
    return 1;
}

#define HOLD_BLOCK 16u

uint64_t sms_multi_generator_hold(sms_multi_generator *g, const sms_real *target, uint64_t n,
                                  sms_real *out)
{
    double bound = 0.0;
    uint64_t window, k, total = n;
    size_t i, m;
    sms_real scratch[4 * SMS_MULTI_MAX_AXES];
    sms_multi_generator probe;
    if (n == 0u)
        return 0u;
    for (i = 0; i < g->n_axes; ++i)
        if (g->chain[i][0].n_stages > 0) {
            const double b = sms_chain_settle_bound(&g->chain[i][0]);
            if (b > bound)
                bound = b;
        }
    /* the alignment delays after the stages: their settle length on top */
    bound += (double)sms_multi_align_settle_length(g);
    if (bound == 0.0) {                   /* no stages: the profile alone */
        hold_profile(g, target, n, out);
        return n;
    }
    if (!(bound < 1e15))
        return 0u;                         /* a notch that does not decay: stepped outside */
    window = (uint64_t)bound + 2u;
    if (n > window) {
        /* the profile to the start of the last `window` samples, on a copy first */
        probe = *g;
        hold_profile(&probe, target, n - window, scratch);
        if (profile_at_rest(&probe, target)) {
            /* the stages see each axis's rest for their last window samples: absorbed */
            *g = probe;
            hold_profile(g, target, window - 1u, scratch);
            for (i = 0; i < g->n_axes; ++i)
                if (g->chain[i][0].n_stages > 0)
                    for (m = 0; m < SMS_MULTI_SIGNALS; ++m)
                        scratch[4 * i + m] = sms_chain_settle(&g->chain[i][m], scratch[4 * i + m],
                                                              n - 1u);
            sms_multi_align_settle(g, scratch, n - 1u);   /* under the stages' outputs */
            sms_multi_generator_step(g, target, out);
            return n;
        }
        /* FIR stages depend only on their last `window` inputs: the profile and the stages'
         * phase jump there, and those samples are stepped. A notch starts them from its stale
         * state, whose transient the window (its settle bound) decays past rounding */
        *g = probe;
        for (i = 0; i < g->n_axes; ++i)
            if (g->chain[i][0].n_stages > 0)
                for (m = 0; m < SMS_MULTI_SIGNALS; ++m)
                    sms_chain_advance(&g->chain[i][m], n - window);
        sms_multi_align_advance(g, n - window);
        n = window;
    }
    /* in blocks: the profile's samples first, then each chain over the block (the profile
     * does not depend on the stages, and a chain's process is its step on a block) */
    while (n > 0u) {
        sms_real prof[HOLD_BLOCK][4 * SMS_MULTI_MAX_AXES], x[HOLD_BLOCK];
        const size_t b = n < HOLD_BLOCK ? (size_t)n : HOLD_BLOCK;
        for (k = 0; k < b; ++k)
            sms_multi_step_profile(g, target, prof[k]);
        for (i = 0; i < g->n_axes; ++i)
            for (m = 0; m < SMS_MULTI_SIGNALS; ++m) {
                for (k = 0; k < b; ++k)
                    x[k] = prof[k][4 * i + m];
                if (g->chain[i][0].n_stages > 0)
                    sms_chain_process(&g->chain[i][m], x, x, b);
                sms_multi_align_process(g, i, m, x, b);
                for (k = 0; k < b; ++k)
                    prof[k][4 * i + m] = x[k];
            }
        for (i = 0; i < 4 * g->n_axes; ++i)
            out[i] = prof[b - 1][i];
        n -= b;
    }
    return total;
}
