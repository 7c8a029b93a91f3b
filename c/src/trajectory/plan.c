/* SPDX-License-Identifier: Apache-2.0 */
/* The time-optimal single-axis plan (plan.h). Every operation is in sms_real. */
#include "trajectory/plan.h"

sms_real sms_plan_sqrt(sms_real x)
{
    sms_real scale = 1, y;
    int i;
    if (!(x > 0))
        return 0;
    if (x - x != 0)
        return x; /* +Inf (an overflowed product): the loop below would never end */
    while (x >= 4) {
        x *= (sms_real)0.25;
        scale *= 2;
    }
    while (x < 1) {
        x *= 4;
        scale *= (sms_real)0.5;
    }
    y = (1 + x) * (sms_real)0.5;
    for (i = 0; i < 7; ++i)
        y = (y + x / y) * (sms_real)0.5;
    return y * scale;
}

/* Relative tolerance of the on-grid test for breakpoints: 8 ulps of sms_real times the
 * breakpoint's sample count, what summing the segment lengths can round away. */
#define PLAN_GRID_TOL (sizeof(sms_real) == sizeof(double) ? 8.0 * 2.220446049250313e-16 \
                                                          : 8.0 * 1.1920929e-7)

/* Below the smallest normal number a relative tolerance underflows: a gap there is a
 * subnormal position step (a move to 2.2e-313 is planned, not dropped). */
#define PLAN_MIN_NORMAL (sizeof(sms_real) == sizeof(double) ? (sms_real)2.2250738585072014e-308 \
                                                            : (sms_real)1.17549435e-38f)

/* Most halvings of the vp search: both exponent ranges plus the mantissa of sms_real. */
#define PLAN_SEARCH_STEPS (sizeof(sms_real) == sizeof(double) ? 2 * 1075 + 60 : 2 * 150 + 30)

/* Up to three constant-jerk pieces. */
typedef struct pieces {
    int count;
    sms_real d[4], j[4];
} pieces;

/* Time-optimal change of (v0, a0) to (v1, 0) within amax, jmax (a0 within amax and the
 * change possible without passing the velocity bound: the caller's precondition). */
static void velocity_change(sms_real v0, sms_real a0, sms_real v1, sms_real A, sms_real J,
                            int shape, pieces *out)
{
    sms_real after = v0 + a0 * (a0 < 0 ? -a0 : a0) / (2 * J); /* a0 -> 0 at once */
    sms_real s, a0s, dv, ap, hold;
    out->count = 0;
    if (v1 == after) {
        if (a0 != 0) {
            out->d[0] = (a0 < 0 ? -a0 : a0) / J;
            out->j[0] = a0 > 0 ? -J : J;
            out->count = 1;
        }
        return;
    }
    s = v1 > after ? 1 : -1; /* the direction of the acceleration peak */
    a0s = s * a0;
    if (shape == SMS_PLAN_COSINE && a0s < 0) {
        /* a half-cosine transition across zero would linger near a0 (its jerk starts at 0)
         * and take v beyond the brake velocity `after`: bring a0 to zero first, then start
         * from (after, 0) */
        velocity_change(after, 0, v1, A, J, shape, out);
        {
            int i;
            for (i = out->count; i > 0; --i) {
                out->d[i] = out->d[i - 1];
                out->j[i] = out->j[i - 1];
            }
        }
        out->d[0] = -a0s / J;
        out->j[0] = s * J;
        out->count += 1;
        return;
    }
    dv = s * (v1 - v0);
    /* a: a0 -> ap (jerk s J), hold ap, ap -> 0 (jerk -s J):
     * dv = (ap^2 - a0^2)/(2J) + ap hold + ap^2/(2J) */
    ap = sms_plan_sqrt(J * dv + (sms_real)0.5 * a0s * a0s);
    hold = 0;
    if (ap > A) {
        ap = A;
        hold = (dv - (2 * A * A - a0s * a0s) / (2 * J)) / A;
        if (hold < 0)
            hold = 0;
    }
    if (ap < a0s)
        ap = a0s; /* rounding only (v1 > after makes ap >= a0s) */
    out->d[0] = (ap - a0s) / J;
    out->j[0] = s * J;
    out->d[1] = hold;
    out->j[1] = 0;
    out->d[2] = ap / J;
    out->j[2] = -s * J;
    out->count = 3;
}

/* Position coefficient of a whole transition of duration d and mean jerk j (the change of a
 * over it is j d): dq = v d + a d^2/2 + c3 j d^3 with c3 = 1/6 for a linear ramp and
 * 1/4 - 1/pi^2 for a half-cosine one (a(t) = a0 + j d (1 - cos(pi t/d))/2). */
#define PLAN_C3_RAMP ((sms_real)(1.0 / 6.0))
#define PLAN_C3_COSINE ((sms_real)0.14867881635766024) /* 1/4 - 1/pi^2 */

/* Advance (p, v, a) by one whole transition of d seconds at mean jerk j (coefficient c3). */
static void advance(sms_real *p, sms_real *v, sms_real *a, sms_real j, sms_real d, sms_real c3)
{
    *p += d * (*v + d * (*a * (sms_real)0.5 + d * j * c3));
    *v += d * (*a + d * j * (sms_real)0.5);
    *a += d * j;
}

/* Distance of the velocity change to vp plus the stop from vp, and the two piece lists. */
static sms_real distance(sms_real v0, sms_real a0, sms_real vp, sms_real A, sms_real J,
                         int shape, pieces *first, pieces *stop)
{
    sms_real p = 0, v = v0, a = a0, c3 = shape == SMS_PLAN_COSINE ? PLAN_C3_COSINE : PLAN_C3_RAMP;
    int i;
    velocity_change(v0, a0, vp, A, J, shape, first);
    velocity_change(vp, 0, 0, A, J, shape, stop);
    for (i = 0; i < first->count; ++i)
        advance(&p, &v, &a, first->j[i], first->d[i], c3);
    v = vp;
    a = 0;
    for (i = 0; i < stop->count; ++i)
        advance(&p, &v, &a, stop->j[i], stop->d[i], c3);
    return p;
}

sms_real sms_plan_mean_jerk(const sms_plan_limits *lim, int shape)
{
    /* a half-cosine transition of peak jerk J changes a by J d 2/pi over d */
    return shape == SMS_PLAN_COSINE ? lim->jmax * (sms_real)0.63661977236758134 : lim->jmax;
}

void sms_plan_push(sms_plan *plan, sms_real Ts, size_t *n, sms_real *f, sms_real p, sms_real v,
                   sms_real a, sms_real j, sms_real d)
{
    size_t i = plan->count;
    sms_real total, whole;
    if (!(d > 0))
        return;
    plan->n[i] = *n;
    plan->f[i] = *f;
    plan->p[i] = p;
    plan->v[i] = v;
    plan->a[i] = a;
    plan->j[i] = j;
    plan->d[i] = d;
    plan->count = i + 1;
    plan->duration += d;
    total = (*f + d) / Ts;
    whole = (sms_real)(size_t)total;
    if (whole > total)
        whole -= 1;
    *n += (size_t)whole;
    *f = *f + d - whole * Ts;
    if (*f >= Ts) {
        *f -= Ts;
        *n += 1;
    }
    if (*f < 0)
        *f = 0;
}

int sms_plan_to_rest(sms_plan *plan, const sms_plan_limits *lim, sms_real Ts, sms_real q,
                     sms_real v, sms_real a, sms_real goal)
{
    return sms_plan_to_rest_shaped(plan, lim, SMS_PLAN_RAMP, Ts, q, v, a, goal);
}

sms_real sms_plan_max_samples(void)
{
    sms_real m = (sms_real)4503599627370496.0, s = (sms_real)((size_t)-1) * (sms_real)0.5;
    return s < m ? s : m;
}

static int is_finite(sms_real x)
{
    return x - x == 0; /* NaN and +-Inf give NaN */
}

static sms_real mag(sms_real x)
{
    return x < 0 ? -x : x;
}

int sms_plan_finite(const sms_plan *plan)
{
    size_t i;
    for (i = 0; i < plan->count; ++i) {
        sms_real d = plan->d[i];
        if (!is_finite(plan->p[i]) || !is_finite(plan->v[i]) || !is_finite(plan->a[i]) ||
            !is_finite(plan->j[i]) || !is_finite(d) || !is_finite(plan->f[i]))
            return 0;
        if (!is_finite(mag(plan->p[i]) + d * (mag(plan->v[i]) +
                                           d * (mag(plan->a[i]) * (sms_real)0.5 +
                                                d * mag(plan->j[i]) * (sms_real)0.25))) ||
            !is_finite(mag(plan->v[i]) + d * (mag(plan->a[i]) + d * mag(plan->j[i]))))
            return 0;
    }
    return is_finite(plan->goal) && is_finite(plan->drift) && is_finite(plan->end_f) &&
           is_finite(plan->duration);
}

int sms_plan_to_rest_shaped(sms_plan *out, const sms_plan_limits *lim, int shape, sms_real Ts,
                            sms_real q, sms_real v, sms_real a, sms_real goal)
{
    sms_plan tmp, *plan = &tmp;
    sms_real total, start, reach, gap, size;
    sms_real D = goal - q, vp, cruise = 0, V = lim->vmax, A = lim->amax, p, vv, aa, f = 0;
    sms_real J = sms_plan_mean_jerk(lim, shape);
    sms_real c3 = shape == SMS_PLAN_COSINE ? PLAN_C3_COSINE : PLAN_C3_RAMP;
    pieces first, stop;
    size_t n = 0;
    int i, on_stop = 0;
    plan->count = 0;
    plan->shape = shape;
    plan->goal = goal;
    plan->drift = 0;
    plan->duration = 0;
    if (D == 0 && v == 0 && a == 0) {
        plan->end = plan->arrive = 0;
        plan->end_f = plan->arrive_f = 0;
        *out = tmp;
        return 1;
    }
    if (!is_finite(D) || !is_finite(q) || !is_finite(v) || !is_finite(a) || !is_finite(goal))
        return 0;
    if (D >= distance(v, a, V, A, J, shape, &first, &stop)) {
        vp = V;
    } else if (D <= distance(v, a, -V, A, J, shape, &first, &stop)) {
        vp = -V;
    } else {
        /* Bisection to the last bit on the side of `after` (the velocity when a returns to
         * zero at once) where the root lies. Above it the distance increases with vp (more
         * acceleration first); below it a plan decelerates to vp and then stops, and just
         * below `after` that split deceleration covers more distance than stopping at once,
         * so a target a little beyond the direct stop would have a second, slower root
         * there. Searching [after, V] when D >= distance(after) takes the faster one. */
        sms_real after = v + a * (a < 0 ? -a : a) / (2 * J), lo = -V, hi = V;
        int it;
        if (after > -V && after < V) {
            /* a target at the direct stop to within the rounding of the positions (a running
             * plan's own goal, or one moved by less than an ulp): vp = after, no search (the
             * side would be decided by rounding, and each side's plan differs) */
            sms_real dA = distance(v, a, after, A, J, shape, &first, &stop), e = D - dA;
            sms_real scale = (q < 0 ? -q : q) + (goal < 0 ? -goal : goal) + (dA < 0 ? -dA : dA);
            if ((e < 0 ? -e : e) <= (sms_real)PLAN_GRID_TOL * scale) {
                lo = hi = after;
                on_stop = 1;
            }
            else if (e > 0)
                lo = after;
            else
                hi = after;
        }
        /* to the last bit even when the root is many binades below V (a short move at a huge
         * vmax): each halving takes at most one binade or one bit off, so the exponent range
         * plus the mantissa bound it; a typical search stops after about 60 (double) */
        for (it = 0; it < PLAN_SEARCH_STEPS; ++it) {
            sms_real mid = (sms_real)0.5 * (lo + hi);
            if (!(mid > lo && mid < hi))
                break;
            if (distance(v, a, mid, A, J, shape, &first, &stop) < D)
                lo = mid;
            else
                hi = mid;
        }
        /* The bracket's end on the side that leaves the parts a distance to cover at vp:
         * the one whose distance falls short of D when vp > 0, the one beyond it when
         * vp < 0. When a opposes the move, the distance grows like the square root of
         * vp - after just above `after` (the peak acceleration of the bump does), so
         * neighbouring vp differ in distance by up to 2 |vp| sqrt(ulp(vp)/J), far more than
         * the rounding of the positions: the parts cannot meet by vp alone. The stop anchored
         * on the goal then started that far from where the velocity change ended (a jump of
         * q that the sampled differences amplify by 1/Ts^i: a third difference up to 2000
         * jmax over its rounding floor in float, 2.5e-5 jmax in double, on random
         * staircases), or beyond the meeting check below, and the target was dropped. The
         * cruise at vp below covers what is left. */
        vp = lo > 0 ? lo : hi < 0 ? hi : (sms_real)0.5 * (lo + hi);
    }
    (void)distance(v, a, vp, A, J, shape, &first, &stop);
    /* the velocity change from the current state, and where the stop anchored on the goal
     * starts (its own distance before the goal); the cruise at vp covers what lies between,
     * so the parts meet to the rounding of the positions (a distance on the wrong side of
     * vp, or vp = 0, is rounding too: no cruise) */
    p = q;
    vv = v;
    aa = a;
    for (i = 0; i < first.count; ++i)
        advance(&p, &vv, &aa, first.j[i], first.d[i], c3);
    {
        sms_real ps = 0, vs = vp, as = 0;
        for (i = 0; i < stop.count; ++i)
            advance(&ps, &vs, &as, stop.j[i], stop.d[i], c3);
        start = goal - ps;
        /* (vp = after, a target at the direct stop to rounding: what is left is rounding, and
         * at a small `after` covering it would crawl) */
        if (vp != 0 && (start - p) / vp > 0 && !on_stop)
            cruise = (start - p) / vp;
        reach = p + cruise * vp;
        gap = reach - start;
        size = mag(q) + mag(goal) + mag(p - q) + mag(ps) + mag(cruise * vp);
    }
    /* the parts meet to the rounding of the positions (the search converged): where the
     * distances underflow or overflow they need not, and the plan would jump */
    if (!(mag(gap) <= 16 * (sms_real)PLAN_GRID_TOL * size || mag(gap) < PLAN_MIN_NORMAL))
        return 0;
    /* the whole plan on the grid: finite and few enough samples, before any is counted */
    total = cruise;
    for (i = 0; i < first.count; ++i)
        total += first.d[i];
    for (i = 0; i < stop.count; ++i)
        total += stop.d[i];
    if (!is_finite(vp) || !is_finite(total) || !(total / Ts + 2 <= sms_plan_max_samples()))
        return 0;
    p = q;
    vv = v;
    aa = a;
    for (i = 0; i < first.count; ++i) {
        sms_plan_push(plan, Ts, &n, &f, p, vv, aa, first.j[i], first.d[i]);
        advance(&p, &vv, &aa, first.j[i], first.d[i], c3);
    }
    if (cruise > 0)
        sms_plan_push(plan, Ts, &n, &f, p, vp, 0, 0, cruise);
    p = start;
    vv = vp;
    aa = 0;
    for (i = 0; i < stop.count; ++i) {
        sms_plan_push(plan, Ts, &n, &f, p, vv, aa, stop.j[i], stop.d[i]);
        advance(&p, &vv, &aa, stop.j[i], stop.d[i], c3);
    }
    plan->end = plan->arrive = n;
    plan->end_f = plan->arrive_f = f;
    if (!sms_plan_finite(plan))
        return 0;
    *out = tmp;
    return 1;
}

int sms_plan_velocity_shaped(sms_plan *out, const sms_plan_limits *lim, int shape, sms_real Ts,
                             sms_real q, sms_real v, sms_real a, sms_real velocity)
{
    sms_plan tmp, *plan = &tmp;
    sms_real J = sms_plan_mean_jerk(lim, shape), f = 0, p = q, vv = v, aa = a, total = 0;
    sms_real c3 = shape == SMS_PLAN_COSINE ? PLAN_C3_COSINE : PLAN_C3_RAMP;
    pieces change;
    size_t n = 0;
    int i;
    if (!is_finite(q) || !is_finite(v) || !is_finite(a) || !is_finite(velocity))
        return 0;
    plan->count = 0;
    plan->shape = shape;
    plan->duration = 0;
    velocity_change(v, a, velocity, lim->amax, J, shape, &change);
    for (i = 0; i < change.count; ++i)
        total += change.d[i];
    if (!is_finite(total) || !(total / Ts + 2 <= sms_plan_max_samples()))
        return 0;
    for (i = 0; i < change.count; ++i) {
        sms_plan_push(plan, Ts, &n, &f, p, vv, aa, change.j[i], change.d[i]);
        advance(&p, &vv, &aa, change.j[i], change.d[i], c3);
    }
    plan->end = plan->arrive = n;
    plan->end_f = plan->arrive_f = f;
    plan->goal = p;
    plan->drift = velocity;
    if (!sms_plan_finite(plan))
        return 0;
    *out = tmp;
    return 1;
}

/* Is sample k at or after the breakpoint (n, f)? A breakpoint within the rounding of its
 * sum (8 ulps of its sample count) of a sample instant is on it, so the sample takes the new
 * segment's values (the right limit) whatever side the rounded sum fell on: v, a, j of its
 * start (none beyond its bound) and q at the sample's own time (sms_plan_eval()). */
static int at_or_after(size_t k, size_t n, sms_real f, sms_real Ts)
{
    sms_real tol;
    if (k != n)
        return k > n;
    tol = (sms_real)PLAN_GRID_TOL * (n > 1u ? (sms_real)n : 1);
    if (tol > (sms_real)0.25)
        tol = (sms_real)0.25;
    return f <= tol * Ts;
}

/* Terms of a half-cosine transition at phase x = pi t/d in [0, pi]: sin x, 1 - cos x,
 * x - sin x and x^2/2 - 1 + cos x, each summed from its leading Taylor term x^n/n! (so each
 * keeps its relative accuracy near x = 0, where the closed forms cancel), without libm.
 * Terms up to x^29/29! (double: pi^30/30! < 4e-18) or x^19/19! (float: pi^20/20! < 4e-9). */
#define PLAN_COSINE_TERMS (sizeof(sms_real) == sizeof(double) ? 29 : 19)

static void cosine_terms(sms_real x, sms_real out[4])
{
    sms_real t = x, s = 0, c1 = 0, s3 = 0, c4 = 0;
    int n;
    for (n = 1; n <= PLAN_COSINE_TERMS; ++n) {
        /* t = x^n / n!; signs: sin +x -x^3/3! ..., 1 - cos +x^2/2 -x^4/4! ...,
         * x - sin +x^3/3! -x^5/5! ..., x^2/2 - 1 + cos +x^4/4! -x^6/6! ... */
        int odd = n & 1, plus = ((n + 1) / 2) & 1; /* n = 1, 2: +; 3, 4: -; 5, 6: + */
        if (odd) {
            s += plus ? t : -t;
            if (n >= 3)
                s3 += plus ? -t : t;
        } else {
            c1 += plus ? t : -t;
            if (n >= 4)
                c4 += plus ? -t : t;
        }
        t *= x / (sms_real)(n + 1);
    }
    out[0] = s;
    out[1] = c1;
    out[2] = s3;
    out[3] = c4;
}

/* Is the breakpoint (n, f) the plan's arrival at its target state (which is landed on
 * exactly, also when snapped onto a sample)? */
static int on_arrival(const sms_plan *plan, size_t n, sms_real f)
{
    return n == plan->arrive && f == plan->arrive_f;
}

void sms_plan_eval(const sms_plan *plan, sms_real Ts, size_t k, sms_real out[4])
{
    size_t i = plan->count;
    sms_real t, d, j;
    /* at or after the end: exactly on the goal, moving on at the drift velocity (0: at rest) */
    if (i == 0 || at_or_after(k, plan->end, plan->end_f, Ts)) {
        out[0] = plan->goal;
        out[1] = plan->drift;
        out[2] = 0;
        out[3] = 0;
        if (plan->drift != 0 &&
            (k > plan->end || sms_plan_arrival_sample(plan, Ts) != k)) {
            /* at the sample's own time, also on an end snapped onto it (t = -end_f): the
             * goal there would be off the drift line by drift end_f, up to 8 eps of the
             * plan's samples, a jump the third difference shows (float: 2 jmax). Where the
             * arrival is snapped onto this sample too, it lands exactly on the goal. */
            t = (sms_real)(k - plan->end) * Ts - plan->end_f;
            out[0] = plan->goal + plan->drift * t;
        }
        return;
    }
    while (i > 1 && !at_or_after(k, plan->n[i - 1], plan->f[i - 1], Ts))
        --i;
    --i;
    /* k >= n[i] here (the first segment starts at sample 0) */
    t = (sms_real)(k - plan->n[i]) * Ts - plan->f[i];
    if (t < 0 && !on_arrival(plan, plan->n[i], plan->f[i])) {
        /* a segment start snapped onto this sample (at most 8 eps of the plan's samples
         * after it, -t): v, a, j are its right limit there, and q its value at the sample's
         * own time, which the previous segment's continues to O(jmax t^3); its start value
         * instead is a jump of v t, which the third difference shows (float: 2 jmax) */
        out[0] = plan->p[i] + t * (plan->v[i] + t * plan->a[i] * (sms_real)0.5);
        out[1] = plan->v[i];
        out[2] = plan->a[i];
        out[3] = plan->shape == SMS_PLAN_COSINE ? 0 : plan->j[i];
        return;
    }
    if (t < 0)
        t = 0; /* the arrival snapped onto this sample: exactly the target state */
    j = plan->j[i];
    d = plan->d[i];
    if (plan->shape == SMS_PLAN_COSINE && j != 0) {
        /* a(t) = a0 + (j d/2)(1 - cos x), x = pi t/d, and its integrals; jerk (pi/2) j sin x */
        sms_real w = d * (sms_real)0.31830988618379067, /* d/pi */
                 x = t < d ? t / w : (sms_real)3.14159265358979323846, half = j * d * (sms_real)0.5,
                 c[4];
        cosine_terms(x, c);
        out[0] = plan->p[i] + t * (plan->v[i] + t * plan->a[i] * (sms_real)0.5) +
                 half * w * w * c[3];
        out[1] = plan->v[i] + t * plan->a[i] + half * w * c[2];
        out[2] = plan->a[i] + half * c[1];
        out[3] = half / w * c[0];
        return;
    }
    out[0] = plan->p[i] + t * (plan->v[i] + t * (plan->a[i] * (sms_real)0.5 +
                                                 t * j * (sms_real)(1.0 / 6.0)));
    out[1] = plan->v[i] + t * (plan->a[i] + t * j * (sms_real)0.5);
    out[2] = plan->a[i] + t * j;
    out[3] = j;
}

size_t sms_plan_arrival_sample(const sms_plan *plan, sms_real Ts)
{
    return at_or_after(plan->arrive, plan->arrive, plan->arrive_f, Ts) ? plan->arrive
                                                                       : plan->arrive + 1u;
}

size_t sms_plan_rest_sample(const sms_plan *plan, sms_real Ts)
{
    if (plan->count == 0)
        return 0;
    return at_or_after(plan->end, plan->end, plan->end_f, Ts) ? plan->end : plan->end + 1u;
}

int sms_plan_extent(const sms_plan *plan, sms_real *lo, sms_real *hi)
{
    sms_real l = plan->goal, h = plan->goal;
    size_t i;
    if (plan->drift != 0 || plan->shape != SMS_PLAN_RAMP)
        return 0;
    for (i = 0; i < plan->count; ++i) {
        const sms_real p = plan->p[i], v = plan->v[i], a = plan->a[i], j = plan->j[i],
                       d = plan->d[i];
        sms_real t[3], x;
        int n = 0, k;
        t[n++] = d;
        if (j != 0) {
            /* v + a t + j t^2/2 = 0 */
            const sms_real disc = a * a - 2 * j * v;
            if (disc >= 0) {
                const sms_real r = sms_plan_sqrt(disc);
                t[n++] = (-a - r) / j;
                t[n++] = (-a + r) / j;
            }
        } else if (a != 0) {
            t[n++] = -v / a;
        }
        if (p < l)
            l = p;
        if (p > h)
            h = p;
        for (k = 0; k < n; ++k) {
            if (!(t[k] > 0) || !(t[k] <= d))
                continue;
            x = p + t[k] * (v + t[k] * (a * (sms_real)0.5 + t[k] * j * (sms_real)(1.0 / 6.0)));
            if (x < l)
                l = x;
            if (x > h)
                h = x;
        }
    }
    *lo = l;
    *hi = h;
    return 1;
}
