/* The finite input range of a stage and of a chain (types.h, SMS_INPUT_MAX), in closed form
 * from the built constants: O(1) per stage, nothing on the per-sample path. */
#include <float.h>
#include <math.h>
#include "smoothshaper/chain.h"
#include "kind.h"

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

/* Upper bound on the l1 norm of the notch's impulse response H = 1 + D/A,
 * D = (1 - z^-1)(d0 - d2 z^-1): ||h||_1 <= 1 + 2 (|d0| + |d2|) ||1/A||_1, and the impulse
 * response of 1/A = 1/((1 - p1 z^-1)(1 - p2 z^-1)) is bounded term by term by the
 * convolution of |p1|^n and |p2|^n, whose sum is 1/((1 - |p1|)(1 - |p2|)). */
static double notch_gain(const sms_notch *f)
{
    const double a1 = (double)f->a1, a2 = (double)f->a2;
    const double disc = a1 * a1 - 4.0 * a2;
    double m1, m2, bound;
    if (disc < 0.0) {
        m1 = m2 = sqrt(a2);
    } else {
        const double s = sqrt(disc);
        m1 = fabs(-a1 + s) * 0.5;
        m2 = fabs(-a1 - s) * 0.5;
    }
    if (!(m1 < 1.0 && m2 < 1.0))
        return HUGE_VAL;
    bound = 1.0 + 2.0 * (fabs((double)f->d0) + fabs((double)f->d2)) / ((1.0 - m1) * (1.0 - m2));
    return bound;
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
