/* SPDX-License-Identifier: Apache-2.0 */
/* Plans to a target state and the velocity interface, built from the third-order motions of
 * third_order.c (linear ramps of the acceleration): a motion's pieces become the plan's
 * segments, a motion to a moving target is stretched onto the sample grid (the convex
 * combination of the two farthest motions of that duration), and after the target the plan
 * moves on: the acceleration back to zero at jmax, then the velocity held (plan.h). */
#include "trajectory/plan_target.h"

static sms_real mag(sms_real x) { return x < 0 ? -x : x; }
static int finite(sms_real x) { return x - x == 0; }

#define PT_EPS (sizeof(sms_real) == sizeof(double) ? (sms_real)2.220446049250313e-16 \
                                                   : (sms_real)1.1920929e-7f)

static void advance(sms_real *p, sms_real *v, sms_real *a, sms_real j, sms_real t)
{
    *p += t * (*v + t * (*a * (sms_real)0.5 + t * j * (sms_real)(1.0 / 6.0)));
    *v += t * (*a + t * j * (sms_real)0.5);
    *a += t * j;
}

static void plan_begin(sms_plan *plan)
{
    plan->count = 0;
    plan->shape = SMS_PLAN_RAMP;
    plan->duration = 0;
    plan->drift = 0;
}

/* After the target state (p, v, a), exact: the acceleration back to zero at jmax, then the
 * velocity it leaves held (the drift). Ends the plan. */
static void move_on(sms_plan *plan, sms_real Ts, size_t n, sms_real f, sms_real p, sms_real v,
                    sms_real a, sms_real J)
{
    plan->arrive = n;
    plan->arrive_f = f;
    if (a != 0) {
        sms_real d = mag(a) / J, j = a > 0 ? -J : J;
        sms_plan_push(plan, Ts, &n, &f, p, v, a, j, d);
        advance(&p, &v, &a, j, d); /* a is zero to rounding: v is the drift */
    }
    plan->end = n;
    plan->end_f = f;
    plan->goal = p;
    plan->drift = v;
}

/* The plan is formed when every value is finite and it spans at most the plan's samples. */
static int formed(const sms_plan *plan, sms_real Ts)
{
    return sms_plan_finite(plan) &&
           (sms_real)plan->end + plan->end_f / Ts + 2 <= sms_plan_max_samples();
}

/* The profile's pieces from (q, v, a); then `last` (the target state, exact) or, when NULL,
 * the state the pieces reach with v and a replaced by vend, aend (the velocity interface). */
static int from_profile(sms_plan *out, sms_real Ts, sms_real q, sms_real v, sms_real a,
                        const sms_to_profile *prof, const sms_real *last, sms_real vend,
                        sms_real aend, sms_real J)
{
    sms_plan tmp;
    size_t n = 0;
    sms_real f = 0, p = q;
    int i;
    if (!(prof->duration / Ts + 2 <= sms_plan_max_samples()))
        return 0;
    plan_begin(&tmp);
    for (i = 0; i < prof->count; ++i) {
        a = prof->a[i];
        if (i == prof->cruise)
            v = prof->v_cruise;
        sms_plan_push(&tmp, Ts, &n, &f, p, v, a, prof->j[i], prof->t[i]);
        advance(&p, &v, &a, prof->j[i], prof->t[i]);
    }
    if (last != NULL) {
        p = last[0];
        v = last[1];
        a = last[2];
    } else {
        v = vend;
        a = aend;
    }
    move_on(&tmp, Ts, n, f, p, v, a, J);
    if (!formed(&tmp, Ts))
        return 0;
    *out = tmp;
    return 1;
}

/* State (displacement, v, a) and jerk of a profile from (0, v0, a0) at time t in it. */
static void profile_at(const sms_to_profile *prof, sms_real v0, sms_real a0, sms_real t,
                       sms_real *p, sms_real *v, sms_real *a, sms_real *j)
{
    sms_real begin = 0;
    int i;
    *p = 0;
    *v = v0;
    *a = a0;
    *j = 0;
    for (i = 0; i < prof->count; ++i) {
        *a = prof->a[i];
        if (i == prof->cruise)
            *v = prof->v_cruise;
        *j = prof->j[i];
        if (t < begin + prof->t[i] || i == prof->count - 1) {
            sms_real s = t - begin;
            if (s > prof->t[i])
                s = prof->t[i];
            if (s > 0)
                advance(p, v, a, prof->j[i], s);
            return;
        }
        advance(p, v, a, prof->j[i], prof->t[i]);
        begin += prof->t[i];
    }
}

/* The convex combination lambda A + (1 - lambda) B of two profiles of duration N Ts from
 * (q, v, a), segment by segment on the union of their breakpoints, then the target (exact)
 * on sample N and the plan moving on. */
static int from_blend(sms_plan *out, sms_real Ts, size_t N, sms_real q, sms_real v, sms_real a,
                      const sms_to_profile *A, const sms_to_profile *B, sms_real lambda,
                      const sms_real *last, sms_real J)
{
    sms_real cut[2 * SMS_TO_PIECES + 2], T = (sms_real)N * Ts, f = 0, mu = 1 - lambda;
    sms_plan tmp;
    size_t n = 0;
    int k, m = 0;
    /* the breakpoints of both, merged in order (each list ascends) */
    {
        sms_real ta = 0, tb = 0;
        int ia = 0, ib = 0;
        cut[m++] = 0;
        while (ia < A->count - 1 || ib < B->count - 1) {
            sms_real next_a = ia < A->count - 1 ? ta + A->t[ia] : T * 2;
            sms_real next_b = ib < B->count - 1 ? tb + B->t[ib] : T * 2;
            sms_real next = next_a < next_b ? next_a : next_b;
            if (next_a <= next) {
                ta = next_a;
                ++ia;
            }
            if (next_b <= next) {
                tb = next_b;
                ++ib;
            }
            if (next > cut[m - 1] && next < T)
                cut[m++] = next;
        }
        cut[m++] = T;
    }
    plan_begin(&tmp);
    for (k = 0; k + 1 < m; ++k) {
        sms_real pa, va, aa, ja, pb, vb, ab, jb, mid = (sms_real)0.5 * (cut[k] + cut[k + 1]);
        sms_real vk, ak, jk, dk = cut[k + 1] - cut[k];
        profile_at(A, v, a, cut[k], &pa, &va, &aa, &ja);
        profile_at(B, v, a, cut[k], &pb, &vb, &ab, &jb);
        /* the jerk of the piece each lies in over this interval (its middle) */
        {
            sms_real x0, x1, x2;
            profile_at(A, v, a, mid, &x0, &x1, &x2, &ja);
            profile_at(B, v, a, mid, &x0, &x1, &x2, &jb);
        }
        vk = lambda * va + mu * vb;
        ak = lambda * aa + mu * ab;
        jk = lambda * ja + mu * jb;
        /* The position by integrating the blend, not blending the positions: two motions that
         * end far apart either way (a long minimum duration) travel far, and lambda pa + mu pb
         * would carry the rounding of their distances into every segment's start (in float
         * a step of u vmax T between segments, far above the jerk's floor). */
        sms_plan_push(&tmp, Ts, &n, &f, q, vk, ak, jk, dk);
        q += dk * (vk + dk * (ak * (sms_real)0.5 + dk * jk * (sms_real)(1.0 / 6.0)));
    }
    /* on the grid: the target state exactly on sample N */
    move_on(&tmp, Ts, N, 0, last[0], last[1], last[2], J);
    if (!formed(&tmp, Ts))
        return 0;
    *out = tmp;
    return 1;
}

/* The first whole number of samples at or above T (T within 8 ulps of its count of a sample
 * is on it). */
static int grid_ceil(sms_real T, sms_real Ts, size_t *N)
{
    sms_real x = T / Ts, r;
    if (!(x >= 0) || !(x + 2 <= sms_plan_max_samples()))
        return 0;
    r = (sms_real)(size_t)x;
    if (r > x)
        r -= 1;
    if (x - r > 8 * PT_EPS * (x > 1 ? x : 1))
        r += 1;
    *N = (size_t)r;
    return 1;
}

/* The two motions of N samples from (v, a) to (vf, af) that end farthest either way and
 * their displacements; 0 when a family has no member that long. */
static int extremes(sms_real v, sms_real a, sms_real vf, sms_real af, const sms_to_limits *lim,
                    sms_real T, sms_to_profile *hi, sms_real *dhi, sms_to_profile *lo,
                    sms_real *dlo)
{
    return sms_to_extremal(v, a, vf, af, lim, T, 1, hi, dhi) &&
           sms_to_extremal(v, a, vf, af, lim, T, -1, lo, dlo);
}

int sms_plan_to_state(sms_plan *plan, const sms_to_limits *lim, sms_real Ts, sms_real q,
                      sms_real v, sms_real a, sms_real pf, sms_real vf, sms_real af,
                      sms_real Tmin)
{
    sms_to_profile best, hi, lo;
    sms_real roots[SMS_TO_MAX_ROOTS], last[3], from;
    int n_roots, i;
    last[0] = pf;
    last[1] = vf;
    last[2] = af;
    if (!finite(q) || !finite(v) || !finite(a) || !finite(pf) || !finite(pf - q))
        return 0;
    if (!sms_to_time_optimal(q, v, a, pf, vf, af, lim, &best, roots, &n_roots))
        return 0;
    if (vf == 0 && af == 0 && Tmin <= best.duration)
        return from_profile(plan, Ts, q, v, a, &best, last, 0, 0, lim->jmax);
    /* on the grid: the first whole number of samples at or after the optimum and Tmin at
     * which a motion exists (past a blocked interval: after the next member's duration).
     * Feasibility changes only at the members' durations (roots), so the candidates are
     * max(optimum, Tmin) and every root above it, each rounded up to the grid (and one more
     * sample, in case the rounding put it just inside a blocked interval). */
    from = best.duration > Tmin ? best.duration : Tmin;
    for (i = -1; i < n_roots; ++i) {
        size_t N, extra;
        if (i >= 0 && !(roots[i] > from))
            continue;
        if (!grid_ceil(i < 0 ? from : roots[i], Ts, &N))
            continue;
        for (extra = 0; extra < 2; ++extra) {
            sms_real T = (sms_real)(N + extra) * Ts, dhi, dlo, D = pf - q, tol, lambda;
            if (!extremes(v, a, vf, af, lim, T, &hi, &dhi, &lo, &dlo))
                continue;
            tol = 16 * PT_EPS * (mag(q) + mag(pf) + mag(dhi) + mag(dlo) +
                                 (lim->vmax - lim->vmin) * T);
            if (!(D <= dhi + tol && D >= dlo - tol))
                continue;
            lambda = dhi - dlo > 0 ? (D - dlo) / (dhi - dlo) : 1;
            if (lambda > 1)
                lambda = 1;
            if (!(lambda >= 0))
                lambda = 0;
            if (from_blend(plan, Ts, N + extra, q, v, a, &hi, &lo, lambda, last, lim->jmax))
                return 1;
        }
    }
    /* no grid duration found (not expected): the optimum itself, arriving between samples */
    return from_profile(plan, Ts, q, v, a, &best, last, 0, 0, lim->jmax);
}

/* The velocity change (v, a) -> (w, 0), w = vf - af|af|/(2J) the target's velocity where its
 * acceleration was last zero, a hold at (w, 0) for `hold` seconds, the ramp at J to af: a
 * motion to (vf, af) of any duration from its own without the hold (T1) on. 0 when it has
 * more pieces than a profile holds or no change is found. */
static int plateau(sms_real v, sms_real a, sms_real vf, sms_real af, const sms_to_limits *lim,
                   sms_real hold, sms_to_profile *out)
{
    sms_real J = lim->jmax, w = vf - af * mag(af) / (2 * J);
    if (!sms_to_velocity(v, a, w, 0, lim, out) || out->count + 2 > SMS_TO_PIECES)
        return 0;
    out->j[out->count] = 0;
    out->t[out->count] = hold;
    out->a[out->count] = 0;
    out->cruise = out->count; /* exactly at w */
    out->v_cruise = w;
    ++out->count;
    out->j[out->count] = af > 0 ? J : -J;
    out->t[out->count] = mag(af) / J;
    out->a[out->count] = 0;
    ++out->count;
    out->duration += hold + mag(af) / J;
    return 1;
}

int sms_plan_velocity(sms_plan *plan, const sms_to_limits *lim, sms_real Ts, sms_real q,
                      sms_real v, sms_real a, sms_real vf, sms_real af, sms_real Tmin)
{
    sms_to_profile prof, hi, lo;
    sms_real last[3], T1;
    size_t N, extra;
    if (!finite(q) || !finite(v) || !finite(a))
        return 0;
    if (!sms_to_velocity(v, a, vf, af, lim, &prof))
        return 0;
    if (Tmin <= prof.duration || !grid_ceil(Tmin, Ts, &N))
        return from_profile(plan, Ts, q, v, a, &prof, NULL, vf, af, lim->jmax);
    last[1] = vf;
    last[2] = af;
    /* the position is free: any motion of N samples ending at (vf, af) will do; the midpoint
     * of the farthest two lies between them (the motions of one duration form a convex set,
     * third_order.h) */
    for (extra = 0; extra < 2; ++extra) {
        sms_real T = (sms_real)(N + extra) * Ts, dhi, dlo;
        if (!extremes(v, a, vf, af, lim, T, &hi, &dhi, &lo, &dlo))
            continue;
        last[0] = q + (sms_real)0.5 * (dhi + dlo);
        if (from_blend(plan, Ts, N + extra, q, v, a, &hi, &lo, (sms_real)0.5, last, lim->jmax))
            return 1;
    }
    /* Tmin in a blocked interval (no motion of N samples: the start's acceleration carries it
     * past where the target's ramp could begin): the plateau motion, at the first sample at or
     * after both Tmin and its own shortest duration T1, at which the blocked interval ends */
    if (plateau(v, a, vf, af, lim, 0, &prof)) {
        T1 = prof.duration;
        if (grid_ceil(T1 > Tmin ? T1 : Tmin, Ts, &N) &&
            plateau(v, a, vf, af, lim, (sms_real)N * Ts - T1, &prof)) {
            sms_real p = 0, vv = v, aa = a;
            prof.duration = (sms_real)N * Ts;
            sms_to_integrate(&prof, &p, &vv, &aa);
            last[0] = q + p;
            if (from_blend(plan, Ts, N, q, v, a, &prof, &prof, 1, last, lim->jmax))
                return 1;
        }
    }
    /* not expected: the optimum, arriving early */
    return from_profile(plan, Ts, q, v, a, &prof, NULL, vf, af, lim->jmax);
}
