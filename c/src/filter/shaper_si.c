/* SPDX-License-Identifier: Apache-2.0 */
/* Specified-insensitivity (SI) shapers: the residual stays at or below a tolerance V over a
 * band of frequencies around the mode (Singhose, Seering and Singer, "Input shaping for
 * vibration reduction with specified insensitivity to modeling errors", Japan-USA Symposium
 * on Flexible Automation, 1996), here in closed form over equally spaced impulses.
 *
 * n = 2d + 1 impulses B_m at m D/(2d) damped periods, symmetric (B_m = B_{2d-m}). With
 * theta = w D Td/(2d) the undamped response is H(jw) e^{j d theta} = R(theta) = sum_k r_k
 * cos(k theta), a polynomial of degree d in c = cos(theta). The band of |H| <= V is an
 * interval [c_lo, c_hi] of c, and the polynomial of degree d with R(c = 1) = 1 (unit gain) that
 * stays within +-V on the widest such interval is the scaled Chebyshev polynomial
 * R = V T_d(x), x = (2c - c_hi - c_lo)/(c_hi - c_lo) (Dolph, "A current distribution for
 * broadside arrays which optimizes the relationship between beam width and side-lobe level",
 * Proc. IRE 34, 1946: the same extremal property, for array weights). Unit gain fixes
 * x(1) = x1 = cosh(acosh(1/V)/d); the band is centred on the mode, w in [wd (1 - I/2),
 * wd (1 + I/2)], i.e. theta in [theta_c - u, theta_c + u], theta_c = pi D/d, u = theta_c I/2:
 * - band below theta = pi (theta_c + u <= pi): c_hi = cos(theta_c - u), c_lo = cos(theta_c + u)
 *   and x(1) = x1 reads cos(theta_c) cos(u) + x1 sin(theta_c) sin(u) = 1, so
 *   u = phi - acos(1/rho), rho = |cos(theta_c) + j x1 sin(theta_c)|, phi its argument;
 * - band across theta = pi: c_lo = -1, c_hi = (3 - x1)/(1 + x1), u = theta_c - acos(c_hi).
 * D = d (spacing Td/2, theta_c = pi) gives EI for n = 3 and the three-hump EI for n = 5 (both
 * closed forms of Singhose, Porter, Tuttle and Singer 1997 are these Chebyshev polynomials);
 * D = d/2 is where an amplitude reaches 0 (n = 3: ZV). Over D in [d/2, d] no amplitude is
 * negative (checked for V from 1e-4 to 0.99 in tests/c/test_shapers.c), so |H| <= 1 at every
 * frequency. Damped: the amplitudes are weighted by e^{-zeta wn t_m} as for EI (shaper.h). */
#include <math.h>
#include "filter/shaper_designs.h"

static const double pi = 3.14159265358979323846;

/* Half-width u of the band in theta and its ends in c, for d, theta_c and x1. */
static void band(double theta_c, double x1, double *u, double *c_lo, double *c_hi)
{
    double rho = sqrt(cos(theta_c) * cos(theta_c) + x1 * x1 * sin(theta_c) * sin(theta_c));
    double phi = atan2(x1 * sin(theta_c), cos(theta_c));
    double ua = phi - acos(1.0 / rho);
    if (theta_c + ua <= pi) {
        *u = ua;
        *c_lo = cos(theta_c + ua);
        *c_hi = cos(theta_c - ua);
    } else {
        *c_hi = (3.0 - x1) / (1.0 + x1);
        *c_lo = -1.0;
        *u = theta_c - acos(*c_hi);
    }
}

/* Chebyshev polynomial T_d(x) by its three-term recurrence (any real x). */
static double chebyshev(unsigned d, double x)
{
    double t0 = 1.0, t1 = x, t2;
    unsigned k;
    if (d == 0u)
        return 1.0;
    for (k = 1u; k < d; ++k) {
        t2 = 2.0 * x * t1 - t0;
        t0 = t1;
        t1 = t2;
    }
    return t1;
}

int sms_si_undamped(unsigned n, double duration, double V, double *amp, double *units,
                    double *insensitivity)
{
    double x1, theta_c, u, c_lo, c_hi, r[SMS_SHAPER_MAX_IMPULSES], f[SMS_SHAPER_MAX_IMPULSES];
    double sum = 0.0, peak = 0.0;
    unsigned d, j, k, m;
    if (n < 3u || n > SMS_SHAPER_MAX_IMPULSES || n % 2u == 0u || !(V > 0.0) || !(V < 1.0))
        return 0;
    d = (n - 1u) / 2u;
    if (!(duration >= 0.5 * (double)d) || !(duration <= (double)d))
        return 0;
    x1 = cosh(acosh(1.0 / V) / (double)d);
    theta_c = pi * duration / (double)d;
    band(theta_c, x1, &u, &c_lo, &c_hi);
    /* R(theta) = V T_d(x(cos theta)) at theta_j = pi j/d, then its cosine coefficients by the
     * type-I discrete cosine transform (exact for a trigonometric polynomial of degree d). */
    for (j = 0; j <= d; ++j) {
        double c = cos(pi * (double)j / (double)d);
        f[j] = V * chebyshev(d, (2.0 * c - c_hi - c_lo) / (c_hi - c_lo));
    }
    for (k = 0; k <= d; ++k) {
        double acc = 0.0;
        for (j = 0; j <= d; ++j)
            acc += (j == 0u || j == d ? 0.5 : 1.0) * f[j] * cos(pi * (double)(k * j) / (double)d);
        r[k] = (k == 0u || k == d ? 1.0 : 2.0) * acc / (double)d;
    }
    amp[d] = r[0];
    for (k = 1; k <= d; ++k)
        amp[d - k] = amp[d + k] = 0.5 * r[k];
    for (m = 0; m < n; ++m) {
        units[m] = duration * (double)m / (double)(2u * d);
        peak = fabs(amp[m]) > peak ? fabs(amp[m]) : peak;
    }
    /* An amplitude that is 0 in exact arithmetic (D = d/2) may come out as -1e-17. */
    for (m = 0; m < n; ++m) {
        if (amp[m] < 0.0 && amp[m] >= -1e-12 * peak)
            amp[m] = 0.0;
        if (!(amp[m] >= 0.0))
            return 0;
        sum += amp[m];
    }
    for (m = 0; m < n; ++m)
        amp[m] /= sum;
    if (insensitivity != NULL)
        *insensitivity = 2.0 * u / theta_c;
    return 1;
}

sms_status sms_shaper_si_insensitivity(unsigned order, double duration, double tolerance,
                                       double *insensitivity)
{
    double amp[SMS_SHAPER_MAX_IMPULSES], units[SMS_SHAPER_MAX_IMPULSES];
    if (insensitivity == NULL)
        return SMS_ERR_NULL;
    if (order < 3u || order > SMS_SHAPER_MAX_IMPULSES || order % 2u == 0u)
        return SMS_ERR_ORDER;
    if (!(tolerance > 0.0) || !(tolerance < 1.0))
        return SMS_ERR_TOLERANCE;
    if (!sms_si_undamped(order, duration, tolerance, amp, units, insensitivity))
        return SMS_ERR_SHAPER_DURATION;
    return SMS_OK;
}

sms_status sms_shaper_si_design(double tolerance, double insensitivity, unsigned *order,
                                double *duration)
{
    double amp[SMS_SHAPER_MAX_IMPULSES], units[SMS_SHAPER_MAX_IMPULSES];
    double best = 0.0, lo_i, hi_i;
    unsigned d, best_n = 0u;
    if (order == NULL || duration == NULL)
        return SMS_ERR_NULL;
    if (!(tolerance > 0.0) || !(tolerance < 1.0))
        return SMS_ERR_TOLERANCE;
    if (!(insensitivity > 0.0) || !(insensitivity < 2.0))
        return SMS_ERR_SHAPER_DURATION;
    for (d = 1u; 2u * d + 1u <= SMS_SHAPER_MAX_IMPULSES; ++d) {
        /* I grows with D over [d/2, d] (tests/c/test_shapers.c): bisect for I(D) = target */
        double lo = 0.5 * (double)d, hi = (double)d;
        int i;
        (void)sms_si_undamped(2u * d + 1u, lo, tolerance, amp, units, &lo_i);
        (void)sms_si_undamped(2u * d + 1u, hi, tolerance, amp, units, &hi_i);
        if (hi_i < insensitivity)
            continue;
        if (lo_i >= insensitivity) {
            hi = lo;
        } else {
            for (i = 0; i < 100 && hi - lo > 1e-15 * hi; ++i) {
                double mid = 0.5 * (lo + hi), got;
                (void)sms_si_undamped(2u * d + 1u, mid, tolerance, amp, units, &got);
                if (got >= insensitivity)
                    hi = mid;
                else
                    lo = mid;
            }
        }
        if (best_n == 0u || hi < best) {
            best = hi;
            best_n = 2u * d + 1u;
        }
    }
    if (best_n == 0u)
        return SMS_ERR_ORDER;     /* wider than SI shapers of SMS_SHAPER_MAX_IMPULSES reach */
    *order = best_n;
    *duration = best;
    return SMS_OK;
}
