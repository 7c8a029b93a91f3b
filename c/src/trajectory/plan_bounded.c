/* SPDX-License-Identifier: Apache-2.0 */
/* Plans kept within position limits (plan_bounded.h): the single-axis generator's rule,
 * shared with the multi-axis per-axis plans. In sms_real, no libm (the per-sample path). */
#include <float.h>
#include <math.h>
#include "trajectory/plan_bounded.h"

#define BOX_UNIT_ROUNDOFF (sizeof(sms_real) == sizeof(double) ? DBL_EPSILON / 2 \
                                                              : (double)FLT_EPSILON / 2)

sms_real sms_plan_box_tolerance(double qmin, double qmax)
{
    return (sms_real)(16.0 * BOX_UNIT_ROUNDOFF * (fabs(qmin) + fabs(qmax)));
}

int sms_plan_inside(const sms_plan_box *box, const sms_plan *plan)
{
    sms_real lo, hi;
    return sms_plan_extent(plan, &lo, &hi) && lo >= box->qmin - box->qtol &&
           hi <= box->qmax + box->qtol;
}

void sms_plan_hold_position(const sms_plan_box *box, sms_real *q)
{
    if (*q > box->qmax)
        *q = box->qmax;
    else if (*q < box->qmin)
        *q = box->qmin;
}

/* The brake `stop` (resting on its goal from stop->end + stop->end_f), a rest there until the
 * next sample S, then `move` (formed from that rest, times from its own first sample) shifted
 * by S samples; 0 when the segments do not fit. */
static int join_plans(sms_real Ts, sms_plan *plan, const sms_plan *stop, size_t S,
                      const sms_plan *move)
{
    size_t i, c, n = stop->end;
    sms_real f = stop->end_f;
    if (stop->count + 1u + move->count > SMS_PLAN_MAX_SEGMENTS)
        return 0;
    *plan = *stop;
    if (S > stop->end)
        sms_plan_push(plan, Ts, &n, &f, stop->goal, 0, 0, 0, Ts - stop->end_f);
    for (i = 0; i < move->count; ++i) {
        c = plan->count++;
        plan->n[c] = move->n[i] + S;
        plan->f[c] = move->f[i];
        plan->p[c] = move->p[i];
        plan->v[c] = move->v[i];
        plan->a[c] = move->a[i];
        plan->j[c] = move->j[i];
        plan->d[c] = move->d[i];
        plan->duration += move->d[i];
    }
    plan->end = move->end + S;
    plan->end_f = move->end_f;
    plan->goal = move->goal;
    plan->drift = move->drift;
    plan->arrive = move->arrive + S;
    plan->arrive_f = move->arrive_f;
    return sms_plan_finite(plan) &&
           (sms_real)plan->end + plan->end_f / Ts + 2 <= sms_plan_max_samples();
}

int sms_plan_within(const sms_plan_box *box, sms_plan_direct_fn direct, const void *ctx,
                    sms_plan *plan, sms_real q, sms_real v, sms_real a, const sms_target *goal)
{
    sms_plan first, stop, move;
    sms_target rest, brake;
    sms_real left;
    size_t S;
    int pass;
    /* the time-optimal motion when it stays inside */
    if (!direct(ctx, &first, q, v, a, goal))
        return 0;
    if (sms_plan_inside(box, &first)) {
        *plan = first;
        return 1;
    }
    if (goal->interface == SMS_INTERFACE_VELOCITY)
        return SMS_REPLAN_WAIT; /* the stop itself crosses: the running plan goes on */
    /* else brake to rest, wait for the next sample, move: with what is left of the minimum
     * duration, then without it */
    brake.interface = SMS_INTERFACE_VELOCITY;
    brake.position = brake.velocity = brake.acceleration = brake.minimum_duration = 0;
    if (!direct(ctx, &stop, q, v, a, &brake))
        return 0;
    if (!sms_plan_inside(box, &stop))
        return SMS_REPLAN_WAIT;
    S = stop.end + (stop.end_f > 0 ? 1u : 0u);
    rest = *goal;
    left = goal->minimum_duration - (sms_real)S * box->Ts;
    for (pass = 0; pass < 2; ++pass) {
        rest.minimum_duration = pass == 0 && left > 0 ? left : 0;
        if (pass == 1 && goal->minimum_duration == 0)
            break;
        if (!direct(ctx, &move, stop.goal, 0, 0, &rest))
            return 0;
        if (sms_plan_inside(box, &move))
            return join_plans(box->Ts, plan, &stop, S, &move);
    }
    return SMS_REPLAN_WAIT;
}
