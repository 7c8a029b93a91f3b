/* SPDX-License-Identifier: Apache-2.0 */
/* The finite input range of a stage and of a chain (types.h, SMS_INPUT_MAX), in closed form
 * from the built constants: O(1) per stage, nothing on the per-sample path; and the states a
 * run within a range can reach. */
#include <float.h>
#include <math.h>
#include "smoothshaper/chain.h"
#include "smoothshaper/coeffs.h"
#include "core/kind.h"
#include "filter/shaper_designs.h"

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
static double notch_gain_of(sms_real d0, sms_real d2, sms_real a1_r, sms_real a2_r)
{
    const double a1 = (double)a1_r, a2 = (double)a2_r;
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
    return 1.0 + (fabs((double)d0) + fabs((double)d2)) * e;
}

static double notch_gain(const sms_notch *f)
{
    return notch_gain_of(f->d0, f->d2, f->a1, f->a2);
}

/* A smoother's bound from its direct taps d_j: sum h = 1 with non-negative base taps, so only
 * the direct taps can be negative. */
static double smoother_gain(const sms_real *correction_gain, size_t n_corrections)
{
    double g = 1.0;
    size_t j;
    for (j = 0; j < n_corrections; ++j)
        g += 2.0 * fabs((double)correction_gain[j]);
    return g;
}

/* A shaper's limit from its sum of |g_k|: y = sum g_k x[n - d_k], every partial sum is at most
 * sum |g_k| max |x|. */
static double shaper_limit(double abs_sum)
{
    return (double)SMS_REAL_MAX / (2.0 * abs_sum);
}

/* The bound stage i of a chain sees its inputs within, in units of the chain's input range X,
 * from the product P of the gain bounds before it (see sms_chain_input_max). */
static double chain_range(size_t i, double product)
{
    return i == 0 ? 1.0 : 1.0 + 2.0 * product;
}

/* Largest |x| keeping every sum of the stage finite, before the cap at SMS_INPUT_MAX. */
static double stage_limit(const sms_stage *stage)
{
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER:
        return stage->u.smoother->input_limit;
    case SMS_FAMILY_SHAPER:
        return shaper_limit(shaper_abs_sum(stage->u.shaper));
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

double sms_stage_input_limit(const sms_stage *stage)
{
    return stage_limit(stage);
}

double sms_stage_gain_bound(const sms_stage *stage)
{
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER:
        return smoother_gain(stage->u.smoother->correction_gain,
                             stage->u.smoother->n_corrections);
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
        bound = min2(bound, stage_limit(&chain->stages[i]) / chain_range(i, product));
        product *= sms_stage_gain_bound(&chain->stages[i]);
    }
    return bound;
}

/* stage_limit() and sms_stage_gain_bound() of the stage a config builds, from the constants
 * sms_stage_init() would give it (rounded to sms_real as it rounds them), without memory. */
static sms_status config_limit(const sms_stage_config *config, double Ts, double *limit_out,
                               double *gain_out)
{
    sms_stage_coeffs coeffs;
    double limit = 0.0, gain = HUGE_VAL, abs_sum;
    sms_status st;
    st = sms_stage_config_validate(config, Ts);
    if (st != SMS_OK)
        return st;
    switch (sms_family_of(config->kind)) {
    case SMS_FAMILY_SMOOTHER:
        st = sms_stage_coeffs_make(config, Ts, &coeffs, NULL, 0);
        if (st != SMS_OK)
            return st;
        limit = coeffs.u.smoother.input_limit;
        gain = smoother_gain(coeffs.u.smoother.correction_gain, coeffs.u.smoother.n_corrections);
        break;
    case SMS_FAMILY_SHAPER:
        st = sms_shaper_abs_gain(config, Ts, &abs_sum);
        if (st != SMS_OK)
            return st;
        limit = shaper_limit(abs_sum);
        gain = abs_sum;
        break;
    case SMS_FAMILY_NOTCH:
        st = sms_stage_coeffs_make(config, Ts, &coeffs, NULL, 0);
        if (st != SMS_OK)
            return st;
        limit = (double)SMS_REAL_MAX;   /* as stage_limit(): an overflow restarts the notch */
        gain = notch_gain_of(coeffs.u.notch.d0, coeffs.u.notch.d2, coeffs.u.notch.a1,
                             coeffs.u.notch.a2);
        break;
    case SMS_FAMILY_NONE:
        return SMS_ERR_KIND;
    }
    *limit_out = limit;
    *gain_out = gain;
    return SMS_OK;
}

sms_status sms_stage_config_range(const sms_stage_config *config, double Ts, double *input_max,
                                  double *gain_bound)
{
    double limit, gain;
    sms_status st;
    if (config == NULL || input_max == NULL || gain_bound == NULL)
        return SMS_ERR_NULL;
    st = config_limit(config, Ts, &limit, &gain);
    if (st != SMS_OK)
        return st;
    *input_max = min2(SMS_INPUT_MAX, limit);   /* as sms_stage_input_max() */
    *gain_bound = gain;
    return SMS_OK;
}

sms_status sms_stage_config_limit(const sms_stage_config *config, double Ts, double *limit,
                                  double *gain_bound)
{
    double l, g;
    sms_status st;
    if (config == NULL || limit == NULL || gain_bound == NULL)
        return SMS_ERR_NULL;
    st = config_limit(config, Ts, &l, &g);
    if (st != SMS_OK)
        return st;
    *limit = l;   /* as sms_stage_input_limit() of the built stage */
    *gain_bound = g;
    return SMS_OK;
}

sms_status sms_chain_config_input_max(const sms_stage_config *configs, size_t n, double Ts,
                                      double *input_max)
{
    double bound = SMS_INPUT_MAX, product = 1.0, limit, gain;
    size_t i;
    sms_status st;
    if (configs == NULL || input_max == NULL)
        return SMS_ERR_NULL;
    if (n == 0 || n > SMS_CHAIN_MAX_STAGES)
        return SMS_ERR_ORDER;
    for (i = 0; i < n; ++i) {
        st = config_limit(&configs[i], Ts, &limit, &gain);
        if (st != SMS_OK)
            return st;
        bound = min2(bound, limit / chain_range(i, product));
        product *= gain;
    }
    *input_max = bound;
    return SMS_OK;
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
        const double range = chain_range(i, product);
        st = sms_stage_check_state_range(&chain->stages[i], src + offset, count,
                                         range * x_max * (1.0 + 0x1p-20));
        if (st != SMS_OK)
            return st;
        product *= sms_stage_gain_bound(&chain->stages[i]);
        offset += count;
    }
    return SMS_OK;
}
