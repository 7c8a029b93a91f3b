/* The single-sample entry points of the filter families: each is its family's process() on
 * one sample, kept in a file of its own so that the compiler does not inline a second copy of
 * each per-sample loop into it (one loop per family in a firmware image). */
#include "smoothshaper/notch.h"
#include "smoothshaper/shaper.h"
#include "smoothshaper/smoother.h"

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
