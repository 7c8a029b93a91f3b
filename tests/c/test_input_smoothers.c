/* SPDX-License-Identifier: Apache-2.0 */
/* Input smoothers (smooth ZV ... smooth SI): the discrete taps against the contract of
 * shaper.h (unit gain, the continuous centroid, near-zero end taps, the design's residual at the
 * mode for any Ts), the continuous transfer against a dense discretisation, the engine against
 * the taps, every invalid configuration and the saved-state identity. */
#include <complex.h>
#include <stdlib.h>
#include <string.h>
#include "check.h"

#define PI 3.14159265358979323846
#define MAX_LEN 40000

static sms_shaper_tap table[MAX_LEN];
static sms_real ring[MAX_LEN];
static double h[MAX_LEN];

static const sms_kind kinds[] = {SMS_SMOOTH_ZV, SMS_SMOOTH_MZV, SMS_SMOOTH_EI, SMS_SMOOTH_EI2,
                                 SMS_SMOOTH_ZVD_EI, SMS_SMOOTH_SI};
/* T f of each kernel at zeta = 0 (shaper_defs.py: t[0] of the cubic, or the constant) */
static const double span[] = {0.66471804, 0.85165483, 0.96753911, 1.14875, 1.475, 1.245};

static sms_stage_config smooth(sms_kind kind, double f, double zeta)
{
    sms_stage_config c = sms_stage_config_default(kind);
    c.wn = 2 * PI * f;
    c.zeta = zeta;
    return c;
}

static double complex transfer(const double *taps, size_t L, double complex z)
{
    double complex acc = 0, zi = 1.0;
    size_t k;
    for (k = 0; k < L; ++k) {
        acc += taps[k] * zi;
        zi /= z;
    }
    return acc;
}

/* Unit gain, the window length, the centroid T/2 of the symmetric kernels at zeta = 0 (and of
 * every smoother, its continuous value: the slope of H_c at s = 0), end taps near 0 and the
 * residual at the mode for sample periods on and off the grid. */
static void test_taps_contract(void)
{
    static const double periods[] = {1e-3, 4.1e-4, 1.234567e-4, 2.5e-5};
    size_t ik, ip, k, L;
    for (ik = 0; ik < 6; ++ik)
        for (ip = 0; ip < 4; ++ip) {
            const double f = 37.5, Ts = periods[ip], zeta = ik < 3 ? 0.0 : 0.13;
            sms_stage_config c = smooth(kinds[ik], f, zeta);
            double T = span[ik] / f, sum = 0, centroid = 0, peak = 0, re, im, eps = 1e-6 / T;
            double complex p = I * 2 * PI * f, hp;
            CHECK_STATUS(sms_shaper_buffer_size(&c, Ts, &L), SMS_OK);
            CHECK(L == (size_t)ceil(T / Ts - 1e-9) + 1);
            CHECK_STATUS(sms_shaper_taps(&c, Ts, h, MAX_LEN), SMS_OK);
            for (k = 0; k < L; ++k) {
                sum += h[k];
                centroid += h[k] * (double)k * Ts;
                peak = fabs(h[k]) > peak ? fabs(h[k]) : peak;
            }
            CHECK_CLOSE(sum, 1.0, 1e-14, 1.0);
            if (ik < 3) {
                CHECK_CLOSE(centroid, T / 2, 1e-13, T);
            } else {
                /* -dH_c/ds at 0 by a central difference: error eps^2 T^2 / 6, 1e-13 of T */
                double hp_re, hm_re, unused;
                CHECK_STATUS(sms_shaper_transfer(&c, eps, 0.0, &hp_re, &unused), SMS_OK);
                CHECK_STATUS(sms_shaper_transfer(&c, -eps, 0.0, &hm_re, &unused), SMS_OK);
                CHECK_CLOSE(centroid, -(hp_re - hm_re) / (2 * eps), 1e-9, T);
            }
            if (ik >= 3)      /* zeta not read: the undamped design point is pinned */
                p = I * 2 * PI * f;
            CHECK_STATUS(sms_shaper_transfer(&c, creal(p), cimag(p), &re, &im), SMS_OK);
            hp = transfer(h, L, cexp(p * Ts));
            CHECK(cabs(hp - (re + I * im)) <= 1e-12);
        }
    /* damped kernels: the pinned point is the damped pole */
    for (ik = 0; ik < 3; ++ik) {
        const double f = 52.0, zeta = 0.2, Ts = 3.3e-4, wn = 2 * PI * f;
        double complex p = -zeta * wn + I * wn * sqrt(1 - zeta * zeta);
        double re, im;
        sms_stage_config c = smooth(kinds[ik], f, zeta);
        CHECK_STATUS(sms_shaper_buffer_size(&c, Ts, &L), SMS_OK);
        CHECK_STATUS(sms_shaper_taps(&c, Ts, h, MAX_LEN), SMS_OK);
        CHECK_STATUS(sms_shaper_transfer(&c, creal(p), cimag(p), &re, &im), SMS_OK);
        CHECK(cabs(transfer(h, L, cexp(p * Ts)) - (re + I * im)) <= 1e-12);
    }
}

/* The kernel is 0 at both ends: an end tap int g(tau) L(tau/Ts) over one sample is then
 * g'(0) Ts^2/6 + O(Ts^3) (g(0) != 0 would give g(0) Ts/2), so halving Ts on the grid
 * (T/Ts = 1000, 2000) divides both end taps by 4, to O(Ts/T) = 0.1 %. */
static void test_zero_end_taps(void)
{
    size_t ik, L1, L2;
    for (ik = 0; ik < 6; ++ik) {
        const double f = 25.0, T = span[ik] / f;
        sms_stage_config c = smooth(kinds[ik], f, 0.0);
        double h1[2];
        CHECK_STATUS(sms_shaper_buffer_size(&c, T / 1000, &L1), SMS_OK);
        CHECK_STATUS(sms_shaper_taps(&c, T / 1000, h, MAX_LEN), SMS_OK);
        h1[0] = h[0];
        h1[1] = h[L1 - 1];
        CHECK_STATUS(sms_shaper_buffer_size(&c, T / 2000, &L2), SMS_OK);
        CHECK_STATUS(sms_shaper_taps(&c, T / 2000, h, MAX_LEN), SMS_OK);
        CHECK(L1 == 1001 && L2 == 2001);
        CHECK_CLOSE(h[0] / h1[0], 0.25, 0.01, 1.0);
        CHECK_CLOSE(h[L2 - 1] / h1[1], 0.25, 0.01, 1.0);
    }
}

/* The continuous transfer against a dense discretisation (T/Ts = 2e4: the linear-interpolation
 * taps differ from the kernel by about (w Ts)^2/12 < 1e-7 over w <= 4 x the design frequency), and the
 * design's residual e^{-zeta wn T} |H_c(p)| at the mode as the source defines it: below 1e-4 for
 * the zero-vibration kernels, below the 5 % tolerance for the EI-like ones. */
static void test_continuous_transfer(void)
{
    size_t ik, k, L;
    int iw;
    for (ik = 0; ik < 6; ++ik) {
        /* the damping-independent kernels were designed at the source's default damping 0.1 */
        const double f = 40.0, zeta = 0.1, wn = 2 * PI * f;
        const double T = span[ik] / f, Ts = T / 20000.0;
        double complex p = -zeta * wn + I * wn * sqrt(1 - zeta * zeta);
        double re, im, residual, Tz, pin;
        sms_stage_config c = smooth(kinds[ik], f, zeta);
        CHECK_STATUS(sms_shaper_buffer_size(&c, Ts, &L), SMS_OK);
        CHECK(L < MAX_LEN);
        CHECK_STATUS(sms_shaper_taps(&c, Ts, h, MAX_LEN), SMS_OK);
        CHECK_STATUS(sms_shaper_transfer(&c, ik < 3 ? creal(p) : 0.0, ik < 3 ? cimag(p) : wn,
                                         &re, &im), SMS_OK);
        pin = cabs(re + I * im);
        for (iw = 0; iw <= 40; ++iw) {
            double w = wn * iw / 10.0;
            CHECK_STATUS(sms_shaper_transfer(&c, 0.0, w, &re, &im), SMS_OK);
            /* linear interpolation: H_d = H_c sinc^2(w Ts/2) + aliases, 1 - sinc^2 <= (w Ts)^2/12;
             * the correction restoring H at the pinned point, whose interpolation error is
             * |H_c(pin)| (wn Ts)^2/12, adds at most twice that anywhere (measured: 0.06 x) */
            CHECK(cabs(transfer(h, L, cexp(I * w * Ts)) - (re + I * im))
                  <= 1.01 * (w * Ts) * (w * Ts) / 12 * cabs(re + I * im)
                     + 2 * (wn * Ts) * (wn * Ts) / 12 * pin + 1e-12);
        }
        CHECK_STATUS(sms_shaper_transfer(&c, creal(p), cimag(p), &re, &im), SMS_OK);
        Tz = (double)(L - 1) * Ts;
        residual = exp(-zeta * wn * Tz) * cabs(re + I * im);
        if (kinds[ik] == SMS_SMOOTH_EI || kinds[ik] == SMS_SMOOTH_EI2)
            CHECK(residual < 0.05);
        else
            CHECK(residual < 1e-4);
        (void)k;
    }
}

/* The engine runs the taps: an impulse response equals them, and a ramp comes out delayed by
 * the centroid once the window has passed. */
static void test_engine(void)
{
    const double Ts = 2e-4, f = 60.0;
    sms_stage_config c = smooth(SMS_SMOOTH_MZV, f, 0.0);
    sms_shaper s;
    size_t L, n_taps, i;
    double T = span[1] / f;
    CHECK_STATUS(sms_shaper_tap_count(&c, Ts, &n_taps), SMS_OK);
    CHECK_STATUS(sms_shaper_buffer_size(&c, Ts, &L), SMS_OK);
    CHECK(n_taps == L);
    CHECK_STATUS(sms_shaper_taps(&c, Ts, h, MAX_LEN), SMS_OK);
    CHECK_STATUS(sms_shaper_init(&s, &c, Ts, table, n_taps, ring, L), SMS_OK);
    for (i = 0; i < L + 2; ++i) {
        sms_real x = i == 0 ? (sms_real)1 : (sms_real)0;
        sms_shaper_step(&s, &x);
        CHECK_CLOSE(x, i < L ? h[i] : 0.0, 4 * SMS_TEST_REL_TOL, 1.0);
    }
    sms_shaper_reset(&s, (sms_real)0);
    for (i = 0; i < 3 * L; ++i) {
        sms_real x = (sms_real)(2.0 * (double)i * Ts);
        sms_shaper_step(&s, &x);
        if (i >= L)
            CHECK_CLOSE(x, 2.0 * ((double)i * Ts - T / 2), 16 * SMS_TEST_REL_TOL, 6.0 * L * Ts);
    }
}

static void test_invalid(void)
{
    const double Ts = 1e-3;
    size_t ik, L;
    sms_shaper f, before;
    double A[9], t[9];
    size_t n;
    memset(&f, 0x33, sizeof f);
    before = f;
#define EXPECT_BAD(cfg, status) do { CHECK_STATUS(sms_shaper_buffer_size(&(cfg), Ts, &L), status); \
    CHECK_STATUS(sms_shaper_init(&f, &(cfg), Ts, table, MAX_LEN, ring, MAX_LEN), status); \
    CHECK(memcmp(&f, &before, sizeof f) == 0); } while (0)
    for (ik = 0; ik < 6; ++ik) {
        sms_stage_config good = smooth(kinds[ik], 30.0, 0.1), c;
        int reads_zeta = ik < 3;
        CHECK_STATUS(sms_shaper_buffer_size(&good, Ts, &L), SMS_OK);
        c = good; c.wn = 0.0; EXPECT_BAD(c, SMS_ERR_WN);
        c = good; c.wn = NAN; EXPECT_BAD(c, SMS_ERR_WN);
        c = good; c.wn = INFINITY; EXPECT_BAD(c, SMS_ERR_WN);
        c = good; c.wn = PI / Ts; EXPECT_BAD(c, SMS_ERR_ABOVE_NYQUIST);
        /* the kernel must span 4 samples: T = span/f >= 4 Ts */
        c = good; c.wn = 2 * PI * span[ik] / (4 * Ts) * 1.001; c.zeta = 0.0; EXPECT_BAD(c, SMS_ERR_ABOVE_NYQUIST);
        c = good; c.wn = 2 * PI * span[ik] / (4 * Ts) * 0.999; c.zeta = 0.0;
        CHECK_STATUS(sms_shaper_buffer_size(&c, Ts, &L), SMS_OK);
        c = good; c.timing = SMS_TIMING_PAPER; EXPECT_BAD(c, SMS_ERR_KIND);
        c = good; c.timing = SMS_TIMING_BOUNDED; EXPECT_BAD(c, SMS_ERR_KIND);
        c = good; c.wn = 1e-300; EXPECT_BAD(c, SMS_ERR_TOO_LONG);
        c = good; c.zeta = 0.2500001;
        if (reads_zeta) EXPECT_BAD(c, SMS_ERR_ZETA);
        else CHECK_STATUS(sms_shaper_buffer_size(&c, Ts, &L), SMS_OK);
        c = good; c.zeta = NAN;
        if (reads_zeta) EXPECT_BAD(c, SMS_ERR_ZETA);
        else CHECK_STATUS(sms_shaper_buffer_size(&c, Ts, &L), SMS_OK);
        c = good; c.zeta = -1e-9;
        if (reads_zeta) EXPECT_BAD(c, SMS_ERR_ZETA);
        c = good; c.zeta = 0.25;
        CHECK_STATUS(sms_shaper_buffer_size(&c, Ts, &L), SMS_OK);
        /* a kernel, not impulses */
        CHECK_STATUS(sms_shaper_impulses(&good, A, t, 9, &n), SMS_ERR_KIND);
        CHECK_STATUS(sms_shaper_init(&f, &good, Ts, table, 2, ring, MAX_LEN), SMS_ERR_BUFFER_TOO_SMALL);
        CHECK(memcmp(&f, &before, sizeof f) == 0);
    }
#undef EXPECT_BAD
}

/* The identity holds zeta only for the kernels that read it. */
static void test_state_identity(void)
{
    static sms_shaper_tap table2[2000];
    static sms_real ring2[2000];
    static double state[4000];
    const double Ts = 1e-3;
    sms_stage_config a = smooth(SMS_SMOOTH_ZV, 30.0, 0.1), b = smooth(SMS_SMOOTH_ZV, 30.0, 0.1000001);
    sms_shaper fa, fb;
    size_t L;
    CHECK_STATUS(sms_shaper_buffer_size(&a, Ts, &L), SMS_OK);
    CHECK_STATUS(sms_shaper_init(&fa, &a, Ts, table, MAX_LEN, ring, MAX_LEN), SMS_OK);
    CHECK_STATUS(sms_shaper_init(&fb, &b, Ts, table2, 2000, ring2, 2000), SMS_OK);
    sms_shaper_get_state(&fa, state);
    CHECK(sms_shaper_state_count(&fa) == sms_shaper_state_count(&fb));
    CHECK_STATUS(sms_shaper_set_state(&fb, state, sms_shaper_state_count(&fa)), SMS_ERR_STATE_ZETA);
    a = smooth(SMS_SMOOTH_SI, 30.0, 0.1);
    b = smooth(SMS_SMOOTH_SI, 30.0, 0.2);    /* zeta not read: the same filter */
    CHECK_STATUS(sms_shaper_init(&fa, &a, Ts, table, MAX_LEN, ring, MAX_LEN), SMS_OK);
    CHECK_STATUS(sms_shaper_init(&fb, &b, Ts, table2, 2000, ring2, 2000), SMS_OK);
    sms_shaper_get_state(&fa, state);
    CHECK_STATUS(sms_shaper_set_state(&fb, state, sms_shaper_state_count(&fa)), SMS_OK);
}

int main(void)
{
    test_taps_contract();
    test_zero_end_taps();
    test_continuous_transfer();
    test_engine();
    test_invalid();
    test_state_identity();
    return check_summary("test_input_smoothers");
}
