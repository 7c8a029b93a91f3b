/* Design of the FIR smoothers (docs/exact-mode.md): validation, taps, recursive constants.
 * Runs once per init in double with libm; nothing here is on the per-sample path. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include "smoother_design.h"

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

/* The pole e^{decay} e^{j pi/nu} in long double (its low part refines the double pole). */
static void pole_long(double decay, double nu, int half_sine, long double *re, long double *im)
{
    const long double pi = 3.14159265358979323846264338327950288L;
    long double mag = expl((long double)decay), x = 1.0L / (long double)nu;
    if (!half_sine) {
        *re = mag;
        *im = 0.0L;
        return;
    }
    /* 1/nu is in (0, 1]; reduce so that x = 1/2 and x = 1 give exact zeros. */
    if (x > 0.5L) {
        *re = -mag * cosl(pi * (1.0L - x));
        *im = mag * sinl(pi * (1.0L - x));
    } else {
        *re = x == 0.5L ? 0.0L : mag * cosl(pi * x);
        *im = mag * sinl(pi * x);
    }
}

/* Neumaier's compensated sum: the normalisation and G(z*) then carry no O(N eps) error. */
typedef struct { double sum, carry; } exact_sum;

static void sum_add(exact_sum *s, double v)
{
    double t = s->sum + v;
    if (fabs(s->sum) >= fabs(v))
        s->carry += (s->sum - t) + v;
    else
        s->carry += (v - t) + s->sum;
    s->sum = t;
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

/* sin(pi x), cos(pi x) in long double for x >= 0, exact zeros at multiples of 1/2. */
static long double sin_pi_long(long double x)
{
    const long double pi = 3.14159265358979323846264338327950288L;
    long double sign = 1.0L;
    x = fmodl(x, 2.0L);
    if (x > 1.0L) {
        x -= 1.0L;
        sign = -1.0L;
    }
    if (x > 0.5L)
        x = 1.0L - x;
    return sign * sinl(pi * x);
}

static long double cos_pi_long(long double x)
{
    return sin_pi_long(fmodl(x, 2.0L) + 0.5L);
}

/* Exact timing (docs/exact-mode.md): the base taps are g[i] = h_c(i Ts), i < N0, and the
 * fraction f of g[N0] that lies inside [0, T); the corrections a on N0-1 and b on N0 solve
 * a z*^-(N0-1) + b z*^-N0 = -G(z*), i.e. a z* + b = R = -G(z*) z*^N0 (two real unknowns, one
 * complex equation). Long double: G is small next to its terms. Writes the unnormalised
 * corrections and returns sum(g) + a + b over the whole support. */
static long double exact_correction(const sms_smoother_design *d, size_t n0, double fraction,
                                    double zero_turns_per_sample, long double *a_out,
                                    long double *b_out)
{
    const long double a = (long double)zero_turns_per_sample; /* w* Ts / pi, in (0, 1) */
    const long double nu = (long double)d->nu, decay = (long double)d->decay;
    long double g_re = 0.0L, g_im = 0.0L, sum = 0.0L, shape, weight, r_mag, r_re, r_im;
    long double z_re, z_im, c_re, c_im, first;
    size_t i;
    /* G(z*) = sum g[i] z*^-i: the damping of g[i] and of z*^-i cancel exactly. */
    for (i = 0; i <= n0; ++i) {
        shape = d->family.half_sine ? sin_pi_long((long double)i / nu) : 1.0L;
        weight = i == n0 ? (long double)fraction : 1.0L;
        g_re += weight * shape * cos_pi_long(a * (long double)i);
        g_im -= weight * shape * sin_pi_long(a * (long double)i);
        sum += weight * shape * expl(decay * (long double)i);
    }
    r_mag = expl(decay * (long double)n0);
    z_re = expl(decay) * cos_pi_long(a);
    z_im = expl(decay) * sin_pi_long(a);
    /* R = -G e^{decay N0} e^{j pi a N0} */
    c_re = cos_pi_long(a * (long double)n0);
    c_im = sin_pi_long(a * (long double)n0);
    r_re = -r_mag * (g_re * c_re - g_im * c_im);
    r_im = -r_mag * (g_re * c_im + g_im * c_re);
    first = r_im / z_im;
    *a_out = first;
    *b_out = r_re - first * z_re;
    return sum + *a_out + *b_out;
}

sms_status sms_smoother_design_make(const sms_stage_config *config, double Ts,
                                    sms_smoother_design *design)
{
    sms_smoother_design d;
    double nu, rounded, sigma = 0.0, max_len, tail_mag;
    int integer;
    exact_sum total = {0.0, 0.0};
    size_t i;

    if (config == NULL || design == NULL)
        return SMS_ERR_NULL;
    if (!(isfinite(Ts) && Ts > 0.0))
        return SMS_ERR_SAMPLE_PERIOD;
    if (!describe(config->kind, &d.family))
        return SMS_ERR_KIND;
    if (config->timing != SMS_TIMING_EXACT && config->timing != SMS_TIMING_PAPER)
        return SMS_ERR_KIND;
    if (!(isfinite(config->T) && config->T > 0.0))
        return SMS_ERR_DURATION;
    nu = config->T / Ts;
    integer = on_grid(nu, &rounded);
    if (nu < 1.0 && !integer)
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
    if (!integer && config->timing == SMS_TIMING_EXACT
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
        if (rounded < 1.0)
            rounded = 1.0;
        d.nu = rounded;
        d.window = (size_t)rounded;
        d.length = d.window;
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

    if (d.length > d.window) {
        const size_t n0 = d.window;
        const double fraction = nu - floor(nu);
        long double a, b, last = (long double)fraction * expl((long double)d.decay * (long double)n0);
        long double scale;
        if (d.family.half_sine)
            last *= sin_pi_long((long double)n0 / (long double)nu);
        scale = 1.0L / exact_correction(&d, n0, fraction,
                                        (double)config->k * d.family.zero_turns / nu, &a, &b);
        d.gain = (double)scale;
        d.n_corrections = 2;
        d.correction_delay[0] = n0 - 1u;
        d.correction_delay[1] = n0;
        d.correction_gain[0] = (double)(scale * a);
        d.correction_gain[1] = (double)(scale * (last + b));
        if (!(fits_real(d.correction_gain[0]) && fits_real(d.correction_gain[1])))
            return SMS_ERR_SIGMA;
    } else {
        for (i = 0; i < d.window; ++i)
            sum_add(&total, base_tap(&d, i));
        d.gain = 1.0 / (total.sum + total.carry);
    }
    tail_mag = exp(d.decay * (double)d.window);
    {
        long double re, im;
        pole_long(d.decay, d.nu, d.family.half_sine, &re, &im);
        d.pole_m1_re = (double)(re - 1.0L);
        d.pole_m1_lo_re = (double)((re - 1.0L) - (long double)d.pole_m1_re);
        d.pole_im = (double)im;
        d.pole_lo_im = (double)(im - (long double)d.pole_im);
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
