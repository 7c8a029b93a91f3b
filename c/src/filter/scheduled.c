/* SPDX-License-Identifier: Apache-2.0 */
/* The scheduled ZV^n shaper of scheduled.h: the schedule table, the exact ZV of the current
 * pole in closed form (exponentials by series: no libm on the per-sample path), its n-fold
 * convolution, and the filter over one ring. */
#include <math.h>
#include "smoothshaper/scheduled.h"

static const double pi = 3.14159265358979323846;

static int is_finite(double v)
{
    return v - v == 0.0;
}

/* ZV^n order of a kind; 0 if it is not one. */
static unsigned zv_order(const sms_scheduled_config *c)
{
    switch (c->kind) {
    case SMS_SHAPER_ZV: return 1u;
    case SMS_SHAPER_ZVD: return 2u;
    case SMS_SHAPER_ZVDD: return 3u;
    case SMS_SHAPER_ZVN: return c->order >= 1u && c->order <= SMS_SHAPER_MAX_ORDER ? c->order : 0u;
    default: return 0u;
    }
}

/* ---- exponentials without libm (Cody-Waite reduction and Taylor series) ---------------- */

/* e^x for |x| <= 700: x = k ln 2 + r, |r| <= ln 2 / 2, e^r by its series to degree 16
 * (remainder below 1e-19 relative), times 2^k. */
static double exp_series(double x)
{
    static const double ln2_hi = 6.93147180369123816490e-01, ln2_lo = 1.90821492927058770002e-10;
    const double kd = x >= 0.0 ? (double)(long)(x / 0.6931471805599453 + 0.5)
                               : -(double)(long)(-x / 0.6931471805599453 + 0.5);
    const double r = (x - kd * ln2_hi) - kd * ln2_lo;
    double term = 1.0, sum = 1.0, scale = 1.0;
    long k = (long)kd, i;
    for (i = 1; i <= 16; ++i) {
        term *= r / (double)i;
        sum += term;
    }
    for (; k > 0; --k)
        scale *= 2.0;
    for (; k < 0; ++k)
        scale *= 0.5;
    return sum * scale;
}

/* cos b and sin b for |b| <= 2 pi: b = q pi/2 + r, |r| <= pi/4, series to degree 18/19. */
static void cos_sin_series(double b, double *c, double *s)
{
    static const double half_pi_hi = 1.57079632673412561417, half_pi_lo = 6.07710050650619224932e-11;
    const double qd = b >= 0.0 ? (double)(long)(b / 1.5707963267948966 + 0.5)
                               : -(double)(long)(-b / 1.5707963267948966 + 0.5);
    const double r = (b - qd * half_pi_hi) - qd * half_pi_lo, r2 = r * r;
    double sr = r, cr = 1.0, ts = r, tc = 1.0;
    long q = (long)qd, i;
    for (i = 1; i <= 9; ++i) {
        tc *= -r2 / (double)((2 * i - 1) * (2 * i));
        ts *= -r2 / (double)((2 * i) * (2 * i + 1));
        cr += tc;
        sr += ts;
    }
    switch (((q % 4) + 4) % 4) {
    case 0: *c = cr; *s = sr; break;
    case 1: *c = -sr; *s = cr; break;
    case 2: *c = -cr; *s = -sr; break;
    default: *c = sr; *s = -cr; break;
    }
}

/* ---- the taps of one pole ------------------------------------------------------------- */

/* The taps of ZV^n: (a0 + a1 z^-m + a2 z^-(m+1))^n expanded by the multinomial theorem, the
 * term a0^(n-i) a1^(i-j) a2^j n!/((n-i)! (i-j)! j!) on delay i m + j (0 <= j <= i <= n). For
 * m > n the delays increase with (i, j) and are distinct; for m <= n (a half period of at
 * most 8 samples) they collide and are summed on a dense grid of at most n (m + 1) + 1. */
typedef struct zv_taps {
    size_t n;
    size_t delay[SMS_SHAPER_MAX_TAPS];
    double gain[SMS_SHAPER_MAX_TAPS];
} zv_taps;

static void expand(const double a[3], size_t m, unsigned order, zv_taps *out)
{
    double binom[SMS_SHAPER_MAX_ORDER + 1][SMS_SHAPER_MAX_ORDER + 1];
    double dense[(SMS_SHAPER_MAX_ORDER + 1) * (SMS_SHAPER_MAX_ORDER + 1)];
    double p0[SMS_SHAPER_MAX_ORDER + 1], p1[SMS_SHAPER_MAX_ORDER + 1], p2[SMS_SHAPER_MAX_ORDER + 1];
    unsigned i, j;
    size_t d;
    for (i = 0; i <= order; ++i) {
        binom[i][0] = binom[i][i] = 1.0;
        for (j = 1; j < i; ++j)
            binom[i][j] = binom[i - 1][j - 1] + binom[i - 1][j];
        p0[i] = i == 0 ? 1.0 : p0[i - 1] * a[0];
        p1[i] = i == 0 ? 1.0 : p1[i - 1] * a[1];
        p2[i] = i == 0 ? 1.0 : p2[i - 1] * a[2];
    }
    out->n = 0;
    if (m <= order)
        for (d = 0; d <= order * (m + 1u); ++d)
            dense[d] = 0.0;
    for (i = 0; i <= order; ++i)
        for (j = 0; j <= i; ++j) {
            const double g = binom[order][i] * binom[i][j] * p0[order - i] * p1[i - j] * p2[j];
            const size_t at = (size_t)i * m + j;
            if (m <= order) {
                dense[at] += g;
            } else if (g != 0.0 || at == 0u) {
                out->delay[out->n] = at;
                out->gain[out->n++] = g;
            }
        }
    if (m <= order)
        for (d = 0; d <= order * (m + 1u); ++d)
            if (dense[d] != 0.0 || d == 0u) {
                out->delay[out->n] = d;
                out->gain[out->n++] = dense[d];
            }
}

/* The exact ZV^order of the pole sigma Ts + j wd Ts (scheduled.h) into out. */
static void design(double sigma_ts, double wd_ts, unsigned order, zv_taps *out)
{
    const double mu = pi / wd_ts;
    const size_t m = (size_t)mu;
    const double f = mu - (double)m, inv_k = exp_series(-sigma_ts * mu);
    double c, s, ur, ui, vr, vi, e, den, a[3];
    e = exp_series(sigma_ts * f);
    cos_sin_series(wd_ts * f, &c, &s);
    ur = -inv_k * e * c;
    ui = -inv_k * e * s;
    e = exp_series(sigma_ts * (f - 1.0));
    cos_sin_series(wd_ts * (f - 1.0), &c, &s);
    vr = -inv_k * e * c;
    vi = -inv_k * e * s;
    den = (1.0 - ur) * vi - (1.0 - vr) * ui;
    a[1] = vi / den;
    a[2] = -ui / den;
    a[0] = 1.0 - a[1] - a[2];
    expand(a, m, order, out);
}

/* The interpolated pole (sigma Ts, wd Ts) at s: linear between the points, the end points'
 * outside. */
static void pole_at(const sms_scheduled *f, double s, double *sigma_ts, double *wd_ts)
{
    size_t lo = 0, hi = f->n_points - 1u;
    double w;
    if (!(s > f->value[0]) || f->n_points == 1u) {
        *sigma_ts = f->sigma_ts[0];
        *wd_ts = f->wd_ts[0];
        return;
    }
    if (!(s < f->value[hi])) {
        *sigma_ts = f->sigma_ts[hi];
        *wd_ts = f->wd_ts[hi];
        return;
    }
    while (hi - lo > 1u) {   /* value[lo] < s < value[hi] */
        const size_t mid = lo + (hi - lo) / 2u;
        if (f->value[mid] <= s)
            lo = mid;
        else
            hi = mid;
    }
    w = (s - f->value[lo]) / (f->value[hi] - f->value[lo]);
    *sigma_ts = f->sigma_ts[lo] + w * (f->sigma_ts[hi] - f->sigma_ts[lo]);
    *wd_ts = f->wd_ts[lo] + w * (f->wd_ts[hi] - f->wd_ts[lo]);
}

/* Recompute the taps for schedule value s (a non-finite s keeps them). */
static void update(sms_scheduled *f, double s)
{
    zv_taps taps;
    double sigma_ts, wd_ts;
    size_t i;
    if (!is_finite(s))
        return;
    pole_at(f, s, &sigma_ts, &wd_ts);
    design(sigma_ts, wd_ts, f->order, &taps);
    f->n_taps = 0;
    for (i = 0; i < taps.n; ++i)
        if (taps.delay[i] > 0u) {
            f->delay[f->n_taps] = taps.delay[i];
            f->gain[f->n_taps++] = (sms_real)taps.gain[i];
        }
    f->schedule = s;
}

/* ---- configuration ------------------------------------------------------------------- */

static sms_status check(const sms_scheduled_config *c, double Ts, size_t *len)
{
    size_t i, longest = 0;
    unsigned order;
    if (c == NULL || len == NULL)
        return SMS_ERR_NULL;
    if (!is_finite(Ts) || Ts <= 0.0)
        return SMS_ERR_SAMPLE_PERIOD;
    if (c->kind != SMS_SHAPER_ZV && c->kind != SMS_SHAPER_ZVD && c->kind != SMS_SHAPER_ZVDD
        && c->kind != SMS_SHAPER_ZVN)
        return SMS_ERR_KIND;
    order = zv_order(c);
    if (order == 0u || c->n_points < 1u || c->n_points > SMS_SCHEDULE_MAX_POINTS)
        return SMS_ERR_ORDER;
    if (c->points == NULL)
        return SMS_ERR_NULL;
    if (c->update_every < 1u)
        return SMS_ERR_MULTIPLE;
    for (i = 0; i < c->n_points; ++i) {
        sms_stage_config one = sms_stage_config_default(c->kind);
        size_t L;
        sms_status st;
        if (!is_finite(c->points[i].value) || (i > 0 && !(c->points[i].value > c->points[i - 1].value)))
            return SMS_ERR_STATE;
        one.wn = c->points[i].wn;
        one.zeta = c->points[i].zeta;
        one.order = order;
        st = sms_shaper_buffer_size(&one, Ts, &L);
        if (st != SMS_OK)
            return st;
        {
            const double wd = c->points[i].wn * sqrt(1.0 - c->points[i].zeta * c->points[i].zeta);
            const double mu = pi / (wd * Ts);
            const size_t need = (size_t)mu * order + order + 1u;
            if (need > longest)
                longest = need;
        }
    }
    *len = longest;
    return SMS_OK;
}

sms_status sms_scheduled_buffer_size(const sms_scheduled_config *config, double Ts,
                                     size_t *n_reals)
{
    return check(config, Ts, n_reals);
}

sms_status sms_scheduled_init(sms_scheduled *f, const sms_scheduled_config *config, double Ts,
                              sms_real *buffer, size_t n_reals)
{
    sms_scheduled built;
    size_t len, i;
    sms_status st;
    if (f == NULL)
        return SMS_ERR_NULL;
    st = check(config, Ts, &len);
    if (st != SMS_OK)
        return st;
    if (buffer == NULL)
        return SMS_ERR_NULL;
    if (n_reals < len)
        return SMS_ERR_BUFFER_TOO_SMALL;
    built.order = zv_order(config);
    built.update_every = config->update_every;
    built.Ts = Ts;
    built.n_points = config->n_points;
    for (i = 0; i < config->n_points; ++i) {
        const double wn = config->points[i].wn, zeta = config->points[i].zeta;
        built.value[i] = config->points[i].value;
        built.sigma_ts[i] = -zeta * wn * Ts;
        built.wd_ts[i] = wn * sqrt(1.0 - zeta * zeta) * Ts;
    }
    built.ring = buffer;
    built.len = len;
    *f = built;
    sms_scheduled_reset(f, (sms_real)0, config->points[0].value);
    return SMS_OK;
}

void sms_scheduled_reset(sms_scheduled *f, sms_real rest, double s)
{
    size_t i;
    for (i = 0; i < f->len; ++i)
        f->ring[i] = rest;
    f->head = 0;
    f->n_taps = 0;
    f->schedule = f->value[0];
    update(f, f->value[0]);
    update(f, s);
    f->countdown = 1u;   /* the first sample updates: samples 0, N, 2N, ... */
}

void sms_scheduled_process(sms_scheduled *f, const sms_real *in, const double *schedule,
                           sms_real *out, size_t n)
{
    const size_t len = f->len;
    sms_real *ring = f->ring;
    size_t i, k, head = f->head;
    for (i = 0; i < n; ++i) {
        const sms_real x = in[i];
        sms_real acc = 0;
        if (f->countdown <= 1u) {
            update(f, schedule[i]);
            f->countdown = f->update_every;
        } else {
            --f->countdown;
        }
        ring[head] = x;
        for (k = 0; k < f->n_taps; ++k) {
            const size_t d = f->delay[k];
            acc += f->gain[k] * (ring[head >= d ? head - d : head + len - d] - x);
        }
        head = head + 1u == len ? 0u : head + 1u;
        out[i] = x + acc;
    }
    f->head = head;
}

void sms_scheduled_step(sms_scheduled *f, sms_real *x, double s)
{
    sms_scheduled_process(f, x, &s, x, 1);
}

void sms_scheduled_mode(const sms_scheduled *f, double s, double *wn, double *zeta)
{
    double sigma_ts, wd_ts, w;
    pole_at(f, is_finite(s) ? s : f->schedule, &sigma_ts, &wd_ts);
    w = sqrt(sigma_ts * sigma_ts + wd_ts * wd_ts);
    *wn = w / f->Ts;
    *zeta = -sigma_ts / w;
}

sms_status sms_scheduled_taps(const sms_scheduled *f, double *taps, size_t n)
{
    size_t i;
    double h0 = 1.0;
    if (f == NULL || taps == NULL)
        return SMS_ERR_NULL;
    if (n < f->len)
        return SMS_ERR_BUFFER_TOO_SMALL;
    for (i = 0; i < f->len; ++i)
        taps[i] = 0.0;
    for (i = 0; i < f->n_taps; ++i) {
        taps[f->delay[i]] = (double)f->gain[i];
        h0 -= (double)f->gain[i];
    }
    taps[0] = h0;
    return SMS_OK;
}

double sms_scheduled_lag(const sms_scheduled *f)
{
    double lag = 0.0;
    size_t i;
    for (i = 0; i < f->n_taps; ++i)
        lag += (double)f->delay[i] * (double)f->gain[i];
    return lag;
}

size_t sms_scheduled_state_count(const sms_scheduled *f)
{
    return 5u + f->len;
}

void sms_scheduled_get_state(const sms_scheduled *f, double *dst)
{
    size_t i;
    dst[0] = (double)f->order;
    dst[1] = (double)f->update_every;
    dst[2] = (double)f->countdown;
    dst[3] = f->schedule;
    dst[4] = (double)f->head;
    for (i = 0; i < f->len; ++i)
        dst[5 + i] = (double)f->ring[i];
}

sms_status sms_scheduled_set_state(sms_scheduled *f, const double *src, size_t n)
{
    size_t i;
    if (f == NULL || src == NULL)
        return SMS_ERR_NULL;
    if (n != sms_scheduled_state_count(f) || src[0] != (double)f->order
        || src[1] != (double)f->update_every || !(src[2] >= 1.0 && src[2] <= src[1])
        || src[2] != floor(src[2]) || !is_finite(src[3]) || !(src[4] >= 0.0 && src[4] < (double)f->len)
        || src[4] != floor(src[4]))
        return SMS_ERR_STATE;
    update(f, src[3]);
    f->countdown = (unsigned)src[2];
    f->head = (size_t)src[4];
    for (i = 0; i < f->len; ++i)
        f->ring[i] = (sms_real)src[5 + i];
    return SMS_OK;
}
