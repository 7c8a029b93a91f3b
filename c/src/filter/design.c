/* SPDX-License-Identifier: Apache-2.0 */
/* A stage that cancels a given vibration mode (docs/design.md). Mirrors for_mode in
 * python/smoothshaper/stages.py. */
#include <math.h>
#include "smoothshaper/design.h"

static const double pi = 3.14159265358979323846;

sms_status sms_design_for_mode(sms_kind kind, double wn, double zeta, unsigned k,
                               sms_stage_config *config)
{
    double wd;
    sms_stage_config c;
    if (config == NULL)
        return SMS_ERR_NULL;
    /* unsigned: negatives wrap, and short enums (ARM EABI) are unsigned already */
    /* user-defined impulses are not designed for a mode */
    if ((unsigned)kind >= (unsigned)SMS_KIND_COUNT || kind == SMS_SHAPER_IMPULSES)
        return SMS_ERR_KIND;
    if (!(wn - wn == 0.0) || wn <= 0.0)
        return SMS_ERR_WN;
    if (!(zeta - zeta == 0.0) || zeta < 0.0 || zeta >= 1.0)
        return SMS_ERR_ZETA;
    if (k < 1u)
        return SMS_ERR_MULTIPLE;
    c = sms_stage_config_default(kind);
    wd = wn * sqrt(1.0 - zeta * zeta);
    switch (kind) {
    case SMS_RECTANGULAR:
        c.T = (double)k * 2.0 * pi / wd;
        break;
    case SMS_HARMONIC:
    case SMS_DAMPED_HARMONIC:
        /* zeros at sigma +- j (2m+1) pi/T: T = k 3 pi/wd puts one on wd only for odd k
         * (then m = (3k-1)/2); an even k leaves the mode between two zeros. */
        if (k % 2u == 0u)
            return SMS_ERR_EVEN_MULTIPLE;
        c.T = (double)k * 3.0 * pi / wd;
        if (kind == SMS_DAMPED_HARMONIC)
            c.sigma = -zeta * wn;
        break;
    case SMS_EXPONENTIAL:
        c.T = (double)k * 2.0 * pi / wd;
        c.sigma = -zeta * wn;
        break;
    default:
        /* shapers and notches sit on the mode itself */
        if (k != 1u)
            return SMS_ERR_MULTIPLE;
        c.wn = wn;
        c.zeta = zeta;
        break;
    }
    /* wn far below 1 rad/s (or zeta within 1e-300 of 1) can overflow T = k 2pi/wd: the
     * duration is then not a number, so the mode is refused rather than designed to Inf. */
    if (!(c.T - c.T == 0.0))
        return SMS_ERR_WN;
    c.k = k;
    *config = c;
    return SMS_OK;
}
