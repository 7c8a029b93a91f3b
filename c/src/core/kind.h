/* SPDX-License-Identifier: Apache-2.0 */
/* Internal: which implementation family a kind belongs to. */
#ifndef SMS_KIND_INTERNAL_H
#define SMS_KIND_INTERNAL_H

#include "smoothshaper/types.h"

typedef enum sms_family { SMS_FAMILY_NONE, SMS_FAMILY_SMOOTHER, SMS_FAMILY_SHAPER, SMS_FAMILY_NOTCH } sms_family;

/* The kinds of each family as bit masks over the kind values: the family is a few
 * instructions, no jump table (it sits on the per-sample dispatch of every stage). Every
 * other kind below SMS_KIND_COUNT is a shaper. */
#define SMS_SMOOTHER_KINDS ((1u << SMS_RECTANGULAR) | (1u << SMS_HARMONIC) \
                            | (1u << SMS_DAMPED_HARMONIC) | (1u << SMS_EXPONENTIAL))
#define SMS_NOTCH_KINDS ((1u << SMS_NOTCH_TUSTIN) | (1u << SMS_NOTCH_MATCHED))

static inline sms_family sms_family_of(sms_kind kind)
{
    /* Through unsigned: a corrupted negative kind is out of range too, never a shift by it. */
    unsigned bit;
    if ((unsigned)kind >= SMS_KIND_COUNT)
        return SMS_FAMILY_NONE;
    bit = 1u << (unsigned)kind;
    return (bit & SMS_SMOOTHER_KINDS) ? SMS_FAMILY_SMOOTHER
           : (bit & SMS_NOTCH_KINDS) ? SMS_FAMILY_NOTCH : SMS_FAMILY_SHAPER;
}

#endif
