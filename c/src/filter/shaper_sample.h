/* SPDX-License-Identifier: Apache-2.0 */
/* Internal: a shaper's one-sample update, shared by sms_shaper_step()/_process() (shaper.c)
 * and the stage's step (step.c), which runs it in place instead of calling the shaper's step:
 * the per-sample path of a shaper stage is then one call. */
#ifndef SMS_SHAPER_SAMPLE_H
#define SMS_SHAPER_SAMPLE_H

#include "smoothshaper/shaper.h"

/* A shaper has a few taps (2 to 5 past the first for the common designs): GCC's vectoriser
 * (-O3) turns their loop into a gather with a prologue that costs more than the loop, and
 * would in the plain sparse FIR too; the scalar loop is what both are measured as. */
#if defined(__GNUC__) && !defined(__clang__)
#define SMS_FEW_TAPS __attribute__((optimize("no-tree-vectorize")))
#else
#define SMS_FEW_TAPS
#endif

/* One sample: y = x + sum_k g_k (x[n - d_k] - x), the sparse FIR sum_k g_k x[n - d_k] with
 * the newest input taken out. The taps sum to 1, so the two agree to rounding, but this one is
 * exact at rest: once the last L inputs are equal every difference is 0 and y is x, bit for
 * bit (the plain sum of rounded products is not: a ZVD fed 3.7 gives 3.6999999999999993). A
 * tap on delay 0 (the first, for every design) contributes x - x = 0 and is skipped. A tap's
 * sample sits d_k slots behind the head, wrapped once. */
static inline sms_real sms_shaper_sample(const sms_shaper_tap *taps, size_t n_taps,
                                         sms_real *ring, size_t head, size_t len, sms_real x)
{
    sms_real acc = 0;
    size_t k;
    ring[head] = x;
    for (k = taps[0].delay == 0u; k < n_taps; ++k) {
        const size_t d = taps[k].delay, wrapped = head + len - d;
        acc += taps[k].gain * (ring[head >= d ? head - d : wrapped] - x);
    }
    return x + acc;
}

/* sms_shaper_step() itself. */
static inline void sms_shaper_step_inline(sms_shaper *f, sms_real *x)
{
    const size_t head = f->head;
    *x = sms_shaper_sample(f->taps, f->n_taps, f->history, head, f->history_len, *x);
    f->head = head + 1u == f->history_len ? 0u : head + 1u;
}

#endif
