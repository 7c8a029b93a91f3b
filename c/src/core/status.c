/* SPDX-License-Identifier: Apache-2.0 */
/* Status and kind names: constant tables, no state. */
#include "smoothshaper/types.h"

const char *sms_status_string(sms_status status)
{
    switch (status) {
    case SMS_OK: return "ok";
    case SMS_ERR_NULL: return "a required pointer argument is NULL";
    case SMS_ERR_SAMPLE_PERIOD: return "Ts must be finite and > 0";
    case SMS_ERR_DURATION: return "T must be finite and > 0 (a minimum duration: >= 0)";
    case SMS_ERR_DURATION_BELOW_TS: return "T must be >= Ts";
    case SMS_ERR_SIGMA: return "sigma must be finite and <= 0, and not so negative that the "
                               "smoother's internal gain (about e^(-sigma Ts)) overflows";
    case SMS_ERR_WN: return "wn must be finite and > 0";
    case SMS_ERR_ZETA:
        return "zeta must be finite and in [0, 1) ([0, 0.25] for smooth_zv, smooth_mzv, smooth_ei)";
    case SMS_ERR_MULTIPLE: return "k must be >= 1 (and 1 for shapers and notches)";
    case SMS_ERR_EVEN_MULTIPLE: return "k must be odd for harmonic families: an even k puts no zero on the mode";
    case SMS_ERR_ORDER: return "order out of range";
    case SMS_ERR_BUFFER_TOO_SMALL: return "buffer smaller than the size query requires";
    case SMS_ERR_KIND: return "unknown kind or timing";
    case SMS_ERR_NOTCH_DAMPING: return "notch_pole_zeta must be finite and > zeta";
    case SMS_ERR_TOLERANCE: return "tolerance must be in (0, 1)";
    case SMS_ERR_TOO_LONG: return "length too large to represent";
    case SMS_ERR_ABOVE_NYQUIST: return "wn must lie below the Nyquist frequency pi/Ts";
    case SMS_ERR_LIMIT: return "kinematic limits and displacement must be finite and > 0";
    case SMS_ERR_RECORD: return "record too short, non-finite, or not a decaying oscillation";
    case SMS_ERR_STATE: return "saved state does not match this object";
    case SMS_ERR_BANDWIDTH: return "bandwidth must be finite, > 0 and narrower than the notch allows";
    case SMS_ERR_SHAPER_DURATION:
        return "duration must lie in (0, (order-1)/2) damped periods ([(order-1)/4, (order-1)/2] "
               "for si) and give no negative impulse";
    case SMS_ERR_STATE_FORMAT: return "saved state is not a state of this format version";
    case SMS_ERR_STATE_PRECISION: return "saved state is from the other precision (float/double)";
    case SMS_ERR_STATE_KIND: return "saved state is from another kind of stage or object";
    case SMS_ERR_STATE_TS: return "saved state is from another sample period Ts";
    case SMS_ERR_STATE_TIMING: return "saved state is from another timing";
    case SMS_ERR_STATE_T: return "saved state is from another duration T";
    case SMS_ERR_STATE_SIGMA: return "saved state is from another sigma";
    case SMS_ERR_STATE_K: return "saved state is from another multiple k";
    case SMS_ERR_STATE_WN: return "saved state is from another wn";
    case SMS_ERR_STATE_ZETA: return "saved state is from another zeta";
    case SMS_ERR_STATE_ORDER: return "saved state is from another order";
    case SMS_ERR_STATE_TOLERANCE: return "saved state is from another tolerance";
    case SMS_ERR_STATE_NOTCH_POLE_ZETA: return "saved state is from another notch_pole_zeta";
    case SMS_ERR_STATE_DURATION:
        return "saved state is from another duration (or other user-defined impulses)";
    case SMS_ERR_STATE_VMAX: return "saved state is from another vmax";
    case SMS_ERR_STATE_AMAX: return "saved state is from another amax";
    case SMS_ERR_STATE_JMAX: return "saved state is from another jmax";
    case SMS_ERR_STATE_PROFILE: return "saved state is from another profile";
    case SMS_ERR_STATE_DEGREE: return "saved state is from another degree";
    case SMS_ERR_STATE_AXES: return "saved state is from another number of axes";
    case SMS_ERR_STATE_SYNC: return "saved state is from another sync";
    case SMS_ERR_STATE_STAGES: return "saved state is from another number of stages on an axis";
    case SMS_ERR_COEFFS:
        return "precomputed coefficients out of range (a length, tap or delay no design gives, "
               "or a non-finite value)";
    case SMS_ERR_RETUNE_BUSY:
        return "stage is still switching from its previous retune (the old filter is fading out)";
    case SMS_ERR_TARGET_POSITION: return "target position must be finite";
    case SMS_ERR_TARGET_VELOCITY:
        return "target velocity must be finite and within the velocity bounds (0 where the "
               "profile plans to rest only)";
    case SMS_ERR_TARGET_ACCELERATION:
        return "target acceleration must be finite, within the acceleration bounds, and keep "
               "v - a|a|/(2 jmax) and v + a|a|/(2 jmax) within the velocity bounds (0 where the "
               "profile cannot hold one)";
    case SMS_ERR_INTERFACE: return "interface must be position, velocity or stop";
    case SMS_ERR_IMPULSE_AMPLITUDE:
        return "impulse amplitudes must be finite and sum to > 0";
    case SMS_ERR_IMPULSE_TIME:
        return "impulse times must be finite, >= 0 and strictly increasing";
    case SMS_ERR_TARGET_SYNC:
        return "a target's per-axis synchronisation is not one the generator's mode takes";
    case SMS_ERR_SAMPLE_PERIOD_RANGE:
        return "Ts must be at most SMS_TS_MAX (2^56 Ts, the longest time sum, would overflow)";
    case SMS_ERR_POSITION_LIMIT:
        return "a position (a target, or where a start state brakes to rest) outside [qmin, qmax]";
    }
    return "unknown status";
}

const char *sms_kind_name(sms_kind kind)
{
    switch (kind) {
    case SMS_RECTANGULAR: return "rectangular";
    case SMS_HARMONIC: return "harmonic";
    case SMS_DAMPED_HARMONIC: return "damped_harmonic";
    case SMS_EXPONENTIAL: return "exponential";
    case SMS_SHAPER_ZV: return "zv";
    case SMS_SHAPER_ZVD: return "zvd";
    case SMS_SHAPER_ZVDD: return "zvdd";
    case SMS_SHAPER_ZVN: return "zvn";
    case SMS_SHAPER_EI: return "ei";
    case SMS_SHAPER_EI2: return "ei2";
    case SMS_SHAPER_MZV: return "mzv";
    case SMS_NOTCH_TUSTIN: return "notch_tustin";
    case SMS_NOTCH_MATCHED: return "notch_matched";
    case SMS_SHAPER_EI3: return "ei3";
    case SMS_SHAPER_GMZV: return "gmzv";
    case SMS_SMOOTH_ZV: return "smooth_zv";
    case SMS_SMOOTH_MZV: return "smooth_mzv";
    case SMS_SMOOTH_EI: return "smooth_ei";
    case SMS_SMOOTH_EI2: return "smooth_ei2";
    case SMS_SMOOTH_ZVD_EI: return "smooth_zvd_ei";
    case SMS_SMOOTH_SI: return "smooth_si";
    case SMS_SHAPER_SI: return "si";
    case SMS_SHAPER_IMPULSES: return "impulses";
    }
    return NULL;
}
