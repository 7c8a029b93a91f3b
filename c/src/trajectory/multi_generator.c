/* Online multi-axis generator. The planning argument (transitions, landing, why no limit is
 * exceeded) is in multi_generator.h; here the arithmetic, all in sms_real without libm in
 * step (roots by Newton), so a float build stays single precision. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>
#include "smoothshaper/multi_generator.h"
#include "trajectory/plan.h"
#include "core/state_identity.h"
#include "trajectory/trajectory_internal.h"

#ifdef SMS_USE_FLOAT
#define REAL_EPS ((sms_real)FLT_EPSILON)
#define REAL_MAX ((sms_real)FLT_MAX)
#else
#define REAL_EPS ((sms_real)DBL_EPSILON)
#define REAL_MAX ((sms_real)DBL_MAX)
#endif

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
 * sample (plan()). The plan's duration carries the root search's bracket (2 eps of T1) and a
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

/* The axes a move drives and their limits. */
typedef struct group {
    size_t n;
    const sms_real *vmax, *amax, *jmax;
} group;

/* The unit limits of the change dV, A = min_i amax_i/|dV_i| and J = min_i jmax_i/|dV_i|;
 * 0 when dV is 0. */
static int unit_limits(const group *G, const sms_real *dV, sms_real *A, sms_real *J)
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
static sms_real transition_time(const group *G, const sms_real *dV, sms_real *rho)
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
static sms_real first_rho(const group *G, const sms_real *dV, sms_real T1)
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
static sms_real landing_kappa(const group *G, const sms_real *u, sms_real T1)
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

static void try_T1(const group *G, const sms_real *D, const sms_real *V, sms_real T1,
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
static sms_real first_transition(const group *G, const sms_real *D, const sms_real *V,
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

/* Plan a move from (p, V, a = 0) at move time 0 towards the target; the first sample of the
 * new move is at move time off. Returns 1 when planned; 0 when the move cannot be represented
 * in sms_real (a displacement, duration or velocity not finite, or more than MAX_MOVE_SAMPLES
 * samples: e.g. |d| = 1e300 with jmax = 1e-300), and then the generator is untouched. */
static int plan(sms_multi_generator *g, size_t first, const group *G, sms_multi_move *m,
                const sms_real *p, const sms_real *V, sms_real off)
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
 * plan ends on the arrival sample (plan(): tau takes up the rounding onto the grid), so the
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

static void step_group(sms_multi_generator *g, size_t first, size_t n, sms_multi_move *m,
                       sms_real *out)
{
    const group G = {n, g->vmax + first, g->amax + first, g->jmax + first};
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
            if (!plan(g, first, &G, m, g->goal + first, zero, 0))
                drop_target(g, m);
            t = 0;
        } else if (t >= m->T1) {
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
                if (plan(g, first, &G, m, p, V, t > tr ? t - tr : 0))
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

static int limit_ok(double x)
{
    return isfinite(x) && x > 0.0 && (sms_real)x > 0 && (double)(sms_real)x < (double)REAL_MAX;
}

/* Every axis's limits must let a move reach its vmax (multi_generator.h): the planner forms,
 * per axis, the same quantities as the single-axis planner with linear jerk ramps (J dv, a^2,
 * durations and distances of the move to vmax), so axis i is checked by the single-axis
 * region (sms_generator_reach() on its vmax, amax, jmax with the polynomial profile). */
/* The planner caps the ratios limit/|dv| at RATIO_CAP (ratio()), which lengthens a transition
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
             * durations (landing_kappa(): b^2, au^2, ju) */
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
    if ((unsigned)config->sync > (unsigned)SMS_SYNC_INDEPENDENT)
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

/* The configuration identity of a saved state (multi_generator.h, SMS_MULTI_IDENTITY_COUNT):
 * the common head, n_axes, sync, then per axis slot vmax, amax, jmax, n_stages (0 beyond
 * n_axes). The stages' configs are in their own stage states. */
enum { ID_AXES = SMS_STATE_IDENTITY_HEAD, ID_SYNC, ID_AXIS, ID_AXIS_FIELDS = 4 };

static void write_identity(const sms_multi_generator_config *c, double Ts,
                           double id[SMS_MULTI_IDENTITY_COUNT])
{
    size_t i;
    sms_state_identity_head(id, SMS_STATE_KIND_MULTI_GENERATOR, Ts);
    id[ID_AXES] = (double)c->n_axes;
    id[ID_SYNC] = (double)c->sync;
    for (i = 0; i < SMS_MULTI_MAX_AXES; ++i) {
        double *axis = id + ID_AXIS + ID_AXIS_FIELDS * i;
        axis[0] = i < c->n_axes ? c->vmax[i] : 0.0;
        axis[1] = i < c->n_axes ? c->amax[i] : 0.0;
        axis[2] = i < c->n_axes ? c->jmax[i] : 0.0;
        axis[3] = i < c->n_axes ? (double)c->n_stages[i] : 0.0;
    }
}

static sms_status check_identity(const sms_multi_generator *g, const double *src)
{
    sms_status field_status[SMS_MULTI_IDENTITY_COUNT - SMS_STATE_IDENTITY_HEAD];
    size_t i;
    field_status[ID_AXES - SMS_STATE_IDENTITY_HEAD] = SMS_ERR_STATE_AXES;
    field_status[ID_SYNC - SMS_STATE_IDENTITY_HEAD] = SMS_ERR_STATE_SYNC;
    for (i = 0; i < SMS_MULTI_MAX_AXES; ++i) {
        sms_status *axis = field_status + ID_AXIS - SMS_STATE_IDENTITY_HEAD + ID_AXIS_FIELDS * i;
        axis[0] = SMS_ERR_STATE_VMAX;
        axis[1] = SMS_ERR_STATE_AMAX;
        axis[2] = SMS_ERR_STATE_JMAX;
        axis[3] = SMS_ERR_STATE_STAGES;
    }
    return sms_state_identity_compare(g->identity, src,
                                      SMS_MULTI_IDENTITY_COUNT - SMS_STATE_IDENTITY_HEAD,
                                      field_status);
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
    write_identity(config, Ts, g->identity);
    sms_multi_generator_reset(g, NULL);
    return SMS_OK;
}

void sms_multi_generator_reset(sms_multi_generator *g, const sms_real *position)
{
    size_t i;
    g->dropped = 0;
    for (i = 0; i < SMS_MULTI_MAX_AXES; ++i) {
        sms_real x = (position != NULL && i < g->n_axes) ? position[i] : 0;
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
}

/* One sample of the profile alone (the targets, the moves, out), without the stages. */
static void step_profile(sms_multi_generator *g, const sms_real *target, sms_real *out)
{
    size_t i;
    for (i = 0; i < g->n_axes; ++i)
        if (target[i] - target[i] == 0 && target[i] != g->target[i]) { /* finite and new */
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

/* Samples until a group's move changes other than by its index: a pending target is planned
 * (or dropped) on that sample (step_group: when not moving at once; while moving once the
 * move time reaches the end of the first transition, or at the arrival if the target came
 * during the stop). UINT64_MAX when nothing is pending. */
static uint64_t group_event(const sms_multi_generator *g, const sms_multi_move *m)
{
    sms_real tr;
    uint64_t lo, hi;
    if (!m->pending)
        return UINT64_MAX;
    if (!m->active)
        return 1u;
    hi = (uint64_t)(m->k_end - m->k);   /* the arrival sample: planned from rest there */
    tr = m->seen > m->T1 ? m->seen : m->T1;
    if (tr > m->T1 + m->tau)
        return hi;
    /* the first sample whose move time reaches T1 (step_group()'s blend test): t = off + k Ts
     * grows with k. A target seen at a sample that time_left() already counted in the stop
     * while seen <= T1 + tau (a rounding apart) blends on the next one, as there */
    lo = 1u;
    while (lo < hi) {
        const uint64_t mid = lo + (hi - lo) / 2u;
        const sms_real t = m->off + (sms_real)(size_t)(m->k + mid) * g->Ts_signal;
        if (t >= m->T1)
            hi = mid;
        else
            lo = mid + 1u;
    }
    return lo;
}

/* n samples of the profile alone with the held targets, in closed form between the samples on
 * which a move changes (new targets, plans, drops: at most two per group), out the last
 * sample's. Each move's sample is a function of its index (evaluate()). */
static void hold_profile(sms_multi_generator *g, const sms_real *target, uint64_t n, sms_real *out)
{
    const size_t groups = g->sync == SMS_SYNC_PHASE ? 1u : g->n_axes;
    size_t i;
    while (n > 0u) {
        uint64_t e = UINT64_MAX;
        int fresh = 0;
        for (i = 0; i < g->n_axes; ++i)
            if (target[i] - target[i] == 0 && target[i] != g->target[i])
                fresh = 1;
        if (!fresh)
            for (i = 0; i < groups; ++i) {
                const uint64_t ev = group_event(g, &g->move[i]);
                if (ev < e)
                    e = ev;
            }
        else
            e = 1u;
        if (e > n)
            e = n;
        for (i = 0; i < groups; ++i) {   /* e - 1 samples of index only */
            sms_multi_move *m = &g->move[i];
            if (m->active) {
                if (e - 1u >= (uint64_t)(m->k_end - m->k)) {
                    m->k = m->k_end;
                    m->active = 0;
                } else {
                    m->k += (size_t)(e - 1u);
                }
            }
        }
        step_profile(g, target, out);
        n -= e;
    }
}

/* At rest: no move running, none pending, every target planned. */
static int profile_at_rest(const sms_multi_generator *g, const sms_real *target)
{
    const size_t groups = g->sync == SMS_SYNC_PHASE ? 1u : g->n_axes;
    size_t i;
    for (i = 0; i < g->n_axes; ++i)
        if (target[i] - target[i] == 0 && target[i] != g->target[i])
            return 0;
    for (i = 0; i < groups; ++i)
        if (g->move[i].active || g->move[i].pending)
            return 0;
    return 1;
}

#define HOLD_BLOCK 16u

uint64_t sms_multi_generator_hold(sms_multi_generator *g, const sms_real *target, uint64_t n,
                                  sms_real *out)
{
    double bound = 0.0;
    uint64_t window, k, total = n;
    size_t i, m;
    sms_real scratch[4 * SMS_MULTI_MAX_AXES];
    sms_multi_generator probe;
    if (n == 0u)
        return 0u;
    for (i = 0; i < g->n_axes; ++i)
        if (g->chain[i][0].n_stages > 0) {
            const double b = sms_chain_settle_bound(&g->chain[i][0]);
            if (b > bound)
                bound = b;
        }
    if (bound == 0.0) {                   /* no stages: the profile alone */
        hold_profile(g, target, n, out);
        return n;
    }
    if (!(bound < 1e15))
        return 0u;                         /* a notch that does not decay: stepped outside */
    window = (uint64_t)bound + 2u;
    if (n > window) {
        /* the profile to the start of the last `window` samples, on a copy first */
        probe = *g;
        hold_profile(&probe, target, n - window, scratch);
        if (profile_at_rest(&probe, target)) {
            /* the stages see each axis's rest for their last window samples: absorbed */
            *g = probe;
            hold_profile(g, target, window - 1u, scratch);
            for (i = 0; i < g->n_axes; ++i)
                if (g->chain[i][0].n_stages > 0)
                    for (m = 0; m < SMS_MULTI_SIGNALS; ++m)
                        (void)sms_chain_settle(&g->chain[i][m], scratch[4 * i + m], n - 1u);
            sms_multi_generator_step(g, target, out);
            return n;
        }
        /* FIR stages depend only on their last `window` inputs: the profile and the stages'
         * phase jump there, and those samples are stepped. A notch starts them from its stale
         * state, whose transient the window (its settle bound) decays past rounding */
        *g = probe;
        for (i = 0; i < g->n_axes; ++i)
            if (g->chain[i][0].n_stages > 0)
                for (m = 0; m < SMS_MULTI_SIGNALS; ++m)
                    sms_chain_advance(&g->chain[i][m], n - window);
        n = window;
    }
    /* in blocks: the profile's samples first, then each chain over the block (the profile
     * does not depend on the stages, and a chain's process is its step on a block) */
    while (n > 0u) {
        sms_real prof[HOLD_BLOCK][4 * SMS_MULTI_MAX_AXES], x[HOLD_BLOCK];
        const size_t b = n < HOLD_BLOCK ? (size_t)n : HOLD_BLOCK;
        for (k = 0; k < b; ++k)
            step_profile(g, target, prof[k]);
        for (i = 0; i < g->n_axes; ++i)
            if (g->chain[i][0].n_stages > 0)
                for (m = 0; m < SMS_MULTI_SIGNALS; ++m) {
                    for (k = 0; k < b; ++k)
                        x[k] = prof[k][4 * i + m];
                    sms_chain_process(&g->chain[i][m], x, x, b);
                    for (k = 0; k < b; ++k)
                        prof[k][4 * i + m] = x[k];
                }
        for (i = 0; i < 4 * g->n_axes; ++i)
            out[i] = prof[b - 1][i];
        n -= b;
    }
    return total;
}

void sms_multi_generator_step(sms_multi_generator *g, const sms_real *target, sms_real *out)
{
    size_t i;
    step_profile(g, target, out);
    for (i = 0; i < g->n_axes; ++i)
        if (g->chain[i][0].n_stages > 0) {
            size_t m;
            for (m = 0; m < SMS_MULTI_SIGNALS; ++m)
                sms_chain_step(&g->chain[i][m], &out[4 * i + m]);
        }
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
    for (i = 0; i < groups; ++i)
        if (g->move[i].active || g->move[i].pending)
            return 1;
    return 0;
}

/* Time-optimal unit rest-to-rest move under path limits V, A, J (closed form). */
static double unit_move_time(double V, double A, double J)
{
    double Tv = V * J >= A * A ? V / A + A / J : 2.0 * sqrt(V / J), c;
    if (V * Tv < 1.0)
        return 1.0 / V + Tv; /* reaches V: cruise 1/V - Tv */
    /* peak velocity c below V: c T(c) = 1 */
    c = 0.5 * (-A * A / J + sqrt(A * A * A * A / (J * J) + 4.0 * A));
    if (c * J >= A * A)
        return 2.0 * (c / A + A / J);
    return 4.0 * cbrt(0.5 / J); /* c = J Tj^2, 2 J Tj^3 = 1, T = 4 Tj */
}

sms_status sms_multi_phase_duration(const sms_multi_generator_config *config,
                                    const double *delta, double *T)
{
    double V = HUGE_VAL, A = HUGE_VAL, J = HUGE_VAL;
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
            V = fmin(V, config->vmax[i] / d);
            A = fmin(A, config->amax[i] / d);
            J = fmin(J, config->jmax[i] / d);
        }
    }
    *T = V == HUGE_VAL ? 0.0 : unit_move_time(V, A, J);
    return SMS_OK;
}

/* ---- state vector: the identity; per axis target, goal, p, V, W; per move its 12 fields;
 * the stages' states ---- */

#define AXIS_FIELDS 5u
#define MOVE_FIELDS 12u

static size_t move_count(const sms_multi_generator *g)
{
    return g->sync == SMS_SYNC_PHASE ? 1u : g->n_axes;
}

static size_t stages_state_count(const sms_multi_generator *g)
{
    size_t i, m, total = 0;
    for (i = 0; i < g->n_axes; ++i)
        for (m = 0; m < SMS_MULTI_SIGNALS; ++m)
            total += sms_chain_state_count(&g->chain[i][m]);
    return total;
}

size_t sms_multi_generator_state_count(const sms_multi_generator *g)
{
    return SMS_MULTI_IDENTITY_COUNT + AXIS_FIELDS * g->n_axes + MOVE_FIELDS * move_count(g)
           + stages_state_count(g);
}

void sms_multi_generator_get_state(const sms_multi_generator *g, double *dst)
{
    size_t i, n = g->n_axes;
    for (i = 0; i < SMS_MULTI_IDENTITY_COUNT; ++i)
        dst[i] = g->identity[i];
    dst += SMS_MULTI_IDENTITY_COUNT;
    for (i = 0; i < n; ++i) {
        dst[i] = (double)g->target[i];
        dst[n + i] = (double)g->goal[i];
        dst[2 * n + i] = (double)g->p[i];
        dst[3 * n + i] = (double)g->V[i];
        dst[4 * n + i] = (double)g->W[i];
    }
    dst += AXIS_FIELDS * n;
    for (i = 0; i < move_count(g); ++i, dst += MOVE_FIELDS) {
        const sms_multi_move *m = &g->move[i];
        dst[0] = (double)m->T1;
        dst[1] = (double)m->rho1;
        dst[2] = (double)m->tau;
        dst[3] = (double)m->T2;
        dst[4] = (double)m->rho2;
        dst[5] = (double)m->off;
        dst[6] = (double)m->seen;
        dst[7] = (double)m->k;
        dst[8] = (double)m->k_end;
        dst[9] = (double)m->active;
        dst[10] = (double)m->pending;
        dst[11] = (double)m->refused;
    }
    for (i = 0; i < n; ++i) {
        size_t s;
        for (s = 0; s < SMS_MULTI_SIGNALS; ++s) {
            sms_chain_get_state(&g->chain[i][s], dst);
            dst += sms_chain_state_count(&g->chain[i][s]);
        }
    }
}

/* Would every stage of every chain accept its part of src (n doubles)? Writes nothing. A stage
 * saved by another stage configuration gets the status naming the field (its stage identity),
 * also when that made the vector longer or shorter. */
static sms_status check_stages_state(const sms_multi_generator *g, const double *src, size_t n)
{
    size_t i, m, k;
    for (i = 0; i < g->n_axes; ++i)
        for (m = 0; m < SMS_MULTI_SIGNALS; ++m)
            for (k = 0; k < g->chain[i][m].n_stages; ++k) {
                const sms_stage *st = &g->chain[i][m].stages[k];
                size_t count = sms_stage_state_count(st);
                sms_status status;
                if (n < SMS_STATE_IDENTITY_COUNT)
                    return SMS_ERR_STATE;
                status = sms_stage_check_state(st, src, n < count ? n : count);
                if (status != SMS_OK)
                    return status <= SMS_ERR_STATE_FORMAT ? status : SMS_ERR_STATE;
                src += count;
                n -= count;
            }
    return n == 0 ? SMS_OK : SMS_ERR_STATE;
}

static int whole(double x)
{
    return x >= 0.0 && x <= 9007199254740992.0 && x == (double)(size_t)x;
}

sms_status sms_multi_generator_check_state(const sms_multi_generator *g, const double *src,
                                           size_t n)
{
    size_t i, na;
    const double *mv;
    sms_status st;
    if (g == NULL || src == NULL)
        return SMS_ERR_NULL;
    /* another configuration first, whatever the length: its state often has another one */
    if (n >= SMS_MULTI_IDENTITY_COUNT && (st = check_identity(g, src)) != SMS_OK)
        return st;
    na = g->n_axes;
    if (n != sms_multi_generator_state_count(g)) {
        /* the same limits, another length: a stage of another configuration, named by the
         * first stage identity that differs */
        const size_t fixed = SMS_MULTI_IDENTITY_COUNT + AXIS_FIELDS * na
                             + MOVE_FIELDS * move_count(g);
        if (n > fixed && (st = check_stages_state(g, src + fixed, n - fixed)) <= SMS_ERR_STATE_FORMAT)
            return st;
        return SMS_ERR_STATE;
    }
    src += SMS_MULTI_IDENTITY_COUNT;
    n -= SMS_MULTI_IDENTITY_COUNT;
    for (i = 0; i < n; ++i)
        if (!isfinite(src[i]))
            return SMS_ERR_STATE;
    for (i = 0; i < na; ++i) {
        /* as sms_real holds them: the start and cruise velocities within the tolerance of
         * the reported values (the planner's own within 12 eps, above) */
        const double vmax = (double)g->vmax[i] * (1.0 + SMS_LIMIT_RTOL);
        if (!(fabs((double)(sms_real)src[3 * na + i]) <= vmax) ||
            !(fabs((double)(sms_real)src[4 * na + i]) <= vmax))
            return SMS_ERR_STATE;
    }
    mv = src + AXIS_FIELDS * na;
    for (i = 0; i < move_count(g); ++i) {
        const double *f = mv + MOVE_FIELDS * i;
        if (f[0] < 0.0 || f[2] < 0.0 || f[3] < 0.0 || f[5] < 0.0 || f[6] < 0.0 ||
            !(f[1] > 0.0 && f[1] <= 0.5) || !(f[4] > 0.0 && f[4] <= 0.5) || !whole(f[7]) ||
            !whole(f[8]) || f[7] > f[8] || (f[9] != 0.0 && f[9] != 1.0) ||
            (f[10] != 0.0 && f[10] != 1.0) || (f[11] != 0.0 && f[11] != 1.0))
            return SMS_ERR_STATE;
    }
    return check_stages_state(g, mv + MOVE_FIELDS * move_count(g),
                              n - AXIS_FIELDS * na - MOVE_FIELDS * move_count(g));
}

sms_status sms_multi_generator_set_state(sms_multi_generator *g, const double *src, size_t n)
{
    size_t i, na;
    const double *mv;
    sms_status st = sms_multi_generator_check_state(g, src, n);
    if (st != SMS_OK)
        return st;
    src += SMS_MULTI_IDENTITY_COUNT;
    na = g->n_axes;
    mv = src + AXIS_FIELDS * na;
    for (i = 0; i < na; ++i) {
        g->target[i] = (sms_real)src[i];
        g->goal[i] = (sms_real)src[na + i];
        g->p[i] = (sms_real)src[2 * na + i];
        g->V[i] = (sms_real)src[3 * na + i];
        g->W[i] = (sms_real)src[4 * na + i];
    }
    for (i = 0; i < move_count(g); ++i) {
        const double *f = mv + MOVE_FIELDS * i;
        sms_multi_move *m = &g->move[i];
        m->T1 = (sms_real)f[0];
        m->rho1 = (sms_real)f[1];
        m->tau = (sms_real)f[2];
        m->T2 = (sms_real)f[3];
        m->rho2 = (sms_real)f[4];
        m->off = (sms_real)f[5];
        m->seen = (sms_real)f[6];
        m->k = (size_t)f[7];
        m->k_end = (size_t)f[8];
        m->active = (int)f[9];
        m->pending = (int)f[10];
        m->refused = (int)f[11];
    }
    mv += MOVE_FIELDS * move_count(g);
    for (i = 0; i < na; ++i) {
        size_t s;
        for (s = 0; s < SMS_MULTI_SIGNALS; ++s) {
            size_t count = sms_chain_state_count(&g->chain[i][s]);
            if (count > 0)
                (void)sms_chain_set_state(&g->chain[i][s], mv, count); /* checked above */
            mv += count;
        }
    }
    return SMS_OK;
}

void sms_multi_generator_rebind(sms_multi_generator *g, sms_stage *stages,
                                sms_memory_cell *memory)
{
    size_t i, m;
    for (i = 0; i < g->n_axes; ++i)
        for (m = 0; m < SMS_MULTI_SIGNALS; ++m) {
            sms_chain *c = &g->chain[i][m];
            if (c->n_stages == 0)
                continue;
            sms_chain_rebind(c, stages, memory);
            stages += c->n_stages;
            memory += c->memory_len;
        }
}
