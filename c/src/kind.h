/* Internal: which implementation family a kind belongs to. */
#ifndef SMS_KIND_INTERNAL_H
#define SMS_KIND_INTERNAL_H

#include "smoothshaper/types.h"

typedef enum sms_family { SMS_FAMILY_NONE, SMS_FAMILY_SMOOTHER, SMS_FAMILY_SHAPER, SMS_FAMILY_NOTCH } sms_family;

static inline sms_family sms_family_of(sms_kind kind)
{
    switch (kind) {
    case SMS_RECTANGULAR: case SMS_HARMONIC: case SMS_DAMPED_HARMONIC: case SMS_EXPONENTIAL:
        return SMS_FAMILY_SMOOTHER;
    case SMS_SHAPER_ZV: case SMS_SHAPER_ZVD: case SMS_SHAPER_ZVDD: case SMS_SHAPER_ZVN:
    case SMS_SHAPER_EI: case SMS_SHAPER_EI2: case SMS_SHAPER_MZV: case SMS_SHAPER_EI3:
    case SMS_SHAPER_GMZV:
        return SMS_FAMILY_SHAPER;
    case SMS_NOTCH_TUSTIN: case SMS_NOTCH_MATCHED:
        return SMS_FAMILY_NOTCH;
    }
    return SMS_FAMILY_NONE;
}

#endif
