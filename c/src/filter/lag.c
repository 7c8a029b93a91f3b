/* SPDX-License-Identifier: Apache-2.0 */
/* The lag (DC group delay, the impulse response's centroid) of stages and chains, from their
 * realised designs (align.h). */
#include "smoothshaper/align.h"
#include "core/double_double.h"
#include "core/kind.h"
#include "core/state_identity.h"
#include "filter/identity_config.h"
#include "filter/shaper_designs.h"
#include "filter/smoother_design.h"

/* Complex double-double: re + j im. */
typedef struct lag_cdd {
    sms_dd re, im;
} lag_cdd;

static lag_cdd cdd_add(lag_cdd a, lag_cdd b)
{
    a.re = sms_dd_add(a.re, b.re);
    a.im = sms_dd_add(a.im, b.im);
    return a;
}

static lag_cdd cdd_mul(lag_cdd a, lag_cdd b)
{
    lag_cdd r;
    r.re = sms_dd_sub(sms_dd_mul(a.re, b.re), sms_dd_mul(a.im, b.im));
    r.im = sms_dd_add(sms_dd_mul(a.re, b.im), sms_dd_mul(a.im, b.re));
    return r;
}

static lag_cdd cdd_scale(lag_cdd a, double m)
{
    a.re = sms_dd_mul(a.re, sms_dd_of(m));
    a.im = sms_dd_mul(a.im, sms_dd_of(m));
    return a;
}

/* S0 = sum_{i<n} q^i and S1 = sum_{i<n} i q^i of the complex q, in O(log n) by binary
 * doubling (S1(2m) = S1(m) + q^m (S1(m) + m S0(m)), S0(2m) = S0(m)(1 + q^m)) and single
 * steps, in double-double: no closed form's cancellation for q near 1. */
static void moment_sums(lag_cdd q, size_t n, lag_cdd *s0, lag_cdd *s1)
{
    const lag_cdd zero = { { 0.0, 0.0 }, { 0.0, 0.0 } };
    lag_cdd a0 = zero, a1 = zero, p = zero;
    size_t m = 0, bit = (size_t)1;
    p.re = sms_dd_of(1.0);
    while (bit <= n / 2u)
        bit <<= 1;
    for (; n > 0u && bit > 0u; bit >>= 1) {
        /* m -> 2 m (m and 2 m are exact in a double: window lengths stay below 2^52) */
        const lag_cdd t = cdd_add(a1, cdd_scale(a0, (double)m));
        a0 = cdd_add(a0, cdd_mul(p, a0));
        a1 = cdd_add(a1, cdd_mul(p, t));
        p = cdd_mul(p, p);
        m *= 2u;
        if (n & bit) {   /* m -> m + 1 */
            a0 = cdd_add(a0, p);
            a1 = cdd_add(a1, cdd_scale(p, (double)m));
            p = cdd_mul(p, q);
            ++m;
        }
    }
    *s0 = a0;
    *s1 = a1;
}

sms_status sms_stage_config_lag(const sms_stage_config *config, double Ts, double *lag)
{
    sms_status st;
    if (config == NULL || lag == NULL)
        return SMS_ERR_NULL;
    switch (sms_family_of(config->kind)) {
    case SMS_FAMILY_SMOOTHER: {
        /* the taps are c Re q^i (c Im q^i for the half-sine families) for i < M, and the
         * direct taps: the moments of the geometric series in O(log M) */
        sms_smoother_design d;
        lag_cdd q, s0, s1;
        sms_dd moment, sum;
        size_t j;
        st = sms_smoother_design_make(config, Ts, &d);
        if (st != SMS_OK)
            return st;
        q.re = sms_dd_add(sms_dd_add(sms_dd_of(1.0), sms_dd_of(d.pole_m1_re)),
                          sms_dd_of(d.pole_m1_lo_re));
        q.im = sms_dd_add(sms_dd_of(d.pole_im), sms_dd_of(d.pole_lo_im));
        moment_sums(q, d.window, &s0, &s1);
        moment = sms_dd_mul(sms_dd_of(d.gain), d.family.half_sine ? s1.im : s1.re);
        sum = sms_dd_mul(sms_dd_of(d.gain), d.family.half_sine ? s0.im : s0.re);
        for (j = 0; j < d.n_corrections; ++j) {
            moment = sms_dd_add(moment, sms_dd_mul(sms_dd_of((double)d.correction_delay[j]),
                                                   sms_dd_of(d.correction_gain[j])));
            sum = sms_dd_add(sum, sms_dd_of(d.correction_gain[j]));
        }
        *lag = sms_dd_div(moment, sum).hi;
        return SMS_OK;
    }
    case SMS_FAMILY_SHAPER:
        return sms_shaper_lag(config, Ts, lag);
    case SMS_FAMILY_NOTCH: {
        /* H = 1 + D/A, D(u) = (1 - u)(d0 - d2 u), u = z^-1: u H'(u)/H(u) at u = 1 is
         * -D'(1)/A(1) = (d2 - d0)/(1 + a1 + a2) (D(1) = 0, H(1) = 1) */
        sms_notch f;
        st = sms_notch_init(&f, config, Ts);
        if (st != SMS_OK)
            return st;
        *lag = ((double)f.d2 - (double)f.d0) / (1.0 + (double)f.a1 + (double)f.a2);
        return SMS_OK;
    }
    case SMS_FAMILY_NONE:
        break;
    }
    return SMS_ERR_KIND;
}

sms_status sms_chain_config_lag(const sms_stage_config *configs, size_t n, double Ts, double *lag)
{
    double total = 0.0;
    size_t i;
    if ((configs == NULL && n > 0) || lag == NULL)
        return SMS_ERR_NULL;
    if (n > SMS_CHAIN_MAX_STAGES)
        return SMS_ERR_ORDER;
    for (i = 0; i < n; ++i) {
        double one;
        sms_status st = sms_stage_config_lag(&configs[i], Ts, &one);
        if (st != SMS_OK)
            return st;
        total += one;
    }
    *lag = total;
    return SMS_OK;
}

double sms_stage_lag(const sms_stage *stage)
{
    sms_stage_config c;
    double lag = 0.0;
    const double *id = sms_stage_identity(stage);
    if (stage->kind == SMS_SHAPER_IMPULSES) {
        /* the identity names the impulses by a checksum only: the built taps' centroid */
        const sms_shaper *f = stage->u.shaper;
        double sum = 0.0, moment = 0.0;
        size_t i;
        for (i = 0; i < f->n_taps; ++i) {
            sum += (double)f->taps[i].gain;
            moment += (double)f->taps[i].delay * (double)f->taps[i].gain;
        }
        return moment / sum;
    }
    if (id != NULL && sms_identity_config(id, &c))
        (void)sms_stage_config_lag(&c, id[SMS_ID_TS], &lag);
    return lag;
}

double sms_chain_lag(const sms_chain *chain)
{
    double total = 0.0;
    size_t i;
    for (i = 0; i < chain->n_stages; ++i)
        total += sms_stage_lag(&chain->stages[i]);
    return total;
}
