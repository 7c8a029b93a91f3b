/* SPDX-License-Identifier: Apache-2.0 */
/* Design of the FIR smoothers (docs/exact-mode.md): validation, taps, recursive constants.
 * Runs once per init in double with libm; nothing here is on the per-sample path. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include "core/double_double.h"
#include "filter/smoother_design.h"

#ifdef SMS_USE_FLOAT
#define SMS_REAL_MAX FLT_MAX
#else
#define SMS_REAL_MAX DBL_MAX
#endif

#define SMS_PI 3.14159265358979323846

/* docs/exact-mode.md: nu is the integer round(nu) when within 1e-9 relative. */
#define SMS_GRID_TOLERANCE 1e-9

/* sin(pi x) and cos(pi x) for x >= 0, exact at multiples of 1/2 (sin(pi) is 0, not 1e-16),
 * so that the integer-N taps vanish where the sampled sine does. */
static double sin_pi(double x)
{
    double sign = 1.0;
    x = fmod(x, 2.0);
    if (x > 1.0) {
        x -= 1.0;
        sign = -1.0;
    }
    if (x > 0.5)
        x = 1.0 - x;
    return sign * sin(SMS_PI * x);
}

static double cos_pi(double x)
{
    double sign = 1.0;
    x = fmod(x, 2.0);
    if (x > 1.0)
        x = 2.0 - x;
    if (x > 0.5) {
        x = 1.0 - x;
        sign = -1.0;
    }
    if (x > 0.25)
        return sign * sin(SMS_PI * (0.5 - x));
    return sign * cos(SMS_PI * x);
}

/* The pole q = e^{decay} e^{j pi/nu} (e^{decay} without the half sine) in double-double, as
 * q - 1 and Im q: Re q - 1 = expm1(decay) - 2 e^{decay} sin^2(pi/(2 nu)), two terms of one sign,
 * so nothing cancels for q near 1 (long windows), and the low parts refine the double pole. */
static void pole_dd(double decay, double nu, int half_sine, sms_dd *re_m1, sms_dd *im)
{
    const sms_dd d = sms_dd_of(decay), x = sms_dd_div(sms_dd_of(1.0), sms_dd_of(nu));
    sms_dd mag, s;
    *re_m1 = sms_dd_expm1(d);
    *im = sms_dd_of(0.0);
    if (!half_sine)
        return;
    mag = sms_dd_exp(d);
    s = sms_dd_sin_pi(sms_dd_scale(x, -1));
    *re_m1 = sms_dd_sub(*re_m1, sms_dd_scale(sms_dd_mul(mag, sms_dd_mul(s, s)), 1));
    *im = sms_dd_mul(mag, sms_dd_sin_pi(x));
}

static int on_grid(double nu, double *rounded)
{
    double n = floor(nu + 0.5);
    *rounded = n;
    return fabs(nu - n) <= SMS_GRID_TOLERANCE * (nu > 1.0 ? nu : 1.0);
}

static int describe(sms_kind kind, sms_smoother_family *family)
{
    switch (kind) {
    case SMS_RECTANGULAR: sms_rectangular_describe(family); return 1;
    case SMS_HARMONIC: sms_harmonic_describe(family); return 1;
    case SMS_DAMPED_HARMONIC: sms_damped_harmonic_describe(family); return 1;
    case SMS_EXPONENTIAL: sms_exponential_describe(family); return 1;
    default: return 0;
    }
}

/* Unnormalised base tap: e^{decay i} (sin(pi i/nu) for half-sine families). */
static double base_tap(const sms_smoother_design *d, size_t i)
{
    double g = exp(d->decay * (double)i);
    if (d->family.half_sine)
        g *= sin_pi((double)i / d->nu);
    return g;
}

static int fits_real(double v)
{
    return fabs(v) <= SMS_REAL_MAX; /* false for NaN and Inf too */
}

static sms_dd dd_mul_d(sms_dd a, double b)
{
    return sms_dd_mul(a, sms_dd_of(b));
}

/* Sum_{i=0}^{n-1} q^i, q = e^{decay} e^{j pi t} (decay <= 0), in closed form: O(1) whatever n,
 * so that sizing and refusing a long filter costs no more than a short one.
 * (1 - q^n)/(1 - q) with 1 - e^{d} e^{j pi t} = -expm1(d) + 2 e^{d} sin^2(pi t/2) - j e^{d} sin(pi t):
 * both real parts are sums of non-negative terms, so nothing cancels when q is near 1 (long,
 * lightly damped windows), and in double-double the result is exact to far below double. */
static void geometric_sum(double decay, sms_dd t, double n, sms_dd *re, sms_dd *im)
{
    const sms_dd d = sms_dd_of(decay), dn = dd_mul_d(d, n), tn = dd_mul_d(t, n);
    const sms_dd r = sms_dd_exp(d), rn = sms_dd_exp(dn);
    const sms_dd s = sms_dd_sin_pi(sms_dd_scale(t, -1)), sn = sms_dd_sin_pi(sms_dd_scale(tn, -1));
    sms_dd den_re, den_im, num_re, num_im, den;
    den_re = sms_dd_add(sms_dd_neg(sms_dd_expm1(d)), sms_dd_scale(sms_dd_mul(r, sms_dd_mul(s, s)), 1));
    den_im = sms_dd_neg(sms_dd_mul(r, sms_dd_sin_pi(t)));
    num_re = sms_dd_add(sms_dd_neg(sms_dd_expm1(dn)),
                        sms_dd_scale(sms_dd_mul(rn, sms_dd_mul(sn, sn)), 1));
    num_im = sms_dd_neg(sms_dd_mul(rn, sms_dd_sin_pi(tn)));
    den = sms_dd_add(sms_dd_mul(den_re, den_re), sms_dd_mul(den_im, den_im));
    if (den.hi == 0.0) { /* q = 1: n terms of 1 */
        *re = sms_dd_of(n);
        *im = sms_dd_of(0.0);
        return;
    }
    /* num / den_c = num * conj(den_c) / |den_c|^2 */
    *re = sms_dd_div(sms_dd_add(sms_dd_mul(num_re, den_re), sms_dd_mul(num_im, den_im)), den);
    *im = sms_dd_div(sms_dd_sub(sms_dd_mul(num_im, den_re), sms_dd_mul(num_re, den_im)), den);
}

/* Sum of the unnormalised base taps e^{decay i} (sin(pi i/nu)), i = 0..n-1, in closed form. */
static sms_dd base_tap_sum(const sms_smoother_design *d, size_t n)
{
    sms_dd re, im;
    if (!d->family.half_sine) {
        geometric_sum(d->decay, sms_dd_of(0.0), (double)n, &re, &im);
        return re;
    }
    geometric_sum(d->decay, sms_dd_div(sms_dd_of(1.0), sms_dd_of(d->nu)), (double)n, &re, &im);
    return im;
}

/* Exact timing (docs/exact-mode.md): the base taps are g[i] = h_c(i Ts), i < N0, and the
 * fraction f of g[N0] that lies inside [0, T); the corrections a on N0-1 and b on N0 solve
 * a z*^-(N0-1) + b z*^-N0 = -G(z*), i.e. a z* + b = R = -G(z*) z*^N0 (two real unknowns, one
 * complex equation). G(z*) = sum g[i] z*^-i: the damping of g[i] and of z*^-i cancel, leaving
 * geometric sums of unit phasors (sin(pi i/nu) = (e^{j pi i/nu} - e^{-j pi i/nu})/2j), summed
 * in closed form in double-double (G is small next to its terms). Writes the unnormalised
 * corrections and returns sum(g) + a + b over the whole support. */
static sms_dd exact_correction(const sms_smoother_design *d, size_t n0, double fraction,
                               sms_dd a, sms_dd *a_out, sms_dd *b_out)
{
    /* a = w* Ts / pi, in (0, 1) */
    const double n = (double)n0;
    const sms_dd f = sms_dd_of(fraction), inv_nu = sms_dd_div(sms_dd_of(1.0), sms_dd_of(d->nu));
    const sms_dd an = dd_mul_d(a, n), e_decay = sms_dd_exp(sms_dd_of(d->decay));
    sms_dd g_re, g_im, sum, shape_n0, r_mag, r_re, r_im, z_re, z_im, c_re, c_im, first, fs;
    if (d->family.half_sine) {
        sms_dd p_re, p_im, m_re, m_im;
        geometric_sum(0.0, sms_dd_sub(inv_nu, a), n, &p_re, &p_im);
        geometric_sum(0.0, sms_dd_neg(sms_dd_add(inv_nu, a)), n, &m_re, &m_im);
        /* (P - M)/(2j) */
        g_re = sms_dd_scale(sms_dd_sub(p_im, m_im), -1);
        g_im = sms_dd_neg(sms_dd_scale(sms_dd_sub(p_re, m_re), -1));
        shape_n0 = sms_dd_sin_pi(dd_mul_d(inv_nu, n));
    } else {
        geometric_sum(0.0, sms_dd_neg(a), n, &g_re, &g_im);
        shape_n0 = sms_dd_of(1.0);
    }
    c_re = sms_dd_cos_pi(an);
    c_im = sms_dd_sin_pi(an);
    fs = sms_dd_mul(f, shape_n0);
    g_re = sms_dd_add(g_re, sms_dd_mul(fs, c_re));
    g_im = sms_dd_sub(g_im, sms_dd_mul(fs, c_im));
    r_mag = sms_dd_exp(sms_dd_mul(sms_dd_of(d->decay), sms_dd_of(n)));
    sum = sms_dd_add(base_tap_sum(d, n0), sms_dd_mul(fs, r_mag));
    z_re = sms_dd_mul(e_decay, sms_dd_cos_pi(a));
    z_im = sms_dd_mul(e_decay, sms_dd_sin_pi(a));
    /* R = -G e^{decay N0} e^{j pi a N0} */
    r_re = sms_dd_neg(sms_dd_mul(r_mag, sms_dd_sub(sms_dd_mul(g_re, c_re), sms_dd_mul(g_im, c_im))));
    r_im = sms_dd_neg(sms_dd_mul(r_mag, sms_dd_add(sms_dd_mul(g_re, c_im), sms_dd_mul(g_im, c_re))));
    first = sms_dd_div(r_im, z_im);
    *a_out = first;
    *b_out = sms_dd_sub(r_re, sms_dd_mul(first, z_re));
    return sms_dd_add(sum, sms_dd_add(*a_out, *b_out));
}

/* Bounded timing (docs/exact-mode.md): taps u, q, q^2 .. q^N0, u q^(N0+1) (before scaling to
 * sum 1), q = e^{sigma Ts}, N0 = floor(nu), f = nu - N0. The zero at z* = q e^{j phi},
 * phi = w* Ts = 2 pi x0 with x0 = k zero_turns/(2 nu), takes one real unknown: the damping
 * cancels in every term t_i z*^-i, and the imaginary part of the condition (times
 * e^{j phi (N0+1)/2}) forces the same u on both ends. The real part gives
 *   u = (1 - tan(pi x0 (N0+1))/tan(pi x0))/2 = sin(pi x0 f)/(2 sin(pi x0) cos(pi x0 (1 - f)))
 * (x0 nu = k zero_turns/2 is a whole number for the real-pole families, so x0 (N0+1) is
 * x0 (1 - f) modulo 1; the second form has no cancellation). 0 < u < 1/2 for nu > 2k, and the
 * largest tap is at most the continuous response's peak density times Ts: that is what these
 * taps are for (a stage that is also a kinematic bound). */
static sms_dd bounded_end_tap(double nu, double zero_turns_k)
{
    const sms_dd x0 = sms_dd_scale(sms_dd_div(sms_dd_of(zero_turns_k), sms_dd_of(nu)), -1);
    const double f = nu - floor(nu);   /* exact */
    const sms_dd den = sms_dd_scale(sms_dd_mul(sms_dd_sin_pi(x0),
                                               sms_dd_cos_pi(dd_mul_d(x0, 1.0 - f))), 1);
    return sms_dd_div(sms_dd_sin_pi(dd_mul_d(x0, f)), den);
}

/* Largest |x| (and |rest|) for which every sum on the per-sample path stays below the
 * overflow threshold of sms_real, in closed form (O(1)); sms_smoother_input_max() caps it at
 * SMS_INPUT_MAX. With |x|, |rest| <= X a copy filters
 * u = x - rest - ref, |u| <= 4X; its state is w = sum_{i<M} c q^i u[n-i] (fewer terms after a
 * restart), so |w| <= 4X |c| S, S = sum_{i<M} r^i = (1 - r^M)/(1 - r); the increment
 * (q - 1) w + c u - c q^M u[n-M] and w + increment stay below 5 |w| + 8X|c| <= 28 X |c| S
 * (S >= 1), and the direct taps add at most 8X (|d0| + |d1|). For most filters |c| S is of
 * order one (1 rectangular and exponential, about pi/2 harmonic) and the bound is
 * far above SMS_INPUT_MAX; a heavily damped harmonic smoother has c ~ e^{-sigma Ts}/sin(pi/N) (its
 * first taps are tiny) and a proportionally smaller range. */
static double input_bound(const sms_smoother_design *d)
{
    double S, gain, bound;
    if (d->decay == 0.0)
        S = (double)d->window;
    else
        S = expm1(d->decay * (double)d->window) / expm1(d->decay); /* (1 - r^M)/(1 - r) */
    if (S < 1.0)
        S = 1.0;
    gain = 32.0 * fabs(d->gain) * S + 8.0;
    if (d->n_corrections > 0)
        gain += 8.0 * (fabs(d->correction_gain[0]) + fabs(d->correction_gain[1]));
    bound = (double)SMS_REAL_MAX / gain;
    return bound;
}

sms_status sms_smoother_design_make(const sms_stage_config *config, double Ts,
                                    sms_smoother_design *design)
{
    sms_smoother_design d;
    double nu, rounded, sigma = 0.0, max_len, tail_mag;
    int integer;

    if (config == NULL || design == NULL)
        return SMS_ERR_NULL;
    if (!(isfinite(Ts) && Ts > 0.0))
        return SMS_ERR_SAMPLE_PERIOD;
    if (!describe(config->kind, &d.family))
        return SMS_ERR_KIND;
    if (config->timing != SMS_TIMING_EXACT && config->timing != SMS_TIMING_PAPER
        && config->timing != SMS_TIMING_BOUNDED)
        return SMS_ERR_KIND;
    /* bounded taps are the real-pole families' (a half sine peaks mid-window, not at an end) */
    if (config->timing == SMS_TIMING_BOUNDED && d.family.half_sine)
        return SMS_ERR_KIND;
    if (!(isfinite(config->T) && config->T > 0.0))
        return SMS_ERR_DURATION;
    nu = config->T / Ts;
    integer = on_grid(nu, &rounded);
    /* One rule for short durations: T below Ts is refused; only T within the grid tolerance
     * of Ts (nu rounds to 1 on the grid) counts as one sample. */
    if (nu < 1.0 && !(integer && rounded >= 1.0))
        return SMS_ERR_DURATION_BELOW_TS;
    if (d.family.damped) {
        if (!(isfinite(config->sigma) && config->sigma <= 0.0))
            return SMS_ERR_SIGMA;
        sigma = config->sigma;
    }
    if (config->k < 1u)
        return SMS_ERR_MULTIPLE;
    if (d.family.half_sine && config->k % 2u == 0u)
        return SMS_ERR_EVEN_MULTIPLE;
    /* Exact timing off the grid pins w* = k zero_turns pi/T: it must lie below pi/Ts. */
    if (!integer && config->timing != SMS_TIMING_PAPER
        && (double)config->k * d.family.zero_turns >= nu)
        return SMS_ERR_ABOVE_NYQUIST;
    /* Lengths, ring indices and ages (up to 2L) must be exact in size_t and in a double. */
    max_len = (double)(SIZE_MAX / (4u * sizeof(double)));
    if (max_len > 4503599627370496.0)
        max_len = 4503599627370496.0; /* 2^52 */
    if (!(nu + 2.0 <= max_len))
        return SMS_ERR_TOO_LONG;

    d.decay = sigma * Ts;
    d.n_corrections = 0;
    if (integer || config->timing == SMS_TIMING_PAPER) {
        d.nu = rounded; /* >= 1: nu >= 1 - 1e-9 here */
        d.window = (size_t)rounded;
        d.length = d.window;
    } else if (config->timing == SMS_TIMING_BOUNDED) {
        /* Taps 0..N0 from the recursion, end taps on 0 and N0 + 1 as direct taps. */
        d.nu = nu;
        d.window = (size_t)floor(nu) + 1u;
        d.length = d.window + 1u;
    } else {
        /* Taps 0..N0-1 from the recursion, tap N0 (fractional, corrected) and the correction
         * on N0-1 as direct taps. N0 >= 2 here: the Nyquist check needs nu > 2k. */
        d.nu = nu;
        d.window = (size_t)floor(nu);
        d.length = d.window + 1u;
    }
    /* One sample of sin(pi t/T) is its zero at t = 0: the harmonic families need N >= 2. */
    if (d.family.half_sine && d.window < 2u)
        return SMS_ERR_DURATION_BELOW_TS;

    if (d.length > d.window && config->timing == SMS_TIMING_BOUNDED) {
        /* the end taps are the only taps that are not c q^i: write them as corrections */
        const size_t m = d.window;
        const sms_dd u = bounded_end_tap(nu, (double)config->k * d.family.zero_turns);
        const sms_dd u_m1 = sms_dd_sub(u, sms_dd_of(1.0));
        const sms_dd u_last = sms_dd_mul(u, sms_dd_exp(dd_mul_d(sms_dd_of(d.decay), (double)m)));
        const sms_dd scale = sms_dd_div(sms_dd_of(1.0), sms_dd_add(sms_dd_add(base_tap_sum(&d, m),
                                                                              u_m1), u_last));
        d.gain = scale.hi;
        d.n_corrections = 2;
        d.correction_delay[0] = 0u;
        d.correction_delay[1] = m;
        d.correction_gain[0] = sms_dd_mul(scale, u_m1).hi;
        d.correction_gain[1] = sms_dd_mul(scale, u_last).hi;
    } else if (d.length > d.window) {
        const size_t n0 = d.window;
        const double fraction = nu - floor(nu);
        /* the zero's turns per sample k zero_turns / nu, kept in double-double */
        const sms_dd turns = sms_dd_div(sms_dd_of((double)config->k * d.family.zero_turns),
                                        sms_dd_of(nu));
        sms_dd a, b, scale;
        sms_dd last = dd_mul_d(sms_dd_exp(dd_mul_d(sms_dd_of(d.decay), (double)n0)), fraction);
        if (d.family.half_sine)
            last = sms_dd_mul(last, sms_dd_sin_pi(sms_dd_div(sms_dd_of((double)n0),
                                                             sms_dd_of(nu))));
        scale = sms_dd_div(sms_dd_of(1.0), exact_correction(&d, n0, fraction, turns, &a, &b));
        d.gain = scale.hi;
        d.n_corrections = 2;
        d.correction_delay[0] = n0 - 1u;
        d.correction_delay[1] = n0;
        d.correction_gain[0] = sms_dd_mul(scale, a).hi;
        d.correction_gain[1] = sms_dd_mul(scale, sms_dd_add(last, b)).hi;
        if (!(fits_real(d.correction_gain[0]) && fits_real(d.correction_gain[1])))
            return SMS_ERR_SIGMA;
    } else {
        d.gain = sms_dd_div(sms_dd_of(1.0), base_tap_sum(&d, d.window)).hi;
    }
    tail_mag = exp(d.decay * (double)d.window);
    {
        sms_dd re_m1, im;
        pole_dd(d.decay, d.nu, d.family.half_sine, &re_m1, &im);
        d.pole_m1_re = re_m1.hi;
        d.pole_m1_lo_re = re_m1.lo;
        d.pole_im = im.hi;
        d.pole_lo_im = im.lo;
    }
    if (d.family.half_sine) {
        d.tail_re = -d.gain * tail_mag * cos_pi((double)d.window / d.nu);
        d.tail_im = -d.gain * tail_mag * sin_pi((double)d.window / d.nu);
    } else {
        d.tail_re = -d.gain * tail_mag;
        d.tail_im = 0.0;
    }
    /* Only an extreme sigma (the response decays below the range of sms_real within the
     * filter) can make a constant overflow. */
    if (!(fits_real(d.gain) && fits_real(d.tail_re) && fits_real(d.tail_im)))
        return SMS_ERR_SIGMA;
    d.input_limit = input_bound(&d);
    /* A response so damped that inputs of order one already overflow a recursion sum. */
    if (!(d.input_limit >= 1.0))
        return SMS_ERR_SIGMA;
    *design = d;
    return SMS_OK;
}

double sms_smoother_design_tap(const sms_smoother_design *design, size_t i)
{
    double h = i < design->window ? design->gain * base_tap(design, i) : 0.0;
    size_t j;
    for (j = 0; j < design->n_corrections; ++j)
        if (design->correction_delay[j] == i)
            h += design->correction_gain[j];
    return h;
}
