/* The time-optimal single-axis plan (plan.h). Every operation is in sms_real. */
#include "plan.h"

sms_real sms_plan_sqrt(sms_real x)
{
    sms_real scale = 1, y;
    int i;
    if (!(x > 0))
        return 0;
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

/* Up to three constant-jerk pieces. */
typedef struct pieces {
    int count;
    sms_real d[3], j[3];
} pieces;

/* Time-optimal change of (v0, a0) to (v1, 0) within amax, jmax (a0 within amax and the
 * change possible without passing the velocity bound: the caller's precondition). */
static void velocity_change(sms_real v0, sms_real a0, sms_real v1, sms_real A, sms_real J,
                            pieces *out)
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

/* Advance (p, v, a) by d seconds at jerk j. */
static void advance(sms_real *p, sms_real *v, sms_real *a, sms_real j, sms_real d)
{
    *p += d * (*v + d * (*a * (sms_real)0.5 + d * j * (sms_real)(1.0 / 6.0)));
    *v += d * (*a + d * j * (sms_real)0.5);
    *a += d * j;
}

/* Distance of the velocity change to vp plus the stop from vp, and the two piece lists. */
static sms_real distance(sms_real v0, sms_real a0, sms_real vp, const sms_plan_limits *lim,
                         pieces *first, pieces *stop)
{
    sms_real p = 0, v = v0, a = a0;
    int i;
    velocity_change(v0, a0, vp, lim->amax, lim->jmax, first);
    velocity_change(vp, 0, 0, lim->amax, lim->jmax, stop);
    for (i = 0; i < first->count; ++i)
        advance(&p, &v, &a, first->j[i], first->d[i]);
    v = vp;
    a = 0;
    for (i = 0; i < stop->count; ++i)
        advance(&p, &v, &a, stop->j[i], stop->d[i]);
    return p;
}

/* Add a segment starting at time (n, f) and move (n, f) to its end. */
static void push(sms_plan *plan, sms_real Ts, size_t *n, sms_real *f, sms_real p, sms_real v,
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

void sms_plan_to_rest(sms_plan *plan, const sms_plan_limits *lim, sms_real Ts, sms_real q,
                      sms_real v, sms_real a, sms_real goal)
{
    sms_real D = goal - q, vp, cruise = 0, V = lim->vmax, p, vv, aa, f = 0;
    pieces first, stop;
    size_t n = 0;
    int i;
    plan->count = 0;
    plan->goal = goal;
    plan->duration = 0;
    if (D == 0 && v == 0 && a == 0) {
        plan->end = 0;
        plan->end_f = 0;
        return;
    }
    if (D >= distance(v, a, V, lim, &first, &stop)) {
        vp = V;
        cruise = (D - distance(v, a, V, lim, &first, &stop)) / V;
    } else if (D <= distance(v, a, -V, lim, &first, &stop)) {
        vp = -V;
        cruise = (D - distance(v, a, -V, lim, &first, &stop)) / -V;
    } else {
        /* distance increases with vp: bisection to the last bit */
        sms_real lo = -V, hi = V;
        int it;
        for (it = 0; it < 200; ++it) {
            sms_real mid = (sms_real)0.5 * (lo + hi);
            if (!(mid > lo && mid < hi))
                break;
            if (distance(v, a, mid, lim, &first, &stop) < D)
                lo = mid;
            else
                hi = mid;
        }
        vp = (sms_real)0.5 * (lo + hi);
        (void)distance(v, a, vp, lim, &first, &stop);
    }
    if (cruise < 0)
        cruise = 0;
    /* the velocity change from the current state */
    p = q;
    vv = v;
    aa = a;
    for (i = 0; i < first.count; ++i) {
        push(plan, Ts, &n, &f, p, vv, aa, first.j[i], first.d[i]);
        advance(&p, &vv, &aa, first.j[i], first.d[i]);
    }
    /* the stop, anchored on the goal: it starts where its own distance before the goal is */
    {
        sms_real ps = 0, vs = vp, as = 0;
        for (i = 0; i < stop.count; ++i)
            advance(&ps, &vs, &as, stop.j[i], stop.d[i]);
        if (cruise > 0)
            push(plan, Ts, &n, &f, p, vp, 0, 0, cruise);
        p = goal - ps;
        vv = vp;
        aa = 0;
        for (i = 0; i < stop.count; ++i) {
            push(plan, Ts, &n, &f, p, vv, aa, stop.j[i], stop.d[i]);
            advance(&p, &vv, &aa, stop.j[i], stop.d[i]);
        }
    }
    plan->end = n;
    plan->end_f = f;
}

/* Is sample k at or after the breakpoint (n, f)? A breakpoint within the rounding of its
 * sum (8 ulps of its sample count) of a sample instant is on it, so the sample takes the new
 * segment's values (the right limit) whatever side the rounded sum fell on; the new segment
 * is then evaluated at its start (t clamped to 0: q off by at most v times that rounding,
 * v and a exact, none beyond its bound). */
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

void sms_plan_eval(const sms_plan *plan, sms_real Ts, size_t k, sms_real out[4])
{
    size_t i = plan->count;
    sms_real t;
    /* at or after the end: exactly at rest on the goal */
    if (i == 0 || at_or_after(k, plan->end, plan->end_f, Ts)) {
        out[0] = plan->goal;
        out[1] = 0;
        out[2] = 0;
        out[3] = 0;
        return;
    }
    while (i > 1 && !at_or_after(k, plan->n[i - 1], plan->f[i - 1], Ts))
        --i;
    --i;
    /* k >= n[i] here (the first segment starts at sample 0) */
    t = (sms_real)(k - plan->n[i]) * Ts - plan->f[i];
    if (t < 0)
        t = 0;
    out[0] = plan->p[i] + t * (plan->v[i] + t * (plan->a[i] * (sms_real)0.5 +
                                                 t * plan->j[i] * (sms_real)(1.0 / 6.0)));
    out[1] = plan->v[i] + t * (plan->a[i] + t * plan->j[i] * (sms_real)0.5);
    out[2] = plan->a[i] + t * plan->j[i];
    out[3] = plan->j[i];
}
