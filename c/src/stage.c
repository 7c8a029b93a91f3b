/* One interface over the three implementation families; dispatch only, no filtering here. */
#include "smoothshaper/stage.h"
#include "kind.h"

sms_stage_config sms_stage_config_default(sms_kind kind)
{
    sms_stage_config c;
    c.kind = kind;
    c.timing = SMS_TIMING_EXACT;
    c.T = 0.0;
    c.sigma = 0.0;
    c.k = 1u;
    c.wn = 0.0;
    c.zeta = 0.0;
    c.order = kind == SMS_SHAPER_GMZV ? 3u : 1u;   /* GMZV: 3 impulses over 0.75 Td = MZV */
    c.tolerance = 0.05;
    c.duration = 0.75;
    c.notch_pole_zeta = 0.7;
    return c;
}

sms_status sms_stage_buffer_size(const sms_stage_config *config, double Ts, size_t *n_reals)
{
    if (config == NULL || n_reals == NULL)
        return SMS_ERR_NULL;
    switch (sms_family_of(config->kind)) {
    case SMS_FAMILY_SMOOTHER:
        return sms_smoother_buffer_size(config, Ts, n_reals);
    case SMS_FAMILY_SHAPER:
        return sms_shaper_buffer_size(config, Ts, n_reals);
    case SMS_FAMILY_NOTCH: {
        sms_notch probe;
        sms_status st = sms_notch_init(&probe, config, Ts);
        if (st == SMS_OK)
            *n_reals = 0;
        return st;
    }
    case SMS_FAMILY_NONE:
        break;
    }
    return SMS_ERR_KIND;
}

sms_status sms_stage_config_validate(const sms_stage_config *config, double Ts)
{
    size_t unused;
    return sms_stage_buffer_size(config, Ts, &unused);
}

sms_status sms_stage_init(sms_stage *stage, const sms_stage_config *config, double Ts,
                          sms_real *buffer, size_t n_reals)
{
    sms_stage built;
    sms_status st;
    if (stage == NULL || config == NULL)
        return SMS_ERR_NULL;
    switch (sms_family_of(config->kind)) {
    case SMS_FAMILY_SMOOTHER:
        st = sms_smoother_init(&built.u.smoother, config, Ts, buffer, n_reals);
        break;
    case SMS_FAMILY_SHAPER:
        st = sms_shaper_init(&built.u.shaper, config, Ts, buffer, n_reals);
        break;
    case SMS_FAMILY_NOTCH:
        st = sms_notch_init(&built.u.notch, config, Ts);
        break;
    default:
        return SMS_ERR_KIND;
    }
    if (st != SMS_OK)
        return st;
    built.kind = config->kind;
    *stage = built;
    return SMS_OK;
}

void sms_stage_reset(sms_stage *stage, sms_real rest)
{
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER: sms_smoother_reset(&stage->u.smoother, rest); break;
    case SMS_FAMILY_SHAPER: sms_shaper_reset(&stage->u.shaper, rest); break;
    case SMS_FAMILY_NOTCH: sms_notch_reset(&stage->u.notch, rest); break;
    case SMS_FAMILY_NONE: break;
    }
}

void sms_stage_step(sms_stage *stage, sms_real *x)
{
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER: sms_smoother_step(&stage->u.smoother, x); break;
    case SMS_FAMILY_SHAPER: sms_shaper_step(&stage->u.shaper, x); break;
    case SMS_FAMILY_NOTCH: sms_notch_step(&stage->u.notch, x); break;
    case SMS_FAMILY_NONE: break;
    }
}

void sms_stage_process(sms_stage *stage, const sms_real *in, sms_real *out, size_t n)
{
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER: sms_smoother_process(&stage->u.smoother, in, out, n); break;
    case SMS_FAMILY_SHAPER: sms_shaper_process(&stage->u.shaper, in, out, n); break;
    case SMS_FAMILY_NOTCH: sms_notch_process(&stage->u.notch, in, out, n); break;
    case SMS_FAMILY_NONE: break;
    }
}

size_t sms_stage_length(const sms_stage *stage)
{
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER: return stage->u.smoother.length;
    case SMS_FAMILY_SHAPER: return stage->u.shaper.length;
    default: return 0;
    }
}

size_t sms_stage_state_count(const sms_stage *stage)
{
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER: return sms_smoother_state_count(&stage->u.smoother);
    case SMS_FAMILY_SHAPER: return sms_shaper_state_count(&stage->u.shaper);
    case SMS_FAMILY_NOTCH: return sms_notch_state_count(&stage->u.notch);
    case SMS_FAMILY_NONE: break;
    }
    return 0;
}

void sms_stage_get_state(const sms_stage *stage, double *dst)
{
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER: sms_smoother_get_state(&stage->u.smoother, dst); break;
    case SMS_FAMILY_SHAPER: sms_shaper_get_state(&stage->u.shaper, dst); break;
    case SMS_FAMILY_NOTCH: sms_notch_get_state(&stage->u.notch, dst); break;
    case SMS_FAMILY_NONE: break;
    }
}

sms_status sms_stage_set_state(sms_stage *stage, const double *src, size_t n)
{
    if (stage == NULL || src == NULL)
        return SMS_ERR_NULL;
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER: return sms_smoother_set_state(&stage->u.smoother, src, n);
    case SMS_FAMILY_SHAPER: return sms_shaper_set_state(&stage->u.shaper, src, n);
    case SMS_FAMILY_NOTCH: return sms_notch_set_state(&stage->u.notch, src, n);
    case SMS_FAMILY_NONE: break;
    }
    return SMS_ERR_KIND;
}

sms_status sms_stage_check_state(const sms_stage *stage, const double *src, size_t n)
{
    if (stage == NULL || src == NULL)
        return SMS_ERR_NULL;
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER: return sms_smoother_check_state(&stage->u.smoother, src, n);
    case SMS_FAMILY_SHAPER: return sms_shaper_check_state(&stage->u.shaper, src, n);
    case SMS_FAMILY_NOTCH: return sms_notch_check_state(&stage->u.notch, src, n);
    case SMS_FAMILY_NONE: break;
    }
    return SMS_ERR_KIND;
}

size_t sms_stage_buffer_len(const sms_stage *stage)
{
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER: return stage->u.smoother.history_len;
    case SMS_FAMILY_SHAPER: return stage->u.shaper.history_len;
    default: return 0;
    }
}

void sms_stage_rebind(sms_stage *stage, sms_real *buffer)
{
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER: stage->u.smoother.history = buffer; break;
    case SMS_FAMILY_SHAPER: stage->u.shaper.history = buffer; break;
    default: break;
    }
}
