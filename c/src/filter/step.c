/* SPDX-License-Identifier: Apache-2.0 */
/* The single-sample entry points of the stage and the chain: each runs its stages' own step
 * (smoother.c, notch.c; a shaper's one-sample update in place, shaper_sample.h, except in a
 * size-optimised build, which keeps the one copy in shaper.c), the
 * per-sample path firmware calls from its sample interrupt. They sit above every filter and
 * no filter calls them. */
#include "smoothshaper/chain.h"
#include "core/kind.h"
#include "filter/shaper_sample.h"

/* The smoothers are the kinds 0 .. 3 (one comparison before their step, the most frequent
 * per-sample stage); the rest as sms_family_of() sorts them. A size-optimised build (-Os)
 * keeps main's one dispatch and calls the shaper's step: the firmware probes' code sizes do
 * not change. */
typedef char smoother_kinds_first[SMS_SMOOTHER_KINDS == 15u ? 1 : -1];

SMS_FEW_TAPS void sms_stage_step(sms_stage *stage, sms_real *x)
{
#ifdef __OPTIMIZE_SIZE__
    /* size-optimised (firmware): one dispatch, the shaper's step called (its one copy) */
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER: sms_smoother_step(stage->u.smoother, x); break;
    case SMS_FAMILY_SHAPER: sms_shaper_step(stage->u.shaper, x); break;
    case SMS_FAMILY_NOTCH: sms_notch_step(stage->u.notch, x); break;
    case SMS_FAMILY_NONE: break;
    }
#else
    if ((unsigned)stage->kind <= (unsigned)SMS_EXPONENTIAL) {
        sms_smoother_step(stage->u.smoother, x);
        return;
    }
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SHAPER: sms_shaper_step_inline(stage->u.shaper, x); break;
    case SMS_FAMILY_NOTCH: sms_notch_step(stage->u.notch, x); break;
    default: break;
    }
#endif
}

SMS_FEW_TAPS void sms_chain_step(sms_chain *chain, sms_real *x)
{
    size_t i;
    for (i = 0; i < chain->n_stages; ++i)
        sms_stage_step(&chain->stages[i], x);
}
