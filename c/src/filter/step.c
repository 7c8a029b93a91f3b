/* The single-sample entry points: each is its object's process() on one sample, kept in a
 * file of its own so that the compiler does not inline a second copy of each per-sample loop
 * or dispatch into it (one loop per family, one dispatch, in a firmware image). They sit above
 * every filter: the filters' own one-sample calls (a settle's last sample) call process() on
 * one sample directly, so no filter depends on this file. */
#include "smoothshaper/chain.h"

void sms_smoother_step(sms_smoother *f, sms_real *x)
{
    sms_smoother_process(f, x, x, 1u);
}

void sms_shaper_step(sms_shaper *f, sms_real *x)
{
    sms_shaper_process(f, x, x, 1u);
}

void sms_notch_step(sms_notch *f, sms_real *x)
{
    sms_notch_process(f, x, x, 1u);
}

void sms_stage_step(sms_stage *stage, sms_real *x)
{
    sms_stage_process(stage, x, x, 1u);
}

void sms_chain_step(sms_chain *chain, sms_real *x)
{
    sms_chain_process(chain, x, x, 1u);
}
