/* SPDX-License-Identifier: Apache-2.0 */
/* The single-sample entry points of the stage and the chain: each calls its stages' own step
 * functions (smoother.c, shaper.c, notch.c), the per-sample path firmware calls from its
 * sample interrupt. They sit above every filter and no filter calls them. */
#include "smoothshaper/chain.h"
#include "core/kind.h"

void sms_stage_step(sms_stage *stage, sms_real *x)
{
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER: sms_smoother_step(stage->u.smoother, x); break;
    case SMS_FAMILY_SHAPER: sms_shaper_step(stage->u.shaper, x); break;
    case SMS_FAMILY_NOTCH: sms_notch_step(stage->u.notch, x); break;
    case SMS_FAMILY_NONE: break;
    }
}

void sms_chain_step(sms_chain *chain, sms_real *x)
{
    size_t i;
    for (i = 0; i < chain->n_stages; ++i)
        sms_stage_step(&chain->stages[i], x);
}
