/* SPDX-License-Identifier: Apache-2.0 */
/* Notch biquads: coefficients against the continuous notch (zeros, poles, pre-warping), the
 * -3 dB bandwidth formula, non-finite recovery, state and errors. */
#include <complex.h>
#include <string.h>
#include <stdlib.h>
#include "check.h"

#define PI 3.14159265358979323846

static sms_stage_config make(sms_kind kind, double wn, double xi1, double xi2)
{
    sms_stage_config c = sms_stage_config_default(kind);
    c.wn = wn;
    c.zeta = xi1;
    c.notch_pole_zeta = xi2;
    return c;
}

/* Realised numerator A + (1 - z^-1)(d0 - d2 z^-1) and denominator A of the filter */
static double complex den(const sms_notch *f, double complex z)
{
    return 1.0 + (double)f->a1 / z + (double)f->a2 / (z * z);
}

static double complex num(const sms_notch *f, double complex z)
{
    return den(f, z) + (1.0 - 1.0 / z) * ((double)f->d0 - (double)f->d2 / z);
}

static double complex gain(const sms_notch *f, double complex z)
{
    return num(f, z) / den(f, z);
}

static double complex continuous(double wn, double xi1, double xi2, double complex s)
{
    return (s * s + 2 * xi1 * wn * s + wn * wn) / (s * s + 2 * xi2 * wn * s + wn * wn);
}

static void test_tustin(void)
{
    const double Ts = 1e-3, wns[] = {50.0, 800.0, 3000.0}, xi1s[] = {0.0, 0.1}, xi2s[] = {0.5, 1.0, 2.5};
    size_t iw, i1, i2;
    for (iw = 0; iw < 3; ++iw)
        for (i1 = 0; i1 < 2; ++i1)
            for (i2 = 0; i2 < 3; ++i2) {
                double wn = wns[iw], xi1 = xi1s[i1], xi2 = xi2s[i2], w;
                double t = tan(0.5 * wn * Ts);
                sms_stage_config c = make(SMS_NOTCH_TUSTIN, wn, xi1, xi2);
                sms_notch f;
                CHECK_STATUS(sms_notch_init(&f, &c, Ts), SMS_OK);
                CHECK(gain(&f, 1.0) == 1.0);
                /* pre-warped: the discrete gain at wn is the continuous G(j wn) = xi1/xi2 */
                CHECK(cabs(gain(&f, cexp(I * wn * Ts)) - xi1 / xi2) <= 4 * SMS_TEST_REL_TOL);
                /* whole mapping: H(e^{jwTs}) = G(j wn tan(w Ts/2)/tan(wn Ts/2)) */
                for (w = 0.1 * wn; w < PI / Ts && w < 3 * wn; w += 0.37 * wn) {
                    double complex s = I * wn * tan(0.5 * w * Ts) / t;
                    CHECK(cabs(gain(&f, cexp(I * w * Ts)) - continuous(wn, xi1, xi2, s))
                          <= 8 * SMS_TEST_REL_TOL);
                }
            }
}

static void test_matched(void)
{
    const double Ts = 500e-6, wns[] = {123.7, 2000.0}, xi1s[] = {0.0, 0.126}, xi2s[] = {0.6, 1.0, 3.0};
    size_t iw, i1, i2;
    for (iw = 0; iw < 2; ++iw)
        for (i1 = 0; i1 < 2; ++i1)
            for (i2 = 0; i2 < 3; ++i2) {
                double wn = wns[iw], xi1 = xi1s[i1], xi2 = xi2s[i2];
                double complex zs = cexp((-xi1 * wn + I * wn * sqrt(1 - xi1 * xi1)) * Ts);
                double complex sp1, sp2;
                sms_stage_config c = make(SMS_NOTCH_MATCHED, wn, xi1, xi2);
                sms_notch f;
                double scale;
                CHECK_STATUS(sms_notch_init(&f, &c, Ts), SMS_OK);
                CHECK(gain(&f, 1.0) == 1.0);
                /* zeros exactly at the sampled mode e^{p Ts} */
                scale = 1.0 + (fabs((double)f.a1) + 2.0 * fabs((double)f.d0) + 2.0 * fabs((double)f.d2)) / cabs(zs)
                        + (fabs((double)f.a2) + fabs((double)f.d2)) / cabs(zs * zs);
                CHECK(cabs(num(&f, zs)) <= 4 * SMS_TEST_REL_TOL * scale);
                CHECK(cabs(num(&f, conj(zs))) <= 4 * SMS_TEST_REL_TOL * scale);
                /* poles at exp(s Ts) of the denominator roots (real when xi2 >= 1) */
                sp1 = -xi2 * wn + csqrt((double complex)(xi2 * xi2 - 1)) * wn;
                sp2 = -xi2 * wn - csqrt((double complex)(xi2 * xi2 - 1)) * wn;
                CHECK(cabs(den(&f, cexp(sp1 * Ts))) <= 1e3 * SMS_TEST_REL_TOL);
                CHECK(cabs(den(&f, cexp(sp2 * Ts))) <= 1e3 * SMS_TEST_REL_TOL);
            }
}

/* Filter output equals a direct evaluation of the difference equation from coefficients
 * computed here independently (double), and its step response settles to 1. */
static void test_response(void)
{
    enum { N = 4000 };
    const double Ts = 1e-3, wn = 300.0, xi1 = 0.05, xi2 = 0.8;
    double t = tan(0.5 * wn * Ts), a0 = 1 + 2 * xi2 * t + t * t;
    double b[3], a[3], x1 = 0, x2 = 0, y1 = 0, y2 = 0;
    sms_stage_config c = make(SMS_NOTCH_TUSTIN, wn, xi1, xi2);
    sms_notch f;
    size_t n;
    b[0] = (1 + 2 * xi1 * t + t * t) / a0; b[1] = 2 * (t * t - 1) / a0; b[2] = (1 - 2 * xi1 * t + t * t) / a0;
    a[1] = b[1]; a[2] = (1 - 2 * xi2 * t + t * t) / a0;
    CHECK_STATUS(sms_notch_init(&f, &c, Ts), SMS_OK);
    for (n = 0; n < N; ++n) {
        double xin = n < 10 ? 0.0 : 1.0 + 0.3 * sin(0.01 * (double)n);
        double y = b[0] * xin + b[1] * x1 + b[2] * x2 - a[1] * y1 - a[2] * y2;
        sms_real v = (sms_real)xin;
        sms_notch_step(&f, &v);
        CHECK_CLOSE(v, y, 20 * SMS_TEST_REL_TOL, 1.0);
        x2 = x1; x1 = xin; y2 = y1; y1 = y;
    }
    /* unit DC gain by structure: a constant input comes out exactly, in any precision, for a
     * notch far below Nyquist too (where a direct-form biquad in float misses by ~1e-5) */
    {
        const double wns[] = {300.0, 5.0}, vals[] = {1.0, 1234.5678, -0.001};
        size_t iw, iv;
        for (iw = 0; iw < 2; ++iw)
            for (iv = 0; iv < 3; ++iv) {
                sms_stage_config m = make(iw ? SMS_NOTCH_MATCHED : SMS_NOTCH_TUSTIN, wns[iw], 0.02, 0.9);
                sms_real v = 0;
                CHECK_STATUS(sms_notch_init(&f, &m, Ts), SMS_OK);
                for (n = 0; n < 20 * N; ++n) {
                    v = (sms_real)vals[iv];
                    sms_notch_step(&f, &v);
                }
                CHECK(v == (sms_real)vals[iv]);
            }
    }
}

/* -3 dB bandwidth: |G(j w+-)|^2 = 1/2 exactly at w+- = wn (sqrt(c^2+1) +- c), w+ - w- = B. */
static void test_bandwidth(void)
{
    const double wn = 200.0, xi1s[] = {0.0, 0.1, 0.3}, Bs[] = {5.0, 80.0, 600.0};
    size_t i, j;
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 3; ++j) {
            double xi2, c, wp, wm;
            CHECK_STATUS(sms_notch_pole_zeta_from_bandwidth(wn, xi1s[i], Bs[j], &xi2), SMS_OK);
            CHECK(xi2 > xi1s[i]);
            c = Bs[j] / (2 * wn);
            wp = wn * (sqrt(c * c + 1) + c);
            wm = wn * (sqrt(c * c + 1) - c);
            CHECK_CLOSE(wp - wm, Bs[j], 1e-12, Bs[j]);
            if (xi2 * xi2 > 2 * xi1s[i] * xi1s[i] + 1e-12) {
                CHECK_CLOSE(cabs(continuous(wn, xi1s[i], xi2, I * wp)), sqrt(0.5), 1e-12, 1.0);
                CHECK_CLOSE(cabs(continuous(wn, xi1s[i], xi2, I * wm)), sqrt(0.5), 1e-12, 1.0);
                /* and only there: inside the band the gain is below -3 dB */
                CHECK(cabs(continuous(wn, xi1s[i], xi2, I * wn)) < sqrt(0.5));
            }
        }
    {
        double xi2 = -1;
        CHECK_STATUS(sms_notch_pole_zeta_from_bandwidth(wn, 0.1, 0.0, &xi2), SMS_ERR_BANDWIDTH);
        CHECK_STATUS(sms_notch_pole_zeta_from_bandwidth(wn, 0.1, -3.0, &xi2), SMS_ERR_BANDWIDTH);
        CHECK_STATUS(sms_notch_pole_zeta_from_bandwidth(wn, 0.1, NAN, &xi2), SMS_ERR_BANDWIDTH);
        CHECK_STATUS(sms_notch_pole_zeta_from_bandwidth(wn, 0.1, INFINITY, &xi2), SMS_ERR_BANDWIDTH);
        CHECK_STATUS(sms_notch_pole_zeta_from_bandwidth(wn, 0.1, 1e9, &xi2), SMS_ERR_BANDWIDTH);
        CHECK_STATUS(sms_notch_pole_zeta_from_bandwidth(0.0, 0.1, 5.0, &xi2), SMS_ERR_WN);
        CHECK_STATUS(sms_notch_pole_zeta_from_bandwidth(NAN, 0.1, 5.0, &xi2), SMS_ERR_WN);
        CHECK_STATUS(sms_notch_pole_zeta_from_bandwidth(wn, 1.0, 5.0, &xi2), SMS_ERR_ZETA);
        CHECK_STATUS(sms_notch_pole_zeta_from_bandwidth(wn, 0.1, 5.0, NULL), SMS_ERR_NULL);
        CHECK(xi2 == -1);
    }
}

/* NaN/Inf input passes through and is skipped; overflow restarts at rest at the input. */
static void test_non_finite(void)
{
    enum { N = 300 };
    const double Ts = 1e-3;
    sms_stage_config c = make(SMS_NOTCH_MATCHED, 400.0, 0.02, 0.7);
    sms_notch f, g;
    size_t n;
    int same = 1, finite_after = 1;
#ifdef SMS_USE_FLOAT
    const sms_real huge = (sms_real)3e38;
#else
    const sms_real huge = (sms_real)1.7e308;
#endif
    CHECK_STATUS(sms_notch_init(&f, &c, Ts), SMS_OK);
    CHECK_STATUS(sms_notch_init(&g, &c, Ts), SMS_OK);
    for (n = 0; n < N; ++n) {
        sms_real in = (sms_real)(1.0 + sin(0.1 * (double)n)), x = in, y = in;
        if (n == 50 || n == 51) {
            x = n == 50 ? (sms_real)NAN : (sms_real)-INFINITY;
            sms_notch_step(&f, &x);
            CHECK(x != x || x == (sms_real)-INFINITY);
            continue;                     /* g never sees the bad samples */
        }
        sms_notch_step(&f, &x);
        sms_notch_step(&g, &y);
        same &= memcmp(&x, &y, sizeof x) == 0;
    }
    CHECK(same);
    /* overflow from finite input */
    sms_notch_reset(&f, 0);
    for (n = 0; n < N; ++n) {
        sms_real x = (n % 2) ? huge : -huge;
        if (n > 20)
            x = 1;
        sms_notch_step(&f, &x);
        if (n > 20)
            finite_after &= x - x == 0;
    }
    CHECK(finite_after);
    {   /* the huge-but-finite transient decays with the pole radius e^{-xi2 wn Ts} = 0.76 per
         * sample: 4000 samples take 1e308 below 1e-400 */
        sms_real x = 1;
        for (n = 0; n < 4000; ++n) {
            x = 1;
            sms_notch_step(&f, &x);
        }
        CHECK_CLOSE(x, 1.0, SMS_TEST_REL_TOL, 1.0);
    }
}

static void test_blocks_and_state(void)
{
    enum { N = 2000 };
    static sms_real in[N], one[N], split[N];
    double st[SMS_STATE_IDENTITY_COUNT + 6], st2[SMS_STATE_IDENTITY_COUNT + 6];
    sms_stage_config c = make(SMS_NOTCH_TUSTIN, 250.0, 0.0, 0.5);
    sms_notch f, g, saved;
    size_t pos = 0, i;
    int same = 1;
    srand(3);
    for (i = 0; i < N; ++i)
        in[i] = (sms_real)(1e3 + (double)rand() / RAND_MAX);
    CHECK_STATUS(sms_notch_init(&f, &c, 1e-3), SMS_OK);
    CHECK_STATUS(sms_notch_init(&g, &c, 1e-3), SMS_OK);
    sms_notch_process(&f, in, one, N);
    while (pos < N) {
        size_t len = (size_t)(rand() % 50);
        if (len > N - pos) len = N - pos;
        memcpy(split + pos, in + pos, len * sizeof *in);
        sms_notch_process(&g, split + pos, split + pos, len);
        pos += len;
    }
    for (i = 0; i < N; ++i)
        same &= memcmp(&one[i], &split[i], sizeof one[i]) == 0;
    CHECK(same);
    CHECK(sms_notch_state_count(&f) == SMS_STATE_IDENTITY_COUNT + 6);
    CHECK_STATUS(sms_notch_init(&f, &c, 1e-3), SMS_OK);
    sms_notch_process(&f, in, one, N / 2);
    sms_notch_get_state(&f, st);
    sms_notch_process(&f, in + N / 2, one + N / 2, N - N / 2);
    CHECK_STATUS(sms_notch_init(&g, &c, 1e-3), SMS_OK);
    CHECK_STATUS(sms_notch_set_state(&g, st, SMS_STATE_IDENTITY_COUNT + 6), SMS_OK);
    sms_notch_process(&g, in + N / 2, split + N / 2, N - N / 2);
    same = 1;
    for (i = N / 2; i < N; ++i)
        same &= memcmp(&one[i], &split[i], sizeof one[i]) == 0;
    CHECK(same);
    saved = g;
    memcpy(st2, st, sizeof st);
    st2[SMS_STATE_IDENTITY_COUNT] = (double)SMS_NOTCH_MATCHED;
    CHECK_STATUS(sms_notch_set_state(&g, st2, SMS_STATE_IDENTITY_COUNT + 6), SMS_ERR_STATE);
    CHECK_STATUS(sms_notch_set_state(&g, st, SMS_STATE_IDENTITY_COUNT + 5), SMS_ERR_STATE);
    CHECK_STATUS(sms_notch_check_state(&g, st, SMS_STATE_IDENTITY_COUNT + 7), SMS_ERR_STATE);
    CHECK_STATUS(sms_notch_set_state(&g, NULL, SMS_STATE_IDENTITY_COUNT + 6), SMS_ERR_NULL);
    CHECK(memcmp(&saved, &g, sizeof g) == 0);
    {   /* a non-finite state (e.g. loaded) restarts at rest at the next finite input */
        double poisoned[SMS_STATE_IDENTITY_COUNT + 6];
        sms_real x = (sms_real)2;
        memcpy(poisoned, st, sizeof st);
        poisoned[SMS_STATE_IDENTITY_COUNT + 3] = NAN;
        poisoned[SMS_STATE_IDENTITY_COUNT + 4] = INFINITY;
        CHECK_STATUS(sms_notch_set_state(&g, poisoned, SMS_STATE_IDENTITY_COUNT + 6), SMS_OK);
        sms_notch_step(&g, &x);
        CHECK(x == (sms_real)2);
        for (i = 0; i < 10; ++i) {
            x = (sms_real)2;
            sms_notch_step(&g, &x);
            CHECK_CLOSE(x, 2.0, 10 * SMS_TEST_REL_TOL, 2.0);
        }
    }
    sms_notch_reset(&g, (sms_real)-4);
    for (i = 0; i < 10; ++i) {
        sms_real x = (sms_real)-4;
        sms_notch_step(&g, &x);
        CHECK_CLOSE(x, -4.0, 10 * SMS_TEST_REL_TOL, 4.0);
    }
}

static void test_invalid(void)
{
    const double Ts = 1e-3;
    sms_notch f, before;
    sms_stage_config good = make(SMS_NOTCH_MATCHED, 100.0, 0.1, 0.7), c;
    memset(&f, 0x3c, sizeof f);
    before = f;
#define EXPECT_BAD(cfg, ts, status) do { \
        CHECK_STATUS(sms_notch_init(&f, &(cfg), (ts)), status); \
        CHECK(memcmp(&f, &before, sizeof f) == 0); } while (0)
    c = good; c.kind = SMS_SHAPER_ZV; EXPECT_BAD(c, Ts, SMS_ERR_KIND);
    c = good; c.kind = (sms_kind)-1; EXPECT_BAD(c, Ts, SMS_ERR_KIND);
    c = good; EXPECT_BAD(c, 0.0, SMS_ERR_SAMPLE_PERIOD);
    c = good; EXPECT_BAD(c, NAN, SMS_ERR_SAMPLE_PERIOD);
    c = good; EXPECT_BAD(c, -INFINITY, SMS_ERR_SAMPLE_PERIOD);
    c = good; c.wn = 0; EXPECT_BAD(c, Ts, SMS_ERR_WN);
    c = good; c.wn = INFINITY; EXPECT_BAD(c, Ts, SMS_ERR_WN);
    c = good; c.wn = PI / Ts; EXPECT_BAD(c, Ts, SMS_ERR_ABOVE_NYQUIST);
    c = good; c.zeta = -0.1; EXPECT_BAD(c, Ts, SMS_ERR_ZETA);
    c = good; c.zeta = 1.0; c.notch_pole_zeta = 2.0; EXPECT_BAD(c, Ts, SMS_ERR_ZETA);
    c = good; c.notch_pole_zeta = 0.1; EXPECT_BAD(c, Ts, SMS_ERR_NOTCH_DAMPING);
    c = good; c.notch_pole_zeta = 0.05; EXPECT_BAD(c, Ts, SMS_ERR_NOTCH_DAMPING);
    c = good; c.notch_pole_zeta = NAN; EXPECT_BAD(c, Ts, SMS_ERR_NOTCH_DAMPING);
    c = good; c.notch_pole_zeta = 2e6; EXPECT_BAD(c, Ts, SMS_ERR_NOTCH_DAMPING);
    c = good; c.kind = SMS_NOTCH_TUSTIN; c.wn = -1; c.zeta = 5; EXPECT_BAD(c, Ts, SMS_ERR_WN);
    CHECK_STATUS(sms_notch_init(NULL, &good, Ts), SMS_ERR_NULL);
    CHECK_STATUS(sms_notch_init(&f, NULL, Ts), SMS_ERR_NULL);
    CHECK(memcmp(&f, &before, sizeof f) == 0);
    /* fields other families use are not read; xi2 >= 1 (real poles) is valid */
    c = good; c.timing = (sms_timing)9; c.T = NAN; c.sigma = 3; c.order = 0; c.tolerance = -1;
    c.notch_pole_zeta = 1.0;
    CHECK_STATUS(sms_notch_init(&f, &c, Ts), SMS_OK);
#undef EXPECT_BAD
}

int main(void)
{
    test_tustin();
    test_matched();
    test_response();
    test_bandwidth();
    test_non_finite();
    test_blocks_and_state();
    test_invalid();
    return check_summary("test_notch");
}
