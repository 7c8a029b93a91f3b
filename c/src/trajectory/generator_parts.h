/* SPDX-License-Identifier: Apache-2.0 */
/* Internal: what the single-axis generator's files share (generator.c: configuration,
 * targets, the sample; generator_state.c: the saved state). */
#ifndef SMS_GENERATOR_PARTS_H
#define SMS_GENERATOR_PARTS_H

#include "smoothshaper/trajectory.h"

/* The identity fields after the common head, in this order (trajectory.h). */
enum { SMS_GEN_ID_VMAX = 5, SMS_GEN_ID_AMAX, SMS_GEN_ID_JMAX, SMS_GEN_ID_PROFILE, SMS_GEN_ID_WN,
       SMS_GEN_ID_ZETA, SMS_GEN_ID_VMIN, SMS_GEN_ID_AMIN };

/* A target in its canonical form (a stop as velocity 0, acceleration 0; the position of a
 * velocity target as 0), or its status (sms_generator_check_target()). */
sms_status sms_generator_canonical(const sms_generator *g, const sms_target *in, sms_target *out);

/* Is (v, a) a state a plan of this generator can start from, to the tolerance `rtol` of the
 * limits? */
int sms_generator_state_ok(const sms_generator *g, double v, double a, double rtol);

/* SMS_REPLAN_WAIT: with position limits, no plan from this state stays inside */
#include "trajectory/plan_bounded.h"

/* Plan from (q, v, a) towards `goal` (canonical) into plan; 1 when planned, 0 when the motion
 * cannot be represented, SMS_REPLAN_WAIT (position limits) when no plan from there stays
 * inside; plan untouched unless 1. */
int sms_generator_replan(const sms_generator *g, sms_plan *plan, sms_real q, sms_real v,
                         sms_real a, const sms_target *goal);

#endif
