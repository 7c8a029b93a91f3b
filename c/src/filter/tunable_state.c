/* SPDX-License-Identifier: Apache-2.0 */
/* A retunable stage's saved state, its configurations and its rebinding. The state is the
 * head (config.h) with the tunable's own fields, the identities of the active and the old
 * configuration (fixed size, so they can be read without knowing either), then the stages'
 * own states. */
#include <math.h>

#include "filter/tunable_internal.h"
#include "core/kind.h"
#include "core/state_identity.h"
#include "filter/identity_config.h"

/* Offsets in a saved state. */
enum {
    ST_SLOT_CELLS = SMS_STATE_IDENTITY_HEAD, ST_SWITCHING, ST_FADE, ST_LAST, ST_HOLD,
    ST_ACTIVE_ID = SMS_TUNABLE_STATE_HEAD,
    ST_OLD_ID = ST_ACTIVE_ID + SMS_STATE_IDENTITY_COUNT,
    ST_STAGES = ST_OLD_ID + SMS_STATE_IDENTITY_COUNT
};

static int whole(double v, double most)
{
    return v >= 0.0 && v <= most && v == (double)(unsigned long)v;
}

sms_stage_config sms_tunable_config(const sms_tunable *t)
{
    sms_stage_config c = sms_stage_config_default(t->slot[t->active].kind);
    (void)sms_identity_config(sms_stage_identity(&t->slot[t->active]), &c);
    return c;
}

static const sms_stage *old_stage(const sms_tunable *t)
{
    return t->switching ? &t->slot[1u - t->active] : NULL;
}

/* The stage a saved state's old filter is loaded into: the other slot, built (by the retune
 * that brought the tunable to this configuration, or an earlier one); NULL if none. */
static const sms_stage *other_slot(const sms_tunable *t)
{
    const sms_stage *s = &t->slot[1u - t->active];
    return sms_family_of(s->kind) != SMS_FAMILY_NONE ? s : NULL;
}

size_t sms_tunable_state_count(const sms_tunable *t)
{
    const sms_stage *old = old_stage(t);
    return ST_STAGES + sms_stage_state_count(&t->slot[t->active])
           + (old != NULL ? sms_stage_state_count(old) : 0u);
}

size_t sms_tunable_saved_state_count(const sms_tunable *t, const double *src, size_t n)
{
    const sms_stage *old;
    if (t == NULL || src == NULL || n < ST_STAGES)
        return 0;
    old = src[ST_SWITCHING] == 1.0 ? other_slot(t) : NULL;
    return ST_STAGES + sms_stage_state_count(&t->slot[t->active])
           + (old != NULL ? sms_stage_state_count(old) : 0u);
}

void sms_tunable_get_state(const sms_tunable *t, double *dst)
{
    const sms_stage *old = old_stage(t);
    const double *id = sms_stage_identity(&t->slot[t->active]);
    size_t i;
    sms_state_identity_head(dst, SMS_STATE_KIND_TUNABLE, t->Ts);
    dst[ST_SLOT_CELLS] = (double)t->slot_cells;
    dst[ST_SWITCHING] = (double)t->switching;
    dst[ST_FADE] = (double)t->fade;
    dst[ST_LAST] = (double)t->last;
    dst[ST_HOLD] = (double)t->hold;
    for (i = 0; i < SMS_STATE_IDENTITY_COUNT; ++i) {
        dst[ST_ACTIVE_ID + i] = id[i];
        dst[ST_OLD_ID + i] = old != NULL ? sms_stage_identity(old)[i] : 0.0;
    }
    sms_stage_get_state(&t->slot[t->active], dst + ST_STAGES);
    if (old != NULL)
        sms_stage_get_state(old, dst + ST_STAGES + sms_stage_state_count(&t->slot[t->active]));
}

/* The common head of a tunable state of this build; SMS_OK or the status of the first
 * field that differs from the one at Ts (Ts < 0: not compared). */
static sms_status check_head(const double *src, size_t n, double Ts)
{
    double mine[SMS_STATE_IDENTITY_HEAD];
    sms_status st;
    if (n < ST_STAGES)
        return n >= SMS_STATE_IDENTITY_HEAD && src[SMS_ID_TAG] != SMS_STATE_TAG
               ? SMS_ERR_STATE_FORMAT : SMS_ERR_STATE;
    sms_state_identity_head(mine, SMS_STATE_KIND_TUNABLE, Ts < 0.0 ? src[SMS_ID_TS] : Ts);
    st = sms_state_identity_compare(mine, src, 0, NULL);
    if (st != SMS_OK)
        return st;
    if (!(src[ST_SWITCHING] == 0.0 || src[ST_SWITCHING] == 1.0))
        return SMS_ERR_STATE;
    return SMS_OK;
}

sms_status sms_tunable_state_configs(const double *src, size_t n, sms_stage_config *active,
                                     sms_stage_config *old, int *switching)
{
    sms_stage_config a, b;
    sms_status st;
    int sw;
    if (src == NULL || active == NULL || switching == NULL)
        return SMS_ERR_NULL;
    st = check_head(src, n, -1.0);
    if (st != SMS_OK)
        return st;
    sw = src[ST_SWITCHING] == 1.0;
    if (src[ST_ACTIVE_ID + SMS_ID_KIND] == (double)SMS_SHAPER_IMPULSES && !sw)
        return SMS_ERR_KIND;   /* its identity holds a checksum, not the impulses */
    if (!sms_identity_config(src + ST_ACTIVE_ID, &a) || (sw && !sms_identity_config(src + ST_OLD_ID, &b)))
        return SMS_ERR_STATE;
    *active = a;
    if (sw && old != NULL)
        *old = b;
    *switching = sw;
    return SMS_OK;
}

static int is_finite(double v)
{
    return v - v == 0.0;
}

sms_status sms_tunable_check_state(const sms_tunable *t, const double *src, size_t n)
{
    const sms_stage *active, *old;
    size_t n_active, n_old, max_fade, i;
    sms_status st;
    if (t == NULL || src == NULL)
        return SMS_ERR_NULL;
    active = &t->slot[t->active];
    st = check_head(src, n, t->Ts);
    if (st != SMS_OK)
        return st;
    old = src[ST_SWITCHING] == 1.0 ? other_slot(t) : NULL;
    if (src[ST_SLOT_CELLS] != (double)t->slot_cells || (src[ST_SWITCHING] == 1.0 && old == NULL)
        || !is_finite(src[ST_LAST]) || !is_finite(src[ST_HOLD]))
        return SMS_ERR_STATE;
    n_active = sms_stage_state_count(active);
    n_old = old != NULL ? sms_stage_state_count(old) : 0u;
    /* the identities in the head are the stages' (an unused old one is 0): set_state reads
     * neither, so a state that differs there is not one get_state writes */
    {
        /* each identity looked up once (a call through the stage's family), not per field */
        const double *active_id = sms_stage_identity(active);
        const double *old_id = old != NULL ? sms_stage_identity(old) : NULL;
        for (i = 0; i < SMS_STATE_IDENTITY_COUNT; ++i)
            if (src[ST_ACTIVE_ID + i] != active_id[i]
                || src[ST_OLD_ID + i] != (old_id != NULL ? old_id[i] : 0.0))
                return SMS_ERR_STATE;
    }
    /* a stage's own check names the first field of its identity that differs */
    st = sms_stage_check_state(active, src + ST_STAGES,
                               n - ST_STAGES < n_active ? n - ST_STAGES : n_active);
    if (st != SMS_OK)
        return st;
    if (old != NULL) {
        if (n - ST_STAGES - n_active < SMS_STATE_IDENTITY_COUNT)
            return SMS_ERR_STATE;
        st = sms_stage_check_state(old, src + ST_STAGES + n_active,
                                   n - ST_STAGES - n_active < n_old ? n - ST_STAGES - n_active
                                                                    : n_old);
        if (st != SMS_OK)
            return st;
    }
    if (n != ST_STAGES + n_active + n_old)
        return SMS_ERR_STATE;
    /* the fade: FIR samples left, 1 .. L - 2, while switching; a notch's age, any count */
    max_fade = old != NULL && sms_family_of(old->kind) != SMS_FAMILY_NOTCH
               ? sms_stage_length(old) - 2u : 0u;
    if (!whole(src[ST_FADE], 9007199254740992.0))
        return SMS_ERR_STATE;
    if (old != NULL && sms_family_of(old->kind) != SMS_FAMILY_NOTCH
        && !(src[ST_FADE] >= 1.0 && src[ST_FADE] <= (double)max_fade))
        return SMS_ERR_STATE;
    if (old == NULL && src[ST_FADE] != 0.0)
        return SMS_ERR_STATE;
    return SMS_OK;
}

/* Both filters ran on inputs within x_max (the old one since the switch on the held h, itself
 * an earlier input), so each stage's part is held to x_max, as are the last input and h. */
sms_status sms_tunable_check_state_range(const sms_tunable *t, const double *src, size_t n,
                                         double x_max)
{
    size_t n_active;
    sms_status st = sms_tunable_check_state(t, src, n);
    if (st != SMS_OK)
        return st;
    if (!(fabs(src[ST_LAST]) <= x_max) || !(fabs(src[ST_HOLD]) <= x_max))
        return SMS_ERR_STATE;
    n_active = sms_stage_state_count(&t->slot[t->active]);
    st = sms_stage_check_state_range(&t->slot[t->active], src + ST_STAGES, n_active, x_max);
    if (st != SMS_OK || src[ST_SWITCHING] != 1.0)
        return st;
    return sms_stage_check_state_range(&t->slot[1u - t->active], src + ST_STAGES + n_active,
                                       n - ST_STAGES - n_active, x_max);
}

sms_status sms_tunable_set_state(sms_tunable *t, const double *src, size_t n)
{
    sms_status st;
    size_t n_active;
    st = sms_tunable_check_state(t, src, n);
    if (st != SMS_OK)
        return st;
    n_active = sms_stage_state_count(&t->slot[t->active]);
    (void)sms_stage_set_state(&t->slot[t->active], src + ST_STAGES, n_active);
    t->last = (sms_real)src[ST_LAST];
    t->hold = (sms_real)src[ST_HOLD];
    if (src[ST_SWITCHING] == 1.0) {
        sms_stage *old = &t->slot[1u - t->active];
        (void)sms_stage_set_state(old, src + ST_STAGES + n_active, n - ST_STAGES - n_active);
        sms_tunable_begin_fade(t, old);   /* the old notch's constants */
    }
    t->switching = src[ST_SWITCHING] == 1.0;
    t->fade = (uint64_t)src[ST_FADE];
    return SMS_OK;
}

void sms_tunable_rebind(sms_tunable *t, sms_memory_cell *memory)
{
    unsigned s;
    t->memory = memory;
    for (s = 0; s < t->n_slots; ++s)
        if (sms_family_of(t->slot[s].kind) != SMS_FAMILY_NONE)
            sms_stage_rebind(&t->slot[s], sms_tunable_slot_memory(t, s));
}
