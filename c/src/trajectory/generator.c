/* SPDX-License-Identifier: Apache-2.0 */
/* Online multi-point generator (trajectory.h, docs/sampled-limits.md): on every new target
 * the time-optimal plan of the profile's shape from the current state (plan.c for half-cosine
 * transitions, plan_target.c for ramps to any target state), run through the stage tuned to
 * the mode when there is one. init may use libm; a sample is O(1) without it, in sms_real.
 * The saved state is generator_state.c's. */
#include <float.h>
#include <math.h>
#include <string.h>
#include "smoothshaper/trajectory.h"
#include "trajectory/plan.h"
#include "trajectory/plan_target.h"
#include "trajectory/plan_bounded.h"
#include "trajectory/generator_parts.h"
#include "core/state_identity.h"
#include "trajectory/trajectory_internal.h"

enum { ID_VMAX = SMS_GEN_ID_VMAX, ID_AMAX, ID_JMAX, ID_PROFILE, ID_WN, ID_ZETA, ID_VMIN, ID_AMIN,
       ID_QMIN, ID_QMAX };

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
    id[ID_VMIN] = c->vmin != 0.0 ? c->vmin : -c->vmax;
    id[ID_AMIN] = c->amin != 0.0 ? c->amin : -c->amax;
    id[ID_QMIN] = c->qmin;
    id[ID_QMAX] = c->qmax;
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

/* The names of one pair of bounds (V, A) in the quantities a refusal reports. */
typedef struct reach_names {
    const char *v, *a, *ratio, *root, *root_cos, *vj, *a2, *va, *vj_args, *dur, *dist, *vaj;
} reach_names;

static const reach_names REACH_NAMES[4] = {
    {"vmax", "amax", "vmax/amax", "sqrt(vmax/jmax)", "sqrt(pi vmax/(2 jmax))", "vmax*jmax",
     "amax^2", "vmax, amax", "vmax, jmax", "the duration to reach vmax",
     "the distance to reach vmax", "vmax, amax, jmax"},
    {"vmin", "amin", "vmin/amin", "sqrt(vmin/jmax)", "sqrt(pi vmin/(2 jmax))", "vmin*jmax",
     "amin^2", "vmin, amin", "vmin, jmax", "the duration to reach vmin",
     "the distance to reach vmin", "vmin, amin, jmax"},
    {"vmax", "amin", "vmax/amin", "sqrt(vmax/jmax)", "sqrt(pi vmax/(2 jmax))", "vmax*jmax",
     "amin^2", "vmax, amin", "vmax, jmax", "the duration to reach vmax",
     "the distance to reach vmax", "vmax, amin, jmax"},
    {"vmin", "amax", "vmin/amax", "sqrt(vmin/jmax)", "sqrt(pi vmin/(2 jmax))", "vmin*jmax",
     "amax^2", "vmin, amax", "vmin, jmax", "the duration to reach vmin",
     "the distance to reach vmin", "vmin, amax, jmax"}
};

/* The derived checks (steps 2 to 5 of sms_generator_reach()) of the move that reaches the
 * velocity bound V from rest at the acceleration bound A and stops; V, A the magnitudes. */
static sms_status reach_pair(sms_generator_reach_info *r, const reach_names *nm, double V,
                             double A, double jmax, int trigonometric, double Ts)
{
    double J = jmax, ap, tv, tj, big = GEN_REAL_MAX, tiny = GEN_REAL_TINY;
    int reached;
    if (trigonometric)
        J *= 0.63661977236758134; /* the half-cosine transitions' mean jerk, 2/pi jmax */
    if (!(V * J * GEN_MARGIN <= big)) /* J dv, |dv| <= 2 vmax */
        return sms_reach_refused(r, nm->vj, nm->vj_args, V * jmax, big / GEN_MARGIN);
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
            return sms_reach_refused(r, nm->ratio, nm->va, tv, per_term);
        return sms_reach_refused(r, trigonometric ? nm->root_cos : nm->root, nm->vj_args, tv,
                                 per_term);
    }
    if (!(ap * ap >= tiny)) /* a^2 of the peak and of every state on the way */
        return reached ? sms_reach_refused(r, nm->a2, nm->a, A * A, tiny)
                       : sms_reach_refused(r, nm->vj, nm->vj_args, V * jmax, tiny);
    if (!(r->duration >= GEN_REAL_MIN))
        return sms_reach_refused(r, nm->dur, nm->vaj, r->duration, GEN_REAL_MIN);
    if (!(r->distance * GEN_MARGIN <= big))
        return sms_reach_refused(r, nm->dist, nm->vaj, r->distance, big / GEN_MARGIN);
    if (!(r->distance >= tiny))
        return sms_reach_refused(r, nm->dist, nm->vaj, r->distance, tiny);
    return SMS_OK;
}

sms_status sms_generator_reach(const sms_generator_config *c, double Ts,
                               sms_generator_reach_info *reach)
{
    sms_generator_reach_info local, *r = reach != NULL ? reach : &local, first;
    double big = GEN_REAL_MAX, Vn, An;
    int trig, asym, i;
    sms_status st;
    memset(r, 0, sizeof *r);
    if (c == NULL)
        return SMS_ERR_NULL;
    if (!isfinite(Ts) || !(Ts > 0.0) || !((sms_real)Ts > 0) || !(Ts <= big)) {
        (void)sms_reach_refused(r, "Ts", "Ts", Ts, big);
        return SMS_ERR_SAMPLE_PERIOD;
    }
    if (!(Ts <= SMS_TS_MAX)) {
        (void)sms_reach_refused(r, "Ts", "Ts", Ts, SMS_TS_MAX);
        return SMS_ERR_SAMPLE_PERIOD_RANGE;
    }
    {
        static const char *const names[3] = {"vmax", "amax", "jmax"};
        const double limit[3] = {c->vmax, c->amax, c->jmax};
        for (i = 0; i < 3; ++i) /* each a normal number with room for 2 x and 16 x */
            if (!(limit[i] >= GEN_REAL_MIN) || !(limit[i] <= big / GEN_MARGIN)) /* also NaN */
                return sms_reach_refused(r, names[i], names[i], limit[i],
                                         limit[i] >= GEN_REAL_MIN ? big / GEN_MARGIN
                                                                  : GEN_REAL_MIN);
    }
    trig = c->profile == SMS_PROFILE_TRIGONOMETRIC;
    asym = c->vmin != 0.0 || c->amin != 0.0;
    if (asym) {
        /* each lower bound 0 (symmetric) or a negative normal number with the same room;
         * ramps only (the half-cosine plans are symmetric) */
        static const char *const names[2] = {"vmin", "amin"};
        const double limit[2] = {c->vmin, c->amin}, upper[2] = {c->vmax, c->amax};
        static const char *const with_profile[2] = {"vmin, profile", "amin, profile"};
        for (i = 0; i < 2; ++i) {
            if (limit[i] == 0.0)
                continue;
            if (trig && limit[i] == -upper[i])
                continue; /* the symmetric bound given explicitly */
            if (trig) /* bound 0: only the symmetric default (or -vmax, -amax) */
                return sms_reach_refused(r, names[i], with_profile[i], limit[i], 0.0);
            if (!(-limit[i] >= GEN_REAL_MIN)) /* positive, NaN or too small */
                return sms_reach_refused(r, names[i], names[i], limit[i], -GEN_REAL_MIN);
            if (!(-limit[i] <= big / GEN_MARGIN))
                return sms_reach_refused(r, names[i], names[i], limit[i], -big / GEN_MARGIN);
        }
    }
    if (c->qmin != 0.0 || c->qmax != 0.0) {
        /* position limits: finite, ordered as sms_real holds them, with room for a reversal
         * (16 x); linear ramps only (the extremes of a half-cosine segment are not formed) */
        if (trig)
            return sms_reach_refused(r, c->qmin != 0.0 ? "qmin" : "qmax", "qmin, qmax, profile",
                                     c->qmin != 0.0 ? c->qmin : c->qmax, 0.0);
        if (!(fabs(c->qmin) <= big / GEN_MARGIN))
            return sms_reach_refused(r, "qmin", "qmin", c->qmin, big / GEN_MARGIN);
        if (!(fabs(c->qmax) <= big / GEN_MARGIN))
            return sms_reach_refused(r, "qmax", "qmax", c->qmax, big / GEN_MARGIN);
        if (!((sms_real)c->qmin < (sms_real)c->qmax))
            return sms_reach_refused(r, "qmax", "qmin, qmax", c->qmax, c->qmin);
    }
    Vn = c->vmin != 0.0 ? -c->vmin : c->vmax;
    An = c->amin != 0.0 ? -c->amin : c->amax;
    st = reach_pair(r, &REACH_NAMES[0], c->vmax, c->amax, c->jmax, trig, Ts);
    if (st != SMS_OK || !asym)
        return st;
    /* the reverse move, and each velocity bound with the other acceleration bound (reaching
     * one bound accelerates with one acceleration bound and stops with the other) */
    first = *r;
    {
        const double V[3] = {Vn, c->vmax, Vn}, A[3] = {An, An, c->amax};
        for (i = 0; i < 3; ++i) {
            st = reach_pair(r, &REACH_NAMES[i + 1], V[i], A[i], c->jmax, trig, Ts);
            if (st != SMS_OK)
                return st;
        }
    }
    *r = first;
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
    g->vmin = config->vmin != 0.0 ? (sms_real)config->vmin : -g->limits.vmax;
    g->amin = config->amin != 0.0 ? (sms_real)config->amin : -g->limits.amax;
    g->asymmetric = g->vmin != -g->limits.vmax || g->amin != -g->limits.amax;
    g->qmin = (sms_real)config->qmin;
    g->qmax = (sms_real)config->qmax;
    g->qtol = sms_plan_box_tolerance(config->qmin, config->qmax);
    generator_identity(config, Ts, g->identity);
    /* rest at 0, or at the limit nearer 0 when 0 is outside; the limits apply from here on */
    g->bounded = 0;
    sms_generator_reset(g, g->qmin > 0 ? g->qmin : g->qmax < 0 ? g->qmax : 0);
    g->bounded = config->qmin != 0.0 || config->qmax != 0.0;
    return SMS_OK;
}

void sms_generator_reset(sms_generator *g, sms_real position)
{
    size_t i;
    if (position - position != 0)
        return; /* NaN/Inf: stay where it is */
    if (g->bounded && !(position >= g->qmin && position <= g->qmax))
        return; /* outside the position limits: the same */
    g->plan_q = position;
    g->plan_v = 0;
    g->plan_a = 0;
    g->k = 0;
    g->plan.count = 0;
    g->plan.shape = g->shape;
    g->plan.goal = position;
    g->plan.drift = 0;
    g->plan.end = 0;
    g->plan.end_f = 0;
    g->plan.arrive = 0;
    g->plan.arrive_f = 0;
    g->plan.duration = 0;
    g->target.position = position;
    g->target.velocity = 0;
    g->target.acceleration = 0;
    g->target.interface = SMS_INTERFACE_POSITION;
    g->target.minimum_duration = 0;
    g->goal = g->target;
    g->request = g->target;
    g->pending = 0;
    g->refused = 0;
    g->dropped = 0;
    g->quiet = g->stage_length;
    if (g->stage_length > 0)
        for (i = 0; i < 4; ++i)
            sms_smoother_reset(&g->stage[i], i == 0 ? position : 0);
}

static int finite_real(sms_real x)
{
    return x - x == 0; /* NaN and +-Inf give NaN */
}

int sms_generator_state_ok(const sms_generator *g, double v, double a, double rtol)
{
    double V = (double)g->limits.vmax * (1.0 + rtol), A = (double)g->limits.amax * (1.0 + rtol);
    double Vl = (double)g->vmin * (1.0 + rtol), Al = (double)g->amin * (1.0 + rtol);
    double J = (double)sms_plan_mean_jerk(&g->limits, g->shape);
    double brake = v + a * fabs(a) / (2.0 * J);
    return v >= Vl && v <= V && a >= Al && a <= A && brake >= Vl && brake <= V;
}

static sms_real mag(sms_real x)
{
    return x < 0 ? -x : x;
}

/* In sms_real (it runs on every sample): the limits as sms_real holds them. */
sms_status sms_generator_canonical(const sms_generator *g, const sms_target *in, sms_target *out)
{
    sms_target t;
    sms_real V, A, reach;
    if (g == NULL || in == NULL)
        return SMS_ERR_NULL;
    t = *in;
    switch (t.interface) {
    case SMS_INTERFACE_STOP:
        t.interface = SMS_INTERFACE_VELOCITY;
        t.velocity = 0;
        t.acceleration = 0;
        t.position = 0;
        t.minimum_duration = 0;
        *out = t;
        return SMS_OK;
    case SMS_INTERFACE_VELOCITY:
        t.position = 0;
        break;
    case SMS_INTERFACE_POSITION:
        if (!finite_real(t.position))
            return SMS_ERR_TARGET_POSITION;
        if (g->bounded && !(t.position >= g->qmin && t.position <= g->qmax))
            return SMS_ERR_POSITION_LIMIT;
        break;
    default:
        return SMS_ERR_INTERFACE;
    }
    if (!finite_real(t.velocity))
        return SMS_ERR_TARGET_VELOCITY;
    if (!finite_real(t.acceleration))
        return SMS_ERR_TARGET_ACCELERATION;
    /* (the sample count bound of the plan's feasible limits, sms_generator_reach()) */
    if (!(t.minimum_duration >= 0) ||
        !(t.minimum_duration / g->Ts_signal <= (sms_real)GEN_MAX_REACH_SAMPLES))
        return SMS_ERR_DURATION;
    if (g->shape == SMS_PLAN_COSINE) {
        /* half-cosine transitions plan to rest, or to a velocity held at a = 0 */
        if (t.interface == SMS_INTERFACE_POSITION && t.velocity != 0)
            return SMS_ERR_TARGET_VELOCITY;
        if (t.acceleration != 0)
            return SMS_ERR_TARGET_ACCELERATION;
        if (t.minimum_duration != 0)
            return SMS_ERR_DURATION;
    }
    if (g->bounded) {
        /* at rest on the target: a motion moving on after it would leave the limits */
        if (t.velocity != 0)
            return SMS_ERR_TARGET_VELOCITY;
        if (t.acceleration != 0)
            return SMS_ERR_TARGET_ACCELERATION;
    }
    V = g->limits.vmax;
    A = g->limits.amax;
    if (!(t.velocity <= V) || !(t.velocity >= g->vmin))
        return SMS_ERR_TARGET_VELOCITY;
    reach = t.acceleration * mag(t.acceleration) / (2 * g->limits.jmax);
    if (!(t.acceleration <= A) || !(t.acceleration >= g->amin) ||
        !(t.velocity - reach <= V) || !(t.velocity - reach >= g->vmin) ||
        !(t.velocity + reach <= V) || !(t.velocity + reach >= g->vmin))
        return SMS_ERR_TARGET_ACCELERATION;
    *out = t;
    return SMS_OK;
}

sms_status sms_generator_check_target(const sms_generator *g, const sms_target *target)
{
    sms_target t;
    return sms_generator_canonical(g, target, &t);
}

sms_status sms_generator_check_targets(const sms_generator *g, const sms_target *targets,
                                       size_t n, size_t *index)
{
    size_t i;
    if (index != NULL)
        *index = n;
    if (g == NULL || (targets == NULL && n > 0))
        return SMS_ERR_NULL;
    for (i = 0; i < n; ++i) {
        sms_status st = sms_generator_check_target(g, &targets[i]);
        if (st != SMS_OK) {
            if (index != NULL)
                *index = i;
            return st;
        }
    }
    return SMS_OK;
}

static int same_target(const sms_target *a, const sms_target *b)
{
    return a->interface == b->interface && a->position == b->position &&
           a->velocity == b->velocity && a->acceleration == b->acceleration &&
           a->minimum_duration == b->minimum_duration;
}

static int plan_direct(const sms_generator *g, sms_plan *plan, sms_real q, sms_real v,
                       sms_real a, const sms_target *goal)
{
    sms_to_limits lim;
    lim.vmax = g->limits.vmax;
    lim.vmin = g->vmin;
    lim.amax = g->limits.amax;
    lim.amin = g->amin;
    lim.jmax = g->limits.jmax;
    if (goal->interface == SMS_INTERFACE_VELOCITY) {
        if (g->shape == SMS_PLAN_COSINE)
            return sms_plan_velocity_shaped(plan, &g->limits, g->shape, g->Ts_signal, q, v, a,
                                            goal->velocity);
        return sms_plan_velocity(plan, &lim, g->Ts_signal, q, v, a, goal->velocity,
                                 goal->acceleration, goal->minimum_duration);
    }
    if (g->shape == SMS_PLAN_COSINE)
        return sms_plan_to_rest_shaped(plan, &g->limits, g->shape, g->Ts_signal, q, v, a,
                                       goal->position);
    if (sms_plan_to_state(plan, &lim, g->Ts_signal, q, v, a, goal->position, goal->velocity,
                          goal->acceleration, goal->minimum_duration))
        return 1;
    /* not expected: the rest planner of the first version, never beyond the limits */
    return !g->asymmetric && goal->velocity == 0 && goal->acceleration == 0 &&
           goal->minimum_duration == 0 && sms_plan_to_rest(plan, &g->limits, g->Ts_signal, q, v, a, goal->position);
}

static int direct_plan(const void *ctx, sms_plan *plan, sms_real q, sms_real v, sms_real a,
                       const sms_target *goal)
{
    return plan_direct((const sms_generator *)ctx, plan, q, v, a, goal);
}

static sms_plan_box generator_box(const sms_generator *g)
{
    sms_plan_box box;
    box.qmin = g->qmin;
    box.qmax = g->qmax;
    box.qtol = g->qtol;
    box.Ts = g->Ts_signal;
    return box;
}

int sms_generator_replan(const sms_generator *g, sms_plan *plan, sms_real q, sms_real v,
                         sms_real a, const sms_target *goal)
{
    sms_plan_box box;
    if (!g->bounded)
        return plan_direct(g, plan, q, v, a, goal);
    /* position limits (goals rest inside, sms_generator_canonical()): plan_bounded.c */
    box = generator_box(g);
    return sms_plan_within(&box, direct_plan, g, plan, q, v, a, goal);
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

/* Take a new valid target (an invalid one is ignored, the previous kept). The same target
 * as on the sample before, field for field, is the common case and costs four compares. */
static void take_target(sms_generator *g, const sms_target *target)
{
    sms_target t;
    if (same_target(target, &g->request))
        return;
    g->request = *target;
    if (sms_generator_canonical(g, target, &t) == SMS_OK && !same_target(&t, &g->target)) {
        g->target = t;
        g->refused = 0;
        g->pending = !same_target(&t, &g->goal);
    }
}

/* With position limits, q held to [qmin, qmax] (plan_bounded.c). */
static void hold_position(const sms_generator *g, sms_real out[4])
{
    const sms_plan_box box = generator_box(g);
    sms_plan_hold_position(&box, &out[0]);
}

/* With asymmetric limits, v and a held to [vmin, vmax] and [amin, amax]. A segment's value
 * rounds relative to the largest terms it sums, which scale with the larger bound (a ramp from
 * vmax down to vmin): near the smaller bound that is its magnitude times their ratio, beyond
 * the reported values' 32 u. The exact motion is within the bounds, so holding the rounded
 * value to them changes it by no more than that rounding. Symmetric limits: untouched. */
static void hold_to_bounds(const sms_generator *g, sms_real out[4])
{
    if (g->bounded) /* the plan's extremes are inside to their rounding: the same holds q */
        hold_position(g, out);
    if (!g->asymmetric)
        return;
    if (out[1] > g->limits.vmax)
        out[1] = g->limits.vmax;
    else if (out[1] < g->vmin)
        out[1] = g->vmin;
    if (out[2] > g->limits.amax)
        out[2] = g->limits.amax;
    else if (out[2] < g->amin)
        out[2] = g->amin;
}

/* Advance the plan one sample under the held target; re-plan from the exact state there when
 * the target differs from the plan's goal (and the state allows it, can_start()). */
static void step_plan(sms_generator *g, sms_real out[4])
{
    ++g->k;
    if (g->k > g->plan.end && g->plan.drift == 0 && !g->pending) {
        /* resting on the goal (what sms_plan_eval() gives past the end), the common case */
        out[0] = g->plan.goal;
        out[1] = out[2] = out[3] = 0;
        return;
    }
    sms_plan_eval(&g->plan, g->Ts_signal, g->k, out);
    hold_to_bounds(g, out);
    if (g->pending && can_start(g, out[1], out[2])) {
        g->pending = 0;
        /* a move that cannot be represented (the planner returns 0) is dropped: the running
         * plan goes on, and the target is not tried again until it changes */
        int planned = sms_generator_replan(g, &g->plan, out[0], out[1], out[2], &g->target);
        if (planned == SMS_REPLAN_WAIT) {
            g->pending = 1; /* position limits: not from this state, tried on the next */
        } else if (planned) {
            g->plan_q = out[0];
            g->plan_v = out[1];
            g->plan_a = out[2];
            g->goal = g->target;
            g->k = 0;
            sms_plan_eval(&g->plan, g->Ts_signal, 0, out); /* the same q, v, a; the new jerk */
            hold_to_bounds(g, out);
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
    if (o[0] == g->plan.goal && o[1] == 0 && o[2] == 0 && o[3] == 0 && g->plan.drift == 0) {
        if (g->quiet < g->stage_length)
            ++g->quiet;
    } else {
        g->quiet = 0;
    }
}

/* One sample under the held target: the plan, then the tuned stage if any. */
static void step_held(sms_generator *g, sms_real out[4])
{
    size_t i;
    step_plan(g, out);
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
    } else if (g->bounded) {
        hold_position(g, out); /* the average of values inside, to its rounding */
    }
}

void sms_generator_step_target(sms_generator *g, const sms_target *target, sms_real out[4])
{
    take_target(g, target);
    step_held(g, out);
}

/* A position target at rest, as sms_generator_step() takes it (non-finite: the held one). */
static sms_target rest_target(const sms_generator *g, sms_real position)
{
    sms_target t;
    if (!finite_real(position))
        return g->target;
    t.position = position;
    t.velocity = 0;
    t.acceleration = 0;
    t.interface = SMS_INTERFACE_POSITION;
    t.minimum_duration = 0;
    return t;
}

void sms_generator_step(sms_generator *g, sms_real target, sms_real out[4])
{
    sms_target t;
    if (target == g->request.position && g->request.interface == SMS_INTERFACE_POSITION &&
        g->request.velocity == 0 && g->request.acceleration == 0 &&
        g->request.minimum_duration == 0) {
        step_held(g, out); /* the held target, as on the sample before */
        return;
    }
    t = rest_target(g, target);
    sms_generator_step_target(g, &t, out);
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
            hold_to_bounds(g, o);
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
    if (g->bounded && g->quiet < g->stage_length)
        hold_position(g, out);
}

/* A re-plan still to come under the held target (a new target, or one waiting for a state
 * the plan can start from, can_start()). */
static int replan_pending(const sms_generator *g, const sms_target *target)
{
    sms_target t;
    if (!same_target(target, &g->request) && sms_generator_canonical(g, target, &t) == SMS_OK &&
        !same_target(&t, &g->target))
        return 1;
    return g->pending;
}

void sms_generator_hold_target(sms_generator *g, const sms_target *target, uint64_t n,
                               sms_real out[4])
{
    uint64_t window, rest_at;
    size_t i;
    /* until the held target has been planned (or dropped): from then on the plan is fixed */
    while (n > 0u && replan_pending(g, target)) {
        sms_generator_step_target(g, target, out);
        --n;
    }
    if (n == 0u)
        return;
    /* the plan in closed form: sample k of it is sms_plan_eval(k) */
    if (g->stage_length == 0) {
        g->k += (size_t)(n - 1u);
        sms_generator_step_target(g, target, out);
        return;
    }
    /* With the tuned stage: a stage's state depends only on its last 2M + 2 inputs (both
     * copies restart within them and the ring is refilled; quiet saturates within L <= M + 1). */
    window = 2u * (uint64_t)g->stage_window + 2u;
    rest_at = sms_plan_rest_sample(&g->plan, g->Ts_signal);
    rest_at = rest_at > g->k ? rest_at - g->k : 0u;   /* samples of this hold before the rest */
    if (g->plan.drift == 0 && n - 1u >= rest_at + window + 1u) {
        /* the stages see the rest (goal, 0, 0, 0) for their last 2M + 3 inputs: absorbed */
        sms_real x[4];
        x[0] = g->plan.goal;
        x[1] = x[2] = x[3] = 0;
        for (i = 0; i < 4; ++i)
            (void)sms_smoother_settle(&g->stage[i], x[i], n - 1u);
        g->k += (size_t)(n - 1u);
        g->quiet = g->stage_length;
        sms_generator_step_target(g, target, out);
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

void sms_generator_hold(sms_generator *g, sms_real target, uint64_t n, sms_real out[4])
{
    sms_target t = rest_target(g, target);
    sms_generator_hold_target(g, &t, n, out);
}

void sms_generator_process(sms_generator *g, const sms_real *targets, size_t n, sms_real *out)
{
    size_t i;
    for (i = 0; i < n; ++i)
        sms_generator_step(g, targets[i], out + 4u * i);
}

void sms_generator_process_targets(sms_generator *g, const sms_target *targets, size_t n,
                                   sms_real *out)
{
    size_t i;
    for (i = 0; i < n; ++i)
        sms_generator_step_target(g, &targets[i], out + 4u * i);
}

sms_status sms_generator_start(sms_generator *g, sms_real q, sms_real v, sms_real a,
                               const sms_target *target)
{
    sms_target t, stop;
    sms_plan plan;
    sms_status st;
    if (g == NULL)
        return SMS_ERR_NULL;
    if (!finite_real(q))
        return SMS_ERR_TARGET_POSITION;
    if (!finite_real(v) || !((double)v <= (double)g->limits.vmax * (1.0 + SMS_LIMIT_RTOL)) ||
        !((double)v >= (double)g->vmin * (1.0 + SMS_LIMIT_RTOL)))
        return SMS_ERR_TARGET_VELOCITY;
    if (!finite_real(a) || !sms_generator_state_ok(g, (double)v, (double)a, SMS_LIMIT_RTOL))
        return SMS_ERR_TARGET_ACCELERATION;
    if (target == NULL) {
        stop.interface = SMS_INTERFACE_STOP;
        stop.position = stop.velocity = stop.acceleration = stop.minimum_duration = 0;
        target = &stop;
    }
    st = sms_generator_canonical(g, target, &t);
    if (st != SMS_OK)
        return st;
    if (g->bounded && !(q >= g->qmin && q <= g->qmax))
        return SMS_ERR_POSITION_LIMIT;
    switch (sms_generator_replan(g, &plan, q, v, a, &t)) {
    case 1:
        break;
    case SMS_REPLAN_WAIT:
        /* position limits: neither the motion to the target nor the brake to rest stays
         * inside (and no plan before this one would go on) */
        return SMS_ERR_POSITION_LIMIT;
    default:
        return SMS_ERR_TOO_LONG;
    }
    g->plan = plan;
    g->plan_q = q;
    g->plan_v = v;
    g->plan_a = a;
    g->k = 0;
    g->target = t;
    g->goal = t;
    g->request = t;
    g->pending = 0;
    g->refused = 0;
    g->quiet = 0;
    return SMS_OK;
}

uint64_t sms_generator_arrival(const sms_generator *g)
{
    size_t at = g->plan.arrive;
    if (g->plan.arrive_f > 0)
        ++at; /* the first sample at or after the arrival instant */
    return at > g->k ? (uint64_t)(at - g->k) : 0u;
}

double sms_generator_tail_duration(const sms_generator *g)
{
    return g->stage_T;
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
