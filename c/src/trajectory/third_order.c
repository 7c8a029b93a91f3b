/* SPDX-License-Identifier: Apache-2.0 */
/* The time-optimal third-order motion between arbitrary states and the motion of a given
 * duration (third_order.h). Everything is computed in units where jmax = 1 and the
 * acceleration scale A = 1 (time A/J, velocity A^2/J, position A^3/J^2), in sms_real without
 * libm: square roots by sms_plan_sqrt(), polynomial roots by bracketed Newton steps. */
#include <float.h>
#include "trajectory/third_order.h"
#include "trajectory/plan.h"

#ifdef SMS_USE_FLOAT
#define TO_EPS ((sms_real)FLT_EPSILON)
#else
#define TO_EPS ((sms_real)DBL_EPSILON)
#endif

/* Structural tolerance: how far a root may stray past the edge of its case (a hold or a
 * ramp of slightly negative length, a crest slightly over the bound) and still be taken, on
 * the edge. What the motion then misses is checked against TO_FIT below. */
#define TO_SNAP ((sms_real)(sizeof(sms_real) == sizeof(double) ? 1e-9 : 1e-4))
/* The motion built from a root must reach the target to this relative rounding of the path's
 * positions, velocities and accelerations (a jump of that size where it ends). */
#define TO_FIT (16 * TO_EPS)

static sms_real mag(sms_real x) { return x < 0 ? -x : x; }
static sms_real mx(sms_real a, sms_real b) { return a > b ? a : b; }
static sms_real mn(sms_real a, sms_real b) { return a < b ? a : b; }
static int finite(sms_real x) { return x - x == 0; }

/* ------------------------------------------------------------------------------------------ */
/* Real roots of polynomials of degree <= 4 on an interval                                     */
/* ------------------------------------------------------------------------------------------ */

static sms_real poly_eval(const sms_real *c, int n, sms_real x)
{
    sms_real r = c[0];
    int i;
    for (i = 1; i <= n; ++i)
        r = r * x + c[i];
    return r;
}

/* What evaluating the polynomial at x may round: 8 eps sum |c_i x^(n-i)|. */
static sms_real poly_noise(const sms_real *c, int n, sms_real x)
{
    sms_real r = mag(c[0]), ax = mag(x);
    int i;
    for (i = 1; i <= n; ++i)
        r = r * ax + mag(c[i]);
    return 8 * TO_EPS * r;
}

/* The root of c in [lo, hi], where c is monotone and c(lo) (of sign fl) and c(hi) differ
 * in sign: Newton steps kept inside the shrinking bracket (a bisection when one would leave
 * it), until a step is within 4 eps of the root or the bracket is two neighbouring numbers. */
static sms_real poly_bracketed(const sms_real *c, int n, sms_real lo, sms_real hi, sms_real fl)
{
    sms_real d[4], x = (sms_real)0.5 * (lo + hi);
    int i, it;
    for (i = 0; i < n; ++i)
        d[i] = c[i] * (sms_real)(n - i);
    for (it = 0; it < 256; ++it) {
        sms_real f = poly_eval(c, n, x), df, nx, mid;
        if (f == 0)
            return x;
        if ((f < 0) == (fl < 0))
            lo = x;
        else
            hi = x;
        mid = (sms_real)0.5 * (lo + hi);
        if (!(mid > lo && mid < hi))
            return x;
        df = poly_eval(d, n - 1, x);
        nx = df != 0 ? x - f / df : mid;
        if (!(nx > lo && nx < hi))
            nx = mid;
        if (mag(nx - x) <= 4 * TO_EPS * mag(nx))
            return nx;
        x = nx;
    }
    return x;
}

/* The real roots of c[0] x^n + ... + c[n] (n <= 4) in [lo, hi], ascending, into r; returns
 * their count. The critical points (the derivative's roots, recursively) cut [lo, hi] into
 * monotone pieces, each holding at most one root. A point where the polynomial only touches
 * zero (a double root) counts when its value is within the rounding of its evaluation. */
static int poly_roots(const sms_real *c, int n, sms_real lo, sms_real hi, sms_real *r)
{
    sms_real d[4] = {0, 0, 0, 0}, ends[6];
    int i, nc, k = 0, a_root;
    while (n > 0 && c[0] == 0) {
        ++c;
        --n;
    }
    if (n == 0 || !(lo <= hi))
        return 0;
    for (i = 0; i <= n; ++i)
        if (!finite(c[i]))
            return 0;
    if (n == 1) {
        sms_real x = -c[1] / c[0];
        if (x >= lo && x <= hi)
            r[k++] = x;
        return k;
    }
    for (i = 0; i < n; ++i)
        d[i] = c[i] * (sms_real)(n - i);
    nc = poly_roots(d, n - 1, lo, hi, ends + 1);
    ends[0] = lo;
    ends[nc + 1] = hi;
    a_root = mag(poly_eval(c, n, lo)) <= poly_noise(c, n, lo);
    if (a_root)
        r[k++] = lo;
    for (i = 0; i <= nc; ++i) {
        sms_real a = ends[i], b = ends[i + 1], fa = poly_eval(c, n, a), fb = poly_eval(c, n, b);
        int b_root = mag(fb) <= poly_noise(c, n, b);
        if (b_root) {
            if (k == 0 || r[k - 1] != b)
                r[k++] = b;
        } else if (!a_root && (fa < 0) != (fb < 0)) {
            r[k++] = poly_bracketed(c, n, a, b, fa);
        }
        a_root = b_root;
    }
    return k;
}

/* The real roots of c0 t^2 + c1 t + c2 (any finite coefficients), into r; returns the count. */
static int quad_roots(sms_real c0, sms_real c1, sms_real c2, sms_real *r)
{
    sms_real disc, q;
    if (c0 == 0) {
        if (c1 == 0)
            return 0;
        r[0] = -c2 / c1;
        return finite(r[0]);
    }
    disc = c1 * c1 - 4 * c0 * c2;
    if (disc < 0) {
        if (disc < -8 * TO_EPS * (c1 * c1 + mag(4 * c0 * c2)))
            return 0;
        disc = 0;
    }
    q = -(sms_real)0.5 * (c1 + (c1 < 0 ? -sms_plan_sqrt(disc) : sms_plan_sqrt(disc)));
    if (q == 0) {
        r[0] = 0;
        return 1;
    }
    r[0] = q / c0;
    r[1] = c2 / q;
    return finite(r[0]) && finite(r[1]) ? 2 : 0;
}

/* ------------------------------------------------------------------------------------------ */
/* A family in its frame                                                                       */
/* ------------------------------------------------------------------------------------------ */

/* The problem mirrored by s and scaled (jmax = 1). */
typedef struct frame {
    int s;
    sms_real pd, v0, a0, vf, af;
    sms_real Vu, Vl, Au, Al;   /* bounds in the frame: Vl < 0 < Vu, Al < 0 < Au */
    sms_real c0, cf;           /* velocities where the first and the last ramp pass a = 0 */
    sms_real vs;               /* velocity scale of the problem (tolerances) */
} frame;

/* A member: peak x (hold t2), the down ramp to y (cruise t4 at a = 0), hold t6, up to af. */
typedef struct member {
    sms_real x, y, t2, t4, t6;
} member;

typedef struct scaled {
    sms_real pd, v0, a0, vf, af, vmax, vmin, amax, amin;
    sms_real tau, vu, A, J;    /* units: time, velocity, acceleration; the jerk */
} scaled;

static void frame_init(frame *f, int s, const scaled *q)
{
    sms_real sg = (sms_real)s;
    f->s = s;
    f->pd = sg * q->pd;
    f->v0 = sg * q->v0;
    f->a0 = sg * q->a0;
    f->vf = sg * q->vf;
    f->af = sg * q->af;
    f->Vu = s > 0 ? q->vmax : -q->vmin;
    f->Vl = s > 0 ? q->vmin : -q->vmax;
    f->Au = s > 0 ? q->amax : -q->amin;
    f->Al = s > 0 ? q->amin : -q->amax;
    f->c0 = f->v0 - (sms_real)0.5 * f->a0 * f->a0;
    f->cf = f->vf - (sms_real)0.5 * f->af * f->af;
    f->vs = mx(mx(f->Vu, -f->Vl), mx(mag(f->v0), mag(f->vf)));
}

/* The member's pieces in the frame: jerk +-1 or 0, duration, and the acceleration each
 * starts at (exact: a0, x, the crest's 0, y), so a long hold or cruise does not integrate the
 * rounding of the ramp before it. Returns their count; *cruise is the index of the cruise at
 * Vu or -1. */
static int member_pieces(const frame *f, const member *m, sms_real *j, sms_real *t, sms_real *a,
                         int *cruise)
{
    int n = 0;
#define PIECE(jj, tt, aa) do { j[n] = (jj); t[n] = (tt); a[n] = (aa); ++n; } while (0)
    PIECE(1, m->x - f->a0, f->a0);
    PIECE(0, m->t2, m->x);
    *cruise = -1;
    if (m->t4 > 0) {
        PIECE(-1, m->x, m->x);
        *cruise = n;
        PIECE(0, m->t4, 0);
        PIECE(-1, -m->y, 0);
    } else {
        PIECE(-1, m->x - m->y, m->x);
    }
    PIECE(0, m->t6, m->y);
    PIECE(1, f->af - m->y, m->y);
#undef PIECE
    return n;
}

static void advance(sms_real *p, sms_real *v, sms_real *a, sms_real j, sms_real t)
{
    *p += t * (*v + t * (*a * (sms_real)0.5 + t * j * (sms_real)(1.0 / 6.0)));
    *v += t * (*a + t * j * (sms_real)0.5);
    *a += t * j;
}

/* End state of the member from (0, v0, a0), and the sum of |displacement| of its pieces. */
static void member_end(const frame *f, const member *m, sms_real *p, sms_real *v, sms_real *a,
                       sms_real *path)
{
    sms_real j[SMS_TO_PIECES], t[SMS_TO_PIECES], as[SMS_TO_PIECES], before;
    int i, cruise, n = member_pieces(f, m, j, t, as, &cruise);
    *p = 0;
    *v = f->v0;
    *a = f->a0;
    *path = 0;
    for (i = 0; i < n; ++i) {
        before = *p;
        *a = as[i];
        if (i == cruise)
            *v = f->Vu;
        advance(p, v, a, j[i], t[i]);
        *path += mag(*p - before);
    }
}

static sms_real member_position(const frame *f, const member *m)
{
    sms_real p, v, a, path;
    member_end(f, m, &p, &v, &a, &path);
    return p;
}

static sms_real member_duration(const frame *f, const member *m)
{
    return 2 * (m->x - m->y) + f->af - f->a0 + m->t2 + m->t4 + m->t6;
}

/* x (and t2) such that the middle ramp's crest lies at m; y (and t6) likewise. Return 0 when
 * the crest lies below the ramp's own (no such member). A crest within TO_FIT vs of the
 * lowest the ramp can reach (x = max(a0, 0): the acceleration only returns to zero) is on
 * it: a start on the ramp into a cruise, or on the cruise, reaches the bound exactly, but
 * its rounded c0 = v0 - a0^2/2 may lie an ulp above it, and the square root turns that ulp
 * into a gap of about vs u / x in x. */
static int top_for_crest(const frame *f, sms_real crest, sms_real *x, sms_real *t2)
{
    sms_real d = crest - f->c0, b = mx(f->a0, 0);
    if (d < b * b && b * b - d <= TO_FIT * f->vs) {
        *x = b;
        *t2 = 0;
        return 1;
    }
    if (!(d >= 0))
        return 0;
    if (d <= f->Au * f->Au) {
        *x = sms_plan_sqrt(d);
        *t2 = 0;
    } else {
        *x = f->Au;
        *t2 = (d - f->Au * f->Au) / f->Au;
    }
    return 1;
}

static int bottom_for_crest(const frame *f, sms_real crest, sms_real *y, sms_real *t6)
{
    sms_real d = crest - f->cf, b = mx(-f->af, 0);
    if (d < b * b && b * b - d <= TO_FIT * f->vs) {
        *y = -b;
        *t6 = 0;
        return 1;
    }
    if (!(d >= 0))
        return 0;
    if (d <= f->Al * f->Al) {
        *y = -sms_plan_sqrt(d);
        *t6 = 0;
    } else {
        *y = f->Al;
        *t6 = (d - f->Al * f->Al) / -f->Al;
    }
    return 1;
}

/* Bring a member onto its case within the relative tolerance tol: lengths >= 0, x in
 * [a0, Au], y in [Al, af], a hold only on its bound, a crest over Vu onto Vu (the cruise case
 * with no cruise). Returns 0 when it lies farther off. */
static int snap(const frame *f, member *m, sms_real tol)
{
    sms_real ta = tol * mx(f->Au, -f->Al), tt = tol * mx((sms_real)1, f->vs / f->Au);
    if (!finite(m->x) || !finite(m->y) || !finite(m->t2) || !finite(m->t4) || !finite(m->t6))
        return 0;
    if (m->x < f->a0 - ta || m->x > f->Au + ta || m->y > f->af + ta || m->y < f->Al - ta ||
        m->x < m->y - ta)
        return 0;
    if (m->t2 < -tt || m->t4 < -tt || m->t6 < -tt)
        return 0;
    if ((m->t2 > tt && m->x < f->Au - ta) || (m->t6 > tt && m->y > f->Al + ta))
        return 0;
    if (m->t4 > tt && !(m->x > -ta && m->y < ta))
        return 0;
    m->x = mn(mx(m->x, f->a0), f->Au);
    m->y = mx(mn(m->y, f->af), f->Al);
    if (m->x < m->y)
        m->x = m->y = (sms_real)0.5 * (m->x + m->y);
    m->t2 = mx(m->t2, 0);
    m->t4 = mx(m->t4, 0);
    m->t6 = mx(m->t6, 0);
    if (m->x > 0 && m->y < 0) {
        sms_real crest = f->c0 + m->x * m->x + f->Au * m->t2;
        if (crest > f->Vu + tol * f->vs)
            return 0;
        if (crest > f->Vu) {
            /* on the edge of the cruise: the member whose crest is the bound */
            sms_real t4 = m->t4;
            if (!top_for_crest(f, f->Vu, &m->x, &m->t2) ||
                !bottom_for_crest(f, f->Vu, &m->y, &m->t6))
                return 0;
            m->x = mx(m->x, f->a0);
            m->y = mn(m->y, f->af);
            m->t4 = t4;
        }
    }
    return 1;
}

/* Does the snapped member reach (pd, vf, af) to the rounding of its path? A position moves
 * by v times the rounding of the time it is reached at, so the scale of a position is the
 * path plus the velocity scale times the duration. */
static int fits(const frame *f, const member *m, sms_real pd)
{
    sms_real p, v, a, path;
    member_end(f, m, &p, &v, &a, &path);
    path += f->vs * member_duration(f, m) + mag(pd);
    return mag(p - pd) <= TO_FIT * path &&
           mag(v - f->vf) <= TO_FIT * (f->vs + mx(f->Au, -f->Al) * (f->Au - f->Al)) &&
           mag(a - f->af) <= TO_FIT * mx(f->Au, -f->Al);
}

/* ------------------------------------------------------------------------------------------ */
/* Step 1: every member that reaches the target                                                */
/* ------------------------------------------------------------------------------------------ */

typedef struct found {
    int n;
    int s[SMS_TO_MAX_ROOTS];
    member m[SMS_TO_MAX_ROOTS];
    sms_real T[SMS_TO_MAX_ROOTS];
} found;

static void keep(found *out, const frame *f, member m)
{
    if (out->n >= SMS_TO_MAX_ROOTS || !snap(f, &m, TO_SNAP) || !fits(f, &m, f->pd))
        return;
    out->s[out->n] = f->s;
    out->m[out->n] = m;
    out->T[out->n] = member_duration(f, &m);
    ++out->n;
}

/* One Newton step on the true position (not the expanded polynomial), slope from the
 * polynomial: the polynomial is the position residual times `factor`. */
static sms_real polish(const frame *f, member (*build)(const frame *, sms_real), sms_real z,
                       const sms_real *c, sms_real factor)
{
    sms_real d[4], slope, e, nz;
    member m = build(f, z);
    int i;
    for (i = 0; i < 4; ++i)
        d[i] = c[i] * (sms_real)(4 - i);
    slope = poly_eval(d, 3, z);
    e = member_position(f, &m) - f->pd;
    if (slope == 0 || e == 0)
        return z;
    nz = z - e * factor / slope;
    m = build(f, nz);
    if (finite(nz) && mag(member_position(f, &m) - f->pd) < mag(e))
        return nz;
    return z;
}

static member build_none(const frame *f, sms_real u)
{
    member m;
    sms_real K = f->cf - f->c0;
    m.x = (sms_real)0.5 * (u + K / u);
    m.y = (sms_real)0.5 * (K / u - u);
    m.t2 = m.t4 = m.t6 = 0;
    return m;
}

static member build_acc0(const frame *f, sms_real y)
{
    member m;
    m.x = f->Au;
    m.y = y;
    m.t2 = (f->cf - f->c0 + y * y - f->Au * f->Au) / f->Au;
    m.t4 = m.t6 = 0;
    return m;
}

static member build_acc1(const frame *f, sms_real x)
{
    member m;
    m.x = x;
    m.y = f->Al;
    m.t2 = m.t4 = 0;
    m.t6 = (f->c0 + x * x - f->cf - f->Al * f->Al) / -f->Al;
    return m;
}

static void step1_vel(const frame *f, found *out)
{
    member m;
    sms_real D;
    if (!top_for_crest(f, f->Vu, &m.x, &m.t2) || !bottom_for_crest(f, f->Vu, &m.y, &m.t6))
        return;
    m.t4 = 0;
    D = member_position(f, &m);
    m.t4 = (f->pd - D) / f->Vu;
    if (m.t4 >= 0)
        keep(out, f, m);
}

static void step1_none(const frame *f, found *out)
{
    const sms_real v0 = f->v0, a0 = f->a0, vf = f->vf, af = f->af, K = f->cf - f->c0;
    sms_real c[5], r[4];
    int i, n;
    c[0] = 1;
    c[1] = 0;
    c[2] = 2 * (2 * (v0 + vf) - a0 * a0 - af * af);
    c[3] = -(sms_real)(4.0 / 3.0) * (a0 * (3 * v0 - a0 * a0) - af * (3 * vf - af * af) + 3 * f->pd);
    c[4] = -K * K;
    n = poly_roots(c, 4, 0, f->Au - f->Al, r);
    for (i = 0; i < n; ++i) {
        sms_real u = r[i];
        if (!(u > 0))
            continue;
        u = polish(f, build_none, u, c, 4 * u);
        keep(out, f, build_none(f, u));
    }
}

static void step1_acc0(const frame *f, found *out)
{
    const sms_real v0 = f->v0, a0 = f->a0, vf = f->vf, af = f->af, Au = f->Au, pd = f->pd;
    sms_real c[5], r[4];
    int i, n;
    c[0] = 1;
    c[1] = -2 * Au;
    c[2] = Au * Au - af * af + 2 * vf;
    c[3] = 2 * Au * (af * af - 2 * vf);
    c[4] = Au * (Au * (vf - af * af * (sms_real)0.5) + af * (2 * vf - af * af * (sms_real)(2.0 / 3.0)) -
                 2 * pd) +
           a0 * a0 * (a0 * (Au * (sms_real)(2.0 / 3.0) - a0 * (sms_real)0.25) - Au * Au * (sms_real)0.5) +
           af * af * (af * af * (sms_real)0.25 - vf) + v0 * (Au * Au + a0 * (a0 - 2 * Au) - v0) +
           vf * vf;
    n = poly_roots(c, 4, f->Al, mn(af, Au), r);
    for (i = 0; i < n; ++i)
        keep(out, f, build_acc0(f, polish(f, build_acc0, r[i], c, 2 * Au)));
}

static void step1_acc1(const frame *f, found *out)
{
    const sms_real v0 = f->v0, a0 = f->a0, vf = f->vf, af = f->af, Al = f->Al, pd = f->pd;
    sms_real c[5], r[4];
    int i, n;
    c[0] = 1;
    c[1] = -2 * Al;
    c[2] = Al * Al - a0 * a0 + 2 * v0;
    c[3] = -2 * Al * (2 * v0 - a0 * a0);
    c[4] = Al * (Al * (vf - af * af * (sms_real)0.5) + af * (af * af * (sms_real)(2.0 / 3.0) - 2 * vf) +
                 2 * pd) +
           a0 * a0 * (a0 * (a0 * (sms_real)0.25 - Al * (sms_real)(2.0 / 3.0)) - Al * Al * (sms_real)0.5) +
           af * af * (vf - af * af * (sms_real)0.25) + v0 * (Al * Al + a0 * (2 * Al - a0) + v0) -
           vf * vf;
    n = poly_roots(c, 4, mx(a0, f->Al), f->Au, r);
    for (i = 0; i < n; ++i)
        keep(out, f, build_acc1(f, polish(f, build_acc1, r[i], c, -2 * f->Al)));
}

/* Both holds: t6 follows t2 linearly (the crest), the position is quadratic in t2: fitted
 * through three evaluations (exact but for rounding), each root then one Newton step on the
 * position itself. */
static member build_acc01(const frame *f, sms_real t2)
{
    member m;
    m.x = f->Au;
    m.y = f->Al;
    m.t2 = t2;
    m.t4 = 0;
    m.t6 = (f->c0 + f->Au * f->Au - f->cf - f->Al * f->Al + f->Au * t2) / -f->Al;
    return m;
}

static void step1_acc01(const frame *f, found *out)
{
    sms_real base = (f->c0 + f->Au * f->Au - f->cf - f->Al * f->Al) / f->Au, r[2], e0, e1, e2, h;
    sms_real c0, c1;
    member m;
    int i, n;
    /* t2 >= max(0, -base) keeps t6 >= 0; the fit spans the scale of the roots */
    h = mx(mx(mag(base), (sms_real)1), sms_plan_sqrt(mag(f->pd) / f->Au));
    m = build_acc01(f, 0);
    e0 = member_position(f, &m) - f->pd;
    m = build_acc01(f, h);
    e1 = member_position(f, &m) - f->pd;
    m = build_acc01(f, 2 * h);
    e2 = member_position(f, &m) - f->pd;
    c0 = (e2 - 2 * e1 + e0) / (2 * h * h);
    c1 = (4 * e1 - 3 * e0 - e2) / (2 * h);
    n = quad_roots(c0, c1, e0, r);
    for (i = 0; i < n; ++i) {
        sms_real t2 = r[i], e, slope = 2 * c0 * r[i] + c1;
        m = build_acc01(f, t2);
        e = member_position(f, &m) - f->pd;
        if (slope != 0) {
            member m2 = build_acc01(f, t2 - e / slope);
            if (mag(member_position(f, &m2) - f->pd) < mag(e))
                m = m2;
        }
        keep(out, f, m);
    }
}

/* One ramp of +J from a0 to af reaches the target (the end states lie on one ramp). */
static void step1_ramp(const frame *f, found *out)
{
    member m;
    if (!(f->af >= f->a0))
        return;
    m.x = m.y = f->af;
    m.t2 = m.t4 = m.t6 = 0;
    keep(out, f, m);
}

static void to_profile(const frame *f, const member *m, const scaled *q, sms_to_profile *out)
{
    sms_real j[SMS_TO_PIECES], t[SMS_TO_PIECES], a[SMS_TO_PIECES], sg = (sms_real)f->s;
    int i, cruise, n = member_pieces(f, m, j, t, a, &cruise), k = 0;
    out->duration = 0;
    out->cruise = -1;
    out->v_cruise = 0;
    for (i = 0; i < n; ++i) {
        if (!(t[i] > 0))
            continue;
        if (i == cruise) {
            out->cruise = k;
            out->v_cruise = sg * f->Vu * q->vu;
        }
        out->j[k] = sg * j[i] * q->J;
        out->t[k] = t[i] * q->tau;
        out->a[k] = sg * a[i] * q->A;
        out->duration += out->t[k];
        ++k;
    }
    out->count = k;
}

/* Scale the problem: A the smallest acceleration bound, capped where no motion within the
 * velocity bounds can reach it (a^2/J <= vmax - vmin), so its square stays finite. */
static int scale(scaled *q, sms_real pd, sms_real v0, sms_real a0, sms_real vf, sms_real af,
                 const sms_to_limits *lim)
{
    sms_real J = lim->jmax, cap = sms_plan_sqrt(J * (lim->vmax - lim->vmin)), A;
    A = mn(mn(lim->amax, -lim->amin), cap);
    if (!(A > 0) || !finite(A) || !(J > 0))
        return 0;
    q->A = A;
    q->J = J;
    q->tau = A / J;
    q->vu = A * q->tau;
    q->pd = pd / q->vu / q->tau; /* in turn: A^3/J^2 alone may underflow a float */
    q->v0 = v0 / q->vu;
    q->vf = vf / q->vu;
    q->a0 = a0 / A;
    q->af = af / A;
    q->vmax = lim->vmax / q->vu;
    q->vmin = lim->vmin / q->vu;
    q->amax = mn(lim->amax, 2 * cap) / A;
    q->amin = mx(lim->amin, -2 * cap) / A;
    return finite(q->pd) && finite(q->v0) && finite(q->vf) && finite(q->vmax) &&
           finite(q->vmin) && q->vmax > 0 && q->vmin < 0;
}

void sms_to_integrate(const sms_to_profile *prof, sms_real *p, sms_real *v, sms_real *a)
{
    int i;
    for (i = 0; i < prof->count; ++i) {
        *a = prof->a[i];
        if (i == prof->cruise)
            *v = prof->v_cruise;
        advance(p, v, a, prof->j[i], prof->t[i]);
    }
}

/* Do the pieces take (p0, v0, a0) to (pf, vf, af), to the rounding of the path's positions
 * (plus the velocity range times the duration: a time's rounding moves a position by v
 * times it), of the velocity range and of the acceleration range? */
static int reaches(const sms_to_profile *prof, sms_real p0, sms_real v0, sms_real a0,
                   sms_real pf, sms_real vf, sms_real af, const sms_to_limits *lim)
{
    sms_real p = p0, v = v0, a = a0, path = mag(p0) + mag(pf), before, tol = 64 * TO_EPS;
    sms_real vr = lim->vmax - lim->vmin, ar = lim->amax - lim->amin;
    int i;
    for (i = 0; i < prof->count; ++i) {
        before = p;
        a = prof->a[i];
        if (i == prof->cruise)
            v = prof->v_cruise;
        advance(&p, &v, &a, prof->j[i], prof->t[i]);
        path += mag(p - before);
    }
    path += vr * prof->duration;
    return mag(p - pf) <= tol * path && mag(v - vf) <= tol * (vr + mag(v0) + mag(vf)) &&
           mag(a - af) <= tol * ar;
}

int sms_to_time_optimal(sms_real p0, sms_real v0, sms_real a0, sms_real pf, sms_real vf,
                        sms_real af, const sms_to_limits *lim, sms_to_profile *best,
                        sms_real *roots, int *n_roots)
{
    scaled q;
    found all;
    int i, b = -1;
    all.n = 0;
    if (n_roots != NULL)
        *n_roots = 0;
    if (pf - p0 == 0 && v0 == vf && a0 == af) {
        best->count = 0;
        best->duration = 0;
        best->cruise = -1;
        best->v_cruise = 0;
        if (roots != NULL && n_roots != NULL) {
            roots[0] = 0;
            *n_roots = 1;
        }
        return 1;
    }
    if (!scale(&q, pf - p0, v0, a0, vf, af, lim))
        return 0;
    {
        /* A target at rest has a single member reaching it (no blocked durations: measured
         * on 5,000 random states, and ruckig relies on it too), so the search stops at the
         * first member that reaches it, the frame of the displacement's sign first. A moving
         * target needs every member: between their durations lie the blocked ones. */
        typedef void (*case_fn)(const frame *, found *);
        static const case_fn cases[6] = {step1_vel, step1_none, step1_acc0, step1_acc1,
                                         step1_acc01, step1_ramp};
        const int rest = vf == 0 && af == 0;
        int order, k;
        for (order = 0; order < 2; ++order) {
            frame f;
            frame_init(&f, (q.pd >= 0) == (order == 0) ? 1 : -1, &q);
            for (k = 0; k < 6; ++k) {
                cases[k](&f, &all);
                if (rest && all.n > 0)
                    break;
            }
            if (rest && all.n > 0)
                break;
        }
    }
    /* the shortest member whose pieces reach the target in the problem's own units (the
     * scaling is checked, not trusted: a unit that underflows would pass the scaled test) */
    for (;;) {
        frame f;
        b = -1;
        for (i = 0; i < all.n; ++i)
            if (all.T[i] >= 0 && (b < 0 || all.T[i] < all.T[b]))
                b = i;
        if (b < 0)
            return 0;
        frame_init(&f, all.s[b], &q);
        to_profile(&f, &all.m[b], &q, best);
        if (reaches(best, p0, v0, a0, pf, vf, af, lim))
            break;
        all.T[b] = -1; /* not this one */
    }
    if (roots != NULL && n_roots != NULL) {
        /* ascending durations, in seconds */
        int k, n = 0;
        for (i = 0; i < all.n; ++i) {
            sms_real T = all.T[i] * q.tau;
            if (all.T[i] < 0)
                continue;
            for (k = n; k > 0 && roots[k - 1] > T; --k)
                roots[k] = roots[k - 1];
            roots[k] = T;
            ++n;
        }
        *n_roots = n;
    }
    return 1;
}

/* ------------------------------------------------------------------------------------------ */
/* Step 2: the member of a given duration that ends farthest                                   */
/* ------------------------------------------------------------------------------------------ */

typedef struct farthest {
    int ok;
    member m;
    sms_real p;
} farthest;

static void consider(farthest *best, const frame *f, member m, sms_real T)
{
    sms_real p, v, a, path;
    /* only rounding's worth of snapping: the duration must stay T */
    if (!snap(f, &m, TO_FIT) || mag(member_duration(f, &m) - T) > TO_FIT * mx(T, (sms_real)1))
        return;
    member_end(f, &m, &p, &v, &a, &path);
    if (mag(v - f->vf) > TO_FIT * (f->vs + mx(f->Au, -f->Al) * (f->Au - f->Al)) ||
        mag(a - f->af) > TO_FIT * mx(f->Au, -f->Al))
        return;
    if (!best->ok || p > best->p) {
        best->ok = 1;
        best->m = m;
        best->p = p;
    }
}

static void farthest_of(const frame *f, sms_real T, farthest *best)
{
    const sms_real v0 = f->v0, a0 = f->a0, vf = f->vf, af = f->af, Au = f->Au, Al = f->Al;
    sms_real u = (sms_real)0.5 * (T - (af - a0)), d, C;
    member m;
    best->ok = 0;
    if (u > 0)
        consider(best, f, build_none(f, u), T);
    /* hold at Au: y^2 - 2 Au y + C = 0, the root below Au */
    C = -(sms_real)0.5 * (-2 * Au * Au + 2 * Au * T + 2 * Au * (a0 - af) + 2 * (v0 - vf) - a0 * a0 +
                          af * af);
    d = Au * Au - C;
    if (d >= 0)
        consider(best, f, build_acc0(f, Au - sms_plan_sqrt(d)), T);
    /* hold at Al: x^2 - 2 Al x + C = 0, the root above Al */
    C = (sms_real)0.5 * (2 * Al * Al + 2 * Al * T + 2 * Al * (a0 - af) + 2 * (v0 - vf) - a0 * a0 +
                         af * af);
    d = Al * Al - C;
    if (d >= 0)
        consider(best, f, build_acc1(f, Al + sms_plan_sqrt(d)), T);
    /* both holds: t2 + t6 = S, Au t2 + Al t6 = R */
    {
        sms_real S = T - (2 * Au - 2 * Al + af - a0);
        sms_real R = f->cf - f->c0 + Al * Al - Au * Au;
        m.x = Au;
        m.y = Al;
        m.t4 = 0;
        m.t2 = (R - Al * S) / (Au - Al);
        m.t6 = S - m.t2;
        if (S >= 0)
            consider(best, f, m, T);
    }
    /* the cruise at Vu */
    if (top_for_crest(f, f->Vu, &m.x, &m.t2) && bottom_for_crest(f, f->Vu, &m.y, &m.t6)) {
        m.t4 = 0;
        m.t4 = T - member_duration(f, &m);
        if (m.t4 >= 0)
            consider(best, f, m, T);
    }
}

int sms_to_extremal(sms_real v0, sms_real a0, sms_real vf, sms_real af, const sms_to_limits *lim,
                    sms_real T, int s, sms_to_profile *out, sms_real *displacement)
{
    scaled q;
    frame f;
    farthest best;
    if (!scale(&q, 0, v0, a0, vf, af, lim) || !(T >= 0) || !finite(T))
        return 0;
    if (T == 0) {
        if (v0 != vf || a0 != af)
            return 0;
        out->count = 0;
        out->duration = 0;
        out->cruise = -1;
        out->v_cruise = 0;
        *displacement = 0;
        return 1;
    }
    frame_init(&f, s, &q);
    farthest_of(&f, T / q.tau, &best);
    if (!best.ok)
        return 0;
    to_profile(&f, &best.m, &q, out);
    {
        /* the end velocity and acceleration in the problem's own units (as for step 1) */
        sms_real p = 0, v = v0, a = a0, vr = lim->vmax - lim->vmin;
        sms_to_integrate(out, &p, &v, &a);
        if (!(mag(v - vf) <= 64 * TO_EPS * (vr + mag(v0) + mag(vf))) ||
            !(mag(a - af) <= 64 * TO_EPS * (lim->amax - lim->amin)))
            return 0;
    }
    *displacement = (sms_real)s * best.p * q.vu * q.tau; /* in turn, as in scale() */
    return 1;
}

/* ------------------------------------------------------------------------------------------ */
/* The velocity interface                                                                      */
/* ------------------------------------------------------------------------------------------ */

int sms_to_velocity(sms_real v0, sms_real a0, sms_real vf, sms_real af, const sms_to_limits *lim,
                    sms_to_profile *out)
{
    scaled q;
    sms_real bestT = 0;
    int s, ok = 0;
    if (!scale(&q, 0, v0, a0, vf, af, lim))
        return 0;
    for (s = 1; s >= -1; s -= 2) {
        sms_real sg = (sms_real)s, A = s > 0 ? q.amax : -q.amin;
        sms_real b0 = sg * q.a0, bf = sg * q.af, dv = sg * (q.vf - q.v0);
        sms_real x2 = dv + (sms_real)0.5 * (b0 * b0 + bf * bf), x, t2 = 0, T, lo = mx(b0, bf);
        sms_real ta = TO_SNAP * A;
        if (!(x2 >= 0))
            continue;
        x = sms_plan_sqrt(x2);
        if (x > A) {
            x = A;
            t2 = (dv - (A * A - (sms_real)0.5 * (b0 * b0 + bf * bf))) / A;
        }
        if (x < lo - ta || t2 < -TO_SNAP * mx((sms_real)1, mag(dv) / A))
            continue;
        x = mx(x, lo);
        t2 = mx(t2, 0);
        T = 2 * x - b0 - bf + t2;
        if (!ok || T < bestT) {
            int k = 0;
            sms_real jj[3], tt[3];
            sms_real aa[3];
            jj[0] = sg;
            tt[0] = x - b0;
            aa[0] = b0;
            jj[1] = 0;
            tt[1] = t2;
            aa[1] = x;
            jj[2] = -sg;
            tt[2] = x - bf;
            aa[2] = x;
            out->duration = 0;
            out->count = 0;
            out->cruise = -1;
            out->v_cruise = 0;
            for (k = 0; k < 3; ++k)
                if (tt[k] > 0) {
                    out->j[out->count] = jj[k] * q.J;
                    out->t[out->count] = tt[k] * q.tau;
                    out->a[out->count] = sg * aa[k] * q.A;
                    out->duration += out->t[out->count];
                    ++out->count;
                }
            bestT = T;
            ok = 1;
        }
    }
    return ok;
}
