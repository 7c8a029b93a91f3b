/* SPDX-License-Identifier: Apache-2.0 */
/* The fractional delay of align.h: a ring of the last m + 2 inputs, linear interpolation
 * between x[n-m] and x[n-m-1]. */
#include <math.h>
#include "smoothshaper/align.h"

static int valid_samples(double d)
{
    return d >= 0.0 && d <= SMS_DELAY_MAX_SAMPLES;   /* false for NaN */
}

sms_status sms_delay_buffer_size(double samples, size_t *n_reals)
{
    if (n_reals == NULL)
        return SMS_ERR_NULL;
    if (!valid_samples(samples))
        return SMS_ERR_DURATION;
    *n_reals = (size_t)floor(samples) + 2u;
    return SMS_OK;
}

sms_status sms_delay_init(sms_delay *d, double samples, sms_real *buffer, size_t n_reals)
{
    size_t need;
    sms_status st;
    if (d == NULL)
        return SMS_ERR_NULL;
    st = sms_delay_buffer_size(samples, &need);
    if (st != SMS_OK)
        return st;
    if (buffer == NULL)
        return SMS_ERR_NULL;
    if (n_reals < need)
        return SMS_ERR_BUFFER_TOO_SMALL;
    d->whole = need - 2u;
    d->fraction = (sms_real)(samples - (double)d->whole);
    d->samples = samples;
    d->ring = buffer;
    d->len = need;
    sms_delay_reset(d, (sms_real)0);
    return SMS_OK;
}

void sms_delay_reset(sms_delay *d, sms_real rest)
{
    size_t i;
    for (i = 0; i < d->len; ++i)
        d->ring[i] = rest;
    d->head = 0;
}

/* y = x[n-m] + f (x[n-m-1] - x[n-m]): exact for a constant input (the difference is 0) and
 * the sample itself for f = 0. The ring holds x[n-m-1] .. x[n] once x[n] is written. */
void sms_delay_process(sms_delay *d, const sms_real *in, sms_real *out, size_t n)
{
    const size_t len = d->len, m = d->whole;
    const sms_real f = d->fraction;
    sms_real *ring = d->ring;
    size_t i, head = d->head;
    for (i = 0; i < n; ++i) {
        const size_t a = head >= m ? head - m : head + len - m;   /* x[n-m] */
        const size_t b = a == 0 ? len - 1u : a - 1u;              /* x[n-m-1] */
        sms_real xa, xb;
        ring[head] = in[i];
        xa = ring[a];
        xb = ring[b];
        out[i] = f == (sms_real)0 ? xa : xa + f * (xb - xa);
        head = head + 1u == len ? 0u : head + 1u;
    }
    d->head = head;
}

void sms_delay_step(sms_delay *d, sms_real *x)
{
    sms_delay_process(d, x, x, 1);
}

uint64_t sms_delay_settle_length(const sms_delay *d)
{
    return (uint64_t)d->len;
}

sms_real sms_delay_settle(sms_delay *d, sms_real x, uint64_t n)
{
    size_t i;
    for (i = 0; i < d->len; ++i)
        d->ring[i] = x;
    sms_delay_advance(d, n);
    return x;
}

void sms_delay_advance(sms_delay *d, uint64_t n)
{
    d->head = (size_t)(((uint64_t)d->head + n % (uint64_t)d->len) % (uint64_t)d->len);
}

size_t sms_delay_state_count(const sms_delay *d)
{
    return 3u + d->len;
}

void sms_delay_get_state(const sms_delay *d, double *dst)
{
    size_t i;
    dst[0] = d->samples;
    dst[1] = (double)d->len;
    dst[2] = (double)d->head;
    for (i = 0; i < d->len; ++i)
        dst[3 + i] = (double)d->ring[i];
}

sms_status sms_delay_check_state(const sms_delay *d, const double *src, size_t n)
{
    if (d == NULL || src == NULL)
        return SMS_ERR_NULL;
    if (n != sms_delay_state_count(d) || !(src[0] == d->samples) || src[1] != (double)d->len
        || !(src[2] >= 0.0 && src[2] < (double)d->len) || src[2] != floor(src[2]))
        return SMS_ERR_STATE;
    return SMS_OK;
}

sms_status sms_delay_set_state(sms_delay *d, const double *src, size_t n)
{
    size_t i;
    sms_status st = sms_delay_check_state(d, src, n);
    if (st != SMS_OK)
        return st;
    d->head = (size_t)src[2];
    for (i = 0; i < d->len; ++i)
        d->ring[i] = (sms_real)src[3 + i];
    return SMS_OK;
}
