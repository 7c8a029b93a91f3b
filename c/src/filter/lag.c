/* SPDX-License-Identifier: Apache-2.0 */
/* The lag (DC group delay, the impulse response's centroid) of stages and chains, from their
 * realised designs (align.h). */
#include "smoothshaper/align.h"
#include "core/kind.h"
#include "core/state_identity.h"
#include "filter/identity_config.h"
#include "filter/shaper_designs.h"
#include "filter/smoother_design.h"

/* S0 = sum_{i<n} q^i and S1 = sum_{i<n} i q^i of the complex q = (qr, qi), in O(log n) by
 * binary doubling (S1(2m) = S1(m) + q^m (S1(m) + m S0(m)), S0(2m) = S0(m)(1 + q^m)) and
 * single steps, in long double: no closed form's cancellation for q near 1. */
static void moment_sums(long double qr, long double qi, size_t n, long double s0[2],
                        long double s1[2])
{
    long double a0r = 0.0L, a0i = 0.0L, a1r = 0.0L, a1i = 0.0L, pr = 1.0L, pi_ = 0.0L;
    size_t m = 0, bit = (size_t)1;
    while (bit <= n / 2u)
        bit <<= 1;
    for (; n > 0u && bit > 0u; bit >>= 1) {
        /* m -> 2 m */
        const long double tr = a1r + (long double)m * a0r, ti = a1i + (long double)m * a0i;
        const long double nr = a0r + (pr * a0r - pi_ * a0i), ni = a0i + (pr * a0i + pi_ * a0r);
        a1r += pr * tr - pi_ * ti;
        a1i += pr * ti + pi_ * tr;
        a0r = nr;
        a0i = ni;
        {
            const long double sr = pr * pr - pi_ * pi_, si = 2.0L * pr * pi_;
            pr = sr;
            pi_ = si;
        }
        m *= 2u;
        if (n & bit) {   /* m -> m + 1 */
            const long double sr = pr * qr - pi_ * qi, si = pr * qi + pi_ * qr;
            a0r += pr;
            a0i += pi_;
            a1r += (long double)m * pr;
            a1i += (long double)m * pi_;
            pr = sr;
            pi_ = si;
            ++m;
        }
    }
    s0[0] = a0r;
    s0[1] = a0i;
    s1[0] = a1r;
    s1[1] = a1i;
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
        long double s0[2], s1[2], moment, sum;
        size_t j;
        st = sms_smoother_design_make(config, Ts, &d);
        if (st != SMS_OK)
            return st;
        moment_sums(1.0L + (long double)d.pole_m1_re + (long double)d.pole_m1_lo_re,
                    (long double)d.pole_im + (long double)d.pole_lo_im, d.window, s0, s1);
        moment = (long double)d.gain * s1[d.family.half_sine ? 1 : 0];
        sum = (long double)d.gain * s0[d.family.half_sine ? 1 : 0];
        for (j = 0; j < d.n_corrections; ++j) {
            moment += (long double)d.correction_delay[j] * (long double)d.correction_gain[j];
            sum += (long double)d.correction_gain[j];
        }
        *lag = (double)(moment / sum);
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
