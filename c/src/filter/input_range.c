/* SPDX-License-Identifier: Apache-2.0 */
/* The finite input range of a stage and of a chain (types.h, SMS_INPUT_MAX), in closed form
 * from the built constants: O(1) per stage, nothing on the per-sample path; and the states a
 * run within a range can reach. */
#include <float.h>
#include <math.h>
#include "smoothshaper/chain.h"
#include "core/kind.h"

#ifdef SMS_USE_FLOAT
#define SMS_REAL_MAX FLT_MAX
#else
#define SMS_REAL_MAX DBL_MAX
#endif

static double min2(double a, double b)
{
    return a < b ? a : b;
}

/* Sum of |g_k|: the shaper's peak gain and, halved, its partial sums' growth. */
static double shaper_abs_sum(const sms_shaper *f)
{
    double sum = 0.0;
    size_t k;
    for (k = 0; k < f->n_taps; ++k)
        sum += fabs((double)f->taps[k].gain);
    return sum;
}

/* Upper bound on the l1 norm of the notch's impulse response H = 1 + D/A with
 * D = (1 - z^-1)(d0 - d2 z^-1): ||h||_1 <= 1 + (|d0| + |d2|) E, E a bound on the l1 norm of
 * (1 - z^-1)/A. Keeping the difference 1 - z^-1 with 1/A matters: d0 and d2 are of the order
 * of wn Ts, and so is the distance of the poles from 1, so E (d0, d2) stays of order one where
 * ||1/A||_1 alone would grow like 1/(wn Ts)^2.
 * - complex poles r e^{+-j theta}: 1/A has g[n] = r^n sin((n+1) theta)/sin(theta), and
 *   |g[n] - g[n-1]| <= r^(n-1) (2 sin(theta/2) + 1 - r)/sin(theta) for n >= 1, g[0] = 1;
 * - real poles p_s (the one nearer 1) and p_f: (1 - z^-1)/(1 - p_s z^-1) has l1 norm 2 for
 *   p_s >= 0 (also when p_s rounds onto 1) and 1 + (1 - p_s)/(1 + p_s) below 0, and
 *   1/(1 - p_f z^-1) has 1/(1 - |p_f|).
 * The bound is HUGE_VAL only when a pole's magnitude rounds to 1 or more where that matters. */
static double notch_gain(const sms_notch *f)
{
    const double a1 = (double)f->a1, a2 = (double)f->a2;
    const double disc = a1 * a1 - 4.0 * a2;
    double e;
    if (disc < 0.0) {
        const double r = sqrt(a2), c = -a1 / (2.0 * r);   /* cos(theta) */
        const double s = sqrt(1.0 - c * c), half = sqrt(0.5 * (1.0 - c)); /* sin, sin(theta/2) */
        if (!(r < 1.0 && s > 0.0))
            return HUGE_VAL;
        e = 1.0 + (2.0 * half + 1.0 - r) / ((1.0 - r) * s);
    } else {
        const double q = sqrt(disc);
        const double p1 = 0.5 * (-a1 + q), p2 = 0.5 * (-a1 - q);
        const double ps = p1 >= p2 ? p1 : p2, pf = p1 >= p2 ? p2 : p1;  /* nearer 1 first */
        const double first = ps >= 0.0 ? 2.0 : 1.0 + (1.0 - ps) / (1.0 + ps);
        if (!(fabs(pf) < 1.0 && ps > -1.0))
            return HUGE_VAL;
        e = first / (1.0 - fabs(pf));
    }
    return 1.0 + (fabs((double)f->d0) + fabs((double)f->d2)) * e;
}

/* Largest |x| keeping every sum of the stage finite, before the cap at SMS_INPUT_MAX. */
static double stage_limit(const sms_stage *stage)
{
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER:
        return stage->u.smoother->input_limit;
    case SMS_FAMILY_SHAPER:
        /* y = sum g_k x[n - d_k]: every partial sum is at most sum |g_k| max |x| */
        return (double)SMS_REAL_MAX / (2.0 * shaper_abs_sum(stage->u.shaper));
    case SMS_FAMILY_NOTCH:
        /* a finite input with an overflowing result restarts the notch (notch.h) */
        return (double)SMS_REAL_MAX;
    case SMS_FAMILY_NONE:
        break;
    }
    return 0.0;
}

double sms_stage_input_max(const sms_stage *stage)
{
    return min2(SMS_INPUT_MAX, stage_limit(stage));
}

double sms_stage_gain_bound(const sms_stage *stage)
{
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER: {
        /* sum h = 1 with non-negative base taps: only the two direct taps can be negative */
        const sms_smoother *f = stage->u.smoother;
        double g = 1.0;
        size_t j;
        for (j = 0; j < f->n_corrections; ++j)
            g += 2.0 * fabs((double)f->correction_gain[j]);
        return g;
    }
    case SMS_FAMILY_SHAPER:
        return shaper_abs_sum(stage->u.shaper);
    case SMS_FAMILY_NOTCH:
        return notch_gain(stage->u.notch);
    case SMS_FAMILY_NONE:
        break;
    }
    return HUGE_VAL;
}

/* Every stage of a chain rests at the same `rest` and maps x - rest to y - rest through its
 * taps, so with |x|, |rest| <= X stage i sees |x - rest| <= 2 X P_i, P_i the product of the
 * gain bounds before it, and |x| <= (1 + 2 P_i) X. */
double sms_chain_input_max(const sms_chain *chain)
{
    double bound = SMS_INPUT_MAX, product = 1.0;
    size_t i;
    for (i = 0; i < chain->n_stages; ++i) {
        const double range = i == 0 ? 1.0 : 1.0 + 2.0 * product;
        bound = min2(bound, stage_limit(&chain->stages[i]) / range);
        product *= sms_stage_gain_bound(&chain->stages[i]);
    }
    return bound;
}

sms_status sms_stage_check_state_range(const sms_stage *stage, const double *src, size_t n,
                                       double x_max)
{
    if (stage == NULL || src == NULL)
        return SMS_ERR_NULL;
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER:
        return sms_smoother_check_state_range(stage->u.smoother, src, n, x_max);
    case SMS_FAMILY_SHAPER:
        return sms_shaper_check_state_range(stage->u.shaper, src, n, x_max);
    case SMS_FAMILY_NOTCH:
        /* w = (1 - z^-1)(d0 - d2 z^-1)/A of x - rest: at most 2 x_max (G - 1), and never
         * above half the largest sms_real (the next sample could overflow) */
        return sms_notch_check_state_range(stage->u.notch, src, n, x_max,
                                           min2(2.0 * x_max * (notch_gain(stage->u.notch) - 1.0)
                                                * (1.0 + 0x1p-20), 0.5 * (double)SMS_REAL_MAX));
    case SMS_FAMILY_NONE:
        break;
    }
    return SMS_ERR_KIND;
}

/* Stage i sees inputs within (1 + 2 P_i) x_max (see sms_chain_input_max), its rest within
 * x_max. */
sms_status sms_chain_check_state_range(const sms_chain *chain, const double *src, size_t n,
                                       double x_max)
{
    double product = 1.0;
    size_t i, offset = 0;
    sms_status st;
    if (chain == NULL || src == NULL)
        return SMS_ERR_NULL;
    if (n != sms_chain_state_count(chain))
        return SMS_ERR_STATE;
    for (i = 0; i < chain->n_stages; ++i) {
        const size_t count = sms_stage_state_count(&chain->stages[i]);
        const double range = i == 0 ? 1.0 : 1.0 + 2.0 * product;
        st = sms_stage_check_state_range(&chain->stages[i], src + offset, count,
                                         range * x_max * (1.0 + 0x1p-20));
        if (st != SMS_OK)
            return st;
        product *= sms_stage_gain_bound(&chain->stages[i]);
        offset += count;
    }
    return SMS_OK;
}
