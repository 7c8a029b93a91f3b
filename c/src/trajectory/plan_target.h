/* SPDX-License-Identifier: Apache-2.0 */
/* Internal: plans of linear acceleration ramps to a target state (position interface) and to
 * a target velocity (velocity interface), from the third-order motions of third_order.h. */
#ifndef SMS_PLAN_TARGET_H
#define SMS_PLAN_TARGET_H

#include "trajectory/plan.h"
#include "trajectory/third_order.h"

/* From (q, v, a) to (pf, vf, af) in the least time within the limits that lasts at least
 * Tmin (>= 0). A target at rest with Tmin at most the optimum: the time-optimal motion,
 * resting exactly on pf from the first sample at or after its end. Otherwise (a moving
 * target, vf or af not 0, or a longer Tmin): the motion of the first whole number of
 * samples at or after both the optimum and Tmin for which one exists (a blocked duration is
 * skipped to the next),
 * reaching (pf, vf, af) exactly on that sample: the convex combination of the two motions of
 * that duration that end farthest either way (third_order.h). After the target the plan moves
 * on: the acceleration back to zero at jmax, then that velocity held. Preconditions as
 * sms_to_time_optimal(). Returns 1 when planned, 0 when the plan cannot be represented (a
 * value not finite, more than 2^52 samples) or no motion is found; plan untouched then. */
int sms_plan_to_state(sms_plan *plan, const sms_to_limits *lim, sms_real Ts, sms_real q,
                      sms_real v, sms_real a, sms_real pf, sms_real vf, sms_real af,
                      sms_real Tmin);

/* From (q, v, a) to the velocity vf with acceleration af in the least time (position free),
 * then moving on as above. With Tmin above the optimum: reached exactly on the first sample
 * N at or after Tmin for which a motion of N Ts exists, the midpoint of the two such motions
 * that end farthest either way (or the one that exists). Returns as sms_plan_to_state(). */
int sms_plan_velocity(sms_plan *plan, const sms_to_limits *lim, sms_real Ts, sms_real q,
                      sms_real v, sms_real a, sms_real vf, sms_real af, sms_real Tmin);

#endif
