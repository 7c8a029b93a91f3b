/* SPDX-License-Identifier: Apache-2.0 */
/* Planning one move of the multi-axis generator: the shortest first transition from the
 * current velocity, the cruise and the stop, landed on the sample grid (multi_generator.h). */
#include "trajectory/multi_parts.h"
#include "trajectory/plan.h"

/* Ratios limit/|change| are capped here (conservative: a lower limit), so that tiny or
 * subnormal changes give tiny finite durations and A^2 stays finite in float too. */
#define RATIO_CAP ((sms_real)1152921504606846976.0) /* 2^60 */

static sms_real ratio(sms_real limit, sms_real d)
{
    sms_real r = limit / d;
    return r < RATIO_CAP ? r : RATIO_CAP;
}

/* The root search for T1 stops when the bracket is this narrow (neighbouring reals, relative)
 * or after MAX_ROOT_STEPS evaluations (a bound never reached: every fourth step bisects). */
#define BRACKET_TOL (2 * REAL_EPS)
#define MAX_ROOT_STEPS 200
/* A planned duration within this many ulps above a whole number of samples arrives on that
 * sample (sms_multi_plan()). The plan's duration carries the root search's bracket (2 eps of T1) and a
 * few roundings: a move whose exact duration is a whole number of samples (limits and Ts of
 * round values: 0.475 s at 1 ms) comes out up to 1.3 eps above it (measured), and rounding
 * it up would cost a whole sample. Shortening the move by GRID_TOL of its duration (at most
 * 2 kappa) raises W = u/kappa, and with it v and the stop's a, j, by up to 2 GRID_TOL =
 * 4 eps, the first transition's a, j by up to twice that (first_rho()); a wider tolerance
 * costs that much more (8 eps raised them by 16 eps).
 *
 * So a planned cruise velocity W (and a move's start velocity V, an earlier W) may round
 * over vmax by the arrival's 2 GRID_TOL and the roundings of kappa and u/kappa (8 eps):
 * 12 eps, within the reported values' 32 u = 16 eps (SMS_LIMIT_RTOL), to which a saved
 * state's V and W are checked (sms_multi_generator_check_state()). */
#define GRID_TOL (2 * REAL_EPS)

/* cbrt(x), x >= 0, by Newton after scaling into [1, 8). */
static sms_real root3(sms_real x)
{
    sms_real scale = 1, y;
    int i;
    if (!(x > 0))
        return 0;
    if (x - x != 0)
        return x; /* +Inf: the scaling loop would never end */
    while (x >= 8) {
        x *= (sms_real)0.125;
        scale *= 2;
    }
    while (x < 1) {
        x *= 8;
        scale *= (sms_real)0.5;
    }
    y = 1 + x * (sms_real)(1.0 / 7.0); /* within 2x of the root on [1, 8) */
    for (i = 0; i < 8; ++i)
        y = (2 * y + x / (y * y)) * (sms_real)(1.0 / 3.0);
    return y * scale;
}

/* Shortest transition of a unit velocity change under unit limits A, J (header). */
static sms_real unit_time(sms_real A, sms_real J, sms_real *rho)
{
    sms_real T, Tj;
    *rho = (sms_real)0.5;
    if (!(A < REAL_MAX) || !(J < REAL_MAX))
        return 0; /* a change too small to resolve in this precision */
    if (A * A <= J) {
        Tj = A / J;
        T = 1 / A + Tj;
        *rho = Tj / T;
    } else {
        Tj = 1 / sms_plan_sqrt(J);
        T = 2 * Tj;
        *rho = (sms_real)0.5;
    }
    return T;
}

/* The unit limits of the change dV, A = min_i amax_i/|dV_i| and J = min_i jmax_i/|dV_i|;
 * 0 when dV is 0. */
static int unit_limits(const sms_multi_group *G, const sms_real *dV, sms_real *A, sms_real *J)
{
    size_t i;
    int any = 0;
    *A = *J = REAL_MAX;
    for (i = 0; i < G->n; ++i) {
        sms_real d = dV[i] < 0 ? -dV[i] : dV[i];
        if (d > 0) {
            sms_real a = ratio(G->amax[i], d), j = ratio(G->jmax[i], d);
            any = 1;
            if (a < *A)
                *A = a;
            if (j < *J)
                *J = j;
        }
    }
    return any;
}

/* Shortest transition for the change dV (0 for no change; rho 1/2 then). */
static sms_real transition_time(const sms_multi_group *G, const sms_real *dV, sms_real *rho)
{
    sms_real A, J;
    *rho = (sms_real)0.5;
    if (!unit_limits(G, dV, &A, &J))
        return 0;
    return unit_time(A, J, rho);
}

/* Jerk fraction of the first transition, the change dV over T1. When the shortest transition
 * fits (T <= T1: every arrival rounded up, docs/multi-axis.md) its own rho, stretched. When it
 * does not (the arrival rounded onto an earlier sample raised W by up to 2 GRID_TOL, and the
 * change by up to twice that when V and W - V both fill T1) the rho that minimises the larger
 * of the peak ratios |a_i|/amax_i = 1/(A (1 - rho) T1) and |j_i|/jmax_i = 1/(J rho (1 - rho)
 * T1^2): rho = A/(J T1), at most 1/2, which keeps the jerk phase A/J of the shortest
 * transition and raises a and j alike by T(dV)/T1 - A/J over T1 - A/J. The stretched rho
 * raised the jerk by the square of T(dV)/T1: 40 u over jmax in double and in float in the
 * case of tests/c/test_multi_generator.c (snapped_arrival_from_a_cruise). */
static sms_real first_rho(const sms_multi_group *G, const sms_real *dV, sms_real T1)
{
    sms_real A, J, rho, T, fit;
    if (!unit_limits(G, dV, &A, &J))
        return (sms_real)0.5;
    T = unit_time(A, J, &rho);
    if (T <= T1)
        return rho;
    fit = A / (J * T1);
    return fit < (sms_real)0.5 ? fit : (sms_real)0.5;
}

/* Smallest kappa with kappa >= T1/2 + T(u/kappa)/2 (tau >= 0) and |u_i|/kappa <= vmax_i. The
 * right side decreases with kappa, so when kv = max_i |u_i|/vmax_i satisfies it (the move
 * reaches a vmax: every long move) kappa = kv. That is decided on the cruise velocity u/kv,
 * whose unit limits stay in range, before the closed form, whose unit limits amax_i/|u_i| and
 * jmax_i/|u_i| (and their squares) underflow for displacements far beyond the distance to
 * reach vmax, which would drop a move that plainly fits the sample count. */
static sms_real landing_kappa(const sms_multi_group *G, const sms_real *u, sms_real T1)
{
    sms_real au = REAL_MAX, ju = REAL_MAX, kv = 0, kh, b, rho, W[SMS_MULTI_MAX_AXES];
    size_t i;
    int any = 0;
    for (i = 0; i < G->n; ++i) {
        sms_real d = u[i] < 0 ? -u[i] : u[i];
        if (d > 0) {
            sms_real k = d / G->vmax[i];
            any = 1;
            if (k > kv)
                kv = k;
        }
    }
    if (!any)
        return T1 / 2;
    for (i = 0; i < G->n; ++i)
        W[i] = u[i] / kv;
    if (kv >= T1 / 2 + transition_time(G, W, &rho) / 2)
        return kv;
    for (i = 0; i < G->n; ++i) {
        sms_real d = u[i] < 0 ? -u[i] : u[i];
        if (d > 0) {
            sms_real a = ratio(G->amax[i], d), j = ratio(G->jmax[i], d);
            if (a < au)
                au = a;
            if (j < ju)
                ju = j;
        }
    }
    /* the stop's unit limits are kappa au, kappa ju; acceleration-limited regime first */
    b = (T1 + au / ju) / 2;
    kh = (b + sms_plan_sqrt(b * b + 2 / au)) / 2;
    if (kh > ju / (au * au)) {
        /* jerk-limited stop: kappa = y^2, y^3 - (T1/2) y - 1/sqrt(ju) = 0; Newton from the
         * right of the root (the cubic is convex there) decreases monotonically */
        sms_real c = T1 / 2, q = 1 / sms_plan_sqrt(ju), y = sms_plan_sqrt(c) + root3(q);
        for (i = 0; i < 100; ++i) {
            sms_real f = (y * y - c) * y - q, y_next = y - f / (3 * y * y - c);
            if (!(y_next < y))
                break;
            y = y_next;
        }
        kh = y * y;
    }
    return kh > kv ? kh : kv;
}

/* A candidate move with first transition T1: its W, tau, T2, rho2 and whether V -> W fits. */
typedef struct candidate {
    sms_real W[SMS_MULTI_MAX_AXES];
    sms_real kappa, tau, T2, rho2, rho1;
    sms_real excess; /* T(W - V) - T1: feasible when <= 0 */
} candidate;

static void try_T1(const sms_multi_group *G, const sms_real *D, const sms_real *V, sms_real T1,
                   candidate *c)
{
    sms_real u[SMS_MULTI_MAX_AXES], dW[SMS_MULTI_MAX_AXES];
    size_t i;
    for (i = 0; i < G->n; ++i)
        u[i] = D[i] - V[i] * (T1 / 2);
    c->kappa = landing_kappa(G, u, T1);
    for (i = 0; i < G->n; ++i) {
        c->W[i] = u[i] / c->kappa;
        dW[i] = c->W[i] - V[i];
    }
    c->T2 = transition_time(G, c->W, &c->rho2);
    c->tau = c->kappa - T1 / 2 - c->T2 / 2;
    if (c->tau < 0)
        c->tau = 0; /* rounding: kappa solves tau = 0 to an ulp */
    c->excess = transition_time(G, dW, &c->rho1) - T1;
}

/* Smallest T1 in [lo, hi] with excess(T1) <= 0, given excess(lo) > 0 >= excess(hi) (excess is
 * continuous in T1): Illinois regula falsi (Dowell and Jarratt 1971, BIT 11, "A modified
 * regula falsi method for computing the root of an equation": the end kept twice in a row has
 * its value halved, which makes the convergence superlinear) with a bisection every fourth
 * step and the new point kept at least a quarter bracket tolerance inside, so the bracket
 * shrinks to neighbouring reals in a few steps. Returns the feasible end hi; c holds its move. */
static sms_real first_transition(const sms_multi_group *G, const sms_real *D, const sms_real *V,
                                 sms_real lo, sms_real e_lo, sms_real hi, candidate *c)
{
    sms_real e_hi, x, margin;
    int kept = 0; /* +1: lo kept last time, -1: hi kept last time */
    size_t it;
    try_T1(G, D, V, hi, c);
    e_hi = c->excess;
    if (!(e_hi <= 0))
        return hi; /* the bound 2 vmax is feasible by construction; rounding only */
    for (it = 0; it < MAX_ROOT_STEPS && hi - lo > BRACKET_TOL * hi; ++it) {
        candidate t;
        margin = (sms_real)0.25 * BRACKET_TOL * hi;
        if (it % 4 == 3)
            x = lo + (hi - lo) / 2;
        else
            x = lo + (hi - lo) * (e_lo / (e_lo - e_hi));
        if (x < lo + margin)
            x = lo + margin;
        if (x > hi - margin)
            x = hi - margin;
        try_T1(G, D, V, x, &t);
        if (t.excess <= 0) {
            hi = x;
            e_hi = t.excess;
            *c = t;
            if (kept == 1)
                e_lo *= (sms_real)0.5;
            kept = 1;
        } else {
            lo = x;
            e_lo = t.excess;
            if (kept == -1)
                e_hi *= (sms_real)0.5;
            kept = -1;
        }
    }
    return hi;
}

/* A move longer than this many samples is not planned (the saved state keeps sample counts
 * exact in double; about 1.4e5 years at 1 ms). */
#define MAX_MOVE_SAMPLES ((sms_real)4503599627370496.0) /* 2^52 */

static int real_finite(sms_real x)
{
    return x - x == 0;
}

/* The contract is in multi_parts.h. */
int sms_multi_plan(sms_multi_generator *g, size_t first, const sms_multi_group *G,
                   sms_multi_move *m, const sms_real *p, const sms_real *V, sms_real off)
{
    sms_real P0[SMS_MULTI_MAX_AXES], V0[SMS_MULTI_MAX_AXES], D[SMS_MULTI_MAX_AXES];
    sms_real u[SMS_MULTI_MAX_AXES], W[SMS_MULTI_MAX_AXES], dW[SMS_MULTI_MAX_AXES] = {0};
    sms_real lo, hi, T1, rho, rho1, total, nu, n_round, delta, kappa, tau;
    const sms_real Ts = g->Ts_signal;
    candidate c;
    size_t i, k_end = 0;
    int moving = 0, any_move = 0, ok = 1;
    for (i = 0; i < G->n; ++i) { /* p and V may alias the generator's own arrays */
        P0[i] = p[i];
        V0[i] = V[i];
        D[i] = g->target[first + i] - P0[i];
        if (V0[i] != 0)
            moving = 1;
        if (D[i] != 0)
            any_move = 1;
        ok &= real_finite(D[i]);
        W[i] = 0;
    }
    T1 = tau = 0;
    rho1 = (sms_real)0.5;
    c.T2 = 0;
    c.rho2 = (sms_real)0.5;
    if (ok && (moving || any_move)) {
        /* smallest feasible first transition in [T(V), T(2 vmax)] (the upper end is feasible) */
        lo = transition_time(G, V0, &rho);
        try_T1(G, D, V0, lo, &c);
        if (c.excess > 0) {
            sms_real A = REAL_MAX, J = REAL_MAX, e_lo = c.excess;
            for (i = 0; i < G->n; ++i) {
                sms_real a = G->amax[i] / (2 * G->vmax[i]), j = G->jmax[i] / (2 * G->vmax[i]);
                if (a < A)
                    A = a;
                if (j < J)
                    J = j;
            }
            hi = unit_time(A, J, &rho) * (1 + 16 * REAL_EPS);
            if (hi < lo)
                hi = lo;
            lo = first_transition(G, D, V0, lo, e_lo, hi, &c);
        }
        T1 = lo;
        /* arrival on the grid: lengthen the cruise by delta, W = u / (kappa + delta); a move
         * that ends within GRID_TOL after a sample arrives on it (delta < 0, W grows by up to
         * 2 GRID_TOL) */
        total = T1 + c.tau + c.T2;
        nu = (total - off) / Ts;
        if (!(nu > 0))
            nu = 0;
        ok = real_finite(total) && nu <= MAX_MOVE_SAMPLES; /* also refuses NaN */
        if (ok) {
            n_round = (sms_real)(size_t)(nu + (sms_real)0.5);
            if ((n_round >= nu ? n_round - nu : nu - n_round) <= GRID_TOL * (nu > 1 ? nu : 1))
                k_end = (size_t)n_round;
            else
                k_end = (size_t)nu + 1u; /* ceil: nu is not on the grid */
            delta = (sms_real)k_end * Ts + off - total;
            tau = c.tau + delta;
            if (tau < 0)
                tau = 0;
            kappa = T1 / 2 + tau + c.T2 / 2;
            for (i = 0; i < G->n; ++i) {
                u[i] = D[i] - V0[i] * (T1 / 2);
                /* k_end = 0: the move ends within this sample (Ts longer than the move); the
                 * goal is output at once and no cruise velocity is kept */
                W[i] = kappa > 0 && k_end > 0 ? u[i] / kappa : 0;
                dW[i] = W[i] - V0[i];
                ok &= real_finite(W[i]) && real_finite(dW[i]);
            }
            rho1 = first_rho(G, dW, T1); /* its length fits T1 (header) but for the snap */
            ok &= real_finite(tau) && real_finite(rho1) && real_finite(c.rho2);
        }
    }
    if (!ok)
        return 0;
    for (i = 0; i < G->n; ++i) {
        g->p[first + i] = P0[i];
        g->V[first + i] = V0[i];
        g->W[first + i] = W[i];
        g->goal[first + i] = g->target[first + i];
    }
    m->pending = 0;
    m->k = 0;
    m->off = off;
    m->T1 = T1;
    m->rho1 = rho1;
    m->tau = tau;
    m->T2 = c.T2;
    m->rho2 = c.rho2;
    m->k_end = k_end;
    m->active = k_end > 0; /* 0: already there at rest, or it ends by this very sample */
    return 1;
}
