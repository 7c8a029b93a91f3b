/* SPDX-License-Identifier: Apache-2.0 */
/* Notch biquad: Tustin (pre-warped at wn) or pole-zero matched coefficients, and the
 * direct-form-I recursion with non-finite recovery (notch.h). */
#include <float.h>
#include <math.h>
#include "smoothshaper/coeffs.h"
#include "filter/coeffs_check.h"
#include "core/state_identity.h"

static const double pi = 3.14159265358979323846;

/* Below this |w| the transient counts as over (notch.h): the smallest normal number over the
 * machine epsilon, so products of normal operands never reach the subnormals first. */
#ifdef SMS_USE_FLOAT
#define TINY ((sms_real)(FLT_MIN / FLT_EPSILON))
#define LOG_RANGE 160.0   /* ln(FLT_MAX / TINY) */
#else
#define TINY ((sms_real)(DBL_MIN / DBL_EPSILON))
#define LOG_RANGE 1382.0  /* ln(DBL_MAX / TINY) */
#endif

static int is_finite(double v)
{
    return v - v == 0.0;
}

static sms_status check(const sms_stage_config *c, double Ts)
{
    if (!is_finite(Ts) || Ts <= 0.0)
        return SMS_ERR_SAMPLE_PERIOD;
    if (c->kind != SMS_NOTCH_TUSTIN && c->kind != SMS_NOTCH_MATCHED)
        return SMS_ERR_KIND;
    if (!is_finite(c->wn) || c->wn <= 0.0)
        return SMS_ERR_WN;
    if (c->wn * Ts >= pi)
        return SMS_ERR_ABOVE_NYQUIST;
    /* wn Ts must be a normal double: the design divides by it (a notch 1e-308 of the sample
     * rate is no filter anyone can realise). */
    if (!(c->wn * Ts >= DBL_MIN))
        return SMS_ERR_WN;
    if (!is_finite(c->zeta) || c->zeta < 0.0 || c->zeta >= 1.0)
        return SMS_ERR_ZETA;
    if (!is_finite(c->notch_pole_zeta) || c->notch_pole_zeta <= c->zeta
        || c->notch_pole_zeta > SMS_NOTCH_MAX_POLE_ZETA)
        return SMS_ERR_NOTCH_DAMPING;
    return SMS_OK;
}

/* Monic second-order polynomial 1 + c1 z^-1 + c2 z^-2 whose roots are exp(s Ts) for the roots s
 * of s^2 + 2 xi wn s + wn^2. */
static void matched_section(double wn, double xi, double Ts, double *c1, double *c2)
{
    if (xi < 1.0) {
        double r = exp(-xi * wn * Ts), th = wn * sqrt(1.0 - xi * xi) * Ts;
        *c1 = -2.0 * r * cos(th);
        *c2 = r * r;
    } else {
        /* real roots; the small one without cancellation: s1 s2 = wn^2 */
        double q = xi + sqrt((xi - 1.0) * (xi + 1.0));
        double p1 = exp(-wn / q * Ts), p2 = exp(-wn * q * Ts);
        *c1 = -(p1 + p2);
        *c2 = p1 * p2;
    }
}

/* (1 + c1 + c2)/(wn Ts)^2 of matched_section, the section's DC value scaled so that it neither
 * cancels nor underflows for a mode far below the sample rate: 1 - 2 r cos th + r^2 =
 * (1 - r)^2 + 4 r sin^2(th/2), and (1 - p1)(1 - p2) for real roots. */
static double matched_dc_scaled(double wn, double xi, double Ts)
{
    double e = wn * Ts;
    if (xi < 1.0) {
        double r = exp(-xi * e), half = 0.5 * sqrt(1.0 - xi * xi);
        double u = expm1(-xi * e) / e, v = half > 0.0 ? sin(half * e) / e : 0.0;
        return u * u + 4.0 * r * v * v;
    } else {
        double q = xi + sqrt((xi - 1.0) * (xi + 1.0));
        return (expm1(-e / q) / e) * (expm1(-e * q) / e);
    }
}

sms_status sms_notch_coeffs_make(const sms_stage_config *config, double Ts,
                                 sms_stage_coeffs *coeffs)
{
    double d0, d2, a1, a2;
    sms_status st = check(config, Ts);
    if (st != SMS_OK)
        return st;
    if (config->kind == SMS_NOTCH_TUSTIN) {
        /* b - a = [2 (xi1 - xi2) t, 0, 2 (xi2 - xi1) t] / a0, without cancellation */
        double t = tan(0.5 * config->wn * Ts), t2 = t * t;
        double xi1 = config->zeta, xi2 = config->notch_pole_zeta;
        double a0 = 1.0 + 2.0 * xi2 * t + t2;
        d0 = 2.0 * (xi1 - xi2) * t / a0;
        d2 = -d0;
        a1 = 2.0 * (t2 - 1.0) / a0;
        a2 = (1.0 - 2.0 * xi2 * t + t2) / a0;
    } else {
        /* b = g [1, n1, n2], g = A(1)/N(1) */
        double n1, n2, g;
        matched_section(config->wn, config->zeta, Ts, &n1, &n2);
        matched_section(config->wn, config->notch_pole_zeta, Ts, &a1, &a2);
        g = matched_dc_scaled(config->wn, config->notch_pole_zeta, Ts)
            / matched_dc_scaled(config->wn, config->zeta, Ts);
        d0 = g - 1.0;
        d2 = g * n2 - a2;
    }
    /* H = 1 + (1 - z^-1)(d0 - d2 z^-1)/A: unit DC gain by structure (notch.h) */
    coeffs->kind = config->kind;
    sms_state_identity(config, Ts, coeffs->identity);
    coeffs->u.notch.d0 = (sms_real)d0;
    coeffs->u.notch.d2 = (sms_real)d2;
    coeffs->u.notch.a1 = (sms_real)a1;
    coeffs->u.notch.a2 = (sms_real)a2;
    return SMS_OK;
}

/* What sms_notch_coeffs_make() can write (sms_real tests only). */
sms_status sms_notch_coeffs_check(const sms_stage_coeffs *coeffs)
{
    const sms_notch_coeffs *c = &coeffs->u.notch;
    if (coeffs->kind != SMS_NOTCH_TUSTIN && coeffs->kind != SMS_NOTCH_MATCHED)
        return SMS_ERR_KIND;
    if (c->d0 - c->d0 != 0 || c->d2 - c->d2 != 0 || c->a1 - c->a1 != 0 || c->a2 - c->a2 != 0)
        return SMS_ERR_COEFFS;
    return SMS_OK;
}

sms_status sms_notch_init_coeffs(sms_notch *f, const sms_stage_coeffs *coeffs)
{
    sms_notch built;
    size_t i;
    sms_status st;
    if (f == NULL || coeffs == NULL)
        return SMS_ERR_NULL;
    st = sms_notch_coeffs_check(coeffs);
    if (st != SMS_OK)
        return st;
    built.kind = coeffs->kind;
    built.d0 = coeffs->u.notch.d0;
    built.d2 = coeffs->u.notch.d2;
    built.a1 = coeffs->u.notch.a1;
    built.a2 = coeffs->u.notch.a2;
    for (i = 0; i < SMS_STATE_IDENTITY_COUNT; ++i)
        built.identity[i] = coeffs->identity[i];
    *f = built;
    sms_notch_reset(f, (sms_real)0);
    return SMS_OK;
}

sms_status sms_notch_init(sms_notch *f, const sms_stage_config *config, double Ts)
{
    sms_stage_coeffs coeffs;
    sms_status st;
    if (f == NULL || config == NULL)
        return SMS_ERR_NULL;
    st = sms_notch_coeffs_make(config, Ts, &coeffs);
    if (st != SMS_OK)
        return st;
    return sms_notch_init_coeffs(f, &coeffs);
}

void sms_notch_reset(sms_notch *f, sms_real rest)
{
    f->x1 = f->x2 = rest;
    f->w1 = f->w2 = 0;
    f->rest = rest;
}

/* One sample of the state (x1, x2, w1, w2); the output. */
static sms_real notch_sample(sms_real d0, sms_real d2, sms_real a1, sms_real a2,
                             sms_real *x1, sms_real *x2, sms_real *w1, sms_real *w2,
                             sms_real v)
{
    sms_real w = d0 * (v - *x1) + d2 * (*x2 - *x1) - a1 * *w1 - a2 * *w2;
    sms_real y;
    /* The transient ends exactly: once w and its previous value are both below TINY, the
     * recursion state is set to zero (a fixed point under a constant input), so a held
     * input is absorbed in a bounded number of samples instead of decaying through the
     * subnormals, where rounding to a fixed quantum can sustain a cycle. */
    if (w < TINY && w > -TINY && *w1 < TINY && *w1 > -TINY) {
        w = 0;
        *w1 = 0;
    }
    y = v + w;
    if (y - y != 0) {
        /* Non-finite: a bad input sample is skipped (passed through, state kept); a finite
         * input with a non-finite result (overflow, bad loaded state) restarts at rest
         * there. */
        if (v - v == 0) {
            *x1 = *x2 = v;
            *w1 = *w2 = 0;
        }
        return v;
    }
    *x2 = *x1;
    *x1 = v;
    *w2 = *w1;
    *w1 = w;
    return y;
}

/* The state lives in locals for the whole block (the instance is read and written once). */
void sms_notch_process(sms_notch *f, const sms_real *in, sms_real *out, size_t n)
{
#ifdef __OPTIMIZE_SIZE__
    /* A size-optimised build (-Os, firmware) keeps one copy of the recursion: the step's,
     * with the state in the instance; the same operations, so the same bits. */
    size_t i;
    for (i = 0; i < n; ++i) {
        out[i] = in[i];
        sms_notch_step(f, &out[i]);
    }
#else
    const sms_real d0 = f->d0, d2 = f->d2, a1 = f->a1, a2 = f->a2;
    sms_real x1 = f->x1, x2 = f->x2, w1 = f->w1, w2 = f->w2;
    size_t i;
    for (i = 0; i < n; ++i)
        out[i] = notch_sample(d0, d2, a1, a2, &x1, &x2, &w1, &w2, in[i]);
    f->x1 = x1;
    f->x2 = x2;
    f->w1 = w1;
    f->w2 = w2;
#endif
}

void sms_notch_step(sms_notch *f, sms_real *x)
{
    *x = notch_sample(f->d0, f->d2, f->a1, f->a2, &f->x1, &f->x2, &f->w1, &f->w2, *x);
}

size_t sms_notch_state_count(const sms_notch *f)
{
    (void)f;
    return SMS_STATE_IDENTITY_COUNT + 6u;
}

void sms_notch_get_state(const sms_notch *f, double *dst)
{
    size_t i;
    for (i = 0; i < SMS_STATE_IDENTITY_COUNT; ++i)
        dst[i] = f->identity[i];
    dst += SMS_STATE_IDENTITY_COUNT;
    dst[0] = (double)f->kind;
    dst[1] = (double)f->x1;
    dst[2] = (double)f->x2;
    dst[3] = (double)f->w1;
    dst[4] = (double)f->w2;
    dst[5] = (double)f->rest;
}

sms_status sms_notch_check_state(const sms_notch *f, const double *src, size_t n)
{
    sms_status id;
    if (f == NULL || src == NULL)
        return SMS_ERR_NULL;
    if (n >= SMS_STATE_IDENTITY_COUNT
        && (id = sms_state_identity_check(f->identity, src)) != SMS_OK)
        return id;
    if (n != sms_notch_state_count(f) || src[SMS_STATE_IDENTITY_COUNT] != (double)f->kind)
        return SMS_ERR_STATE;
    return SMS_OK;
}

sms_status sms_notch_check_state_range(const sms_notch *f, const double *src, size_t n,
                                       double x_max, double w_max)
{
    sms_status st = sms_notch_check_state(f, src, n);
    if (st != SMS_OK)
        return st;
    /* x1, x2, rest: inputs as they came; w1, w2: the recursion (finite: NaN fails the test) */
    src += SMS_STATE_IDENTITY_COUNT;
    if (!(fabs(src[1]) <= x_max && fabs(src[2]) <= x_max && fabs(src[5]) <= x_max))
        return SMS_ERR_STATE;
    if (!(fabs(src[3]) <= w_max && fabs(src[4]) <= w_max))
        return SMS_ERR_STATE;
    return SMS_OK;
}

sms_status sms_notch_set_state(sms_notch *f, const double *src, size_t n)
{
    sms_status st = sms_notch_check_state(f, src, n);
    if (st != SMS_OK)
        return st;
    src += SMS_STATE_IDENTITY_COUNT;
    f->x1 = (sms_real)src[1];
    f->x2 = (sms_real)src[2];
    f->w1 = (sms_real)src[3];
    f->w2 = (sms_real)src[4];
    f->rest = (sms_real)src[5];
    return SMS_OK;
}

sms_status sms_notch_pole_zeta_from_bandwidth(double wn, double zeta, double bandwidth,
                                              double *pole_zeta)
{
    double c, xi2;
    if (pole_zeta == NULL)
        return SMS_ERR_NULL;
    if (!is_finite(wn) || wn <= 0.0)
        return SMS_ERR_WN;
    if (!is_finite(zeta) || zeta < 0.0 || zeta >= 1.0)
        return SMS_ERR_ZETA;
    if (!is_finite(bandwidth) || bandwidth <= 0.0)
        return SMS_ERR_BANDWIDTH;
    c = bandwidth / (2.0 * wn);
    xi2 = hypot(c, sqrt(2.0) * zeta);
    /* A band so narrow (or so wide) that xi2 rounds onto zeta (or overflows) is no notch. */
    if (!(xi2 <= SMS_NOTCH_MAX_POLE_ZETA) || !(xi2 > zeta))
        return SMS_ERR_BANDWIDTH;
    *pole_zeta = xi2;
    return SMS_OK;
}

double sms_notch_settle_bound(const sms_notch *f)
{
    const double a1 = (double)f->a1, a2 = (double)f->a2, disc = a1 * a1 - 4.0 * a2;
    double decay; /* -ln of the largest pole radius */
    if (disc < 0.0) {
        decay = -0.5 * log(a2);
    } else {
        const double root = sqrt(disc);
        const double big = fabs(-a1 + (a1 < 0.0 ? root : -root)) / 2.0;
        decay = -log(big);
    }
    if (!(decay > 0.0))
        return HUGE_VAL;
    /* r^n takes LOG_RANGE/decay samples from the largest number to TINY; twice that covers
     * the factor (n + 1) of two close poles and the rounding of the recursion */
    return 2.0 * LOG_RANGE / decay + 4.0;
}

int sms_notch_is_settled(const sms_notch *f, sms_real x)
{
    return f->x1 == x && f->x2 == x && f->w1 == 0 && f->w2 == 0 && !signbit(f->w1)
           && !signbit(f->w2);
}
