/* SPDX-License-Identifier: Apache-2.0 */
/* Specified-insensitivity shapers and user-defined impulses: the SI closed form against its
 * defining properties (|H| <= V over the band it states, equal to V at its edge, EI, EI3 and ZV
 * as special cases,
 * no negative impulse, the shortest design for a band), user impulses against the firmware's
 * definition and the linear split, every invalid configuration, and the saved-state identity. */
#include <complex.h>
#include <string.h>
#include "check.h"

#define PI 3.14159265358979323846
#define MAX_LEN 4096

static sms_shaper_tap table[SMS_SHAPER_MAX_TAPS];
static sms_real ring[MAX_LEN];

static sms_stage_config si(unsigned n, double D, double V, double wn, double zeta)
{
    sms_stage_config c = sms_stage_config_default(SMS_SHAPER_SI);
    c.order = n;
    c.duration = D;
    c.tolerance = V;
    c.wn = wn;
    c.zeta = zeta;
    return c;
}

/* |H(jw)| of impulses (A, t) at w [rad/s] with the undamped amplitudes (zeta = 0 designs). */
static double gain_at(const double *A, const double *t, size_t n, double w)
{
    double complex h = 0;
    size_t m;
    for (m = 0; m < n; ++m)
        h += A[m] * cexp(-I * w * t[m]);
    return cabs(h);
}

static void impulses_of(const sms_stage_config *c, double *A, double *t, size_t *n)
{
    CHECK_STATUS(sms_shaper_impulses(c, A, t, SMS_SHAPER_MAX_IMPULSES, n), SMS_OK);
}

/* SI with D = (n-1)/2 is EI (n = 3) and the three-hump EI (n = 5); n = 3, D = 1/2 is ZV: the
 * closed forms of Singhose et al. are the Chebyshev polynomials of degree 1 and 2. */
static void test_si_special_cases(void)
{
    static const double tolerances[] = {1e-4, 0.01, 0.05, 0.2, 0.6, 0.95};
    static const double zetas[] = {0.0, 0.1, 0.4};
    size_t iv, iz, m, n, n_ref;
    for (iv = 0; iv < sizeof tolerances / sizeof tolerances[0]; ++iv)
        for (iz = 0; iz < 3; ++iz) {
            double V = tolerances[iv], zeta = zetas[iz], wn = 2 * PI * 40;
            double A[9], t[9], Ar[9], tr[9];
            sms_stage_config ei = sms_stage_config_default(SMS_SHAPER_EI), ref;
            ei.wn = wn;
            ei.zeta = zeta;
            ei.tolerance = V;
            ref = ei;
            impulses_of(&ref, Ar, tr, &n_ref);
            ref = si(3, 1.0, V, wn, zeta);
            impulses_of(&ref, A, t, &n);
            CHECK(n == 3 && n_ref == 3);
            for (m = 0; m < 3; ++m) {
                CHECK_CLOSE(A[m], Ar[m], 4e-15, 1.0);
                CHECK_CLOSE(t[m], tr[m], 4e-15, tr[2]);
            }
            ei.kind = SMS_SHAPER_EI3;
            impulses_of(&ei, Ar, tr, &n_ref);
            ref = si(5, 2.0, V, wn, zeta);
            impulses_of(&ref, A, t, &n);
            CHECK(n == 5 && n_ref == 5);
            for (m = 0; m < 5; ++m) {
                CHECK_CLOSE(A[m], Ar[m], 1e-14, 1.0);
                CHECK_CLOSE(t[m], tr[m], 4e-15, tr[4]);
            }
            ei.kind = SMS_SHAPER_ZV;
            impulses_of(&ei, Ar, tr, &n_ref);
            ref = si(3, 0.5, V, wn, zeta);
            impulses_of(&ref, A, t, &n);
            CHECK(A[1] == 0.0);             /* the middle impulse vanishes */
            CHECK_CLOSE(A[0], Ar[0], 4e-15, 1.0);
            CHECK_CLOSE(A[2], Ar[1], 4e-15, 1.0);
            CHECK_CLOSE(t[2], tr[1], 4e-15, tr[1]);
        }
}

/* The closed form's claims, undamped: |H| <= V over w/wd in [1 - I/2, 1 + I/2] with equality at
 * the lower edge (and the upper one while the band lies below theta = pi), |H| > V just below
 * it (the band is the widest), no negative impulse, and
 * I growing with D over [d/2, d]. The tolerance 1e-12 covers the rounding of the Chebyshev
 * recurrence and the cosine transform (terms of size <= x1^d / V, here <= 1e3). */
static void test_si_equal_ripple(void)
{
    static const double tolerances[] = {1e-3, 0.05, 0.3, 0.9};
    unsigned n;
    size_t iv, j, i;
    for (iv = 0; iv < 4; ++iv)
        for (n = 3; n <= 9; n += 2)
            for (j = 0; j <= 8; ++j) {
                double V = tolerances[iv], d = 0.5 * (n - 1), D = d * (0.5 + j / 16.0);
                double I_now, I_next, A[9], t[9], peak = 0, wd = 1.0;
                size_t m, count;
                sms_stage_config c = si(n, D, V, wd, 0.0);
                CHECK_STATUS(sms_shaper_si_insensitivity(n, D, V, &I_now), SMS_OK);
                if (j < 8) {
                    CHECK_STATUS(sms_shaper_si_insensitivity(n, d * (0.5 + (j + 1) / 16.0), V,
                                                             &I_next), SMS_OK);
                    CHECK(I_next > I_now);
                }
                impulses_of(&c, A, t, &count);
                for (m = 0; m < count; ++m)
                    CHECK(A[m] >= 0.0);
                for (i = 0; i <= 400; ++i) {
                    double w = wd * (1.0 - I_now / 2 + I_now * i / 400.0), g = gain_at(A, t, count, w);
                    peak = g > peak ? g : peak;
                }
                CHECK(peak <= V * (1 + 1e-12));
                CHECK_CLOSE(gain_at(A, t, count, wd * (1 - I_now / 2)), V, 1e-12, 1.0);
                CHECK(gain_at(A, t, count, wd * (1 - I_now / 2) * (1 - 1e-4)) > V);
                /* the upper edge binds too while the band stays below theta = pi; across it
                 * the region of |H| <= V reaches further up than the centred band */
                if (D / d * (1 + I_now / 2) < 1.0)
                    CHECK_CLOSE(gain_at(A, t, count, wd * (1 + I_now / 2)), V, 1e-12, 1.0);
            }
}

/* sms_shaper_si_design: the band reached is at least the one asked for, and no SI shaper of
 * another order reaches it sooner. */
static void test_si_design(void)
{
    static const double bands[] = {0.01, 0.2, 0.39, 0.41, 0.8, 1.0, 1.4};
    size_t ib;
    for (ib = 0; ib < sizeof bands / sizeof bands[0]; ++ib) {
        unsigned n, other;
        double D, got;
        CHECK_STATUS(sms_shaper_si_design(0.05, bands[ib], &n, &D), SMS_OK);
        CHECK_STATUS(sms_shaper_si_insensitivity(n, D, 0.05, &got), SMS_OK);
        if (bands[ib] > 0.07) {
            CHECK(got >= bands[ib] * (1 - 1e-15));
            CHECK(got <= bands[ib] * (1 + 1e-12));
        } else {
            CHECK(n == 3 && D == 0.5);   /* narrower than ZV's band: ZV */
        }
        for (other = 3; other <= 9; other += 2) {
            /* at a shorter duration the other order's band is narrower */
            double d = 0.5 * (other - 1), shorter = D * (1 - 1e-9), I_other;
            if (other == n || shorter < 0.5 * d || shorter > d)
                continue;
            CHECK_STATUS(sms_shaper_si_insensitivity(other, shorter, 0.05, &I_other), SMS_OK);
            CHECK(I_other < bands[ib]);
        }
    }
    {
        unsigned n = 77;
        double D = 77;
        CHECK_STATUS(sms_shaper_si_design(0.05, 1.45, &n, &D), SMS_ERR_ORDER);
        CHECK_STATUS(sms_shaper_si_design(0.05, 0.0, &n, &D), SMS_ERR_SHAPER_DURATION);
        CHECK_STATUS(sms_shaper_si_design(0.05, NAN, &n, &D), SMS_ERR_SHAPER_DURATION);
        CHECK_STATUS(sms_shaper_si_design(1.0, 0.3, &n, &D), SMS_ERR_TOLERANCE);
        CHECK_STATUS(sms_shaper_si_design(0.05, 0.3, NULL, &D), SMS_ERR_NULL);
        CHECK(n == 77 && D == 77);
        CHECK_STATUS(sms_shaper_si_insensitivity(4, 1.0, 0.05, &D), SMS_ERR_ORDER);
        CHECK_STATUS(sms_shaper_si_insensitivity(11, 1.0, 0.05, &D), SMS_ERR_ORDER);
        CHECK_STATUS(sms_shaper_si_insensitivity(3, 1.0, 0.0, &D), SMS_ERR_TOLERANCE);
        CHECK_STATUS(sms_shaper_si_insensitivity(3, 0.49, 0.05, &D), SMS_ERR_SHAPER_DURATION);
        CHECK_STATUS(sms_shaper_si_insensitivity(3, 1.01, 0.05, &D), SMS_ERR_SHAPER_DURATION);
        CHECK_STATUS(sms_shaper_si_insensitivity(3, 1.0, 0.05, NULL), SMS_ERR_NULL);
        CHECK(D == 77);
    }
}

/* Exact timing at any Ts: H(z_p) = H_c(p) at the damped mode (the design's residual). */
static void test_si_exact_timing(void)
{
    static const double periods[] = {1e-3, 7.3e-4, 2.9e-3, 1.234567e-4};
    size_t i;
    for (i = 0; i < 4; ++i) {
        double Ts = periods[i], wn = 2 * PI * 47.3, zeta = 0.12, h[MAX_LEN], re, im;
        double complex p = -zeta * wn + I * wn * sqrt(1 - zeta * zeta), zp = cexp(p * Ts), H = 0;
        double complex zi = 1.0;
        size_t L, k;
        sms_stage_config c = si(7, 2.3, 0.05, wn, zeta);
        CHECK_STATUS(sms_shaper_buffer_size(&c, Ts, &L), SMS_OK);
        CHECK_STATUS(sms_shaper_taps(&c, Ts, h, MAX_LEN), SMS_OK);
        for (k = 0; k < L; ++k) {
            H += h[k] * zi;
            zi /= zp;
        }
        CHECK_STATUS(sms_shaper_transfer(&c, creal(p), cimag(p), &re, &im), SMS_OK);
        CHECK(cabs(H - (re + I * im)) <= 1e-12);
    }
}

static sms_stage_config user(unsigned n, const double *A, const double *t)
{
    sms_stage_config c = sms_stage_config_default(SMS_SHAPER_IMPULSES);
    unsigned m;
    c.order = n;
    for (m = 0; m < n; ++m) {
        c.amplitudes[m] = A[m];
        c.times[m] = t[m];
    }
    return c;
}

/* Klipper's MZV at 41 Hz, zeta 0.1, pasted as its impulses (klippy/extras/shaper_defs.py,
 * get_mzv_shaper, before its normalisation): the same impulses as the mzv kind, and at paper
 * timing the same taps. */
static void test_impulses_firmware_paste(void)
{
    const double f = 41.0, zeta = 0.1, df = sqrt(1 - zeta * zeta), K = exp(-0.75 * zeta * PI / df);
    const double td = 1.0 / (f * df), a1 = 1.0 - 1.0 / sqrt(2.0);
    double A[3], t[3], Am[9], tm[9], Au[9], tu[9], hm[MAX_LEN], hu[MAX_LEN];
    size_t n_m, n_u, Lm, Lu, i;
    sms_stage_config mzv = sms_stage_config_default(SMS_SHAPER_MZV), pasted;
    A[0] = a1; A[1] = (sqrt(2.0) - 1.0) * K; A[2] = a1 * K * K;
    t[0] = 0.0; t[1] = 0.375 * td; t[2] = 0.75 * td;
    pasted = user(3, A, t);
    mzv.wn = 2 * PI * f;
    mzv.zeta = zeta;
    impulses_of(&mzv, Am, tm, &n_m);
    impulses_of(&pasted, Au, tu, &n_u);
    CHECK(n_u == 3);
    for (i = 0; i < 3; ++i) {
        CHECK_CLOSE(Au[i], Am[i], 4e-16, 1.0);
        CHECK_CLOSE(tu[i], tm[i], 4e-16, tm[2]);
    }
    mzv.timing = pasted.timing = SMS_TIMING_PAPER;
    CHECK_STATUS(sms_shaper_buffer_size(&mzv, 1e-3, &Lm), SMS_OK);
    CHECK_STATUS(sms_shaper_buffer_size(&pasted, 1e-3, &Lu), SMS_OK);
    CHECK(Lm == Lu);
    CHECK_STATUS(sms_shaper_taps(&mzv, 1e-3, hm, MAX_LEN), SMS_OK);
    CHECK_STATUS(sms_shaper_taps(&pasted, 1e-3, hu, MAX_LEN), SMS_OK);
    for (i = 0; i < Lm; ++i)
        CHECK_CLOSE(hu[i], hm[i], 4e-16, 1.0);
}

/* Exact timing of user impulses: a linear split (sum 1, the centroid sum A t exactly), so a
 * sampled ramp comes out as the continuous shaper's output sum_m A_m r(t - t_m), negative
 * amplitudes and a leading delay included. */
static void test_impulses_linear_split(void)
{
    static const double A[4] = {0.7, -0.2, 0.9, 0.1}, t[4] = {0.0013, 0.0041, 0.0105, 0.0188};
    const double Ts = 1e-3;
    sms_stage_config c = user(4, A, t);
    sms_shaper f;
    double h[MAX_LEN], sum = 0, centroid = 0, want = 0, scale;
    size_t L, k, n_taps;
    int step;
    CHECK_STATUS(sms_shaper_buffer_size(&c, Ts, &L), SMS_OK);
    CHECK(L == 20);                              /* the last impulse at 18.8 samples */
    CHECK_STATUS(sms_shaper_taps(&c, Ts, h, MAX_LEN), SMS_OK);
    for (k = 0; k < L; ++k) {
        sum += h[k];
        centroid += h[k] * (double)k * Ts;
    }
    for (k = 0; k < 4; ++k)
        want += A[k] * t[k] / 1.5;               /* the amplitudes sum to 1.5 */
    CHECK_CLOSE(sum, 1.0, 4e-16, 1.0);
    CHECK_CLOSE(centroid, want, 1e-15, t[3]);
    CHECK(h[0] == 0.0);                          /* nothing before the first impulse's split */
    CHECK_STATUS(sms_shaper_tap_count(&c, Ts, &n_taps), SMS_OK);
    CHECK(n_taps == 8);                          /* four impulses, each on two samples */
    CHECK_STATUS(sms_shaper_init(&f, &c, Ts, table, SMS_SHAPER_MAX_TAPS, ring, MAX_LEN), SMS_OK);
    scale = 3.0 * Ts * 100;
    for (step = 0; step < 100; ++step) {
        sms_real x = (sms_real)(3.0 * step * Ts);
        double y = 0;
        sms_shaper_step(&f, &x);
        for (k = 0; k < 4; ++k) {
            double tau = step * Ts - t[k];
            y += A[k] / 1.5 * (tau > 0 ? 3.0 * tau : 0.0);
        }
        if (step >= 20)                          /* past the window the ramp is exact */
            CHECK_CLOSE(x, y, 8 * SMS_TEST_REL_TOL, scale);
    }
}

/* Every invalid configuration, each with the status of the first failing check, and nothing
 * written; wn and zeta are not read. */
static void test_invalid(void)
{
    static const double A[3] = {0.25, 0.5, 0.25}, t[3] = {0.0, 0.005, 0.01};
    const double Ts = 1e-3;
    sms_stage_config good = user(3, A, t), c;
    sms_shaper f, before;
    size_t L;
    memset(&f, 0x5a, sizeof f);
    before = f;
#define EXPECT_BAD(cfg, status) do { CHECK_STATUS(sms_shaper_buffer_size(&(cfg), Ts, &L), status); \
    CHECK_STATUS(sms_shaper_init(&f, &(cfg), Ts, table, SMS_SHAPER_MAX_TAPS, ring, MAX_LEN), status); \
    CHECK(memcmp(&f, &before, sizeof f) == 0); } while (0)
    c = good; c.wn = NAN; c.zeta = 7.0;
    CHECK_STATUS(sms_shaper_buffer_size(&c, Ts, &L), SMS_OK);       /* no mode: not read */
    c = good; c.order = 0; EXPECT_BAD(c, SMS_ERR_ORDER);
    c = good; c.order = SMS_SHAPER_MAX_IMPULSES + 1; EXPECT_BAD(c, SMS_ERR_ORDER);
    c = good; c.amplitudes[1] = NAN; EXPECT_BAD(c, SMS_ERR_IMPULSE_AMPLITUDE);
    c = good; c.amplitudes[1] = INFINITY; EXPECT_BAD(c, SMS_ERR_IMPULSE_AMPLITUDE);
    c = good; c.amplitudes[1] = -0.5; EXPECT_BAD(c, SMS_ERR_IMPULSE_AMPLITUDE);   /* sum 0 */
    c = good; c.amplitudes[0] = 1e308; c.amplitudes[2] = 1e308; EXPECT_BAD(c, SMS_ERR_IMPULSE_AMPLITUDE);
    c = good; c.times[1] = NAN; EXPECT_BAD(c, SMS_ERR_IMPULSE_TIME);
    c = good; c.times[0] = -1e-9; EXPECT_BAD(c, SMS_ERR_IMPULSE_TIME);
    c = good; c.times[2] = 0.005; EXPECT_BAD(c, SMS_ERR_IMPULSE_TIME);            /* not increasing */
    c = good; c.times[2] = 1e300; EXPECT_BAD(c, SMS_ERR_TOO_LONG);
    c = good; c.amplitudes[1] = NAN; c.times[1] = NAN; EXPECT_BAD(c, SMS_ERR_IMPULSE_AMPLITUDE);
    c = good; c.timing = SMS_TIMING_BOUNDED; EXPECT_BAD(c, SMS_ERR_KIND);
    c = sms_stage_config_default(SMS_SHAPER_IMPULSES); EXPECT_BAD(c, SMS_ERR_ORDER);  /* must be set */
    {
        sms_stage_config out;
        CHECK_STATUS(sms_design_for_mode(SMS_SHAPER_IMPULSES, 100.0, 0.0, 1, &out), SMS_ERR_KIND);
    }
    good = si(5, 1.5, 0.05, 100.0, 0.1);
    CHECK_STATUS(sms_shaper_buffer_size(&good, Ts, &L), SMS_OK);
    c = good; c.order = 4; EXPECT_BAD(c, SMS_ERR_ORDER);
    c = good; c.order = 1; EXPECT_BAD(c, SMS_ERR_ORDER);
    c = good; c.order = 11; EXPECT_BAD(c, SMS_ERR_ORDER);
    c = good; c.tolerance = 0.0; EXPECT_BAD(c, SMS_ERR_TOLERANCE);
    c = good; c.tolerance = 1.0; EXPECT_BAD(c, SMS_ERR_TOLERANCE);
    c = good; c.tolerance = NAN; EXPECT_BAD(c, SMS_ERR_TOLERANCE);
    c = good; c.duration = 0.999; EXPECT_BAD(c, SMS_ERR_SHAPER_DURATION);
    c = good; c.duration = 2.001; EXPECT_BAD(c, SMS_ERR_SHAPER_DURATION);
    c = good; c.duration = NAN; EXPECT_BAD(c, SMS_ERR_SHAPER_DURATION);
    c = good; c.zeta = 1.0; EXPECT_BAD(c, SMS_ERR_ZETA);
    c = good; c.wn = 0.0; EXPECT_BAD(c, SMS_ERR_WN);
    c = good; c.wn = PI / Ts; EXPECT_BAD(c, SMS_ERR_ABOVE_NYQUIST);
    c = good; c.order = 4; c.tolerance = 0.0; EXPECT_BAD(c, SMS_ERR_ORDER);   /* order first */
#undef EXPECT_BAD
}

/* A saved state loads only into the same configuration: other impulses (same count and last
 * time) or another SI duration are refused with SMS_ERR_STATE_DURATION. */
static void test_state_identity(void)
{
    static const double A[3] = {0.25, 0.5, 0.25}, t[3] = {0.0, 0.005, 0.01};
    static const double B[3] = {0.25, 0.5, 0.2500001};
    static sms_shaper_tap table2[SMS_SHAPER_MAX_TAPS];
    static sms_real ring2[MAX_LEN];
    static double state[MAX_LEN + 64];
    const double Ts = 1e-3;
    sms_stage_config a = user(3, A, t), b = user(3, B, t);
    sms_shaper fa, fb;
    CHECK_STATUS(sms_shaper_init(&fa, &a, Ts, table, SMS_SHAPER_MAX_TAPS, ring, MAX_LEN), SMS_OK);
    CHECK_STATUS(sms_shaper_init(&fb, &b, Ts, table2, SMS_SHAPER_MAX_TAPS, ring2, MAX_LEN), SMS_OK);
    sms_shaper_get_state(&fa, state);
    CHECK(sms_shaper_state_count(&fa) == sms_shaper_state_count(&fb));
    CHECK_STATUS(sms_shaper_set_state(&fb, state, sms_shaper_state_count(&fa)), SMS_ERR_STATE_DURATION);
    CHECK_STATUS(sms_shaper_set_state(&fa, state, sms_shaper_state_count(&fa)), SMS_OK);
    a = si(5, 1.5, 0.05, 100.0, 0.1);
    b = si(5, 1.5000001, 0.05, 100.0, 0.1);
    CHECK_STATUS(sms_shaper_init(&fa, &a, Ts, table, SMS_SHAPER_MAX_TAPS, ring, MAX_LEN), SMS_OK);
    CHECK_STATUS(sms_shaper_init(&fb, &b, Ts, table2, SMS_SHAPER_MAX_TAPS, ring2, MAX_LEN), SMS_OK);
    sms_shaper_get_state(&fa, state);
    if (sms_shaper_state_count(&fa) == sms_shaper_state_count(&fb))
        CHECK_STATUS(sms_shaper_set_state(&fb, state, sms_shaper_state_count(&fa)), SMS_ERR_STATE_DURATION);
}

int main(void)
{
    test_si_special_cases();
    test_si_equal_ripple();
    test_si_design();
    test_si_exact_timing();
    test_impulses_firmware_paste();
    test_impulses_linear_split();
    test_invalid();
    test_state_identity();
    return check_summary("test_si_impulses");
}
