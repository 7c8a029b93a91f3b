/* SPDX-License-Identifier: Apache-2.0 */
/* The smoothers as streams: one block == random splits == in place == sample by sample (bit
 * for bit), reset to a rest value, state save/load, NaN/Inf input recovery, and every invalid
 * configuration rejected with its status and the instance untouched. */
#include <string.h>
#include "check.h"

#define ID SMS_STATE_IDENTITY_COUNT   /* a saved state starts with its configuration identity */
#include "smoother_fixtures.h"

#define MAX_LEN 4096

static sms_real ring_a[MAX_LEN], ring_b[MAX_LEN];
static double taps[MAX_LEN], expect[MAX_LEN];
static sms_real sig_in[3 * MAX_LEN], sig_out[3 * MAX_LEN], sig_out2[3 * MAX_LEN];

/* Deterministic uniform numbers in [-1, 1). */
static unsigned long lcg_state = 12345u;
static double uniform(void)
{
    lcg_state = (lcg_state * 1103515245u + 12345u) & 0x7fffffffu;
    return (double)lcg_state / 1073741824.0 - 1.0;
}

/* Unit step through an initialised smoother into taps[0..n-1]. */
static void step_response(sms_smoother *f, double *out, size_t n)
{
    size_t i;
    sms_smoother_reset(f, (sms_real)0);
    for (i = 0; i < n; ++i) {
        sms_real x = (sms_real)1;
        sms_smoother_step(f, &x);
        out[i] = (double)x;
    }
}

/* One call == random splits (bit for bit) == in place == step by step. */
static void test_blocks(const sms_stage_config *c, double Ts)
{
    sms_smoother f;
    size_t n = 3 * MAX_LEN, i, done;
    for (i = 0; i < n; ++i)
        sig_in[i] = (sms_real)(5.0 + uniform());
    CHECK_STATUS(sms_smoother_init(&f, c, Ts, ring_a, MAX_LEN), SMS_OK);
    sms_smoother_process(&f, sig_in, sig_out, n);
    CHECK_STATUS(sms_smoother_init(&f, c, Ts, ring_a, MAX_LEN), SMS_OK);
    for (done = 0; done < n;) {
        size_t len = (size_t)((uniform() + 1.0) * 150.0);
        if (len > n - done)
            len = n - done;
        sms_smoother_process(&f, sig_in + done, sig_out2 + done, len);
        done += len;
    }
    CHECK(memcmp(sig_out, sig_out2, n * sizeof(sms_real)) == 0);
    CHECK_STATUS(sms_smoother_init(&f, c, Ts, ring_a, MAX_LEN), SMS_OK);
    memcpy(sig_out2, sig_in, n * sizeof(sms_real));
    sms_smoother_process(&f, sig_out2, sig_out2, n);
    CHECK(memcmp(sig_out, sig_out2, n * sizeof(sms_real)) == 0);
    CHECK_STATUS(sms_smoother_init(&f, c, Ts, ring_a, MAX_LEN), SMS_OK);
    for (i = 0; i < n; ++i) {
        sig_out2[i] = sig_in[i];
        sms_smoother_step(&f, &sig_out2[i]);
    }
    CHECK(memcmp(sig_out, sig_out2, n * sizeof(sms_real)) == 0);
}

/* reset(rest): a filter at rest outputs rest; a step from rest behaves as from 0, shifted. */
static void test_reset_rest(const sms_stage_config *c, double Ts)
{
    sms_smoother f;
    size_t i, L;
    CHECK_STATUS(sms_smoother_init(&f, c, Ts, ring_a, MAX_LEN), SMS_OK);
    L = f.length;
    step_response(&f, expect, L + 4);
    sms_smoother_reset(&f, (sms_real)-3);
    for (i = 0; i < L + 4; ++i) {
        sms_real x = (sms_real)-3;
        sms_smoother_step(&f, &x);
        CHECK(x == (sms_real)-3);
    }
    sms_smoother_reset(&f, (sms_real)-3);
    for (i = 0; i < L + 4; ++i) {
        sms_real x = (sms_real)-2;
        sms_smoother_step(&f, &x);
        CHECK_CLOSE(x, -3.0 + expect[i], SMS_TEST_REL_TOL, 3.0);
    }
}

/* Save mid-run, load into a fresh instance: both continue bit-exactly; bad vectors rejected. */
static void test_state(const sms_stage_config *c, double Ts)
{
    static double saved[SMS_STATE_IDENTITY_COUNT + MAX_LEN + 16];
    static double bad[ID + MAX_LEN + 16];
    sms_smoother a, b, before;
    size_t n = 2 * MAX_LEN, i, count;
    for (i = 0; i < n; ++i)
        sig_in[i] = (sms_real)(uniform() * 10.0);
    CHECK_STATUS(sms_smoother_init(&a, c, Ts, ring_a, MAX_LEN), SMS_OK);
    CHECK_STATUS(sms_smoother_init(&b, c, Ts, ring_b, MAX_LEN), SMS_OK);
    sms_smoother_reset(&a, (sms_real)2);
    sms_smoother_process(&a, sig_in, sig_out, 1234);
    count = sms_smoother_state_count(&a);
    CHECK(count == SMS_STATE_IDENTITY_COUNT + a.window + 13u);
    sms_smoother_get_state(&a, saved);
    CHECK_STATUS(sms_smoother_check_state(&b, saved, count), SMS_OK);
    CHECK_STATUS(sms_smoother_set_state(&b, saved, count), SMS_OK);
    sms_smoother_process(&a, sig_in + 1234, sig_out + 1234, n - 1234);
    sms_smoother_process(&b, sig_in + 1234, sig_out2 + 1234, n - 1234);
    CHECK(memcmp(sig_out + 1234, sig_out2 + 1234, (n - 1234) * sizeof(sms_real)) == 0);

    /* Each corruption is rejected and leaves b (and its ring) exactly as it was. */
    for (i = 0; i < 9; ++i) {
        memcpy(bad, saved, count * sizeof(double));
        switch (i) {
        case 0: bad[ID + 0] = (double)a.window; break;        /* head out of range */
        case 1: bad[ID + 0] = 0.5; break;                     /* head not integral */
        case 2: bad[ID + 1] = (double)a.length + 1.0; break;  /* run beyond L */
        case 3: bad[ID + 1] = 0.5; break;                     /* run not integral */
        case 4: bad[ID + 1] = -1.0; break;
        case 5: bad[ID + 2] = NAN; break;                     /* rest not finite */
        case 6: bad[ID + 0] = NAN; break;
        case 7: bad[ID + 8] = 1e300; break;                   /* a copy's value (rejected in float only) */
        default: break;
        }
        memcpy(&before, &b, sizeof b);
        memcpy(ring_a, ring_b, b.window * sizeof(sms_real));
        if (i == 7) {
#ifdef SMS_USE_FLOAT
            CHECK_STATUS(sms_smoother_set_state(&b, bad, count), SMS_ERR_STATE);
#endif
        } else if (i == 8) {
            CHECK_STATUS(sms_smoother_set_state(&b, bad, count + 1), SMS_ERR_STATE);
        } else {
            CHECK_STATUS(sms_smoother_check_state(&b, bad, count), SMS_ERR_STATE);
            CHECK_STATUS(sms_smoother_set_state(&b, bad, count), SMS_ERR_STATE);
        }
        CHECK(memcmp(&before, &b, sizeof b) == 0);
        CHECK(memcmp(ring_a, ring_b, b.window * sizeof(sms_real)) == 0);
    }
    CHECK_STATUS(sms_smoother_set_state(&b, NULL, count), SMS_ERR_NULL);
}

/* A NaN or Inf sample: NaN out while it is in the window, then exact again within 2M + 1. */
static void test_non_finite(const sms_stage_config *c, double Ts, double bad_value)
{
    sms_smoother f;
    size_t n, i, j, L, M, hit = 1000, recovered, last_bad = 0;
    CHECK_STATUS(sms_smoother_init(&f, c, Ts, ring_a, MAX_LEN), SMS_OK);
    L = f.length;
    M = f.window;
    n = hit + 3 * L + 10;
    CHECK(n <= 3 * MAX_LEN);
    CHECK_STATUS(sms_smoother_taps(c, Ts, taps, MAX_LEN), SMS_OK);
    for (i = 0; i < n; ++i)
        sig_in[i] = (sms_real)(1.0 + uniform());
    sig_in[hit] = (sms_real)bad_value;
    /* Through the bad sample, then a state round trip (NaN/Inf in the state is accepted). */
    sms_smoother_process(&f, sig_in, sig_out, hit + 1);
    {
        static double saved[SMS_STATE_IDENTITY_COUNT + MAX_LEN + 16];
        sms_smoother g;
        CHECK_STATUS(sms_smoother_init(&g, c, Ts, ring_b, MAX_LEN), SMS_OK);
        sms_smoother_get_state(&f, saved);
        CHECK_STATUS(sms_smoother_set_state(&g, saved, sms_smoother_state_count(&f)), SMS_OK);
        sms_smoother_process(&g, sig_in + hit + 1, sig_out2 + hit + 1, n - hit - 1);
    }
    sms_smoother_process(&f, sig_in + hit + 1, sig_out + hit + 1, n - hit - 1);
    for (i = hit + 1; i < n; ++i)
        CHECK(sig_out[i] == sig_out2[i] || (isnan((double)sig_out[i]) && isnan((double)sig_out2[i])));
    for (i = hit; i < n; ++i)
        if (!isfinite((double)sig_out[i]))
            last_bad = i;
    /* The bad sample is inside the window of every output from hit to hit + L - 1. */
    CHECK(!isfinite((double)sig_out[hit]));
    CHECK(last_bad >= hit + L - 1);
    recovered = hit + 2 * M + 1;
    CHECK(last_bad < recovered);
    for (i = recovered; i < n; ++i) {
        double y = 0.0;
        for (j = 0; j < L; ++j)
            y += taps[j] * (double)sig_in[i - j];
        CHECK_CLOSE(sig_out[i], y, 4.0 * SMS_TEST_REL_TOL, 2.0);
    }
}

/* Every invalid configuration: its status, and the instance left untouched. */
static void expect_rejected(const sms_stage_config *c, double Ts, sms_status status)
{
    sms_smoother f, before;
    size_t n = 7;
    memset(&f, 0xA5, sizeof f);
    memcpy(&before, &f, sizeof f);
    CHECK_STATUS(sms_smoother_init(&f, c, Ts, ring_a, MAX_LEN), status);
    CHECK(memcmp(&f, &before, sizeof f) == 0);
    CHECK_STATUS(sms_smoother_buffer_size(c, Ts, &n), status);
    CHECK(n == 7);
    CHECK_STATUS(sms_smoother_taps(c, Ts, taps, MAX_LEN), status);
}

static void test_invalid(void)
{
    const double Ts = 1e-3;
    sms_stage_config c = smoother(SMS_DAMPED_HARMONIC, 0.1, -2.0, 1u, SMS_TIMING_EXACT);
    sms_smoother f, before;
    size_t need;
    expect_rejected(&c, 0.0, SMS_ERR_SAMPLE_PERIOD);
    expect_rejected(&c, -1e-3, SMS_ERR_SAMPLE_PERIOD);
    expect_rejected(&c, NAN, SMS_ERR_SAMPLE_PERIOD);
    expect_rejected(&c, INFINITY, SMS_ERR_SAMPLE_PERIOD);
    c.kind = SMS_SHAPER_ZV;
    expect_rejected(&c, Ts, SMS_ERR_KIND);
    c.kind = (sms_kind)99;
    expect_rejected(&c, Ts, SMS_ERR_KIND);
    c = smoother(SMS_DAMPED_HARMONIC, 0.1, -2.0, 1u, (sms_timing)7);
    expect_rejected(&c, Ts, SMS_ERR_KIND);
    c.timing = SMS_TIMING_EXACT;
    c.T = 0.0;
    expect_rejected(&c, Ts, SMS_ERR_DURATION);
    c.T = -0.1;
    expect_rejected(&c, Ts, SMS_ERR_DURATION);
    c.T = NAN;
    expect_rejected(&c, Ts, SMS_ERR_DURATION);
    c.T = INFINITY;
    expect_rejected(&c, Ts, SMS_ERR_DURATION);
    c.T = 0.9e-3;
    expect_rejected(&c, Ts, SMS_ERR_DURATION_BELOW_TS);
    c.T = 1e-3; /* one sample of a half sine is its zero */
    expect_rejected(&c, Ts, SMS_ERR_DURATION_BELOW_TS);
    c.T = 1.3e-3;
    c.timing = SMS_TIMING_PAPER;
    expect_rejected(&c, Ts, SMS_ERR_DURATION_BELOW_TS);
    c = smoother(SMS_DAMPED_HARMONIC, 0.1, 0.5, 1u, SMS_TIMING_EXACT);
    expect_rejected(&c, Ts, SMS_ERR_SIGMA);
    c.sigma = NAN;
    expect_rejected(&c, Ts, SMS_ERR_SIGMA);
    c.sigma = -INFINITY;
    expect_rejected(&c, Ts, SMS_ERR_SIGMA);
    c.kind = SMS_EXPONENTIAL;
    expect_rejected(&c, Ts, SMS_ERR_SIGMA);
    c.kind = SMS_HARMONIC; /* the undamped families ignore sigma */
    CHECK_STATUS(sms_smoother_buffer_size(&c, Ts, &need), SMS_OK);
    c = smoother(SMS_RECTANGULAR, 0.1, 0.0, 0u, SMS_TIMING_EXACT);
    expect_rejected(&c, Ts, SMS_ERR_MULTIPLE);
    c = smoother(SMS_HARMONIC, 0.1, 0.0, 2u, SMS_TIMING_EXACT);
    expect_rejected(&c, Ts, SMS_ERR_EVEN_MULTIPLE);
    c.kind = SMS_DAMPED_HARMONIC;
    c.timing = SMS_TIMING_PAPER;
    expect_rejected(&c, Ts, SMS_ERR_EVEN_MULTIPLE);
    c.kind = SMS_RECTANGULAR; /* even k is fine for the rectangular family */
    CHECK_STATUS(sms_smoother_buffer_size(&c, Ts, &need), SMS_OK);
    /* Exact timing off the grid: w* = 2 pi k/T (3 pi k/T) must be below pi/Ts. */
    c = smoother(SMS_RECTANGULAR, 3.5e-3, 0.0, 2u, SMS_TIMING_EXACT);
    expect_rejected(&c, Ts, SMS_ERR_ABOVE_NYQUIST);
    c.k = 1u;
    CHECK_STATUS(sms_smoother_buffer_size(&c, Ts, &need), SMS_OK);
    c = smoother(SMS_HARMONIC, 8.5e-3, 0.0, 3u, SMS_TIMING_EXACT);
    expect_rejected(&c, Ts, SMS_ERR_ABOVE_NYQUIST);
    c.timing = SMS_TIMING_BOUNDED; /* bounded taps: real-pole families only */
    expect_rejected(&c, Ts, SMS_ERR_KIND);
    c = smoother(SMS_EXPONENTIAL, 3.5e-3, -1.0, 2u, SMS_TIMING_BOUNDED);
    expect_rejected(&c, Ts, SMS_ERR_ABOVE_NYQUIST);
    c.timing = SMS_TIMING_PAPER; /* paper timing pins nothing */
    CHECK_STATUS(sms_smoother_buffer_size(&c, Ts, &need), SMS_OK);
    c = smoother(SMS_EXPONENTIAL, 1e300, -1.0, 1u, SMS_TIMING_EXACT);
    expect_rejected(&c, Ts, SMS_ERR_TOO_LONG);
    c = smoother(SMS_RECTANGULAR, 1e4, 0.0, 1u, SMS_TIMING_PAPER);
    expect_rejected(&c, 1e-300, SMS_ERR_TOO_LONG);
    /* Buffers and pointers. */
    c = smoother(SMS_RECTANGULAR, 0.1, 0.0, 1u, SMS_TIMING_EXACT);
    CHECK_STATUS(sms_smoother_buffer_size(&c, Ts, &need), SMS_OK);
    CHECK(need == 100u);
    memset(&f, 0x5A, sizeof f);
    memcpy(&before, &f, sizeof f);
    CHECK_STATUS(sms_smoother_init(&f, &c, Ts, ring_a, need - 1), SMS_ERR_BUFFER_TOO_SMALL);
    CHECK_STATUS(sms_smoother_init(&f, &c, Ts, NULL, need), SMS_ERR_NULL);
    CHECK_STATUS(sms_smoother_init(&f, NULL, Ts, ring_a, need), SMS_ERR_NULL);
    CHECK(memcmp(&f, &before, sizeof f) == 0);
    CHECK_STATUS(sms_smoother_init(NULL, &c, Ts, ring_a, need), SMS_ERR_NULL);
    CHECK_STATUS(sms_smoother_buffer_size(&c, Ts, NULL), SMS_ERR_NULL);
    CHECK_STATUS(sms_smoother_taps(&c, Ts, NULL, 100), SMS_ERR_NULL);
    CHECK_STATUS(sms_smoother_init(&f, &c, Ts, ring_a, need), SMS_OK);
    c.T = 0.1234; /* exact timing off the grid: ring floor(nu), L = floor(nu) + 1 */
    CHECK_STATUS(sms_smoother_buffer_size(&c, Ts, &need), SMS_OK);
    CHECK(need == 123u);
}

int main(void)
{
    const double Ts = 1e-3;
    static const sms_kind kinds[4] = {SMS_RECTANGULAR, SMS_HARMONIC, SMS_DAMPED_HARMONIC, SMS_EXPONENTIAL};
    int f;
    for (f = 0; f < 4; ++f) {
        sms_stage_config grid = smoother(kinds[f], 0.057, -9.0, 1u, SMS_TIMING_EXACT);
        sms_stage_config off = smoother(kinds[f], 0.0614, -9.0, 1u, SMS_TIMING_EXACT);
        sms_stage_config tiny = smoother(kinds[f], is_harmonic(kinds[f]) ? 3.5e-3 : 2.5e-3,
                                         -9.0, 1u, SMS_TIMING_EXACT);
        test_blocks(&grid, Ts);
        test_blocks(&off, Ts);
        test_reset_rest(&grid, Ts);
        test_reset_rest(&off, Ts);
        test_state(&grid, Ts);
        test_state(&off, Ts);
        test_non_finite(&grid, Ts, NAN);
        test_non_finite(&off, Ts, INFINITY);
        test_non_finite(&tiny, Ts, -INFINITY);
        if (!is_harmonic(kinds[f])) { /* bounded timing: direct taps on x[n] and x[n-M] */
            off.timing = tiny.timing = SMS_TIMING_BOUNDED;
            test_blocks(&off, Ts);
            test_reset_rest(&off, Ts);
            test_state(&off, Ts);
            test_non_finite(&off, Ts, NAN);
            test_non_finite(&tiny, Ts, INFINITY);
        }
    }
    test_invalid();
    return check_summary("test_smoother_stream");
}
