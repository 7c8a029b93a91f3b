/* SPDX-License-Identifier: Apache-2.0 */
/* Online multi-axis generator: the configuration (what init checks, the memory it needs, the
 * reach of every axis's limits), init and reset, and the phase-synchronised move's duration.
 * Planning, sampling, holding and the saved state are in multi_plan.c, multi_step.c,
 * multi_hold.c and multi_state.c (multi_parts.h). */
#include <float.h>
#include <math.h>
#include <string.h>
#include "trajectory/multi_parts.h"
#include "trajectory/trajectory_internal.h"
#include "trajectory/plan_bounded.h"

static int limit_ok(double x)
{
    return isfinite(x) && x > 0.0 && (sms_real)x > 0 && (double)(sms_real)x < (double)REAL_MAX;
}

/* Every axis's limits must let a move reach its vmax (multi_generator.h): the planner forms,
 * per axis, the same quantities as the single-axis planner with linear jerk ramps (J dv, a^2,
 * durations and distances of the move to vmax), so axis i is checked by the single-axis
 * region (sms_generator_reach() on its vmax, amax, jmax with the polynomial profile). */
/* The planner caps the ratios limit/|dv| at RATIO_CAP (multi_plan.c), which lengthens a transition
 * of dv whose true ratio is larger. For the move to vmax (dv = vmax) and its stop and reversal
 * (|dv| up to 2 vmax) not to be lengthened, amax/vmax and jmax/vmax stay a factor 16 below the
 * cap; then every capped transition (a smaller move) lasts at most about 2/sqrt(RATIO_CAP) s,
 * within a few times the duration to reach vmax, so it fits the plan's sample count too. */
#define MAX_LIMIT_RATIO (1152921504606846976.0 / 16.0) /* 2^56 */

/* Moves up to MOVE_SPAN times the distance h to reach vmax (and durations up to MOVE_SPAN
 * times its duration) keep the unit limits' products normal and finite. */
#define MOVE_SPAN 16.0
#ifdef SMS_USE_FLOAT
#define UNIT_TINY ((double)FLT_MIN / (double)FLT_EPSILON)
#else
#define UNIT_TINY (DBL_MIN / DBL_EPSILON)
#endif

sms_status sms_multi_generator_reach(const sms_multi_generator_config *config, double Ts,
                                     sms_generator_reach_info *reach, size_t *axis)
{
    sms_generator_reach_info local, *r = reach != NULL ? reach : &local;
    sms_generator_config one;
    size_t i;
    sms_status st = SMS_OK;
    if (axis != NULL)
        *axis = 0;
    memset(r, 0, sizeof *r);
    if (config == NULL)
        return SMS_ERR_NULL;
    if (config->n_axes < 1 || config->n_axes > SMS_MULTI_MAX_AXES)
        return SMS_ERR_ORDER;
    memset(&one, 0, sizeof one);
    one.profile = SMS_PROFILE_POLYNOMIAL;
    for (i = 0; i < config->n_axes; ++i) {
        one.vmax = config->vmax[i];
        one.amax = config->amax[i];
        one.jmax = config->jmax[i];
        one.qmin = config->qmin[i]; /* position limits: the single-axis rule (finite, ordered) */
        one.qmax = config->qmax[i];
        st = sms_generator_reach(&one, Ts, r);
        if (st == SMS_OK && !(one.amax <= MAX_LIMIT_RATIO * one.vmax))
            st = sms_reach_refused(r, "amax/vmax", "vmax, amax", one.amax / one.vmax,
                                   MAX_LIMIT_RATIO);
        if (st == SMS_OK && !(one.jmax <= MAX_LIMIT_RATIO * one.vmax))
            st = sms_reach_refused(r, "jmax/vmax", "vmax, jmax", one.jmax / one.vmax,
                                   MAX_LIMIT_RATIO);
        if (st == SMS_OK && !(one.amax <= MAX_LIMIT_RATIO * r->distance))
            st = sms_reach_refused(r, "amax/h", "vmax, amax, jmax", one.amax / r->distance,
                                   MAX_LIMIT_RATIO);
        if (st == SMS_OK && !(one.jmax <= MAX_LIMIT_RATIO * r->distance))
            st = sms_reach_refused(r, "jmax/h", "vmax, amax, jmax", one.jmax / r->distance,
                                   MAX_LIMIT_RATIO);
        if (st == SMS_OK) {
            /* the unit limits of a displacement up to MOVE_SPAN h and the square of the
             * durations (multi_plan.c, landing_kappa(): b^2, au^2, ju) */
            const double h = MOVE_SPAN * r->distance, T = MOVE_SPAN * r->duration;
            const double au = one.amax / h, ju = one.jmax / h;
            if (!(T * T <= (double)REAL_MAX))
                st = sms_reach_refused(r, "the duration to reach vmax, squared",
                                       "vmax, amax, jmax", r->duration * r->duration,
                                       (double)REAL_MAX / (MOVE_SPAN * MOVE_SPAN));
            else if (!(au * au >= UNIT_TINY))
                st = sms_reach_refused(r, "(amax/h)^2", "vmax, amax, jmax",
                                       one.amax / r->distance * (one.amax / r->distance),
                                       UNIT_TINY * MOVE_SPAN * MOVE_SPAN);
            else if (!(ju >= UNIT_TINY))
                st = sms_reach_refused(r, "jmax/h", "vmax, amax, jmax", one.jmax / r->distance,
                                       UNIT_TINY * MOVE_SPAN);
        }
        if (st != SMS_OK) {
            if (axis != NULL && st == SMS_ERR_LIMIT)
                *axis = i;
            return st;
        }
    }
    return SMS_OK;
}

/* Everything init checks, and the memory the stages need; O(stages). */
static sms_status check_config(const sms_multi_generator_config *config, double Ts,
                               size_t *n_structs, size_t *n_cells, size_t *bad_axis)
{
    size_t i, n;
    *n_structs = 0;
    *n_cells = 0;
    if (bad_axis != NULL)
        *bad_axis = 0;
    if (config == NULL)
        return SMS_ERR_NULL;
    n = config->n_axes;
    if (n < 1 || n > SMS_MULTI_MAX_AXES)
        return SMS_ERR_ORDER;
    if (!isfinite(Ts) || !(Ts > 0.0) || !((sms_real)Ts > 0))
        return SMS_ERR_SAMPLE_PERIOD;
    /* Ts above SMS_TS_MAX: refused by sms_multi_generator_reach() below, with its reach info */
    for (i = 0; i < n; ++i) {
        if (!limit_ok(config->vmax[i]) || !limit_ok(config->amax[i]) ||
            !limit_ok(config->jmax[i])) {
            if (bad_axis != NULL)
                *bad_axis = i;
            return SMS_ERR_LIMIT;
        }
    }
    {
        size_t axis = 0;
        sms_status st = sms_multi_generator_reach(config, Ts, NULL, &axis);
        if (st != SMS_OK) {
            if (bad_axis != NULL)
                *bad_axis = axis;
            return st;
        }
    }
    if ((unsigned)config->sync > (unsigned)SMS_SYNC_NONE)
        return SMS_ERR_KIND;
    for (i = 0; i < n; ++i) {
        size_t need = 0;
        sms_status st;
        if (config->n_stages[i] == 0)
            continue;
        if (bad_axis != NULL)
            *bad_axis = i;
        if (config->n_stages[i] > SMS_CHAIN_MAX_STAGES)
            return SMS_ERR_ORDER;
        if (config->stages[i] == NULL)
            return SMS_ERR_NULL;
        st = sms_chain_memory_size(config->stages[i], config->n_stages[i], Ts, &need);
        if (st != SMS_OK)
            return st;
        if (need > ((size_t)-1) / 8 / SMS_MULTI_MAX_AXES)
            return SMS_ERR_TOO_LONG;
        *n_structs += SMS_MULTI_SIGNALS * config->n_stages[i];
        *n_cells += SMS_MULTI_SIGNALS * need;
    }
    if (bad_axis != NULL)
        *bad_axis = 0;
    if (config->align != 0 && config->align != 1)
        return SMS_ERR_KIND;
    {
        size_t align_cells;
        sms_status st = sms_multi_align_cells(config, Ts, &align_cells);
        if (st != SMS_OK)
            return st;
        *n_cells += align_cells;
    }
    return SMS_OK;
}

sms_status sms_multi_generator_memory(const sms_multi_generator_config *config, double Ts,
                                      size_t *n_stage_structs, size_t *n_cells, size_t *bad_axis)
{
    size_t structs, cells;
    sms_status st;
    if (n_stage_structs == NULL || n_cells == NULL)
        return SMS_ERR_NULL;
    st = check_config(config, Ts, &structs, &cells, bad_axis);
    if (st == SMS_OK) {
        *n_stage_structs = structs;
        *n_cells = cells;
    }
    return st;
}
sms_status sms_multi_generator_init(sms_multi_generator *g,
                                    const sms_multi_generator_config *config, double Ts,
                                    sms_stage *stages, size_t n_stage_structs,
                                    sms_memory_cell *memory, size_t n_cells, size_t *bad_axis)
{
    size_t i, m, n, structs, cells;
    sms_status st;
    if (g == NULL) {
        if (bad_axis != NULL)
            *bad_axis = 0;
        return SMS_ERR_NULL;
    }
    st = check_config(config, Ts, &structs, &cells, bad_axis);
    if (st != SMS_OK)
        return st;
    if ((structs > 0 && stages == NULL) || (cells > 0 && memory == NULL))
        return SMS_ERR_NULL;
    if (n_stage_structs < structs || n_cells < cells)
        return SMS_ERR_BUFFER_TOO_SMALL;
    n = config->n_axes;
    /* the configs were validated above: every chain builds */
    for (i = 0; i < SMS_MULTI_MAX_AXES; ++i)
        for (m = 0; m < SMS_MULTI_SIGNALS; ++m) {
            sms_chain *c = &g->chain[i][m];
            size_t need = 0;
            c->stages = NULL;
            c->n_stages = 0;
            c->memory = NULL;
            c->memory_len = 0;
            if (i >= n || config->n_stages[i] == 0)
                continue;
            (void)sms_chain_memory_size(config->stages[i], config->n_stages[i], Ts, &need);
            (void)sms_chain_init(c, stages, config->stages[i], config->n_stages[i], Ts,
                                 memory, need);
            stages += config->n_stages[i];
            memory += need;
        }
    g->n_axes = n;
    g->sync = config->sync;
    g->Ts = Ts;
    g->Ts_signal = (sms_real)Ts;
    for (i = 0; i < SMS_MULTI_MAX_AXES; ++i) {
        g->vmax[i] = i < n ? (sms_real)config->vmax[i] : 1;
        g->amax[i] = i < n ? (sms_real)config->amax[i] : 1;
        g->jmax[i] = i < n ? (sms_real)config->jmax[i] : 1;
    }
    for (i = 0; i < SMS_MULTI_MAX_AXES; ++i) {
        const int b = i < n && (config->qmin[i] != 0.0 || config->qmax[i] != 0.0);
        g->bounded[i] = 0; /* the initial rest below is free; the limits apply from there */
        g->qmin[i] = b ? (sms_real)config->qmin[i] : 0;
        g->qmax[i] = b ? (sms_real)config->qmax[i] : 0;
        g->qtol[i] = b ? sms_plan_box_tolerance(config->qmin[i], config->qmax[i]) : 0;
    }
    sms_multi_identity_write(config, Ts, g->identity);
    sms_multi_align_init(g, config, Ts, memory);   /* memory: past the stages' */
    sms_multi_generator_reset(g, NULL);
    for (i = 0; i < n; ++i)
        g->bounded[i] = config->qmin[i] != 0.0 || config->qmax[i] != 0.0;
    return SMS_OK;
}

/* Where axis i rests by default: 0, or its limit nearer 0 when its limits exclude 0. */
static sms_real default_rest(const sms_multi_generator *g, size_t i)
{
    return g->qmin[i] > 0 ? g->qmin[i] : g->qmax[i] < 0 ? g->qmax[i] : 0;
}

void sms_multi_generator_reset(sms_multi_generator *g, const sms_real *position)
{
    sms_real rest[SMS_MULTI_MAX_AXES];
    size_t i;
    for (i = 0; i < SMS_MULTI_MAX_AXES; ++i) {
        rest[i] = (position != NULL && i < g->n_axes) ? position[i] : default_rest(g, i);
        if (g->bounded[i] && !(rest[i] >= g->qmin[i] && rest[i] <= g->qmax[i]))
            return; /* outside an axis's position limits: nothing changes */
    }
    position = rest;
    g->dropped = 0;
    for (i = 0; i < SMS_MULTI_MAX_AXES; ++i) {
        sms_real x = position[i];
        g->target[i] = x;
        g->goal[i] = x;
        g->p[i] = x;
        g->V[i] = 0;
        g->W[i] = 0;
        g->move[i].T1 = g->move[i].tau = g->move[i].T2 = 0;
        g->move[i].rho1 = g->move[i].rho2 = (sms_real)0.5;
        g->move[i].off = g->move[i].seen = 0;
        g->move[i].k = g->move[i].k_end = 0;
        g->move[i].active = 0;
        g->move[i].pending = 0;
        g->move[i].refused = 0;
        if (g->chain[i][0].n_stages > 0) {
            sms_chain_reset(&g->chain[i][0], x);
            sms_chain_reset(&g->chain[i][1], 0);
            sms_chain_reset(&g->chain[i][2], 0);
            sms_chain_reset(&g->chain[i][3], 0);
        }
    }
    sms_multi_align_reset(g, position);
    sms_multi_sync_reset(g, position);
}
/* A time constant below TIME_FLOOR of the largest is raised to it: its limit is then 2^100 times
 * more than the move can use, which changes the duration far below a rounding, and every product
 * below stays normal and finite. */
#define TIME_FLOOR 7.8886090522101181e-31 /* 2^-100 */

/* Time-optimal rest-to-rest duration of a unit move under the path limits V = 1/v, A = 1/a^2,
 * J = 1/j^3 (closed form), written in the time constants v, a, j relative to the largest (in
 * [TIME_FLOOR, 1]): the limits themselves over- or underflow for long or short moves. */
static double unit_move_time(double v, double a, double j)
{
    double a2 = a * a, j3 = j * j * j, q, r;
    /* time to accelerate to V: reaching A (V J >= A^2) or not */
    double Tv = a2 * a2 >= v * j3 ? a2 / v + j3 / a2 : 2.0 * sqrt(j3 / v);
    if (Tv < v)
        return v + Tv; /* reaches V (V Tv < 1): cruise 1/V - Tv */
    /* peak velocity c = 1/r below V: c T(c) = 1, T(c) = c/A + A/J */
    q = j3 / a2;
    r = 0.5 * (q + sqrt(q * q + 4.0 * a2));
    if (r * q <= a2)
        return 2.0 * (a2 / r + q); /* reaches A (c J >= A^2) */
    return 4.0 * cbrt(0.5) * j; /* c = J Tj^2, 2 J Tj^3 = 1, T = 4 Tj */
}

sms_status sms_multi_phase_duration(const sms_multi_generator_config *config,
                                    const double *delta, double *T)
{
    /* the move's time constants: the longest |d|/vmax, sqrt(|d|/amax), cbrt(|d|/jmax) of
     * the axes (each root taken apart, so a quotient that over- or underflows does not) */
    double tv = 0.0, ta = 0.0, tj = 0.0, top, t;
    size_t i;
    if (config == NULL || delta == NULL || T == NULL)
        return SMS_ERR_NULL;
    if (config->n_axes < 1 || config->n_axes > SMS_MULTI_MAX_AXES)
        return SMS_ERR_ORDER;
    for (i = 0; i < config->n_axes; ++i) {
        double d = fabs(delta[i]);
        if (!isfinite(delta[i]) || !(isfinite(config->vmax[i]) && config->vmax[i] > 0.0) ||
            !(isfinite(config->amax[i]) && config->amax[i] > 0.0) ||
            !(isfinite(config->jmax[i]) && config->jmax[i] > 0.0))
            return SMS_ERR_LIMIT;
        if (d > 0.0) {
            tv = fmax(tv, d / config->vmax[i]);
            ta = fmax(ta, sqrt(d) / sqrt(config->amax[i]));
            tj = fmax(tj, cbrt(d) / cbrt(config->jmax[i]));
        }
    }
    top = fmax(tv, fmax(ta, tj));
    if (top == 0.0) {
        *T = 0.0; /* no displacement: ta > 0 for any d > 0 */
        return SMS_OK;
    }
    if (!isfinite(top))
        return SMS_ERR_TOO_LONG; /* T >= max(tv, 2 ta, 3 tj) */
    t = top * unit_move_time(fmax(tv / top, TIME_FLOOR), fmax(ta / top, TIME_FLOOR),
                             fmax(tj / top, TIME_FLOOR));
    if (!isfinite(t))
        return SMS_ERR_TOO_LONG;
    *T = t;
    return SMS_OK;
}
