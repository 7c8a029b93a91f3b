/* SPDX-License-Identifier: Apache-2.0 */
/* The identity header of saved states (config.h): tag, format version, precision, kind, Ts,
 * then the configuration fields of the object (for a stage: those its kind reads). */
#include <stdint.h>
#include <string.h>
#include "core/state_identity.h"
#include "core/kind.h"

/* A stage's fields after the common head. */
enum {
    ID_TIMING = SMS_STATE_IDENTITY_HEAD, ID_T, ID_SIGMA, ID_K, ID_WN, ID_ZETA, ID_ORDER,
    ID_TOLERANCE, ID_NOTCH_POLE_ZETA, ID_DURATION
};

void sms_state_identity_head(double *id, double kind, double Ts)
{
    id[SMS_ID_TAG] = SMS_STATE_TAG;
    id[SMS_ID_VERSION] = SMS_STATE_VERSION;
    id[SMS_ID_PRECISION] = (double)sizeof(sms_real);
    id[SMS_ID_KIND] = kind;
    id[SMS_ID_TS] = Ts;
}

sms_status sms_state_identity_compare(const double *id, const double *saved, size_t n_fields,
                                      const sms_status *field_status)
{
    static const sms_status head_status[SMS_STATE_IDENTITY_HEAD] = {
        SMS_ERR_STATE_FORMAT, SMS_ERR_STATE_FORMAT, SMS_ERR_STATE_PRECISION, SMS_ERR_STATE_KIND,
        SMS_ERR_STATE_TS
    };
    size_t i;
    for (i = 0; i < SMS_STATE_IDENTITY_HEAD + n_fields; ++i)
        if (!(saved[i] == id[i]))   /* NaN differs too */
            return i < SMS_STATE_IDENTITY_HEAD ? head_status[i]
                                               : field_status[i - SMS_STATE_IDENTITY_HEAD];
    return SMS_OK;
}

/* User-defined impulses: FNV-1a (64 bit) over the bit patterns of the first n amplitudes and
 * times, its top 53 bits as an exact integer-valued double. The same impulses always give the
 * same value (on any byte order: the pattern is read as an integer); a state saved for other
 * impulses differs with probability 1 - 2^-53. */
static double impulses_checksum(const sms_stage_config *c)
{
    uint64_t h = 14695981039346656037u, word;
    unsigned i, n = c->order < SMS_SHAPER_MAX_IMPULSES ? c->order : SMS_SHAPER_MAX_IMPULSES;
    for (i = 0; i < 2u * n; ++i) {
        double v = i < n ? c->amplitudes[i] : c->times[i - n];
        unsigned b;
        memcpy(&word, &v, sizeof word);
        for (b = 0; b < 64u; b += 8u) {
            h ^= (word >> b) & 0xffu;
            h *= 1099511628211u;
        }
    }
    return (double)(h >> 11);
}

/* The kinds that read each shaper field (shaper.h). */
static int reads_zeta(sms_kind k)
{
    return k != SMS_SHAPER_IMPULSES && k != SMS_SMOOTH_EI2 && k != SMS_SMOOTH_ZVD_EI
           && k != SMS_SMOOTH_SI;
}

void sms_state_identity(const sms_stage_config *c, double Ts, double id[SMS_STATE_IDENTITY_COUNT])
{
    const sms_family fam = sms_family_of(c->kind);
    size_t i;
    for (i = SMS_STATE_IDENTITY_HEAD; i < SMS_STATE_IDENTITY_COUNT; ++i)
        id[i] = 0.0;
    sms_state_identity_head(id, (double)c->kind, Ts);
    if (fam == SMS_FAMILY_SMOOTHER) {
        id[ID_TIMING] = (double)c->timing;
        id[ID_T] = c->T;
        id[ID_SIGMA] = c->kind == SMS_DAMPED_HARMONIC || c->kind == SMS_EXPONENTIAL ? c->sigma : 0.0;
        id[ID_K] = (double)c->k;
    } else if (fam == SMS_FAMILY_SHAPER && c->kind == SMS_SHAPER_IMPULSES) {
        /* no mode: T holds the last impulse time, order the count, duration a checksum */
        id[ID_TIMING] = (double)c->timing;
        id[ID_ORDER] = (double)c->order;
        id[ID_T] = c->order >= 1u && c->order <= SMS_SHAPER_MAX_IMPULSES
                   ? c->times[c->order - 1u] : 0.0;
        id[ID_DURATION] = impulses_checksum(c);
    } else if (fam == SMS_FAMILY_SHAPER) {
        const int gmzv_or_si = c->kind == SMS_SHAPER_GMZV || c->kind == SMS_SHAPER_SI;
        id[ID_TIMING] = (double)c->timing;
        id[ID_WN] = c->wn;
        id[ID_ZETA] = reads_zeta(c->kind) ? c->zeta : 0.0;
        id[ID_ORDER] = c->kind == SMS_SHAPER_ZVN || gmzv_or_si ? (double)c->order : 0.0;
        id[ID_TOLERANCE] = c->kind == SMS_SHAPER_EI || c->kind == SMS_SHAPER_EI2
                           || c->kind == SMS_SHAPER_EI3 || c->kind == SMS_SHAPER_SI
                           ? c->tolerance : 0.0;
        id[ID_DURATION] = gmzv_or_si ? c->duration : 0.0;
    } else if (fam == SMS_FAMILY_NOTCH) {
        id[ID_WN] = c->wn;
        id[ID_ZETA] = c->zeta;
        id[ID_NOTCH_POLE_ZETA] = c->notch_pole_zeta;
    }
}

sms_status sms_state_identity_check(const double id[SMS_STATE_IDENTITY_COUNT], const double *saved)
{
    static const sms_status field_status[SMS_STATE_IDENTITY_COUNT - SMS_STATE_IDENTITY_HEAD] = {
        SMS_ERR_STATE_TIMING, SMS_ERR_STATE_T, SMS_ERR_STATE_SIGMA, SMS_ERR_STATE_K,
        SMS_ERR_STATE_WN, SMS_ERR_STATE_ZETA, SMS_ERR_STATE_ORDER, SMS_ERR_STATE_TOLERANCE,
        SMS_ERR_STATE_NOTCH_POLE_ZETA, SMS_ERR_STATE_DURATION
    };
    return sms_state_identity_compare(id, saved, SMS_STATE_IDENTITY_COUNT - SMS_STATE_IDENTITY_HEAD,
                                      field_status);
}
