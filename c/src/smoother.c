/* The O(1) drift-free engine shared by the four smoothers: two restarted copies of a complex
 * first-order recursion plus at most two direct taps (exact timing) (see smoother.h). */
#include <float.h>
#include <math.h>
#include "smoothshaper/smoother.h"
#include "smoother_design.h"

#ifdef SMS_USE_FLOAT
#define SMS_REAL_MAX FLT_MAX
#else
#define SMS_REAL_MAX DBL_MAX
#endif

/* Fixed part of the saved state, before the ring. */
enum {
    STATE_HEAD, STATE_AGE0, STATE_AGE1, STATE_REST,
    STATE_W0_RE, STATE_W0_IM, STATE_W1_RE, STATE_W1_IM,
    STATE_LO0_RE, STATE_LO0_IM, STATE_LO1_RE, STATE_LO1_IM,
    STATE_REF0, STATE_REF1, STATE_FIXED
};

sms_status sms_smoother_buffer_size(const sms_stage_config *config, double Ts, size_t *n_reals)
{
    sms_smoother_design d;
    sms_status st;
    if (config == NULL || n_reals == NULL)
        return SMS_ERR_NULL;
    st = sms_smoother_design_make(config, Ts, &d);
    if (st == SMS_OK)
        *n_reals = d.window;
    return st;
}

sms_status sms_smoother_length(const sms_stage_config *config, double Ts, size_t *length)
{
    sms_smoother_design d;
    sms_status st;
    if (config == NULL || length == NULL)
        return SMS_ERR_NULL;
    st = sms_smoother_design_make(config, Ts, &d);
    if (st == SMS_OK)
        *length = d.length;
    return st;
}

sms_status sms_smoother_taps(const sms_stage_config *config, double Ts, double *taps, size_t n_taps)
{
    sms_smoother_design d;
    sms_status st;
    size_t i;
    if (config == NULL || taps == NULL)
        return SMS_ERR_NULL;
    st = sms_smoother_design_make(config, Ts, &d);
    if (st != SMS_OK)
        return st;
    if (n_taps < d.length)
        return SMS_ERR_BUFFER_TOO_SMALL;
    for (i = 0; i < d.length; ++i)
        taps[i] = sms_smoother_design_tap(&d, i);
    return SMS_OK;
}

sms_status sms_smoother_init(sms_smoother *f, const sms_stage_config *config, double Ts,
                             sms_real *buffer, size_t n_reals)
{
    sms_smoother_design d;
    sms_smoother built;
    sms_status st;
    size_t j;
    if (f == NULL || config == NULL)
        return SMS_ERR_NULL;
    st = sms_smoother_design_make(config, Ts, &d);
    if (st != SMS_OK)
        return st;
    if (buffer == NULL)
        return SMS_ERR_NULL;
    if (n_reals < d.window)
        return SMS_ERR_BUFFER_TOO_SMALL;
    built.kind = config->kind;
    built.length = d.length;
    built.window = d.window;
    built.pole_m1_re = (sms_real)d.pole_m1_re;
    built.pole_im = (sms_real)d.pole_im;
    /* What rounding to sms_real lost (exact in double for float), plus the long double part. */
    built.pole_lo_re = (sms_real)((d.pole_m1_re - (double)built.pole_m1_re) + d.pole_m1_lo_re);
    built.pole_lo_im = (sms_real)((d.pole_im - (double)built.pole_im) + d.pole_lo_im);
    built.gain_re = (sms_real)d.gain;
    built.gain_im = (sms_real)0;
    built.tail_re = (sms_real)d.tail_re;
    built.tail_im = (sms_real)d.tail_im;
    built.imag_out = d.family.half_sine;
    built.real_only = !d.family.half_sine;
    built.n_corrections = d.n_corrections;
    for (j = 0; j < SMS_SMOOTHER_MAX_CORRECTIONS; ++j) {
        built.correction_delay[j] = j < d.n_corrections ? d.correction_delay[j] : 0u;
        built.correction_gain[j] = (sms_real)(j < d.n_corrections ? d.correction_gain[j] : 0.0);
    }
    built.history = buffer;
    built.history_len = d.window;
    sms_smoother_reset(&built, (sms_real)0);
    *f = built;
    return SMS_OK;
}

void sms_smoother_reset(sms_smoother *f, sms_real rest)
{
    size_t i;
    for (i = 0; i < f->window; ++i)
        f->history[i] = (sms_real)0;
    f->head = 0;
    f->rest = rest;
    f->w_re[0] = f->w_re[1] = f->w_im[0] = f->w_im[1] = (sms_real)0;
    f->lo_re[0] = f->lo_re[1] = f->lo_im[0] = f->lo_im[1] = (sms_real)0;
    f->ref[0] = f->ref[1] = (sms_real)0;
    /* All past inputs are zero (relative to rest), so a zero copy is exact at any age: copy 0
     * is in use now, copy 1 takes over after M samples. */
    f->age[0] = f->window;
    f->age[1] = 0;
}

/* Sum a + b and its exact rounding error (Knuth's TwoSum). Needs IEEE evaluation in
 * sms_real: no -ffast-math reassociation, no x87 excess precision (FLT_EVAL_METHOD 0). */
static sms_real two_sum(sms_real a, sms_real b, sms_real *err)
{
    sms_real s = a + b, bb = s - a;
    *err = (a - (s - bb)) + (b - bb);
    return s;
}

/* One copy of the recursion; `oldest_input` is x[n-M], used only if the copy consumed it.
 * - The copy filters x - ref, ref being its input when it restarted, and adds ref back (the
 *   taps sum to 1): its state stays as small as the input's variation, not its offset.
 * - The state is w + lo: w takes the update w += (q - 1) w + c x - c q^M x[n-M] (an increment
 *   small against w), and lo, a small state on the same pole, collects what that addition
 *   rounds away (exactly, by TwoSum) and what the rounded pole misses (q_lo w). Without it
 *   both errors are systematic for a pole near 1 (the increment below half an ulp of w is
 *   lost every sample) and tap i would be off by ~i eps. */
static void copy_update(sms_smoother *f, int c, sms_real input, sms_real oldest_input)
{
    const size_t window = f->window;
    sms_real x, oldest, d_re, d_im, e_re, e_im, w_re, w_im, lo_re, lo_im;
    if (f->age[c] == 2u * window) {
        f->w_re[c] = f->w_im[c] = (sms_real)0;
        f->lo_re[c] = f->lo_im[c] = (sms_real)0;
        /* A finite input (x - x == 0) becomes the copy's reference; NaN/Inf must not. */
        f->ref[c] = input - input == (sms_real)0 ? input : (sms_real)0;
        f->age[c] = 0;
    }
    x = input - f->ref[c];
    oldest = f->age[c] >= window ? oldest_input - f->ref[c] : (sms_real)0;
    w_re = f->w_re[c];
    lo_re = f->lo_re[c];
    if (f->real_only) {
        d_re = f->pole_m1_re * w_re + (f->gain_re * x + f->tail_re * oldest);
        f->w_re[c] = two_sum(w_re, d_re, &e_re);
        f->lo_re[c] = lo_re + (f->pole_m1_re * lo_re + f->pole_lo_re * w_re + e_re);
    } else {
        w_im = f->w_im[c];
        lo_im = f->lo_im[c];
        d_re = f->pole_m1_re * w_re - f->pole_im * w_im + (f->gain_re * x + f->tail_re * oldest);
        d_im = f->pole_m1_re * w_im + f->pole_im * w_re + (f->gain_im * x + f->tail_im * oldest);
        f->w_re[c] = two_sum(w_re, d_re, &e_re);
        f->w_im[c] = two_sum(w_im, d_im, &e_im);
        f->lo_re[c] = lo_re + (f->pole_m1_re * lo_re - f->pole_im * lo_im
                               + (f->pole_lo_re * w_re - f->pole_lo_im * w_im) + e_re);
        f->lo_im[c] = lo_im + (f->pole_m1_re * lo_im + f->pole_im * lo_re
                               + (f->pole_lo_re * w_im + f->pole_lo_im * w_re) + e_im);
    }
    ++f->age[c];
}

static sms_real filter_sample(sms_smoother *f, sms_real input)
{
    const size_t window = f->window;
    const sms_real x = input - f->rest;
    const sms_real oldest = f->history[f->head];
    sms_real y = (sms_real)0, ref;
    size_t j;
    int use;
    copy_update(f, 0, x, oldest);
    copy_update(f, 1, x, oldest);
    /* The older copy has consumed between M and 2M samples: it is exact and young. */
    use = f->age[0] >= f->age[1] ? 0 : 1;
    /* The recursion's taps and the direct ones sum to 1 together: the direct taps act on
     * x - ref too, and ref is added once (smaller rounding). */
    ref = f->ref[use];
    for (j = 0; j < f->n_corrections; ++j) {
        size_t delay = f->correction_delay[j], idx;
        sms_real v = x;
        if (delay > 0) {
            /* x[n-delay] sits delay slots behind the head's successor: head + M - delay. */
            idx = f->head + window - delay;
            if (idx >= window)
                idx -= window;
            v = f->history[idx];
        }
        y += f->correction_gain[j] * (v - ref);
    }
    f->history[f->head] = x;
    f->head = f->head + 1u == window ? 0u : f->head + 1u;
    y += f->imag_out ? f->w_im[use] + f->lo_im[use] : f->w_re[use] + f->lo_re[use];
    return y + ref + f->rest;
}

void sms_smoother_step(sms_smoother *f, sms_real *x)
{
    *x = filter_sample(f, *x);
}

void sms_smoother_process(sms_smoother *f, const sms_real *in, sms_real *out, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i)
        out[i] = filter_sample(f, in[i]);
}

size_t sms_smoother_state_count(const sms_smoother *f)
{
    return (size_t)STATE_FIXED + f->window;
}

void sms_smoother_save_state(const sms_smoother *f, double *dst)
{
    size_t i;
    dst[STATE_HEAD] = (double)f->head;
    dst[STATE_AGE0] = (double)f->age[0];
    dst[STATE_AGE1] = (double)f->age[1];
    dst[STATE_REST] = (double)f->rest;
    dst[STATE_W0_RE] = (double)f->w_re[0];
    dst[STATE_W0_IM] = (double)f->w_im[0];
    dst[STATE_W1_RE] = (double)f->w_re[1];
    dst[STATE_W1_IM] = (double)f->w_im[1];
    dst[STATE_LO0_RE] = (double)f->lo_re[0];
    dst[STATE_LO0_IM] = (double)f->lo_im[0];
    dst[STATE_LO1_RE] = (double)f->lo_re[1];
    dst[STATE_LO1_IM] = (double)f->lo_im[1];
    dst[STATE_REF0] = (double)f->ref[0];
    dst[STATE_REF1] = (double)f->ref[1];
    for (i = 0; i < f->window; ++i)
        dst[STATE_FIXED + i] = (double)f->history[i];
}

static int is_index(double v, double bound_inclusive)
{
    return v >= 0.0 && v <= bound_inclusive && v == floor(v);
}

/* Finite values must fit sms_real (converting a larger double to float is undefined). */
static int fits_real_or_nonfinite(double v)
{
    return !isfinite(v) || fabs(v) <= SMS_REAL_MAX;
}

sms_status sms_smoother_check_state(const sms_smoother *f, const double *src, size_t n)
{
    const double window = (double)(f != NULL ? f->window : 0u);
    size_t i;
    if (f == NULL || src == NULL)
        return SMS_ERR_NULL;
    if (n != sms_smoother_state_count(f))
        return SMS_ERR_STATE;
    if (!is_index(src[STATE_HEAD], window - 1.0))
        return SMS_ERR_STATE;
    if (!is_index(src[STATE_AGE0], 2.0 * window) || !is_index(src[STATE_AGE1], 2.0 * window)
        || fabs(src[STATE_AGE0] - src[STATE_AGE1]) != window)
        return SMS_ERR_STATE;
    if (!isfinite(src[STATE_REST]) || !fits_real_or_nonfinite(src[STATE_REST]))
        return SMS_ERR_STATE;
    if (!isfinite(src[STATE_REF0]) || !isfinite(src[STATE_REF1]))
        return SMS_ERR_STATE;
    for (i = STATE_W0_RE; i < n; ++i)
        if (!fits_real_or_nonfinite(src[i]))
            return SMS_ERR_STATE;
    return SMS_OK;
}

sms_status sms_smoother_load_state(sms_smoother *f, const double *src, size_t n)
{
    size_t i;
    sms_status st = sms_smoother_check_state(f, src, n);
    if (st != SMS_OK)
        return st;
    f->head = (size_t)src[STATE_HEAD];
    f->age[0] = (size_t)src[STATE_AGE0];
    f->age[1] = (size_t)src[STATE_AGE1];
    f->rest = (sms_real)src[STATE_REST];
    f->w_re[0] = (sms_real)src[STATE_W0_RE];
    f->w_im[0] = (sms_real)src[STATE_W0_IM];
    f->w_re[1] = (sms_real)src[STATE_W1_RE];
    f->w_im[1] = (sms_real)src[STATE_W1_IM];
    f->lo_re[0] = (sms_real)src[STATE_LO0_RE];
    f->lo_im[0] = (sms_real)src[STATE_LO0_IM];
    f->lo_re[1] = (sms_real)src[STATE_LO1_RE];
    f->lo_im[1] = (sms_real)src[STATE_LO1_IM];
    f->ref[0] = (sms_real)src[STATE_REF0];
    f->ref[1] = (sms_real)src[STATE_REF1];
    for (i = 0; i < f->window; ++i)
        f->history[i] = (sms_real)src[STATE_FIXED + i];
    return SMS_OK;
}
