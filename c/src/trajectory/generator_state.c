/* SPDX-License-Identifier: Apache-2.0 */
/* The single-axis generator's saved state (trajectory.h): the configuration identity, the
 * target and the goal of the running plan, the plan's start state and the samples since it;
 * with a mode the samples the plan has rested and the four stage states. Loading re-forms the
 * running plan from its start state and goal, as the generator formed it. */
#include <math.h>
#include "smoothshaper/trajectory.h"
#include "trajectory/generator_parts.h"
#include "core/state_identity.h"

/* Target (position, velocity, acceleration, interface, minimum_duration), goal (the same),
 * the plan's start q, v, a, and k. */
#define GEN_TARGET_COUNT 5u
#define GEN_PLAN_STATE_COUNT ((size_t)SMS_GENERATOR_PLAN_STATE_COUNT)
#define GEN_PLAN (SMS_GENERATOR_IDENTITY_COUNT)
#define GEN_STAGES (GEN_PLAN + GEN_PLAN_STATE_COUNT)

size_t sms_generator_state_count(const sms_generator *g)
{
    if (g->stage_length == 0)
        return GEN_STAGES;
    return GEN_STAGES + 1u + 4u * sms_smoother_state_count(&g->stage[0]);
}

static void put_target(double *dst, const sms_target *t)
{
    dst[0] = (double)t->position;
    dst[1] = (double)t->velocity;
    dst[2] = (double)t->acceleration;
    dst[3] = (double)t->interface;
    dst[4] = (double)t->minimum_duration;
}

void sms_generator_get_state(const sms_generator *g, double *dst)
{
    size_t i, per;
    double *p = dst + GEN_PLAN;
    for (i = 0; i < SMS_GENERATOR_IDENTITY_COUNT; ++i)
        dst[i] = g->identity[i];
    put_target(p, &g->target);
    put_target(p + GEN_TARGET_COUNT, &g->goal);
    p += 2u * GEN_TARGET_COUNT;
    p[0] = (double)g->plan_q;
    p[1] = (double)g->plan_v;
    p[2] = (double)g->plan_a;
    p[3] = (double)g->k;
    if (g->stage_length == 0)
        return;
    dst[GEN_STAGES] = (double)g->quiet;
    per = sms_smoother_state_count(&g->stage[0]);
    for (i = 0; i < 4; ++i)
        sms_smoother_get_state(&g->stage[i], dst + GEN_STAGES + 1u + i * per);
}

static int is_count(double x, double max)
{
    return x >= 0.0 && x <= max && x == (double)(size_t)x;
}

static sms_status check_identity(const sms_generator *g, const double *src)
{
    static const sms_status field_status[SMS_GENERATOR_IDENTITY_COUNT - SMS_STATE_IDENTITY_HEAD] = {
        SMS_ERR_STATE_VMAX, SMS_ERR_STATE_AMAX, SMS_ERR_STATE_JMAX, SMS_ERR_STATE_PROFILE,
        SMS_ERR_STATE_WN, SMS_ERR_STATE_ZETA, SMS_ERR_STATE_VMAX, SMS_ERR_STATE_AMAX,
        SMS_ERR_POSITION_LIMIT, SMS_ERR_POSITION_LIMIT
    };
    return sms_state_identity_compare(g->identity, src,
                                      SMS_GENERATOR_IDENTITY_COUNT - SMS_STATE_IDENTITY_HEAD,
                                      field_status);
}

/* A saved target: a valid one in its canonical form (what the generator itself holds). */
static int get_target(const sms_generator *g, const double *src, sms_target *t)
{
    sms_target c;
    if (!is_count(src[3], 2.0))
        return 0;
    t->position = (sms_real)src[0];
    t->velocity = (sms_real)src[1];
    t->acceleration = (sms_real)src[2];
    t->interface = (int)src[3];
    t->minimum_duration = (sms_real)src[4];
    if (sms_generator_canonical(g, t, &c) != SMS_OK || c.interface != t->interface ||
        c.position != t->position || c.velocity != t->velocity ||
        c.acceleration != t->acceleration || c.minimum_duration != t->minimum_duration)
        return 0;
    return 1;
}

sms_status sms_generator_check_state(const sms_generator *g, const double *src, size_t n)
{
    const double *p;
    sms_target target, goal;
    size_t i, per;
    sms_status st;
    if (g == NULL || src == NULL)
        return SMS_ERR_NULL;
    /* another configuration first, whatever the length: its state often has another one */
    if (n >= SMS_GENERATOR_IDENTITY_COUNT && (st = check_identity(g, src)) != SMS_OK)
        return st;
    if (n != sms_generator_state_count(g))
        return SMS_ERR_STATE;
    p = src + GEN_PLAN;
    for (i = 0; i < GEN_PLAN_STATE_COUNT - 1u; ++i)
        if (!isfinite(p[i]) || (sms_real)p[i] - (sms_real)p[i] != 0)
            return SMS_ERR_STATE;
    if (!get_target(g, p, &target) || !get_target(g, p + GEN_TARGET_COUNT, &goal))
        return SMS_ERR_STATE;
    p += 2u * GEN_TARGET_COUNT;
    /* a state a plan can start from, as the generator itself leaves them: v and a within
     * the bounds, and able to bring a to zero (at the shape's mean jerk) without passing vmax,
     * each to the reported values' 32 u (SMS_LIMIT_RTOL; the generator's own states stay
     * within 15 u, tests/c/test_generator.c), checked on the values as sms_real holds them */
    if (!sms_generator_state_ok(g, (double)(sms_real)p[1], (double)(sms_real)p[2], SMS_LIMIT_RTOL))
        return SMS_ERR_STATE;
    if (!is_count(p[3], 9007199254740992.0)) /* 2^53 */
        return SMS_ERR_STATE;
    {
        /* the running plan must be one the generator can form again */
        sms_plan plan;
        if (sms_generator_replan(g, &plan, (sms_real)p[0], (sms_real)p[1], (sms_real)p[2], &goal) != 1)
            return SMS_ERR_STATE;
    }
    if (g->stage_length == 0)
        return SMS_OK;
    if (!is_count(src[GEN_STAGES], (double)g->stage_length))
        return SMS_ERR_STATE;
    per = sms_smoother_state_count(&g->stage[0]);
    {
        /* each stage's values within what its signal leaves in it: positions within the
         * stage's input range, v, a, j within the limits to the reported values' tolerance
         * (a state no run produces, a forged one, would report beyond them) */
        const double range[4] = {
            sms_smoother_input_max(&g->stage[0]),
            (double)(g->limits.vmax > -g->vmin ? g->limits.vmax : -g->vmin) *
                (1.0 + SMS_LIMIT_RTOL),
            (double)(g->limits.amax > -g->amin ? g->limits.amax : -g->amin) *
                (1.0 + SMS_LIMIT_RTOL),
            (double)g->limits.jmax * (1.0 + SMS_LIMIT_RTOL)
        };
        for (i = 0; i < 4; ++i)
            if (sms_smoother_check_state_range(&g->stage[i], src + GEN_STAGES + 1u + i * per, per,
                                               range[i]) != SMS_OK)
                return SMS_ERR_STATE;
    }
    return SMS_OK;
}

sms_status sms_generator_set_state(sms_generator *g, const double *src, size_t n)
{
    size_t i, per;
    const double *p;
    sms_status st = sms_generator_check_state(g, src, n);
    if (st != SMS_OK)
        return st;
    p = src + GEN_PLAN;
    (void)get_target(g, p, &g->target);
    (void)get_target(g, p + GEN_TARGET_COUNT, &g->goal);
    g->request = g->target;
    p += 2u * GEN_TARGET_COUNT;
    g->plan_q = (sms_real)p[0];
    g->plan_v = (sms_real)p[1];
    g->plan_a = (sms_real)p[2];
    g->k = (size_t)p[3];
    g->refused = 0; /* a dropped target is tried (and dropped) again on the next sample */
    g->pending = g->target.interface != g->goal.interface ||
                 g->target.position != g->goal.position ||
                 g->target.velocity != g->goal.velocity ||
                 g->target.acceleration != g->goal.acceleration ||
                 g->target.minimum_duration != g->goal.minimum_duration;
    (void)sms_generator_replan(g, &g->plan, g->plan_q, g->plan_v, g->plan_a, &g->goal);
    if (g->stage_length == 0)
        return SMS_OK;
    g->quiet = (size_t)src[GEN_STAGES];
    per = sms_smoother_state_count(&g->stage[0]);
    for (i = 0; i < 4; ++i)
        (void)sms_smoother_set_state(&g->stage[i], src + GEN_STAGES + 1u + i * per, per);
    return SMS_OK;
}
