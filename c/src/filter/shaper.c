/* SPDX-License-Identifier: Apache-2.0 */
/* Input shapers: validation, discretisation (paper rounding or exact split + least-norm
 * correction, docs/exact-mode.md) and the sparse FIR engine. */
#include <math.h>
#include <string.h>
#include "filter/shaper_designs.h"
#include "filter/input_smoother.h"
#include "filter/coeffs_check.h"
#include "filter/shaper_sample.h"
#include "core/state_identity.h"

static const double pi = 3.14159265358979323846;
/* Longest accepted shaper: state indices are saved as doubles and must stay exact. */
static const double max_length = 1099511627776.0; /* 2^40 */

/* A sparse impulse response, delays strictly increasing. */
typedef struct sparse {
    size_t n;
    size_t delay[SMS_SHAPER_MAX_TAPS];
    double gain[SMS_SHAPER_MAX_TAPS];
} sparse;

static int is_shaper(sms_kind kind)
{
    return (kind >= SMS_SHAPER_ZV && kind <= SMS_SHAPER_MZV) || kind == SMS_SHAPER_EI3
           || (kind >= SMS_SHAPER_GMZV && kind <= SMS_SHAPER_IMPULSES);
}

static int is_finite(double v)
{
    return v - v == 0.0;
}

/* User-defined impulses: a count, finite amplitudes of positive sum, finite times >= 0 that
 * strictly increase. */
static sms_status check_impulses(const sms_stage_config *c)
{
    double sum = 0.0;
    unsigned m;
    if (c->order < 1u || c->order > SMS_SHAPER_MAX_IMPULSES)
        return SMS_ERR_ORDER;
    for (m = 0; m < c->order; ++m) {
        if (!is_finite(c->amplitudes[m]))
            return SMS_ERR_IMPULSE_AMPLITUDE;
        sum += c->amplitudes[m];
    }
    if (!(sum > 0.0) || !is_finite(sum))
        return SMS_ERR_IMPULSE_AMPLITUDE;
    for (m = 0; m < c->order; ++m)
        if (!is_finite(c->times[m]) || c->times[m] < 0.0
            || (m > 0u && !(c->times[m] > c->times[m - 1u])))
            return SMS_ERR_IMPULSE_TIME;
    return SMS_OK;
}

/* Checks that do not need Ts (shared with sms_shaper_impulses). */
static sms_status check_fields(const sms_stage_config *c)
{
    if (c->kind == SMS_SHAPER_IMPULSES)
        return check_impulses(c);
    if (!is_finite(c->wn) || c->wn <= 0.0)
        return SMS_ERR_WN;
    if (sms_is_input_smoother(c->kind)) {     /* zeta only where the kernel depends on it */
        if (sms_input_smoother_reads_zeta(c->kind)
            && (!is_finite(c->zeta) || c->zeta < 0.0 || c->zeta > 0.25))
            return SMS_ERR_ZETA;
        return SMS_OK;
    }
    if (!is_finite(c->zeta) || c->zeta < 0.0 || c->zeta >= 1.0)
        return SMS_ERR_ZETA;
    if (c->kind == SMS_SHAPER_ZVN && (c->order < 1u || c->order > SMS_SHAPER_MAX_ORDER))
        return SMS_ERR_ORDER;
    if (c->kind == SMS_SHAPER_GMZV && (c->order < 3u || c->order > SMS_SHAPER_MAX_IMPULSES))
        return SMS_ERR_ORDER;
    if ((c->kind == SMS_SHAPER_EI || c->kind == SMS_SHAPER_EI2 || c->kind == SMS_SHAPER_EI3)
        && (!is_finite(c->tolerance) || c->tolerance <= 0.0 || c->tolerance >= 1.0))
        return SMS_ERR_TOLERANCE;
    if (c->kind == SMS_SHAPER_GMZV) {
        double amp[SMS_SHAPER_MAX_IMPULSES], units[SMS_SHAPER_MAX_IMPULSES];
        if (!is_finite(c->duration) || !sms_gmzv_undamped(c->order, c->duration, amp, units))
            return SMS_ERR_SHAPER_DURATION;
    }
    if (c->kind == SMS_SHAPER_SI) {
        double amp[SMS_SHAPER_MAX_IMPULSES], units[SMS_SHAPER_MAX_IMPULSES];
        if (c->order < 3u || c->order > SMS_SHAPER_MAX_IMPULSES || c->order % 2u == 0u)
            return SMS_ERR_ORDER;
        if (!is_finite(c->tolerance) || c->tolerance <= 0.0 || c->tolerance >= 1.0)
            return SMS_ERR_TOLERANCE;
        if (!sms_si_undamped(c->order, c->duration, c->tolerance, amp, units, NULL))
            return SMS_ERR_SHAPER_DURATION;
    }
    return SMS_OK;
}

/* The timings a kind has: the input smoothers are continuous kernels, realised one way. */
static int has_timing(const sms_stage_config *c)
{
    if (sms_is_input_smoother(c->kind))
        return c->timing == SMS_TIMING_EXACT;
    return c->timing == SMS_TIMING_EXACT || c->timing == SMS_TIMING_PAPER;
}

static sms_status check_config(const sms_stage_config *c, double Ts)
{
    sms_status st;
    if (!is_finite(Ts) || Ts <= 0.0)
        return SMS_ERR_SAMPLE_PERIOD;
    if (!is_shaper(c->kind) || !has_timing(c))
        return SMS_ERR_KIND;
    if (c->kind == SMS_SHAPER_IMPULSES)
        return check_impulses(c);
    if (!is_finite(c->wn) || c->wn <= 0.0)
        return SMS_ERR_WN;
    if (c->wn * Ts >= pi)
        return SMS_ERR_ABOVE_NYQUIST;
    st = check_fields(c);
    if (st != SMS_OK)
        return st;
    return SMS_OK;
}

/* Add g at delay d, keeping delays sorted and merging equal ones. Capacity is guaranteed by
 * the tap-count bound in shaper.h. */
static void sparse_add(sparse *s, size_t d, double g)
{
    size_t i = 0, j;
    while (i < s->n && s->delay[i] < d)
        ++i;
    if (i < s->n && s->delay[i] == d) {
        s->gain[i] += g;
        return;
    }
    for (j = s->n; j > i; --j) {
        s->delay[j] = s->delay[j - 1];
        s->gain[j] = s->gain[j - 1];
    }
    s->delay[i] = d;
    s->gain[i] = g;
    ++s->n;
}

/* docs/exact-mode.md integer test: mu is on the grid when within 1e-9 max(1, mu) of round(mu). */
static int on_grid(double mu, double *rounded)
{
    double r = floor(mu + 0.5);
    *rounded = r;
    return fabs(mu - r) <= 1e-9 * (mu > 1.0 ? mu : 1.0);
}

/* z^{-i} at z = exp(p Ts), p = -zeta wn + j wd: e^{zeta wn i Ts} (cos(wd i Ts) - j sin(wd i Ts)). */
static void z_inv_power(double sigma_ts, double wd_ts, size_t i, double *re, double *im)
{
    double mag = exp(-sigma_ts * (double)i), arg = wd_ts * (double)i;
    *re = mag * cos(arg);
    *im = -mag * sin(arg);
}

/* Solve the 3x3 system M y = r by Gaussian elimination with partial pivoting. */
static void solve3(double M[3][3], double r[3], double y[3])
{
    int i, j, k;
    for (k = 0; k < 3; ++k) {
        int p = k;
        for (i = k + 1; i < 3; ++i)
            if (fabs(M[i][k]) > fabs(M[p][k]))
                p = i;
        if (p != k) {
            double t;
            for (j = 0; j < 3; ++j) {
                t = M[k][j]; M[k][j] = M[p][j]; M[p][j] = t;
            }
            t = r[k]; r[k] = r[p]; r[p] = t;
        }
        for (i = k + 1; i < 3; ++i) {
            double f = M[i][k] / M[k][k];
            for (j = k; j < 3; ++j)
                M[i][j] -= f * M[k][j];
            r[i] -= f * r[k];
        }
    }
    for (i = 2; i >= 0; --i) {
        double acc = r[i];
        for (j = i + 1; j < 3; ++j)
            acc -= M[i][j] * y[j];
        y[i] = acc / M[i][i];
    }
}

/* Exact timing of one continuous design: linear split of off-grid impulses, then the
 * least-norm correction d on S = {0} + split indices with sum d = 0 and
 * sum d_i z^{-i} = H_c(p) - G(z_p), d = C^T (C C^T)^{-1} r. */
static void realise_exact(const double *amp, const double *time, size_t n_imp, double Ts,
                          double sigma, double wd, int correct, sparse *out)
{
    size_t support[2 * SMS_SHAPER_MAX_IMPULSES + 1], n_s = 1, m, i, j;
    double cr[2 * SMS_SHAPER_MAX_IMPULSES + 1], ci[2 * SMS_SHAPER_MAX_IMPULSES + 1];
    double hc_re = 0.0, hc_im = 0.0, g_re = 0.0, g_im = 0.0;
    double M[3][3], r[3], y[3];
    double sigma_ts = sigma * Ts, wd_ts = wd * Ts;
    out->n = 0;
    support[0] = 0;
    for (m = 0; m < n_imp; ++m) {
        double mu = time[m] / Ts, rounded;
        /* continuous H_c(p) = sum A e^{-p t} */
        double mag = exp(-sigma * time[m]), arg = wd * time[m];
        hc_re += amp[m] * mag * cos(arg);
        hc_im -= amp[m] * mag * sin(arg);
        if (on_grid(mu, &rounded)) {
            sparse_add(out, (size_t)rounded, amp[m]);
        } else {
            double m0 = floor(mu), f = mu - m0;
            size_t k0 = (size_t)m0;
            sparse_add(out, k0, amp[m] * (1.0 - f));
            sparse_add(out, k0 + 1u, amp[m] * f);
            for (j = 0; j < 2; ++j) {
                size_t idx = k0 + j;
                for (i = 0; i < n_s && support[i] != idx; ++i)
                    ;
                if (i == n_s)
                    support[n_s++] = idx;
            }
        }
    }
    /* No split: no correction. A split at m0 >= 1 gives |S| = 3. m0 = 0 (t < Ts) only happens
     * when the impulse spacing is below Ts (MZV's middle impulse when Td < 8/3 Ts, GMZV with
     * many impulses near Nyquist); the last impulse lies at >= Td/2 > Ts, so either it splits
     * at m0 >= 1 or it sits on a sample m >= 2 and the one before it, less than Ts earlier,
     * splits onto {m-1, m}: |S| >= 3 always, so C C^T is invertible. */
    if (n_s == 1 || !correct)
        return;
    for (i = 0; i < out->n; ++i) {
        double re, im;
        z_inv_power(sigma_ts, wd_ts, out->delay[i], &re, &im);
        g_re += out->gain[i] * re;
        g_im += out->gain[i] * im;
    }
    for (i = 0; i < n_s; ++i)
        z_inv_power(sigma_ts, wd_ts, support[i], &cr[i], &ci[i]);
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j)
            M[i][j] = 0.0;
    for (i = 0; i < n_s; ++i) {
        double row[3];
        row[0] = 1.0;
        row[1] = cr[i];
        row[2] = ci[i];
        for (m = 0; m < 3; ++m)
            for (j = 0; j < 3; ++j)
                M[m][j] += row[m] * row[j];
    }
    r[0] = 0.0;
    r[1] = hc_re - g_re;
    r[2] = hc_im - g_im;
    solve3(M, r, y);
    for (i = 0; i < n_s; ++i)
        sparse_add(out, support[i], y[0] + y[1] * cr[i] + y[2] * ci[i]);
}

static void realise_paper(const double *amp, const double *time, size_t n_imp, double Ts,
                          sparse *out)
{
    size_t m;
    out->n = 0;
    for (m = 0; m < n_imp; ++m)
        sparse_add(out, (size_t)floor(time[m] / Ts + 0.5), amp[m]);
}

static void convolve(const sparse *a, const sparse *b, sparse *out)
{
    size_t i, j;
    out->n = 0;
    for (i = 0; i < a->n; ++i)
        for (j = 0; j < b->n; ++j)
            sparse_add(out, a->delay[i] + b->delay[j], a->gain[i] * b->gain[j]);
}

/* The discrete taps of a config already validated by check_config. */
static sms_status realise(const sms_stage_config *c, double Ts, sparse *out)
{
    double amp[SMS_SHAPER_MAX_IMPULSES], time[SMS_SHAPER_MAX_IMPULSES];
    double sigma = -c->zeta * c->wn, wd = c->wn * sqrt(1.0 - c->zeta * c->zeta);
    unsigned order = sms_shaper_zv_order(c);
    size_t n_imp = sms_shaper_design(c, amp, time);
    if (time[n_imp - 1] / Ts + 2.0 > max_length)
        return SMS_ERR_TOO_LONG;
    if (c->timing == SMS_TIMING_PAPER) {
        realise_paper(amp, time, n_imp, Ts, out);
    } else if (c->kind == SMS_SHAPER_IMPULSES) {
        /* no mode to pin: the linear split alone (keeps sum 1 and the centroid exactly) */
        realise_exact(amp, time, n_imp, Ts, 0.0, 0.0, 0, out);
    } else if (order > 0u) {
        /* ZV^n: n-fold convolution of the exact ZV, a zero of multiplicity n at e^{p Ts}. */
        sms_stage_config zv = *c;
        sparse single, acc;
        unsigned m;
        zv.kind = SMS_SHAPER_ZV;
        n_imp = sms_shaper_design(&zv, amp, time);
        realise_exact(amp, time, n_imp, Ts, sigma, wd, 1, &single);
        *out = single;
        for (m = 1; m < order; ++m) {
            acc = *out;
            convolve(&acc, &single, out);
        }
    } else {
        realise_exact(amp, time, n_imp, Ts, sigma, wd, 1, out);
    }
    /* Exact timing weighs the impulses with z^-i = e^{zeta wn i Ts}...: for zeta near 1 over a
     * long span that overflows (while K^m underflows), and the correction is not a number.
     * Refuse the mode instead of returning NaN taps (paper timing still realises it). */
    {
        size_t i;
        for (i = 0; i < out->n; ++i)
            if (!is_finite(out->gain[i]))
                return SMS_ERR_ZETA;
    }
    return SMS_OK;
}

static sms_status build(const sms_stage_config *config, double Ts, sparse *taps)
{
    sms_status st;
    if (config == NULL)
        return SMS_ERR_NULL;
    st = check_config(config, Ts);
    if (st != SMS_OK)
        return st;
    return realise(config, Ts, taps);
}

/* An input smoother's length L (its tap count too: every sample of the window is a tap). */
static sms_status smoother_length(const sms_stage_config *config, double Ts, size_t *length)
{
    sms_status st;
    if (config == NULL)
        return SMS_ERR_NULL;
    st = check_config(config, Ts);
    if (st != SMS_OK)
        return st;
    return sms_input_smoother_length(config, Ts, length);
}

sms_status sms_shaper_sizes(const sms_stage_config *config, double Ts, size_t *n_reals,
                            size_t *n_taps)
{
    sparse taps;
    sms_status st;
    if (n_reals == NULL || n_taps == NULL)
        return SMS_ERR_NULL;
    if (config != NULL && sms_is_input_smoother(config->kind)) {
        size_t length;
        st = smoother_length(config, Ts, &length);
        if (st == SMS_OK)
            *n_reals = *n_taps = length;
        return st;
    }
    st = build(config, Ts, &taps);
    if (st == SMS_OK) {
        *n_reals = taps.delay[taps.n - 1] + 1u;
        *n_taps = taps.n;
    }
    return st;
}

sms_status sms_shaper_buffer_size(const sms_stage_config *config, double Ts, size_t *n_reals)
{
    size_t n_taps;
    return sms_shaper_sizes(config, Ts, n_reals, &n_taps);
}

sms_status sms_shaper_tap_count(const sms_stage_config *config, double Ts, size_t *n_taps)
{
    size_t n_reals;
    return sms_shaper_sizes(config, Ts, &n_reals, n_taps);
}

sms_status sms_shaper_abs_gain(const sms_stage_config *config, double Ts, double *abs_sum)
{
    sparse design;
    double sum = 0.0;
    size_t i;
    sms_status st;
    if (config != NULL && sms_is_input_smoother(config->kind)) {
        size_t length;
        st = smoother_length(config, Ts, &length);
        if (st != SMS_OK)
            return st;
        return sms_input_smoother_taps(config, Ts, length, NULL, NULL, abs_sum) ? SMS_OK
                                                                                : SMS_ERR_ZETA;
    }
    st = build(config, Ts, &design);
    if (st != SMS_OK)
        return st;
    for (i = 0; i < design.n; ++i)   /* as coeffs_of_design() rounds them, in tap order */
        sum += fabs((double)(sms_real)design.gain[i]);
    *abs_sum = sum;
    return SMS_OK;
}

/* A design's taps into the caller's table and its coefficients pointing at them. */
static void coeffs_of_design(const sms_stage_config *config, double Ts, const sparse *design,
                             sms_stage_coeffs *coeffs, sms_shaper_tap *taps)
{
    size_t i;
    for (i = 0; i < design->n; ++i) {
        taps[i].delay = design->delay[i];
        taps[i].gain = (sms_real)design->gain[i];
    }
    coeffs->kind = config->kind;
    sms_state_identity(config, Ts, coeffs->identity);
    coeffs->u.shaper.length = design->delay[design->n - 1] + 1u;
    coeffs->u.shaper.n_taps = design->n;
    coeffs->u.shaper.taps = taps;
}

/* An input smoother's L taps (delays 0 .. L-1) into the caller's table and its coefficients
 * pointing at them; SMS_ERR_ZETA (nothing written) if the correction is not a number. */
static sms_status smoother_coeffs(const sms_stage_config *config, double Ts, size_t length,
                                  sms_stage_coeffs *coeffs, sms_shaper_tap *taps)
{
    if (!sms_input_smoother_taps(config, Ts, length, taps, NULL, NULL))
        return SMS_ERR_ZETA;
    coeffs->kind = config->kind;
    sms_state_identity(config, Ts, coeffs->identity);
    coeffs->u.shaper.length = length;
    coeffs->u.shaper.n_taps = length;
    coeffs->u.shaper.taps = taps;
    return SMS_OK;
}

sms_status sms_shaper_coeffs_make(const sms_stage_config *config, double Ts,
                                  sms_stage_coeffs *coeffs, sms_shaper_tap *taps, size_t n_taps)
{
    sparse design;
    sms_status st;
    if (config != NULL && sms_is_input_smoother(config->kind)) {
        size_t length;
        st = smoother_length(config, Ts, &length);
        if (st != SMS_OK)
            return st;
        if (taps == NULL)
            return SMS_ERR_NULL;
        if (n_taps < length)
            return SMS_ERR_BUFFER_TOO_SMALL;
        return smoother_coeffs(config, Ts, length, coeffs, taps);
    }
    st = build(config, Ts, &design);
    if (st != SMS_OK)
        return st;
    if (taps == NULL)
        return SMS_ERR_NULL;
    if (n_taps < design.n)
        return SMS_ERR_BUFFER_TOO_SMALL;
    coeffs_of_design(config, Ts, &design, coeffs, taps);
    return SMS_OK;
}

/* What sms_shaper_coeffs_make() can write (integer and sms_real tests only). */
sms_status sms_shaper_coeffs_check(const sms_stage_coeffs *coeffs)
{
    const sms_shaper_coeffs *c = &coeffs->u.shaper;
    size_t i;
    if (!is_shaper(coeffs->kind))
        return SMS_ERR_KIND;
    if (sms_is_input_smoother(coeffs->kind)) {
        /* every sample of the window a tap: delays 0 .. L-1, 5 <= L <= the cap (the kernel
         * spans at least 4 samples) */
        if (c->taps == NULL || c->n_taps < 5u || c->n_taps > SMS_INPUT_SMOOTHER_MAX_LENGTH
            || c->length != c->n_taps)
            return SMS_ERR_COEFFS;
        for (i = 0; i < c->n_taps; ++i)
            if (c->taps[i].delay != i || c->taps[i].gain - c->taps[i].gain != (sms_real)0)
                return SMS_ERR_COEFFS;
        return SMS_OK;
    }
    if (c->taps == NULL || c->n_taps < 1u || c->n_taps > SMS_SHAPER_MAX_TAPS)
        return SMS_ERR_COEFFS;
    for (i = 0; i < c->n_taps; ++i) {
        if (i > 0u && c->taps[i].delay <= c->taps[i - 1u].delay)
            return SMS_ERR_COEFFS;
        if (c->taps[i].gain - c->taps[i].gain != (sms_real)0)
            return SMS_ERR_COEFFS;
    }
    /* the longest design is below 2^40 samples (saved indices stay exact doubles) */
    if (c->taps[c->n_taps - 1u].delay >= ((size_t)1 << 20) * ((size_t)1 << 20) - 1u
        || c->length != c->taps[c->n_taps - 1u].delay + 1u)
        return SMS_ERR_COEFFS;
    return SMS_OK;
}

sms_status sms_shaper_init_coeffs(sms_shaper *f, const sms_stage_coeffs *coeffs,
                                  sms_shaper_tap *taps, size_t n_taps, sms_real *buffer,
                                  size_t n_reals)
{
    const sms_shaper_coeffs *c;
    sms_shaper built;
    size_t i;
    sms_status st;
    if (f == NULL || coeffs == NULL)
        return SMS_ERR_NULL;
    st = sms_shaper_coeffs_check(coeffs);
    if (st != SMS_OK)
        return st;
    c = &coeffs->u.shaper;
    if (taps == NULL || buffer == NULL)
        return SMS_ERR_NULL;
    if (n_taps < c->n_taps || n_reals < c->length)
        return SMS_ERR_BUFFER_TOO_SMALL;
    if (taps != c->taps)
        for (i = 0; i < c->n_taps; ++i)
            taps[i] = c->taps[i];
    built.kind = coeffs->kind;
    built.length = c->length;
    built.n_taps = c->n_taps;
    built.taps = taps;
    built.history = buffer;
    built.history_len = c->length;
    for (i = 0; i < SMS_STATE_IDENTITY_COUNT; ++i)
        built.identity[i] = coeffs->identity[i];
    *f = built;
    sms_shaper_reset(f, (sms_real)0);
    return SMS_OK;
}

sms_status sms_shaper_init(sms_shaper *f, const sms_stage_config *config, double Ts,
                           sms_shaper_tap *taps, size_t n_taps, sms_real *buffer, size_t n_reals)
{
    sms_stage_coeffs coeffs;
    sparse design;
    sms_status st;
    if (f == NULL)
        return SMS_ERR_NULL;
    if (config != NULL && sms_is_input_smoother(config->kind)) {
        size_t length;
        st = smoother_length(config, Ts, &length);
        if (st != SMS_OK)
            return st;
        if (taps == NULL || buffer == NULL)
            return SMS_ERR_NULL;
        if (n_taps < length || n_reals < length)
            return SMS_ERR_BUFFER_TOO_SMALL;
        st = smoother_coeffs(config, Ts, length, &coeffs, taps);
        if (st != SMS_OK)
            return st;
        return sms_shaper_init_coeffs(f, &coeffs, taps, n_taps, buffer, n_reals);
    }
    st = build(config, Ts, &design);
    if (st != SMS_OK)
        return st;
    if (taps == NULL || buffer == NULL)
        return SMS_ERR_NULL;
    if (n_taps < design.n || n_reals < design.delay[design.n - 1] + 1u)
        return SMS_ERR_BUFFER_TOO_SMALL;
    coeffs_of_design(config, Ts, &design, &coeffs, taps);
    return sms_shaper_init_coeffs(f, &coeffs, taps, n_taps, buffer, n_reals);
}

void sms_shaper_reset(sms_shaper *f, sms_real rest)
{
    size_t i;
    for (i = 0; i < f->history_len; ++i)
        f->history[i] = rest;
    f->rest = rest;
    f->head = 0;
}

/* The ring index and the tap table stay in locals for the whole block. */
SMS_FEW_TAPS void sms_shaper_process(sms_shaper *f, const sms_real *in, sms_real *out, size_t n)
{
    const size_t len = f->history_len, n_taps = f->n_taps;
    const sms_shaper_tap *taps = f->taps;
    sms_real *ring = f->history;
    size_t i, head = f->head;
    for (i = 0; i < n; ++i) {
        out[i] = sms_shaper_sample(taps, n_taps, ring, head, len, in[i]);
        head = head + 1u == len ? 0u : head + 1u;
    }
    f->head = head;
}

SMS_FEW_TAPS void sms_shaper_step(sms_shaper *f, sms_real *x)
{
    sms_shaper_step_inline(f, x);
}

size_t sms_shaper_state_count(const sms_shaper *f)
{
    return SMS_STATE_IDENTITY_COUNT + f->history_len + 4u;
}

void sms_shaper_get_state(const sms_shaper *f, double *dst)
{
    size_t i;
    for (i = 0; i < SMS_STATE_IDENTITY_COUNT; ++i)
        dst[i] = f->identity[i];
    dst += SMS_STATE_IDENTITY_COUNT;
    dst[0] = (double)f->kind;
    dst[1] = (double)f->history_len;
    dst[2] = (double)f->head;
    dst[3] = (double)f->rest;
    for (i = 0; i < f->history_len; ++i)
        dst[4 + i] = (double)f->history[i];
}

sms_status sms_shaper_check_state(const sms_shaper *f, const double *src, size_t n)
{
    sms_status id;
    if (f == NULL || src == NULL)
        return SMS_ERR_NULL;
    if (n >= SMS_STATE_IDENTITY_COUNT
        && (id = sms_state_identity_check(f->identity, src)) != SMS_OK)
        return id;
    if (n != sms_shaper_state_count(f))
        return SMS_ERR_STATE;
    src += SMS_STATE_IDENTITY_COUNT;
    if (src[0] != (double)f->kind
        || src[1] != (double)f->history_len)
        return SMS_ERR_STATE;
    /* head: an integer in [0, L) (the negated test also rejects NaN) */
    if (!(src[2] >= 0.0 && src[2] < (double)f->history_len) || src[2] != floor(src[2]))
        return SMS_ERR_STATE;
    return SMS_OK;
}

sms_status sms_shaper_check_state_range(const sms_shaper *f, const double *src, size_t n,
                                        double x_max)
{
    size_t i;
    sms_status st = sms_shaper_check_state(f, src, n);
    if (st != SMS_OK)
        return st;
    /* the rest and the delay line hold inputs as they came (finite: NaN fails the test) */
    src += SMS_STATE_IDENTITY_COUNT;
    for (i = 3; i < 4 + f->history_len; ++i)
        if (!(fabs(src[i]) <= x_max))
            return SMS_ERR_STATE;
    return SMS_OK;
}

sms_status sms_shaper_set_state(sms_shaper *f, const double *src, size_t n)
{
    size_t i;
    sms_status st = sms_shaper_check_state(f, src, n);
    if (st != SMS_OK)
        return st;
    src += SMS_STATE_IDENTITY_COUNT;
    f->head = (size_t)src[2];
    f->rest = (sms_real)src[3];
    for (i = 0; i < f->history_len; ++i)
        f->history[i] = (sms_real)src[4 + i];
    return SMS_OK;
}

sms_status sms_shaper_impulses(const sms_stage_config *config, double *amplitudes,
                               double *times, size_t capacity, size_t *count)
{
    double amp[SMS_SHAPER_MAX_IMPULSES], time[SMS_SHAPER_MAX_IMPULSES];
    size_t n, i;
    sms_status st;
    if (config == NULL || amplitudes == NULL || times == NULL || count == NULL)
        return SMS_ERR_NULL;
    /* an input smoother is a kernel, not impulses */
    if (!is_shaper(config->kind) || sms_is_input_smoother(config->kind) || !has_timing(config))
        return SMS_ERR_KIND;
    st = check_fields(config);
    if (st != SMS_OK)
        return st;
    n = sms_shaper_design(config, amp, time);
    if (capacity < n)
        return SMS_ERR_BUFFER_TOO_SMALL;
    /* A period beyond double (wn sqrt(1 - zeta^2) below ~1e-308) has no finite impulse times. */
    for (i = 0; i < n; ++i)
        if (!is_finite(time[i]))
            return SMS_ERR_TOO_LONG;
    for (i = 0; i < n; ++i) {
        amplitudes[i] = amp[i];
        times[i] = time[i];
    }
    *count = n;
    return SMS_OK;
}

sms_status sms_shaper_taps(const sms_stage_config *config, double Ts, double *taps, size_t n_taps)
{
    sparse s;
    size_t i, len;
    sms_status st;
    if (taps == NULL)
        return SMS_ERR_NULL;
    if (config != NULL && sms_is_input_smoother(config->kind)) {
        st = smoother_length(config, Ts, &len);
        if (st != SMS_OK)
            return st;
        if (n_taps < len)
            return SMS_ERR_BUFFER_TOO_SMALL;
        return sms_input_smoother_taps(config, Ts, len, NULL, taps, NULL) ? SMS_OK : SMS_ERR_ZETA;
    }
    st = build(config, Ts, &s);
    if (st != SMS_OK)
        return st;
    len = s.delay[s.n - 1] + 1u;
    if (n_taps < len)
        return SMS_ERR_BUFFER_TOO_SMALL;
    for (i = 0; i < len; ++i)
        taps[i] = 0.0;
    for (i = 0; i < s.n; ++i)
        taps[s.delay[i]] = s.gain[i];
    return SMS_OK;
}

sms_status sms_shaper_transfer(const sms_stage_config *config, double s_re, double s_im,
                               double *h_re, double *h_im)
{
    double amp[SMS_SHAPER_MAX_IMPULSES], time[SMS_SHAPER_MAX_IMPULSES], re = 0.0, im = 0.0;
    size_t n, m;
    sms_status st;
    if (config == NULL || h_re == NULL || h_im == NULL)
        return SMS_ERR_NULL;
    if (!is_shaper(config->kind) || !has_timing(config))
        return SMS_ERR_KIND;
    st = check_fields(config);
    if (st != SMS_OK)
        return st;
    if (!is_finite(s_re) || !is_finite(s_im))
        return SMS_ERR_WN;
    if (sms_is_input_smoother(config->kind)) {
        sms_input_smoother_transfer(config, s_re, s_im, &re, &im);
    } else {
        n = sms_shaper_design(config, amp, time);
        for (m = 0; m < n; ++m) {
            double mag = exp(-s_re * time[m]);
            re += amp[m] * mag * cos(s_im * time[m]);
            im -= amp[m] * mag * sin(s_im * time[m]);
        }
    }
    if (!is_finite(re) || !is_finite(im))
        return SMS_ERR_TOO_LONG;
    *h_re = re;
    *h_im = im;
    return SMS_OK;
}

sms_status sms_shaper_lag(const sms_stage_config *config, double Ts, double *lag)
{
    sparse s;
    double sum = 0.0, moment = 0.0;
    size_t i;
    sms_status st;
    if (config != NULL && sms_is_input_smoother(config->kind)) {
        /* no sparse design: the correction pins the taps' sum to 1 and their centroid to the
         * kernel's, int g(tau) tau dtau / Ts (sms_input_smoother_taps) */
        size_t length;
        st = smoother_length(config, Ts, &length);
        if (st == SMS_OK)
            *lag = sms_input_smoother_lag(config, Ts);
        return st;
    }
    st = build(config, Ts, &s);
    if (st != SMS_OK)
        return st;
    for (i = 0; i < s.n; ++i) {
        sum += s.gain[i];
        moment += (double)s.delay[i] * s.gain[i];
    }
    *lag = moment / sum;
    return SMS_OK;
}
