/* SPDX-License-Identifier: Apache-2.0 */
/* The stage configuration a saved state's identity describes (config.h): what a retunable
 * stage restores from and what a built stage's lag is computed from. */
#include "filter/identity_config.h"
#include "smoothshaper/stage.h"
#include "core/kind.h"
#include "core/state_identity.h"

/* Identity fields after the common head, in the order of config.h. */
enum {
    ID_TIMING = SMS_STATE_IDENTITY_HEAD, ID_T, ID_SIGMA, ID_K, ID_WN, ID_ZETA, ID_ORDER,
    ID_TOLERANCE, ID_NOTCH_POLE_ZETA, ID_DURATION
};

static int whole(double v, double most)
{
    return v >= 0.0 && v <= most && v == (double)(unsigned long)v;
}

/* The configuration an identity describes: the fields its kind reads, the others at their
 * defaults. 0 if the kind is no stage kind, an integer field does not fit, or user-defined
 * impulses. */
int sms_identity_config(const double *id, sms_stage_config *out)
{
    sms_stage_config c;
    sms_family fam;
    if (!whole(id[SMS_ID_KIND], (double)(SMS_KIND_COUNT - 1)) || !whole(id[ID_TIMING], 2.0)
        || !whole(id[ID_K], 4294967295.0) || !whole(id[ID_ORDER], 4294967295.0))
        return 0;
    c = sms_stage_config_default((sms_kind)(unsigned)id[SMS_ID_KIND]);
    fam = sms_family_of(c.kind);
    if (c.kind == SMS_SHAPER_IMPULSES)
        return 0;   /* the identity holds a checksum of the impulses, not the impulses */
    if (fam == SMS_FAMILY_SMOOTHER) {
        c.timing = (sms_timing)(unsigned)id[ID_TIMING];
        c.T = id[ID_T];
        c.sigma = id[ID_SIGMA];
        c.k = (unsigned)id[ID_K];
    } else {
        c.wn = id[ID_WN];
        c.zeta = id[ID_ZETA];
        if (fam == SMS_FAMILY_NOTCH) {
            c.notch_pole_zeta = id[ID_NOTCH_POLE_ZETA];
        } else {
            c.timing = (sms_timing)(unsigned)id[ID_TIMING];
            if (c.kind == SMS_SHAPER_ZVN || c.kind == SMS_SHAPER_GMZV || c.kind == SMS_SHAPER_SI)
                c.order = (unsigned)id[ID_ORDER];
            if (c.kind == SMS_SHAPER_EI || c.kind == SMS_SHAPER_EI2 || c.kind == SMS_SHAPER_EI3
                || c.kind == SMS_SHAPER_SI)
                c.tolerance = id[ID_TOLERANCE];
            if (c.kind == SMS_SHAPER_GMZV || c.kind == SMS_SHAPER_SI)
                c.duration = id[ID_DURATION];
        }
    }
    *out = c;
    return 1;
}

const double *sms_stage_identity(const sms_stage *stage)
{
    switch (sms_family_of(stage->kind)) {
    case SMS_FAMILY_SMOOTHER: return stage->u.smoother->identity;
    case SMS_FAMILY_SHAPER: return stage->u.shaper->identity;
    case SMS_FAMILY_NOTCH: return stage->u.notch->identity;
    case SMS_FAMILY_NONE: break;
    }
    return NULL;
}
