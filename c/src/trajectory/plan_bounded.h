/* SPDX-License-Identifier: Apache-2.0 */
/* Internal: plans of linear ramps kept within position limits [qmin, qmax], shared by the
 * single-axis generator (generator.c) and the multi-axis per-axis plans (multi_sync.c). The
 * rule is the one trajectory.h states for ::sms_generator_config's qmin, qmax: the direct
 * plan when its continuous extremes stay inside, else the brake to rest, a rest until the
 * next sample and the move from there, else wait. In sms_real, no libm. */
#ifndef SMS_PLAN_BOUNDED_H
#define SMS_PLAN_BOUNDED_H

#include "smoothshaper/trajectory.h"
#include "trajectory/plan.h"

/* A re-plan under position limits from a state from which no plan stays inside (its brake
 * would cross a limit): the running plan goes on and the re-plan is tried on the next sample. */
#define SMS_REPLAN_WAIT 2

/* Position limits of one axis in signal precision: qtol is how far a plan's computed extremes
 * may pass them, 16 u (|qmin| + |qmax|) (sms_plan_box_tolerance()). */
typedef struct sms_plan_box {
    sms_real qmin, qmax, qtol, Ts;
} sms_plan_box;

/* The planner of one axis without limits: from (q, v, a) to `goal` (position or velocity
 * interface, canonical) into plan; 1 when planned, 0 when it cannot be represented. */
typedef int (*sms_plan_direct_fn)(const void *ctx, sms_plan *plan, sms_real q, sms_real v,
                                  sms_real a, const sms_target *goal);

/* 16 u (|qmin| + |qmax|), u the unit roundoff of sms_real: the rounding of a plan's extremes. */
sms_real sms_plan_box_tolerance(double qmin, double qmax);

/* Do the plan's positions (linear ramps) stay within the box to its tolerance? */
int sms_plan_inside(const sms_plan_box *box, const sms_plan *plan);

/* The plan under position limits (goal at rest inside for the position interface): the
 * direct plan when it stays inside; for the position interface else the brake to rest at
 * once, a rest until the next sample and the move to the goal from there (with what is left
 * of goal->minimum_duration, then without it), the first that stays inside. Returns 1
 * (planned), 0 (a motion cannot be represented) or SMS_REPLAN_WAIT; plan untouched unless 1. */
int sms_plan_within(const sms_plan_box *box, sms_plan_direct_fn direct, const void *ctx,
                    sms_plan *plan, sms_real q, sms_real v, sms_real a, const sms_target *goal);

/* q held to the box: the plan's extremes are inside to its tolerance, so this moves q by no
 * more than that and the rounding of the sample. */
void sms_plan_hold_position(const sms_plan_box *box, sms_real *q);

#endif
