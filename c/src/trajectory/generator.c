/* SPDX-License-Identifier: Apache-2.0 */
/* Online multi-point generator (trajectory.h, docs/sampled-limits.md): the time-optimal plan of
 * the profile's shape from the current state on every new target (plan.c), run through the
 * stage tuned to the mode when there is one. init may use libm; step is O(1) without it. */
#include <float.h>
#include <math.h>
#include <string.h>
#include "smoothshaper/trajectory.h"
#include "trajectory/plan.h"
#include "core/state_identity.h"
#include "trajectory/trajectory_internal.h"

/* A saved state: the identity (SMS_GENERATOR_IDENTITY_COUNT), then target, goal, the plan's
 * start q, v, a and k (GEN_PLAN_STATE_COUNT), then with a mode quiet and the stage states. */
#define GEN_PLAN_STATE_COUNT 6u
#define GEN_PLAN (SMS_GENERATOR_IDENTITY_COUNT)
#define GEN_STAGES (GEN_PLAN + GEN_PLAN_STATE_COUNT)

/* The identity fields after the common head, in this order (trajectory.h). */
enum { ID_VMAX = SMS_STATE_IDENTITY_HEAD, ID_AMAX, ID_JMAX, ID_PROFILE, ID_WN, ID_ZETA };

static void generator_identity(const sms_generator_config *c, double Ts,
                               double id[SMS_GENERATOR_IDENTITY_COUNT])
{
    sms_state_identity_head(id, SMS_STATE_KIND_GENERATOR, Ts);
    id[ID_VMAX] = c->vmax;
    id[ID_AMAX] = c->amax;
    id[ID_JMAX] = c->jmax;
    id[ID_PROFILE] = (double)c->profile;
    id[ID_WN] = c->wn;
    id[ID_ZETA] = c->zeta;
}

/* The feasible limit sets (trajectory.h, sms_generator_reach()). For a move from any state
 * within the bounds the planner forms velocity changes J dv with |dv| <= 2 vmax (J the shape's
 * mean jerk), squares of accelerations up to the peak ap = min(amax, sqrt(vmax J)), durations
 * up to about those of the move that reaches vmax from rest and stops, T = 2 (vmax/ap + ap/J),
 * and distances up to a few times its distance h = vmax T/2. Each must stay finite with room
 * for a reversal (GEN_MARGIN) and well above the smallest normal number (GEN_REAL_TINY), and
 * T must fit the plan's sample counts with the same room (2^50 of the plan's 2^52). */
#define GEN_REAL_MAX (sizeof(sms_real) == sizeof(double) ? DBL_MAX : (double)FLT_MAX)
#define GEN_REAL_MIN (sizeof(sms_real) == sizeof(double) ? DBL_MIN : (double)FLT_MIN)
/* the smallest normal number over the machine epsilon: products at least this large keep the
 * shorter moves' own products (down to about eps^1.5 of h) normal */
#define GEN_REAL_TINY (sizeof(sms_real) == sizeof(double) ? DBL_MIN / DBL_EPSILON \
                                                          : (double)FLT_MIN / (double)FLT_EPSILON)
#define GEN_MARGIN 16.0
#define GEN_MAX_REACH_SAMPLES 1125899906842624.0 /* 2^50 */

sms_status sms_reach_refused(sms_generator_reach_info *r, const char *quantity,
                             const char *arguments, double value, double bound)
{
    r->quantity = quantity;
    r->arguments = arguments;
    r->value = value;
    r->bound = bound;
    return SMS_ERR_LIMIT;
}

sms_status sms_generator_reach(const sms_generator_config *c, double Ts,
                               sms_generator_reach_info *reach)
{
    sms_generator_reach_info local, *r = reach != NULL ? reach : &local;
    double V, A, J, ap, tv, tj, big = GEN_REAL_MAX, tiny = GEN_REAL_TINY;
    int reached;
    memset(r, 0, sizeof *r);
    if (c == NULL)
        return SMS_ERR_NULL;
    if (!isfinite(Ts) || !(Ts > 0.0) || !((sms_real)Ts > 0) || !(Ts <= big)) {
        (void)sms_reach_refused(r, "Ts", "Ts", Ts, big);
        return SMS_ERR_SAMPLE_PERIOD;
    }
    {
        static const char *const names[3] = {"vmax", "amax", "jmax"};
        const double limit[3] = {c->vmax, c->amax, c->jmax};
        int i;
        for (i = 0; i < 3; ++i) /* each a normal number with room for 2 x and 16 x */
            if (!(limit[i] >= GEN_REAL_MIN) || !(limit[i] <= big / GEN_MARGIN)) /* also NaN */
                return sms_reach_refused(r, names[i], names[i], limit[i],
                                         limit[i] >= GEN_REAL_MIN ? big / GEN_MARGIN
                                                                  : GEN_REAL_MIN);
    }
    V = c->vmax;
    A = c->amax;
    J = c->jmax;
    if (c->profile == SMS_PROFILE_TRIGONOMETRIC)
        J *= 0.63661977236758134; /* the half-cosine transitions' mean jerk, 2/pi jmax */
    if (!(V * J * GEN_MARGIN <= big)) /* J dv, |dv| <= 2 vmax */
        return sms_reach_refused(r, "vmax*jmax", "vmax, jmax", c->vmax * c->jmax,
                                 big / GEN_MARGIN);
    ap = sqrt(V) * sqrt(J);
    reached = A < ap;
    if (reached)
        ap = A;
    r->peak_acceleration = ap;
    tv = V / ap; /* vmax/amax, or sqrt(vmax/J) when amax is not reached */
    tj = ap / J; /* amax/J, or the same sqrt(vmax/J) */
    r->duration = 2.0 * (tv + tj);
    r->samples = r->duration / Ts;
    r->distance = V * (tv + tj);
    if (!(r->samples <= GEN_MAX_REACH_SAMPLES)) {
        double per_term = GEN_MAX_REACH_SAMPLES * Ts / (reached ? 2.0 : 4.0);
        /* amax reached (amax^2 < vmax J) makes amax/J < vmax/amax: the longer term */
        if (reached)
            return sms_reach_refused(r, "vmax/amax", "vmax, amax", tv, per_term);
        return sms_reach_refused(r, c->profile == SMS_PROFILE_TRIGONOMETRIC
                                        ? "sqrt(pi vmax/(2 jmax))" : "sqrt(vmax/jmax)",
                                 "vmax, jmax", tv, per_term);
    }
    if (!(ap * ap >= tiny)) /* a^2 of the peak and of every state on the way */
        return reached ? sms_reach_refused(r, "amax^2", "amax", A * A, tiny)
                       : sms_reach_refused(r, "vmax*jmax", "vmax, jmax", c->vmax * c->jmax, tiny);
    if (!(r->duration >= GEN_REAL_MIN))
        return sms_reach_refused(r, "the duration to reach vmax", "vmax, amax, jmax",
                                 r->duration, GEN_REAL_MIN);
    if (!(r->distance * GEN_MARGIN <= big))
        return sms_reach_refused(r, "the distance to reach vmax", "vmax, amax, jmax",
                                 r->distance, big / GEN_MARGIN);
    if (!(r->distance >= tiny))
        return sms_reach_refused(r, "the distance to reach vmax", "vmax, amax, jmax",
                                 r->distance, tiny);
    return SMS_OK;
}

/* Validate the config; with a mode, the stage tuned to it (the shortest whose zero cancels
 * it: k = 1) and its ring length. */
static sms_status design(const sms_generator_config *c, double Ts, sms_stage_config *stage,
                         size_t *ring)
{
    sms_status st;
    double wd;
    if (c == NULL)
        return SMS_ERR_NULL;
    st = sms_generator_reach(c, Ts, NULL);
    if (st != SMS_OK)
        return st;
    if ((unsigned)c->profile > (unsigned)SMS_PROFILE_DAMPED)
        return SMS_ERR_KIND;
    if (!isfinite(c->wn) || c->wn < 0.0 || (c->profile == SMS_PROFILE_DAMPED && c->wn == 0.0))
        return SMS_ERR_WN;
    if (!isfinite(c->zeta) || c->zeta < 0.0 || c->zeta >= 1.0)
        return SMS_ERR_ZETA;
    *ring = 0;
    if (c->wn == 0.0)
        return SMS_OK;
    if (c->wn * Ts >= 3.14159265358979323846)
        return SMS_ERR_ABOVE_NYQUIST;
    wd = c->wn * sqrt(1.0 - c->zeta * c->zeta);
    switch (c->profile) {
    case SMS_PROFILE_TRIGONOMETRIC:
        /* a damped mode: the damped half sine, whose zero carries the decay */
        *stage = sms_stage_config_default(c->zeta > 0.0 ? SMS_DAMPED_HARMONIC : SMS_HARMONIC);
        stage->T = 3.0 * 3.14159265358979323846 / wd;
        stage->sigma = -c->zeta * c->wn;
        break;
    case SMS_PROFILE_DAMPED:
        *stage = sms_stage_config_default(SMS_EXPONENTIAL);
        stage->T = 2.0 * 3.14159265358979323846 / wd;
        stage->sigma = -c->zeta * c->wn;
        break;
    default:
        *stage = sms_stage_config_default(SMS_RECTANGULAR);
        stage->T = 2.0 * 3.14159265358979323846 / wd;
        break;
    }
    stage->k = 1u;
    stage->timing = SMS_TIMING_EXACT;
    st = sms_smoother_buffer_size(stage, Ts, ring);
    if (st != SMS_OK)
        return st;
    if (*ring > ((size_t)-1) / (4u * sizeof(sms_real)))
        return SMS_ERR_TOO_LONG;
    return SMS_OK;
}

sms_status sms_generator_buffer_size(const sms_generator_config *config, double Ts, size_t *n_reals)
{
    sms_stage_config stage;
    size_t ring;
    sms_status st;
    if (n_reals == NULL || config == NULL)
        return SMS_ERR_NULL;
    st = design(config, Ts, &stage, &ring);
    if (st == SMS_OK)
        *n_reals = 4u * ring;
    return st;
}

sms_status sms_generator_init(sms_generator *g, const sms_generator_config *config, double Ts,
                              sms_real *buffer, size_t n_reals)
{
    sms_stage_config stage;
    sms_smoother f[4];
    size_t ring, i;
    sms_status st;
    if (g == NULL || config == NULL)
        return SMS_ERR_NULL;
    st = design(config, Ts, &stage, &ring);
    if (st != SMS_OK)
        return st;
    if (ring > 0) {
        if (buffer == NULL)
            return SMS_ERR_NULL;
        if (n_reals < 4u * ring)
            return SMS_ERR_BUFFER_TOO_SMALL;
        for (i = 0; i < 4; ++i) {
            st = sms_smoother_init(&f[i], &stage, Ts, buffer + i * ring, ring);
            if (st != SMS_OK)
                return st;
        }
        for (i = 0; i < 4; ++i)
            g->stage[i] = f[i];
        g->stage_T = stage.T;
        g->stage_length = f[0].length;
    } else {
        g->stage_T = 0.0;
        g->stage_length = 0;
    }
    g->stage_window = ring;
    g->buffer = ring > 0 ? buffer : NULL;
    g->Ts = Ts;
    g->vmax = config->vmax;
    g->shape = config->profile == SMS_PROFILE_TRIGONOMETRIC ? SMS_PLAN_COSINE : SMS_PLAN_RAMP;
    g->Ts_signal = (sms_real)Ts;
    g->time_optimal = 1;
    g->limits.vmax = (sms_real)config->vmax;
    g->limits.amax = (sms_real)config->amax;
    g->limits.jmax = (sms_real)config->jmax;
    generator_identity(config, Ts, g->identity);
    sms_generator_reset(g, 0);
    return SMS_OK;
}

void sms_generator_reset(sms_generator *g, sms_real position)
{
    size_t i;
    if (position - position != 0)
        return; /* NaN/Inf: stay where it is */
    g->plan_q = position;
    g->plan_v = 0;
    g->plan_a = 0;
    g->k = 0;
    g->plan.count = 0;
    g->plan.shape = g->shape;
    g->plan.goal = position;
    g->plan.end = 0;
    g->plan.end_f = 0;
    g->plan.duration = 0;
    g->target = position;
    g->refused = 0;
    g->dropped = 0;
    g->quiet = g->stage_length;
    if (g->stage_length > 0)
        for (i = 0; i < 4; ++i)
            sms_smoother_reset(&g->stage[i], i == 0 ? position : 0);
}

/* Can a plan of the generator's shape start from (v, a)? The planner's precondition: bringing
 * a to zero at once (a fresh transition at the shape's mean jerk) keeps |v| <= vmax. A ramp
 * plan's own states always satisfy it (to rounding, which the planner absorbs). A half-cosine
 * transition that brings a to zero starts with zero jerk, so early in it the fresh estimate
 * exceeds vmax although the transition itself ends on vmax: the re-plan then waits for a
 * sample where it holds (at the latest the end of that transition, whose next segment starts
 * on vmax with a = 0 exactly). No tolerance: a plan started from a state whose estimate is
 * over vmax takes v that far over it (a relative 1e-5 in float reported v 1e-5 above vmax). */
static int can_start(const sms_generator *g, sms_real v, sms_real a)
{
    sms_real brake, V = g->limits.vmax;
    if (g->shape != SMS_PLAN_COSINE)
        return 1;
    brake = v + a * (a < 0 ? -a : a) / (2 * sms_plan_mean_jerk(&g->limits, g->shape));
    if (brake < 0)
        brake = -brake;
    return brake <= V;
}

/* Advance the plan one sample; re-plan from the exact state there when the target differs
 * from the plan's goal (and the state allows it, can_start()). */
static void step_plan(sms_generator *g, sms_real target, sms_real out[4])
{
    if (target - target == 0 && target != g->target) { /* finite (NaN, Inf give NaN), new */
        g->target = target;
        g->refused = 0;
    }
    ++g->k;
    sms_plan_eval(&g->plan, g->Ts_signal, g->k, out);
    if (g->target != g->plan.goal && !g->refused && can_start(g, out[1], out[2])) {
        /* a move that cannot be represented (sms_plan_to_rest_shaped() returns 0) is dropped:
         * the running plan goes on, and the target is not tried again until it changes */
        if (sms_plan_to_rest_shaped(&g->plan, &g->limits, g->shape, g->Ts_signal, out[0],
                                    out[1], out[2], g->target)) {
            g->plan_q = out[0];
            g->plan_v = out[1];
            g->plan_a = out[2];
            g->k = 0;
            sms_plan_eval(&g->plan, g->Ts_signal, 0, out); /* the same q, v, a; the new jerk */
        } else {
            g->refused = 1;
            ++g->dropped;
        }
    }
}

/* The plan at rest on its goal for the stage's whole length: the average of equal values is
 * that value, so the output is the goal exactly (the rings keep running). Counts the samples
 * of the plan's output o at rest, up to the stage's length. */
static void count_quiet(sms_generator *g, const sms_real o[4])
{
    if (o[0] == g->plan.goal && o[1] == 0 && o[2] == 0 && o[3] == 0) {
        if (g->quiet < g->stage_length)
            ++g->quiet;
    } else {
        g->quiet = 0;
    }
}

void sms_generator_step(sms_generator *g, sms_real target, sms_real out[4])
{
    size_t i;
    step_plan(g, target, out);
    if (g->stage_length == 0)
        return;
    count_quiet(g, out);
    for (i = 0; i < 4; ++i)
        sms_smoother_step(&g->stage[i], &out[i]);
    if (g->quiet >= g->stage_length) {
        out[0] = g->plan.goal;
        out[1] = 0;
        out[2] = 0;
        out[3] = 0;
    }
}

/* n samples of a fixed plan (no re-plan to come) through the tuned stage, in blocks: the
 * plan's samples first, then each signal's stage over the block; what n calls of
 * sms_generator_step() do, bit for bit (the stage's process is its step on a block). */
static void hold_plan_through_stage(sms_generator *g, uint64_t n, sms_real out[4])
{
    sms_real x[4][64], o[4];
    size_t i, c, b = 0;
    while (n > 0u) {
        b = n < 64u ? (size_t)n : 64u;
        for (i = 0; i < b; ++i) {
            sms_plan_eval(&g->plan, g->Ts_signal, ++g->k, o);
            count_quiet(g, o);
            for (c = 0; c < 4; ++c)
                x[c][i] = o[c];
        }
        for (c = 0; c < 4; ++c)
            sms_smoother_process(&g->stage[c], x[c], x[c], b);
        n -= b;
    }
    if (b == 0)
        return;
    for (c = 0; c < 4; ++c)
        out[c] = g->quiet >= g->stage_length ? (c == 0 ? g->plan.goal : (sms_real)0)
                                             : x[c][b - 1];
}

/* A re-plan still to come under the held target (a new target, or one waiting for a state
 * the plan can start from, can_start()). */
static int replan_pending(const sms_generator *g, sms_real target)
{
    if (target - target == 0 && target != g->target)
        return 1;
    return g->target != g->plan.goal && !g->refused;
}

void sms_generator_hold(sms_generator *g, sms_real target, uint64_t n, sms_real out[4])
{
    uint64_t window, rest_at;
    size_t i;
    /* until the held target has been planned (or dropped): from then on the plan is fixed */
    while (n > 0u && replan_pending(g, target)) {
        sms_generator_step(g, target, out);
        --n;
    }
    if (n == 0u)
        return;
    /* the plan in closed form: sample k of it is sms_plan_eval(k) */
    if (g->stage_length == 0) {
        g->k += (size_t)(n - 1u);
        sms_generator_step(g, target, out);
        return;
    }
    /* With the tuned stage: a stage's state depends only on its last 2M + 2 inputs (both
     * copies restart within them and the ring is refilled; quiet saturates within L <= M + 1). */
    window = 2u * (uint64_t)g->stage_window + 2u;
    rest_at = sms_plan_rest_sample(&g->plan, g->Ts_signal);
    rest_at = rest_at > g->k ? rest_at - g->k : 0u;   /* samples of this hold before the rest */
    if (n - 1u >= rest_at + window + 1u) {
        /* the stages see the rest (goal, 0, 0, 0) for their last 2M + 3 inputs: absorbed */
        sms_real x[4];
        x[0] = g->plan.goal;
        x[1] = x[2] = x[3] = 0;
        for (i = 0; i < 4; ++i)
            (void)sms_smoother_settle(&g->stage[i], x[i], n - 1u);
        g->k += (size_t)(n - 1u);
        g->quiet = g->stage_length;
        sms_generator_step(g, target, out);
        return;
    }
    {
        /* At the end the elder copy will have consumed M + s samples (s in [1, M], from the
         * phase now), so the stage's state depends on the last M + s inputs alone. */
        const uint64_t M = g->stage_window;
        const uint64_t s_now = g->stage[0].head;   /* the elder has consumed M + head (mod M) */
        window = M + (s_now + n - 1u) % M + 1u + 2u;
    }
    if (n > window) {
        /* jump to the last M + s + 2 samples: the plan by its index, the stages by their phase
         * (the values they hold then are replaced by the samples below) */
        g->k += (size_t)(n - window);
        for (i = 0; i < 4; ++i)
            sms_smoother_advance(&g->stage[i], n - window);
        g->quiet = 0;
        n = window;
    }
    hold_plan_through_stage(g, n, out);
}

void sms_generator_process(sms_generator *g, const sms_real *targets, size_t n, sms_real *out)
{
    size_t i;
    for (i = 0; i < n; ++i)
        sms_generator_step(g, targets[i], out + 4u * i);
}

double sms_generator_tail_duration(const sms_generator *g)
{
    return g->stage_T;
}

size_t sms_generator_state_count(const sms_generator *g)
{
    if (g->stage_length == 0)
        return GEN_STAGES;
    return GEN_STAGES + 1u + 4u * sms_smoother_state_count(&g->stage[0]);
}

void sms_generator_get_state(const sms_generator *g, double *dst)
{
    size_t i, per;
    for (i = 0; i < SMS_GENERATOR_IDENTITY_COUNT; ++i)
        dst[i] = g->identity[i];
    dst[GEN_PLAN + 0] = (double)g->target;
    dst[GEN_PLAN + 1] = (double)g->plan.goal;
    dst[GEN_PLAN + 2] = (double)g->plan_q;
    dst[GEN_PLAN + 3] = (double)g->plan_v;
    dst[GEN_PLAN + 4] = (double)g->plan_a;
    dst[GEN_PLAN + 5] = (double)g->k;
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
        SMS_ERR_STATE_WN, SMS_ERR_STATE_ZETA
    };
    return sms_state_identity_compare(g->identity, src,
                                      SMS_GENERATOR_IDENTITY_COUNT - SMS_STATE_IDENTITY_HEAD,
                                      field_status);
}

sms_status sms_generator_check_state(const sms_generator *g, const double *src, size_t n)
{
    double V, A, J, v, a, brake;
    const double *p;
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
    for (i = 0; i < 5; ++i)
        if (!isfinite(p[i]) || (sms_real)p[i] - (sms_real)p[i] != 0)
            return SMS_ERR_STATE;
    /* a state a plan can start from, as the generator itself leaves them: v and a within
     * the bounds, and able to bring a to zero (at the shape's mean jerk) without passing vmax,
     * each to the reported values' 32 u (SMS_LIMIT_RTOL; the generator's own states stay
     * within 15 u, tests/c/test_generator.c), checked on the values as sms_real holds them */
    V = (double)g->limits.vmax * (1.0 + SMS_LIMIT_RTOL);
    A = (double)g->limits.amax * (1.0 + SMS_LIMIT_RTOL);
    J = (double)sms_plan_mean_jerk(&g->limits, g->shape);
    v = (double)(sms_real)p[3];
    a = (double)(sms_real)p[4];
    brake = v + a * fabs(a) / (2.0 * J);
    if (!(fabs(v) <= V) || !(fabs(a) <= A) || !(fabs(brake) <= V))
        return SMS_ERR_STATE;
    if (!is_count(p[5], 9007199254740992.0)) /* 2^53 */
        return SMS_ERR_STATE;
    {
        /* the running plan must be one the generator can form again */
        sms_plan plan;
        if (!sms_plan_to_rest_shaped(&plan, &g->limits, g->shape, g->Ts_signal,
                                     (sms_real)p[2], (sms_real)p[3], (sms_real)p[4],
                                     (sms_real)p[1]))
            return SMS_ERR_STATE;
    }
    if (g->stage_length == 0)
        return SMS_OK;
    if (!is_count(src[GEN_STAGES], (double)g->stage_length))
        return SMS_ERR_STATE;
    per = sms_smoother_state_count(&g->stage[0]);
    for (i = 0; i < 4; ++i)
        if (sms_smoother_check_state(&g->stage[i], src + GEN_STAGES + 1u + i * per, per) != SMS_OK)
            return SMS_ERR_STATE;
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
    g->target = (sms_real)p[0];
    g->plan_q = (sms_real)p[2];
    g->plan_v = (sms_real)p[3];
    g->plan_a = (sms_real)p[4];
    g->k = (size_t)p[5];
    g->refused = 0; /* a dropped target is tried (and dropped) again on the next sample */
    (void)sms_plan_to_rest_shaped(&g->plan, &g->limits, g->shape, g->Ts_signal, g->plan_q,
                                  g->plan_v, g->plan_a, (sms_real)p[1]); /* checked above */
    if (g->stage_length == 0)
        return SMS_OK;
    g->quiet = (size_t)src[GEN_STAGES];
    per = sms_smoother_state_count(&g->stage[0]);
    for (i = 0; i < 4; ++i)
        (void)sms_smoother_set_state(&g->stage[i], src + GEN_STAGES + 1u + i * per, per);
    return SMS_OK;
}

void sms_generator_rebind(sms_generator *g, sms_real *buffer)
{
    size_t i;
    if (g->stage_length == 0)
        return;
    g->buffer = buffer;
    for (i = 0; i < 4; ++i)
        g->stage[i].history = buffer + i * g->stage_window;
}
