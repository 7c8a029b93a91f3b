/* SPDX-License-Identifier: Apache-2.0 */
/* The lag (DC group delay, the impulse response's centroid) of stages and chains, from their
 * realised designs (align.h). */
#include "smoothshaper/align.h"
#include "core/kind.h"
#include "core/state_identity.h"
#include "filter/identity_config.h"
#include "filter/shaper_designs.h"
#include "filter/smoother_design.h"

sms_status sms_stage_config_lag(const sms_stage_config *config, double Ts, double *lag)
{
    sms_status st;
    if (config == NULL || lag == NULL)
        return SMS_ERR_NULL;
    switch (sms_family_of(config->kind)) {
    case SMS_FAMILY_SMOOTHER: {
        /* the normalised taps one by one: sum h = 1 */
        sms_smoother_design d;
        double moment = 0.0, sum = 0.0;
        size_t i;
        st = sms_smoother_design_make(config, Ts, &d);
        if (st != SMS_OK)
            return st;
        for (i = 0; i < d.length; ++i) {
            const double h = sms_smoother_design_tap(&d, i);
            sum += h;
            moment += (double)i * h;
        }
        *lag = moment / sum;
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
