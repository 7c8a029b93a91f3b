/* SPDX-License-Identifier: Apache-2.0 */
/* Double-double arithmetic (core/double_double.h): init-time designs only, libm allowed. */
#include <math.h>
#include "core/double_double.h"

/* pi and ln 2 to 107 bits */
static const sms_dd dd_pi = { 3.141592653589793116e+00, 1.2246467991473532072e-16 };
static const sms_dd dd_ln2 = { 6.931471805599452862e-01, 2.3190468138462995584e-17 };

/* Stop a series once its term is below this fraction of the sum (2^-110). */
#define DD_SERIES_EPS 7.7037197775489434e-34

static int is_finite(double a)
{
    return a - a == 0.0;
}

/* Knuth's TwoSum: s + e = a + b exactly. */
static sms_dd two_sum(double a, double b)
{
    sms_dd r;
    double bb;
    r.hi = a + b;
    if (!is_finite(r.hi)) {
        r.lo = 0.0;
        return r;
    }
    bb = r.hi - a;
    r.lo = (a - (r.hi - bb)) + (b - bb);
    return r;
}

/* s + e = a + b exactly when |a| >= |b| (or a = 0). */
static sms_dd fast_two_sum(double a, double b)
{
    sms_dd r;
    r.hi = a + b;
    r.lo = is_finite(r.hi) ? b - (r.hi - a) : 0.0;
    return r;
}

/* TwoProduct: p + e = a b exactly (one fma), unless it under- or overflows. */
static sms_dd two_prod(double a, double b)
{
    sms_dd r;
    r.hi = a * b;
    r.lo = is_finite(r.hi) ? fma(a, b, -r.hi) : 0.0;
    return r;
}

sms_dd sms_dd_of(double a)
{
    sms_dd r;
    r.hi = a;
    r.lo = 0.0;
    return r;
}

sms_dd sms_dd_add(sms_dd a, sms_dd b)
{
    sms_dd s = two_sum(a.hi, b.hi), t = two_sum(a.lo, b.lo);
    s.lo += t.hi;
    s = fast_two_sum(s.hi, s.lo);
    s.lo += t.lo;
    return fast_two_sum(s.hi, s.lo);
}

sms_dd sms_dd_neg(sms_dd a)
{
    a.hi = -a.hi;
    a.lo = -a.lo;
    return a;
}

sms_dd sms_dd_sub(sms_dd a, sms_dd b)
{
    return sms_dd_add(a, sms_dd_neg(b));
}

sms_dd sms_dd_mul(sms_dd a, sms_dd b)
{
    sms_dd p = two_prod(a.hi, b.hi);
    p.lo += a.hi * b.lo + a.lo * b.hi;
    return fast_two_sum(p.hi, p.lo);
}

sms_dd sms_dd_div(sms_dd a, sms_dd b)
{
    /* three quotient digits, each from the remainder so far */
    const double q1 = a.hi / b.hi;
    sms_dd r, q;
    double q2, q3;
    if (!is_finite(q1))
        return sms_dd_of(q1);
    r = sms_dd_sub(a, sms_dd_mul(b, sms_dd_of(q1)));
    q2 = r.hi / b.hi;
    r = sms_dd_sub(r, sms_dd_mul(b, sms_dd_of(q2)));
    q3 = r.hi / b.hi;
    q = fast_two_sum(q1, q2);
    return sms_dd_add(q, sms_dd_of(q3));
}

sms_dd sms_dd_scale(sms_dd a, int e)
{
    a.hi = ldexp(a.hi, e);
    a.lo = ldexp(a.lo, e);
    return a;
}

/* e^r - 1 for |r| <= 0.35 or so: the Taylor series of r / 2^10 (9 terms reach 2^-110), then
 * ten doublings e^{2y} - 1 = (e^y - 1)(2 + e^y - 1), which keep the relative accuracy. */
static sms_dd expm1_reduced(sms_dd r)
{
    const sms_dd y = sms_dd_scale(r, -10);
    sms_dd sum = y, term = y;
    int n;
    for (n = 2; n < 40; ++n) {
        term = sms_dd_div(sms_dd_mul(term, y), sms_dd_of((double)n));
        sum = sms_dd_add(sum, term);
        if (!(fabs(term.hi) > DD_SERIES_EPS * fabs(sum.hi)))
            break;
    }
    for (n = 0; n < 10; ++n)
        sum = sms_dd_add(sms_dd_scale(sum, 1), sms_dd_mul(sum, sum));
    return sum;
}

sms_dd sms_dd_exp(sms_dd x)
{
    double k;
    sms_dd r;
    if (x.hi != x.hi)
        return x;
    if (x.hi < -745.2)
        return sms_dd_of(0.0);
    if (x.hi > 709.0)
        return sms_dd_of(HUGE_VAL);
    /* x = k ln 2 + r, |r| <= ln 2 / 2 (k ln 2 exact in double-double: |k| < 2^11) */
    k = floor(x.hi / dd_ln2.hi + 0.5);
    r = sms_dd_sub(x, sms_dd_mul(sms_dd_of(k), dd_ln2));
    r = sms_dd_add(sms_dd_of(1.0), expm1_reduced(r));
    return sms_dd_scale(r, (int)k);
}

sms_dd sms_dd_expm1(sms_dd x)
{
    if (fabs(x.hi) <= 0.35)
        return expm1_reduced(x);
    return sms_dd_sub(sms_dd_exp(x), sms_dd_of(1.0));   /* |result| > 0.29: no cancellation */
}

/* sin and cos of t, |t| <= pi/4, by their Taylor series (up to 14 terms each). */
static void sin_cos_reduced(sms_dd t, sms_dd *s, sms_dd *c)
{
    const sms_dd t2 = sms_dd_mul(t, t);
    sms_dd term = t;
    int n;
    *s = t;
    for (n = 3; n < 60; n += 2) {
        term = sms_dd_div(sms_dd_neg(sms_dd_mul(term, t2)), sms_dd_of((double)((n - 1) * n)));
        *s = sms_dd_add(*s, term);
        if (!(fabs(term.hi) > DD_SERIES_EPS * fabs(s->hi)))
            break;
    }
    term = sms_dd_of(1.0);
    *c = term;
    for (n = 2; n < 60; n += 2) {
        term = sms_dd_div(sms_dd_neg(sms_dd_mul(term, t2)), sms_dd_of((double)((n - 1) * n)));
        *c = sms_dd_add(*c, term);
        if (!(fabs(term.hi) > DD_SERIES_EPS))
            break;
    }
}

/* sin(pi x) and cos(pi x): x reduced exactly modulo 2 (fmod is exact), then to y in
 * [-1/4, 1/4] and the quadrant q of x = y + q/2. */
static void sin_cos_pi(sms_dd x, sms_dd *s, sms_dd *c)
{
    double half_turns;
    int q;
    sms_dd y, sy, cy;
    x = sms_dd_add(sms_dd_of(fmod(x.hi, 2.0)), sms_dd_of(fmod(x.lo, 2.0)));   /* in (-4, 4) */
    half_turns = floor(2.0 * x.hi + 0.5);
    q = ((int)half_turns % 4 + 4) % 4;
    y = sms_dd_sub(x, sms_dd_of(0.5 * half_turns));
    sin_cos_reduced(sms_dd_mul(dd_pi, y), &sy, &cy);
    switch (q) {
    case 0: *s = sy; *c = cy; break;
    case 1: *s = cy; *c = sms_dd_neg(sy); break;
    case 2: *s = sms_dd_neg(sy); *c = sms_dd_neg(cy); break;
    default: *s = sms_dd_neg(cy); *c = sy; break;
    }
    /* -0 + 0 = +0: the exact zeros come out positive */
    s->hi += 0.0;
    s->lo += 0.0;
    c->hi += 0.0;
    c->lo += 0.0;
}

sms_dd sms_dd_sin_pi(sms_dd x)
{
    sms_dd s, c;
    sin_cos_pi(x, &s, &c);
    return s;
}

sms_dd sms_dd_cos_pi(sms_dd x)
{
    sms_dd s, c;
    sin_cos_pi(x, &s, &c);
    return c;
}
