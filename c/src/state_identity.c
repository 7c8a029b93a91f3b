/* The identity header of saved stage states (config.h): tag, format version, precision, kind,
 * Ts and the configuration fields the kind reads. */
#include "state_identity.h"
#include "kind.h"

enum {
    ID_TAG, ID_VERSION, ID_PRECISION, ID_KIND, ID_TS, ID_TIMING, ID_T, ID_SIGMA, ID_K, ID_WN,
    ID_ZETA, ID_ORDER, ID_TOLERANCE, ID_NOTCH_POLE_ZETA, ID_DURATION
};

void sms_state_identity(const sms_stage_config *c, double Ts, double id[SMS_STATE_IDENTITY_COUNT])
{
    const sms_family fam = sms_family_of(c->kind);
    size_t i;
    for (i = 0; i < SMS_STATE_IDENTITY_COUNT; ++i)
        id[i] = 0.0;
    id[ID_TAG] = SMS_STATE_TAG;
    id[ID_VERSION] = SMS_STATE_VERSION;
    id[ID_PRECISION] = (double)sizeof(sms_real);
    id[ID_KIND] = (double)c->kind;
    id[ID_TS] = Ts;
    if (fam == SMS_FAMILY_SMOOTHER) {
        id[ID_TIMING] = (double)c->timing;
        id[ID_T] = c->T;
        id[ID_SIGMA] = c->kind == SMS_DAMPED_HARMONIC || c->kind == SMS_EXPONENTIAL ? c->sigma : 0.0;
        id[ID_K] = (double)c->k;
    } else if (fam == SMS_FAMILY_SHAPER) {
        id[ID_TIMING] = (double)c->timing;
        id[ID_WN] = c->wn;
        id[ID_ZETA] = c->zeta;
        id[ID_ORDER] = c->kind == SMS_SHAPER_ZVN || c->kind == SMS_SHAPER_GMZV ? (double)c->order : 0.0;
        id[ID_TOLERANCE] = c->kind == SMS_SHAPER_EI || c->kind == SMS_SHAPER_EI2
                           || c->kind == SMS_SHAPER_EI3 ? c->tolerance : 0.0;
        id[ID_DURATION] = c->kind == SMS_SHAPER_GMZV ? c->duration : 0.0;
    } else if (fam == SMS_FAMILY_NOTCH) {
        id[ID_WN] = c->wn;
        id[ID_ZETA] = c->zeta;
        id[ID_NOTCH_POLE_ZETA] = c->notch_pole_zeta;
    }
}

sms_status sms_state_identity_check(const double id[SMS_STATE_IDENTITY_COUNT], const double *saved)
{
    static const sms_status field_status[SMS_STATE_IDENTITY_COUNT] = {
        SMS_ERR_STATE_FORMAT, SMS_ERR_STATE_FORMAT, SMS_ERR_STATE_PRECISION, SMS_ERR_STATE_KIND,
        SMS_ERR_STATE_TS, SMS_ERR_STATE_TIMING, SMS_ERR_STATE_T, SMS_ERR_STATE_SIGMA,
        SMS_ERR_STATE_K, SMS_ERR_STATE_WN, SMS_ERR_STATE_ZETA, SMS_ERR_STATE_ORDER,
        SMS_ERR_STATE_TOLERANCE, SMS_ERR_STATE_NOTCH_POLE_ZETA, SMS_ERR_STATE_DURATION
    };
    size_t i;
    for (i = 0; i < SMS_STATE_IDENTITY_COUNT; ++i)
        if (!(saved[i] == id[i]))   /* NaN differs too */
            return field_status[i];
    return SMS_OK;
}
