/* SPDX-License-Identifier: Apache-2.0 */
/* One sample of the multi-axis generator: each group of axes follows its move, takes a new
 * target (planned from rest, or blended in at zero acceleration), and is evaluated exactly at
 * the sample instant; then each axis's stages filter the profile. */
#include "trajectory/multi_parts.h"

/* Normalised S-curve (header) on the piece that contains the sample, chosen by xs and ys
 * (x and the fraction left 1 - x with their breakpoints snapped within SNAP, see
 * evaluate()): F'(xs) or F'(1 - ys) (acceleration) and F'' (jerk) there, and that piece's
 * F(x) and G(x) = int_0^x F at x itself. The last jerk phase is located and evaluated by
 * the fraction left, never by x against 1 - rho: 1 - rho rounds by up to half an ulp of 1,
 * which is eps/(4 rho) of that phase (rho is as small as amax^2/(jmax |dV|)), and a sample
 * at or snapped onto fl(1 - rho) then reported F' = ap (1 - fl(1 - rho))/rho, more than the
 * peak ap (in float up to 4.8e-5 of amax on random staircases). With ys <= rho decided on the
 * value the acceleration uses, F' <= ap up to its own rounding. The pieces continue each other to
 * second order at every breakpoint, so choosing the piece by xs, ys moves F and G by the
 * square and the cube of the snap, and the position keeps the rounding of the sample's own
 * time: snapping x itself would move it by v SNAP T, 64 eps of the transition's distance. */
static void s_curve(sms_real x, sms_real xs, sms_real ys, sms_real rho, sms_real *G,
                    sms_real *F, sms_real *dF, sms_real *ddF)
{
    const sms_real ap = 1 / (1 - rho);
    if (!(ys > 0)) {
        *ddF = 0;
        *dF = 0;
        *F = 1;
        *G = x - (sms_real)0.5;
    } else if (xs < rho) {
        *ddF = ap / rho;
        *dF = ap * xs / rho;
        *F = ap * x * x / (2 * rho);
        *G = ap * x * x * x / (6 * rho);
    } else if (ys > rho) {
        *ddF = 0;
        *dF = ap;
        *F = ap * (x - rho / 2);
        *G = ap * (x * x / 2 - rho * x / 2 + rho * rho / 6);
    } else {
        sms_real y = 1 - x;
        *ddF = -ap / rho;
        *dF = ap * ys / rho;
        *F = 1 - ap * y * y / (2 * rho);
        *G = x - (sms_real)0.5 + ap * y * y * y / (6 * rho);
    }
}

/* Breakpoints (phase ends, jerk jumps) within SNAP of a sample instant, relative to the
 * length of their own phase, count as on it, and the sample takes the right limit there; the
 * decision then does not hang on the last ulp. */
#define SNAP (64 * REAL_EPS)

static sms_real snap(sms_real x, sms_real b, sms_real tol)
{
    return (x - b <= tol && b - x <= tol) ? b : x;
}

/* Time left from the sample k of move m to the end of its stop transition. With a cruise the
 * plan ends on the arrival sample (sms_multi_plan(): tau takes up the rounding onto the grid), so the
 * time left is (k_end - k) Ts, a whole number of samples: it carries no rounding of the move
 * time off + k Ts, which in float is about 6e-8 of the move (at 1000 s and Ts = 1 ms, 0.06 of
 * a sample; at 10^5 s, 6 samples). Without a cruise the stop follows the first transition
 * directly, the arrival may be rounded before T1 + T2 by the grid snap, and the time is
 * counted from T1 (the move is then as long as its transitions, so its rounding is theirs). */
static sms_real time_left(const sms_multi_move *m, sms_real t, sms_real Ts)
{
    if (m->tau > 0)
        return (sms_real)(m->k_end - m->k) * Ts;
    return m->T2 - (t - m->T1);
}

/* Is the sample in the stop transition? (Its time left is within the stop, to SNAP of T2.) */
static int in_stop(const sms_multi_move *m, sms_real left)
{
    return m->T2 > 0 && left <= m->T2 + SNAP * m->T2;
}

/* Output of the axes [first, first + n) at sample k = m->k (k < k_end), move time t. Each
 * phase is located and evaluated by its own time: the first transition by t (there t <= T1),
 * the cruise by t - T1, the stop by the time left to its end (time_left()), and each
 * breakpoint is snapped within SNAP of its own phase's length, never of the whole move's:
 * a tolerance of 64 eps of the move spans 7.6 samples of a 1000 s move at Ts = 1 ms in float,
 * and the positions stood still there, then jumped by 8 vmax. */
static void evaluate(const sms_multi_generator *g, size_t first, size_t n,
                     const sms_multi_move *m, sms_real t, sms_real *out)
{
    sms_real G, F, dF, ddF;
    const sms_real left = time_left(m, t, g->Ts_signal);
    size_t i;
    if (t < m->T1 - SNAP * m->T1) {
        sms_real x = t / m->T1;
        s_curve(x, snap(x, m->rho1, SNAP), snap(1 - x, m->rho1, SNAP), m->rho1, &G, &F, &dF,
                &ddF);
        for (i = first; i < first + n; ++i) {
            sms_real dV = g->W[i] - g->V[i];
            out[4 * i + 0] = g->p[i] + g->V[i] * t + dV * (m->T1 * G);
            out[4 * i + 1] = g->V[i] + dV * F;
            out[4 * i + 2] = dV * (dF / m->T1);
            out[4 * i + 3] = dV * (ddF / (m->T1 * m->T1));
        }
    } else if (!in_stop(m, left)) {
        sms_real c = t - m->T1; /* may be below 0 by SNAP T1: the cruise continues T1's end */
        for (i = first; i < first + n; ++i) {
            out[4 * i + 0] = g->p[i] + (g->V[i] + g->W[i]) * (m->T1 / 2) + g->W[i] * c;
            out[4 * i + 1] = g->W[i];
            out[4 * i + 2] = 0;
            out[4 * i + 3] = 0;
        }
    } else {
        /* x = 1 - y of the stop, y = left / T2 the fraction left: the S-curve is point-
         * symmetric, so the distance still to go is W T2 G(y), and the position is counted
         * back from the goal the move lands on */
        sms_real y = left / m->T2, Gy, Fy, dFy, ddFy;
        sms_real xs = snap(snap(1 - y, 0, SNAP), m->rho2, SNAP);
        s_curve(xs, xs, snap(snap(y, m->rho2, SNAP), 0, SNAP), m->rho2, &G, &F, &dF, &ddF);
        s_curve(y, y, 1 - y, m->rho2, &Gy, &Fy, &dFy, &ddFy);
        for (i = first; i < first + n; ++i) {
            sms_real W = g->W[i];
            out[4 * i + 0] = g->goal[i] - W * (m->T2 * Gy);
            out[4 * i + 1] = W * Fy;
            out[4 * i + 2] = -W * (dF / m->T2);
            out[4 * i + 3] = -W * (ddF / (m->T2 * m->T2));
        }
    }
}

/* A target vector whose move cannot be represented is dropped: the group keeps the goal it
 * has and does not try that target again until it changes (sms_multi_generator_step). */
static void drop_target(sms_multi_generator *g, sms_multi_move *m)
{
    m->pending = 0;
    m->refused = 1;
    ++g->dropped;
}

int sms_multi_group_bounded(const sms_multi_generator *g, size_t first, size_t n)
{
    size_t i;
    for (i = first; i < first + n; ++i)
        if (g->bounded[i])
            return 1;
    return 0;
}

static void step_group(sms_multi_generator *g, size_t first, size_t n, sms_multi_move *m,
                       sms_real *out)
{
    const sms_multi_group G = {n, g->vmax + first, g->amax + first, g->jmax + first};
    sms_real t = 0;
    size_t i;
    int differs = 0;
    if (m->active) {
        ++m->k;
        if (m->k >= m->k_end)
            m->active = 0; /* arrived: rest exactly at the goal */
        else
            t = m->off + (sms_real)m->k * g->Ts_signal;
    }
    for (i = first; i < first + n; ++i)
        if (g->target[i] != g->goal[i])
            differs = 1;
    if (m->refused)
        differs = 0; /* the held target was refused: nothing to do until it changes */
    if (!differs) {
        m->pending = 0;
    } else if (!m->pending) {
        m->pending = 1;
        m->seen = t;
    }
    if (m->pending) {
        if (!m->active) {
            sms_real zero[SMS_MULTI_MAX_AXES] = {0};
            if (!sms_multi_plan(g, first, &G, m, g->goal + first, zero, 0))
                drop_target(g, m);
            t = 0;
        } else if (t >= m->T1 && !sms_multi_group_bounded(g, first, n)) {
            /* (a group with an axis under position limits does not blend: the new target
             * waits for the arrival and starts from rest, multi_generator.h, so every move
             * runs from rest to rest between points inside, on the segment between them) */
            /* blend at tr: the end of the first transition, or the instant the target came
             * during the cruise (at this very sample: when the stop has not begun there by
             * the rule evaluate() uses). Not before T1, not even by a rounding: the new move
             * starts at tr and its first sample is off = t - tr >= 0 after it; a sample a
             * little before T1 taken as on it would shift all that follows by T1 - t (in
             * float up to 64 eps of T1, a jump of 7e-5 in a position of 9 in the tests) */
            sms_real tr = m->seen > m->T1 ? m->seen : m->T1;
            int before_stop;
            if (!(m->seen > m->T1))
                before_stop = 1;
            else if (m->seen < t)
                before_stop = m->seen <= m->T1 + m->tau;
            else
                before_stop = !in_stop(m, time_left(m, t, g->Ts_signal));
            if (before_stop) {
                /* zero acceleration at tr: blend into a new move from there */
                sms_real p[SMS_MULTI_MAX_AXES], V[SMS_MULTI_MAX_AXES];
                for (i = 0; i < n; ++i) {
                    sms_real W = g->W[first + i];
                    p[i] = g->p[first + i] + (g->V[first + i] + W) * (m->T1 / 2) +
                           W * (tr - m->T1);
                    V[i] = W;
                }
                if (sms_multi_plan(g, first, &G, m, p, V, t > tr ? t - tr : 0))
                    t = m->off;
                else
                    drop_target(g, m); /* the running move goes on */
            }
        }
    }
    if (m->active) {
        evaluate(g, first, n, m, t, out);
    } else {
        for (i = first; i < first + n; ++i) {
            out[4 * i + 0] = g->goal[i];
            out[4 * i + 1] = 0;
            out[4 * i + 2] = 0;
            out[4 * i + 3] = 0;
        }
    }
}
void sms_multi_step_profile(sms_multi_generator *g, const sms_real *target, sms_real *out)
{
    size_t i;
    if (SMS_SYNC_PER_AXIS_PLANS(g->sync)) {
        sms_multi_target t;
        sms_multi_sync_rest_target(g, target, &t);
        sms_multi_sync_step_profile(g, &t, out);
        return;
    }
    for (i = 0; i < g->n_axes; ++i)
        if (sms_multi_takes_position(g, i, target[i]) && target[i] != g->target[i]) {
            g->target[i] = target[i];
            g->move[g->sync == SMS_SYNC_PHASE ? 0 : i].refused = 0;
        }
    if (g->sync == SMS_SYNC_PHASE) {
        step_group(g, 0, g->n_axes, &g->move[0], out);
    } else {
        for (i = 0; i < g->n_axes; ++i)
            step_group(g, i, 1, &g->move[i], out);
    }
}
void sms_multi_generator_step(sms_multi_generator *g, const sms_real *target, sms_real *out)
{
    sms_multi_step_profile(g, target, out);
    sms_multi_filter_output(g, out);
}

void sms_multi_filter_output(sms_multi_generator *g, sms_real *out)
{
    size_t i;
    for (i = 0; i < g->n_axes; ++i)
        if (g->chain[i][0].n_stages > 0) {
            size_t m;
            for (m = 0; m < SMS_MULTI_SIGNALS; ++m)
                sms_chain_step(&g->chain[i][m], &out[4 * i + m]);
        }
    sms_multi_align_step(g, out);
}

void sms_multi_generator_process(sms_multi_generator *g, const sms_real *targets, size_t n,
                                 sms_real *out)
{
    size_t k;
    for (k = 0; k < n; ++k)
        sms_multi_generator_step(g, targets + k * g->n_axes, out + 4u * k * g->n_axes);
}

int sms_multi_generator_busy(const sms_multi_generator *g)
{
    size_t i, groups = g->sync == SMS_SYNC_PHASE ? 1u : g->n_axes;
    if (SMS_SYNC_PER_AXIS_PLANS(g->sync))
        return sms_multi_sync_busy(g);
    for (i = 0; i < groups; ++i)
        if (g->move[i].active || g->move[i].pending)
            return 1;
    return 0;
}

/* The target entry points dispatch here, beside sms_multi_generator_step, so that the
 * per-axis plan modes' file (multi_sync.c) never calls back into this one. */
void sms_multi_generator_step_target(sms_multi_generator *g, const sms_multi_target *target,
                                     sms_real *out)
{
    if (!SMS_SYNC_PER_AXIS_PLANS(g->sync)) {
        /* positions at rest only: an invalid target keeps the previous ones */
        if (sms_multi_generator_check_target(g, target, NULL) == SMS_OK)
            sms_multi_generator_step(g, target->position, out);
        else
            sms_multi_generator_step(g, g->target, out);
        return;
    }
    sms_multi_sync_step_profile(g, target, out);
    sms_multi_filter_output(g, out);
}

void sms_multi_generator_process_targets(sms_multi_generator *g,
                                         const sms_multi_target *targets, size_t n,
                                         sms_real *out)
{
    size_t k;
    for (k = 0; k < n; ++k)
        sms_multi_generator_step_target(g, &targets[k], out + 4u * k * g->n_axes);
}
