/* SPDX-License-Identifier: Apache-2.0 */
/* The multi-axis generator's per-axis plan modes (Time, TimeIfNecessary, None): each axis runs
 * a single-axis plan from its exact state to its target state (plan_target.c), and the
 * synchronised axes are planned to arrive on one common sample (multi_generator.h,
 * sms_multi_generator_step_target()). In sms_real, no libm: it runs on the per-sample path. */
#include <math.h>
#include <string.h>
#include "trajectory/multi_parts.h"
#include "trajectory/plan.h"
#include "trajectory/plan_target.h"
#include "trajectory/plan_bounded.h"

/* A minimum duration beyond this many samples is refused (the generator's feasible limits
 * reach vmax within it, sms_generator_reach()). */
#define MAX_MINIMUM_SAMPLES 1125899906842624.0 /* 2^50 */
/* Rounds of "raise N to the next duration a synchronised axis can reach": each round moves N
 * past one blocked interval of one axis, and an axis has at most two (third_order.h, the
 * farthest members either way bound a convex set per family). */
#define MAX_SYNC_ROUNDS (4 * SMS_MULTI_MAX_AXES + 4)

static int finite_real(sms_real x)
{
    return x - x == 0;
}

static sms_real mag(sms_real x)
{
    return x < 0 ? -x : x;
}

static sms_to_limits axis_limits(const sms_multi_generator *g, size_t i)
{
    sms_to_limits lim;
    lim.vmax = g->vmax[i];
    lim.vmin = -g->vmax[i];
    lim.amax = g->amax[i];
    lim.amin = -g->amax[i];
    lim.jmax = g->jmax[i];
    return lim;
}

sms_status sms_multi_generator_check_target(const sms_multi_generator *g,
                                            const sms_multi_target *t, size_t *axis)
{
    size_t i;
    const int plans = g != NULL && SMS_SYNC_PER_AXIS_PLANS(g->sync);
    if (axis != NULL)
        *axis = 0;
    if (g == NULL || t == NULL)
        return SMS_ERR_NULL;
    for (i = 0; i < g->n_axes; ++i) {
        const sms_real v = t->velocity[i], a = t->acceleration[i];
        sms_real reach;
        sms_status st = SMS_OK;
        const int s = t->sync[i];
        if (!finite_real(t->position[i]))
            st = SMS_ERR_TARGET_POSITION;
        else if (!finite_real(v) || !(mag(v) <= g->vmax[i]) || (!plans && v != 0))
            st = SMS_ERR_TARGET_VELOCITY;
        else if (!finite_real(a) || !(mag(a) <= g->amax[i]) || (!plans && a != 0))
            st = SMS_ERR_TARGET_ACCELERATION;
        else if (s != 0 && (!plans || !SMS_SYNC_PER_AXIS_PLANS(s)))
            st = SMS_ERR_TARGET_SYNC;
        else if (g->bounded[i] && v != 0) /* a target drifting on would leave the limits */
            st = SMS_ERR_TARGET_VELOCITY;
        else if (g->bounded[i] && a != 0)
            st = SMS_ERR_TARGET_ACCELERATION;
        else if (g->bounded[i] &&
                 !(t->position[i] >= g->qmin[i] && t->position[i] <= g->qmax[i]))
            st = SMS_ERR_POSITION_LIMIT;
        if (st == SMS_OK) {
            /* the velocity within its bound on the way in and after the target */
            reach = a * mag(a) / (2 * g->jmax[i]);
            if (!(mag(v - reach) <= g->vmax[i]) || !(mag(v + reach) <= g->vmax[i]))
                st = SMS_ERR_TARGET_ACCELERATION;
        }
        if (st != SMS_OK) {
            if (axis != NULL)
                *axis = i;
            return st;
        }
    }
    if (!(t->minimum_duration >= 0) ||
        !(t->minimum_duration / g->Ts_signal <= (sms_real)MAX_MINIMUM_SAMPLES) ||
        (!plans && t->minimum_duration != 0))
        return SMS_ERR_DURATION;
    return SMS_OK;
}

static int same_target(const sms_multi_target *x, const sms_multi_target *y, size_t n)
{
    size_t i;
    if (x->minimum_duration != y->minimum_duration)
        return 0;
    for (i = 0; i < n; ++i)
        if (x->position[i] != y->position[i] || x->velocity[i] != y->velocity[i] ||
            x->acceleration[i] != y->acceleration[i] || x->sync[i] != y->sync[i])
            return 0;
    return 1;
}


/* One axis of the per-axis modes, the single-axis planner without position limits. */
typedef struct axis_ctx {
    const sms_multi_generator *g;
    size_t i;
} axis_ctx;

static int axis_direct(const void *ctx, sms_plan *plan, sms_real q, sms_real v, sms_real a,
                       const sms_target *goal)
{
    const axis_ctx *c = (const axis_ctx *)ctx;
    const sms_to_limits lim = axis_limits(c->g, c->i);
    if (goal->interface == SMS_INTERFACE_VELOCITY)
        return sms_plan_velocity(plan, &lim, c->g->Ts_signal, q, v, a, goal->velocity,
                                 goal->acceleration, goal->minimum_duration);
    return sms_plan_to_state(plan, &lim, c->g->Ts_signal, q, v, a, goal->position,
                             goal->velocity, goal->acceleration, goal->minimum_duration);
}

static sms_plan_box axis_box(const sms_multi_generator *g, size_t i)
{
    sms_plan_box box;
    box.qmin = g->qmin[i];
    box.qmax = g->qmax[i];
    box.qtol = g->qtol[i];
    box.Ts = g->Ts_signal;
    return box;
}

/* Axis i from (q, v, a) to its target state in t with minimum duration Tmin: 1 planned, 0 not
 * representable, SMS_REPLAN_WAIT (position limits: no plan from there stays inside). An axis
 * with position limits plans by the single-axis generator's rule (plan_bounded.c). */
static int plan_axis(const sms_multi_generator *g, size_t i, sms_plan *plan, sms_real q,
                     sms_real v, sms_real a, const sms_multi_target *t, sms_real Tmin)
{
    axis_ctx ctx;
    sms_target goal;
    sms_plan_box box;
    ctx.g = g;
    ctx.i = i;
    goal.interface = SMS_INTERFACE_POSITION;
    goal.position = t->position[i];
    goal.velocity = t->velocity[i];
    goal.acceleration = t->acceleration[i];
    goal.minimum_duration = Tmin;
    if (!g->bounded[i])
        return axis_direct(&ctx, plan, q, v, a, &goal);
    box = axis_box(g, i);
    return sms_plan_within(&box, axis_direct, &ctx, plan, q, v, a, &goal);
}

/* Plans every axis from its state s[4 i + 0..2] to the target into plans[], tmin[] the minimum
 * durations used. Returns 1 when every axis is planned, 0 when a motion cannot be formed,
 * SMS_REPLAN_WAIT when no plan of a bounded axis stays inside (that axis in *bad). */
static int plan_all(const sms_multi_generator *g, const sms_multi_target *t, const sms_real *s,
                    sms_plan *plans, sms_real *tmin, size_t *bad)
{
    const size_t n = g->n_axes;
    int synced[SMS_MULTI_MAX_AXES];
    size_t i, N = 0, round;
    const sms_real Ts = g->Ts_signal;
    for (i = 0; i < n; ++i) {
        const int mode = t->sync[i] != 0 ? t->sync[i] : (int)g->sync;
        synced[i] = mode == SMS_SYNC_TIME ||
                    (mode == SMS_SYNC_TIME_IF_NECESSARY &&
                     (t->velocity[i] != 0 || t->acceleration[i] != 0));
        int planned;
        tmin[i] = synced[i] ? t->minimum_duration : 0;
        planned = plan_axis(g, i, &plans[i], s[4 * i], s[4 * i + 1], s[4 * i + 2], t, tmin[i]);
        if (planned != 1) {
            *bad = i;
            return planned;
        }
        if (mode != SMS_SYNC_NONE && sms_plan_arrival_sample(&plans[i], Ts) > N)
            N = sms_plan_arrival_sample(&plans[i], Ts);
    }
    /* every synchronised axis onto sample N; an axis that cannot make N (a blocked duration)
     * returns the next N' it can, and the others are planned again for N' */
    for (round = 0; round < MAX_SYNC_ROUNDS; ++round) {
        int raised = 0;
        for (i = 0; i < n && !raised; ++i) {
            size_t at;
            if (!synced[i] || sms_plan_arrival_sample(&plans[i], Ts) == N)
                continue;
            {
                const sms_real T = (sms_real)N * Ts;
                const int planned = plan_axis(g, i, &plans[i], s[4 * i], s[4 * i + 1],
                                              s[4 * i + 2], t, T);
                if (planned != 1) {
                    *bad = i;
                    return planned;
                }
                tmin[i] = T;
            }
            at = sms_plan_arrival_sample(&plans[i], Ts);
            if (at > N) {
                N = at;
                raised = 1;
            } else if (at < N && !g->bounded[i]) {
                return 0; /* not expected: the planner honours its minimum duration */
            } /* (a bounded axis whose stretched move would cross takes it unstretched) */
        }
        if (!raised)
            return 1;
    }
    return 0;
}

/* Install plans made from the states s (this sample is their sample 0). */
static void install(sms_multi_generator *g, const sms_multi_target *t, const sms_real *s,
                    const sms_plan *plans, const sms_real *tmin)
{
    size_t i;
    for (i = 0; i < g->n_axes; ++i) {
        sms_multi_axis_plan *ax = &g->axis[i];
        ax->plan = plans[i];
        ax->q0 = s[4 * i];
        ax->v0 = s[4 * i + 1];
        ax->a0 = s[4 * i + 2];
        ax->tmin = tmin[i];
        ax->k = 0;
    }
    g->aim = *t;
    g->plan_pending = 0;
    g->plan_refused = 0;
}

static void eval_axis(const sms_multi_generator *g, size_t i, sms_real *out)
{
    const sms_multi_axis_plan *ax = &g->axis[i];
    if (ax->k > ax->plan.end && ax->plan.drift == 0) {
        out[0] = ax->plan.goal; /* resting on the goal, the common case */
        out[1] = out[2] = out[3] = 0;
        return;
    }
    sms_plan_eval(&ax->plan, g->Ts_signal, ax->k, out);
    if (g->bounded[i]) {
        const sms_plan_box box = axis_box(g, i);
        sms_plan_hold_position(&box, &out[0]);
    }
}

void sms_multi_sync_reset(sms_multi_generator *g, const sms_real *position)
{
    size_t i;
    memset(&g->request, 0, sizeof g->request);
    for (i = 0; i < SMS_MULTI_MAX_AXES; ++i) {
        sms_multi_axis_plan *ax = &g->axis[i];
        const sms_real x = (position != NULL && i < g->n_axes) ? position[i] : 0;
        memset(&ax->plan, 0, sizeof ax->plan);
        ax->plan.goal = x; /* no segment: at rest on the goal from sample 0 */
        ax->q0 = x;
        ax->v0 = ax->a0 = ax->tmin = 0;
        ax->k = 0;
        g->request.position[i] = x;
    }
    g->aim = g->request;
    g->plan_pending = 0;
    g->plan_refused = 0;
}

/* Take a new target vector: an invalid one is ignored (the previous kept); the same as on the
 * sample before costs the comparison. */
static void take_target(sms_multi_generator *g, const sms_multi_target *t)
{
    if (same_target(t, &g->request, g->n_axes))
        return;
    g->request = *t;
    if (sms_multi_generator_check_target(g, t, NULL) == SMS_OK) {
        g->plan_refused = 0;
        g->plan_pending = !same_target(t, &g->aim, g->n_axes);
    }
}

/* One sample of the per-axis plans under the held request: every axis's next sample; on a
 * pending target, the re-plan from the exact states there. */
void sms_multi_sync_step_held(sms_multi_generator *g, sms_real *out)
{
    size_t i;
    for (i = 0; i < g->n_axes; ++i) {
        ++g->axis[i].k;
        eval_axis(g, i, out + 4 * i);
    }
    if (g->plan_pending) {
        sms_plan plans[SMS_MULTI_MAX_AXES];
        sms_real tmin[SMS_MULTI_MAX_AXES];
        size_t bad;
        int planned;
        g->plan_pending = 0;
        planned = plan_all(g, &g->request, out, plans, tmin, &bad);
        if (planned == SMS_REPLAN_WAIT) {
            g->plan_pending = 1; /* position limits: not from this state, tried on the next */
        } else if (planned) {
            install(g, &g->request, out, plans, tmin);
            for (i = 0; i < g->n_axes; ++i) { /* the same q, v, a; the new jerk */
                sms_plan_eval(&g->axis[i].plan, g->Ts_signal, 0, out + 4 * i);
                if (g->bounded[i]) {
                    const sms_plan_box box = axis_box(g, i);
                    sms_plan_hold_position(&box, out + 4 * i);
                }
            }
        } else {
            g->plan_refused = 1; /* the running plans go on until the target changes */
            ++g->dropped;
        }
    }
}

void sms_multi_sync_step_profile(sms_multi_generator *g, const sms_multi_target *t,
                                 sms_real *out)
{
    take_target(g, t);
    sms_multi_sync_step_held(g, out);
}

int sms_multi_takes_position(const sms_multi_generator *g, size_t i, sms_real x)
{
    return finite_real(x) && (!g->bounded[i] || (x >= g->qmin[i] && x <= g->qmax[i]));
}

/* sms_multi_generator_step() in the per-axis plan modes: positions at rest, a non-finite
 * component keeping that axis's previous target position. */
void sms_multi_sync_rest_target(const sms_multi_generator *g, const sms_real *position,
                                sms_multi_target *t)
{
    size_t i;
    *t = g->request;
    for (i = 0; i < g->n_axes; ++i) {
        if (sms_multi_takes_position(g, i, position[i]))
            t->position[i] = position[i];
        t->velocity[i] = 0;
        t->acceleration[i] = 0;
        t->sync[i] = 0;
    }
    t->minimum_duration = 0;
}

int sms_multi_sync_fresh(const sms_multi_generator *g, const sms_multi_target *t)
{
    return !same_target(t, &g->request, g->n_axes);
}

int sms_multi_sync_fresh_aim(const sms_multi_generator *g)
{
    return !same_target(&g->request, &g->aim, g->n_axes) &&
           sms_multi_generator_check_target(g, &g->request, NULL) == SMS_OK;
}

int sms_multi_sync_busy(const sms_multi_generator *g)
{
    size_t i;
    if (g->plan_pending)
        return 1;
    for (i = 0; i < g->n_axes; ++i)
        if (g->axis[i].k <= g->axis[i].plan.end || g->axis[i].plan.drift != 0)
            return 1;
    return 0;
}

/* n - 1 samples of index only: nothing but k changes while the request holds and nothing is
 * pending (a plan's sample k is closed form). A plan at rest saturates at its end + 1. */
void sms_multi_sync_skip(sms_multi_generator *g, uint64_t n)
{
    size_t i;
    for (i = 0; i < g->n_axes; ++i) {
        sms_multi_axis_plan *ax = &g->axis[i];
        if (ax->plan.drift == 0) {
            const uint64_t rest = ax->k > ax->plan.end ? 0u : (uint64_t)(ax->plan.end + 1 - ax->k);
            ax->k += (size_t)(n < rest ? n : rest);
        } else {
            ax->k += (size_t)n;
        }
    }
}

uint64_t sms_multi_generator_axis_arrival(const sms_multi_generator *g, size_t axis)
{
    size_t at;
    if (!SMS_SYNC_PER_AXIS_PLANS(g->sync) || axis >= g->n_axes)
        return 0u;
    at = sms_plan_arrival_sample(&g->axis[axis].plan, g->Ts_signal);
    return at > g->axis[axis].k ? (uint64_t)(at - g->axis[axis].k) : 0u;
}

uint64_t sms_multi_generator_arrival(const sms_multi_generator *g)
{
    size_t i;
    uint64_t left = 0;
    for (i = 0; i < g->n_axes; ++i) {
        const uint64_t at = sms_multi_generator_axis_arrival(g, i);
        if (at > left)
            left = at;
    }
    return left;
}

/* The planner's precondition on a start state, to the reported values' tolerance. */
static sms_status start_state_ok(const sms_multi_generator *g, size_t i, sms_real q,
                                 sms_real v, sms_real a)
{
    const double V = (double)g->vmax[i] * (1.0 + SMS_LIMIT_RTOL);
    const double A = (double)g->amax[i] * (1.0 + SMS_LIMIT_RTOL);
    const double brake = (double)v + (double)a * fabs((double)a) / (2.0 * (double)g->jmax[i]);
    if (!finite_real(q))
        return SMS_ERR_TARGET_POSITION;
    if (g->bounded[i] && !(q >= g->qmin[i] && q <= g->qmax[i]))
        return SMS_ERR_POSITION_LIMIT;
    if (!finite_real(v) || !(fabs((double)v) <= V))
        return SMS_ERR_TARGET_VELOCITY;
    if (!finite_real(a) || !(fabs((double)a) <= A) || !(fabs(brake) <= V))
        return SMS_ERR_TARGET_ACCELERATION;
    return SMS_OK;
}

/* plan_all() for sms_multi_generator_start(): its status, the axis that waits in *axis. */
static sms_status start_plans(const sms_multi_generator *g, const sms_multi_target *t,
                              const sms_real *s, sms_plan *plans, sms_real *tmin, size_t *axis)
{
    size_t bad = 0;
    const int planned = plan_all(g, t, s, plans, tmin, &bad);
    if (planned == 1)
        return SMS_OK;
    if (planned == SMS_REPLAN_WAIT) {
        /* position limits: neither the motion to the target nor the brake to rest stays
         * inside */
        if (axis != NULL)
            *axis = bad;
        return SMS_ERR_POSITION_LIMIT;
    }
    return SMS_ERR_TOO_LONG;
}

sms_status sms_multi_generator_start(sms_multi_generator *g, const sms_real *q,
                                     const sms_real *v, const sms_real *a,
                                     const sms_multi_target *target, size_t *axis)
{
    sms_real s[4 * SMS_MULTI_MAX_AXES], tmin[SMS_MULTI_MAX_AXES];
    sms_plan plans[SMS_MULTI_MAX_AXES];
    sms_multi_target t;
    size_t i;
    sms_status st;
    if (axis != NULL)
        *axis = 0;
    if (g == NULL || q == NULL || v == NULL || a == NULL)
        return SMS_ERR_NULL;
    if (!SMS_SYNC_PER_AXIS_PLANS(g->sync))
        return SMS_ERR_KIND;
    for (i = 0; i < g->n_axes; ++i) {
        st = start_state_ok(g, i, q[i], v[i], a[i]);
        if (st != SMS_OK) {
            if (axis != NULL)
                *axis = i;
            return st;
        }
        s[4 * i] = q[i];
        s[4 * i + 1] = v[i];
        s[4 * i + 2] = a[i];
        s[4 * i + 3] = 0;
    }
    if (target != NULL) {
        st = sms_multi_generator_check_target(g, target, axis);
        if (st != SMS_OK)
            return st;
        st = start_plans(g, target, s, plans, tmin, axis);
        if (st != SMS_OK)
            return st;
        t = *target;
    } else {
        /* each axis's own stop: its target is where the fastest stop rests, planned as a
         * position target of its own (so a saved state re-forms the same plan) */
        memset(&t, 0, sizeof t);
        for (i = 0; i < g->n_axes; ++i) {
            const sms_to_limits lim = axis_limits(g, i);
            const sms_plan_box box = axis_box(g, i);
            if (!sms_plan_velocity(&plans[i], &lim, g->Ts_signal, q[i], v[i], a[i], 0, 0, 0))
                return SMS_ERR_TOO_LONG;
            if (g->bounded[i] && !sms_plan_inside(&box, &plans[i])) {
                if (axis != NULL)
                    *axis = i;
                return SMS_ERR_POSITION_LIMIT; /* the brake itself crosses */
            }
            t.position[i] = plans[i].goal;
            if (g->bounded[i]) /* inside to the rounding of the brake's extremes */
                sms_plan_hold_position(&box, &t.position[i]);
            t.sync[i] = SMS_SYNC_NONE;
        }
        st = start_plans(g, &t, s, plans, tmin, axis);
        if (st != SMS_OK)
            return st;
    }
    install(g, &t, s, plans, tmin);
    g->request = t;
    return SMS_OK;
}

/* Re-form axis i's plan from its saved start state and minimum duration (the saved state):
 * 1 when it is formed. */
int sms_multi_sync_replan_axis(const sms_multi_generator *g, size_t i,
                               const sms_multi_target *t, sms_multi_axis_plan *ax)
{
    return plan_axis(g, i, &ax->plan, ax->q0, ax->v0, ax->a0, t, ax->tmin) == 1;
}

int sms_multi_sync_start_ok(const sms_multi_generator *g, size_t i, double q, double v,
                            double a)
{
    return start_state_ok(g, i, (sms_real)q, (sms_real)v, (sms_real)a) == SMS_OK;
}
