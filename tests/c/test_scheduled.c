/* SPDX-License-Identifier: Apache-2.0 */
/* The scheduled ZV^n shaper (scheduled.h): at every schedule value its taps are the fixed
 * exact-timing shaper's of the interpolated mode (sms_shaper_taps, designed with libm), so
 * the frozen filter's zero sits on the mode; the taps are continuous in the schedule; a
 * constant input passes exactly whatever the schedule; the output is the definition
 * y[n] = sum_i h_{s[n]}[i] x[n-i]; updates every N samples; blocks equal steps; the saved
 * state continues; refusals. */
#include <string.h>
#include "check.h"

#define PI 3.14159265358979323846
#define MAX_L 4096

static const double Ts = 1e-3;
static sms_real ring[MAX_L], ring2[MAX_L];
static double taps[MAX_L], fixed[MAX_L];

/* A table over a travel of 0.4: the mode from 2 pi 25 rad/s (zeta 0.02) to 2 pi 40 (0.05). */
static const sms_schedule_point table[4] = {
    {0.0, 2.0 * PI * 25.0, 0.02}, {0.1, 2.0 * PI * 29.0, 0.03},
    {0.25, 2.0 * PI * 35.0, 0.04}, {0.4, 2.0 * PI * 40.0, 0.05}};

static sms_scheduled_config config_of(sms_kind kind, unsigned every)
{
    sms_scheduled_config c;
    c.kind = kind;
    c.order = 4;
    c.points = table;
    c.n_points = 4;
    c.update_every = every;
    return c;
}

static unsigned order_of(sms_kind kind)
{
    return kind == SMS_SHAPER_ZV ? 1u : kind == SMS_SHAPER_ZVD ? 2u : kind == SMS_SHAPER_ZVDD ? 3u : 4u;
}

/* |taps - fixed exact shaper of the mode at s| over the longer of the two. */
static double against_fixed(sms_scheduled *f, sms_kind kind, double s)
{
    sms_stage_config c = sms_stage_config_default(kind);
    size_t L = 0, i;
    double wn, zeta, worst = 0.0;
    sms_real x = 0;
    sms_scheduled_mode(f, s, &wn, &zeta);
    c.wn = wn;
    c.zeta = zeta;
    c.order = order_of(kind);
    sms_scheduled_reset(f, 0, s);
    sms_scheduled_step(f, &x, s);
    CHECK_STATUS(sms_scheduled_taps(f, taps, MAX_L), SMS_OK);
    CHECK_STATUS(sms_shaper_buffer_size(&c, Ts, &L), SMS_OK);
    CHECK_STATUS(sms_shaper_taps(&c, Ts, fixed, MAX_L), SMS_OK);
    for (i = 0; i < f->len; ++i) {
        const double e = fabs(taps[i] - (i < L ? fixed[i] : 0.0));
        if (e > worst)
            worst = e;
    }
    return worst;
}

static void test_taps_are_the_fixed_shapers(void)
{
    static const sms_kind kinds[4] = {SMS_SHAPER_ZV, SMS_SHAPER_ZVD, SMS_SHAPER_ZVDD, SMS_SHAPER_ZVN};
    int k, j;
    double worst = 0.0;
    for (k = 0; k < 4; ++k) {
        sms_scheduled_config c = config_of(kinds[k], 1);
        sms_scheduled f;
        size_t need = 0;
        CHECK_STATUS(sms_scheduled_buffer_size(&c, Ts, &need), SMS_OK);
        CHECK(need <= MAX_L);
        CHECK_STATUS(sms_scheduled_init(&f, &c, Ts, ring, MAX_L), SMS_OK);
        for (j = 0; j <= 400; ++j) {
            const double s = -0.05 + 0.5 * (double)j / 400.0;   /* beyond both ends too */
            const double e = against_fixed(&f, kinds[k], s);
            if (e > worst)
                worst = e;
        }
    }
    /* the fixed design weighs z_p with libm, this one by series: both to rounding (the taps
     * are O(1); float rounds them to sms_real) */
    CHECK(worst <= (sizeof(sms_real) == 4 ? 2e-7 : 1e-13));
    printf("scheduled taps against the fixed exact shaper of the interpolated mode: %.3g\n", worst);
}

/* The frozen filter's zero: H(z_p) = 0 at the interpolated mode, for every schedule value. */
static void test_zero_on_the_mode(void)
{
    sms_scheduled_config c = config_of(SMS_SHAPER_ZVD, 1);
    sms_scheduled f;
    int j;
    double worst = 0.0;
    CHECK_STATUS(sms_scheduled_init(&f, &c, Ts, ring, MAX_L), SMS_OK);
    for (j = 0; j <= 200; ++j) {
        const double s = 0.4 * (double)j / 200.0;
        double wn, zeta, re = 0.0, im = 0.0, dre = 0.0, dim = 0.0;
        size_t i;
        sms_real x = 0;
        sms_scheduled_mode(&f, s, &wn, &zeta);
        sms_scheduled_reset(&f, 0, s);
        sms_scheduled_step(&f, &x, s);
        (void)sms_scheduled_taps(&f, taps, MAX_L);
        for (i = 0; i < f.len; ++i) {
            /* z_p^-i = e^{-p Ts i}, p = -zeta wn + j wd */
            const double a = zeta * wn * Ts * (double)i, b = -wn * sqrt(1.0 - zeta * zeta) * Ts * (double)i;
            re += taps[i] * exp(a) * cos(b);
            im += taps[i] * exp(a) * sin(b);
            dre += (double)i * taps[i] * exp(a) * cos(b);   /* the double zero of ZVD */
            dim += (double)i * taps[i] * exp(a) * sin(b);
        }
        if (sqrt(re * re + im * im) > worst)
            worst = sqrt(re * re + im * im);
        if (sqrt(dre * dre + dim * dim) / (double)f.len > worst)
            worst = sqrt(dre * dre + dim * dim) / (double)f.len;
    }
    CHECK(worst <= (sizeof(sms_real) == 4 ? 1e-5 : 1e-12));
    printf("|H(z_p)| and |H'(z_p)|/L of the frozen ZVD over the schedule: %.3g\n", worst);
}

/* Continuity: the taps move by O(ds) (a tap passes to the next delay as f passes 1). */
static void test_taps_continuous(void)
{
    sms_scheduled_config c = config_of(SMS_SHAPER_ZVD, 1);
    sms_scheduled f;
    static double prev[MAX_L];
    const double ds = 1e-5;
    double worst = 0.0, s;
    size_t i;
    CHECK_STATUS(sms_scheduled_init(&f, &c, Ts, ring, MAX_L), SMS_OK);
    (void)against_fixed(&f, SMS_SHAPER_ZVD, 0.0);
    memcpy(prev, taps, sizeof prev);
    for (s = ds; s <= 0.4; s += ds) {
        double step = 0.0;
        sms_real x = 0;
        sms_scheduled_reset(&f, 0, s);
        sms_scheduled_step(&f, &x, s);
        (void)sms_scheduled_taps(&f, taps, MAX_L);
        for (i = 0; i < f.len; ++i)
            step += fabs(taps[i] - prev[i]);
        if (step > worst)
            worst = step;
        memcpy(prev, taps, f.len * sizeof taps[0]);
    }
    /* the half period moves by about 3 samples per 0.1 of travel here, so ds = 1e-5 moves the
     * split by 3e-4 samples: the taps by a few 1e-4 in l1, never a jump */
    CHECK(worst <= 2e-3);
    printf("largest l1 change of the taps per 1e-5 of schedule: %.3g\n", worst);
}

/* The output is the definition; constants pass exactly; blocks equal steps; update every N. */
static void test_output(void)
{
    enum { N = 1500 };
    static sms_real x[N], y[N], y2[N];
    static double s[N], hist[N][64];
    static size_t hist_delay[N][64], hist_n[N];
    sms_scheduled_config c = config_of(SMS_SHAPER_ZVD, 1);
    sms_scheduled f, g;
    size_t n, k;
    double worst = 0.0;
    CHECK_STATUS(sms_scheduled_init(&f, &c, Ts, ring, MAX_L), SMS_OK);
    for (n = 0; n < N; ++n) {
        x[n] = (sms_real)(0.5 * sin(0.011 * (double)n) + 0.2 * (double)(n > 300));
        s[n] = 0.2 + 0.2 * sin(0.004 * (double)n);
    }
    sms_scheduled_reset(&f, 0, s[0]);
    for (n = 0; n < N; ++n) {
        sms_real v = x[n];
        sms_scheduled_step(&f, &v, s[n]);
        y[n] = v;
        hist_n[n] = f.n_taps;
        for (k = 0; k < f.n_taps; ++k) {
            hist[n][k] = (double)f.gain[k];
            hist_delay[n][k] = f.delay[k];
        }
    }
    for (n = 0; n < N; ++n) {
        double want = (double)x[n];
        for (k = 0; k < hist_n[n]; ++k) {
            const size_t d = hist_delay[n][k];
            want += hist[n][k] * ((d <= n ? (double)x[n - d] : 0.0) - (double)x[n]);
        }
        if (fabs(want - (double)y[n]) > worst)
            worst = fabs(want - (double)y[n]);
    }
    CHECK(worst <= 32.0 * (sizeof(sms_real) == 4 ? 6e-8 : 1.1e-16));
    /* blocks */
    CHECK_STATUS(sms_scheduled_init(&g, &c, Ts, ring2, MAX_L), SMS_OK);
    sms_scheduled_reset(&g, 0, s[0]);
    for (n = 0; n < N; n += 37)
        sms_scheduled_process(&g, x + n, s + n, y2 + n, n + 37 <= N ? 37 : N - n);
    CHECK(memcmp(y, y2, sizeof y) == 0);
    /* a constant input passes exactly under any schedule */
    sms_scheduled_reset(&g, (sms_real)0.3, s[0]);
    for (n = 0; n < N; ++n) {
        sms_real v = (sms_real)0.3;
        sms_scheduled_step(&g, &v, s[n]);
        CHECK(v == (sms_real)0.3);
    }
    /* every N: the taps change only on samples 0, N, 2N, ... */
    c.update_every = 7;
    CHECK_STATUS(sms_scheduled_init(&g, &c, Ts, ring2, MAX_L), SMS_OK);
    sms_scheduled_reset(&g, 0, 0.0);
    for (n = 0; n < 100; ++n) {
        const double before = g.schedule;
        sms_real v = 0;
        sms_scheduled_step(&g, &v, 0.001 * (double)(n + 1));
        CHECK((g.schedule != before) == (n % 7 == 0));
    }
    /* state */
    {
        static double st[MAX_L + 8];
        sms_real a = 0.1, b = 0.1;
        sms_scheduled_get_state(&f, st);
        CHECK_STATUS(sms_scheduled_init(&g, &c, Ts, ring2, MAX_L), SMS_OK);
        CHECK_STATUS(sms_scheduled_set_state(&g, st, sms_scheduled_state_count(&f)), SMS_ERR_STATE);
        c.update_every = 1;
        CHECK_STATUS(sms_scheduled_init(&g, &c, Ts, ring2, MAX_L), SMS_OK);
        CHECK_STATUS(sms_scheduled_set_state(&g, st, sms_scheduled_state_count(&f) - 1), SMS_ERR_STATE);
        CHECK_STATUS(sms_scheduled_set_state(&g, st, sms_scheduled_state_count(&f)), SMS_OK);
        for (n = 0; n < 200; ++n) {
            sms_scheduled_step(&f, &a, 0.3);
            sms_scheduled_step(&g, &b, 0.3);
            CHECK(a == b);
        }
    }
    printf("scheduled output against its definition: %.3g\n", worst);
}

static void test_refusals(void)
{
    sms_schedule_point bad[2] = {{0.0, 100.0, 0.0}, {0.0, 120.0, 0.0}};
    sms_scheduled_config c = config_of(SMS_SHAPER_ZV, 1);
    sms_scheduled f;
    size_t need;
    CHECK_STATUS(sms_scheduled_buffer_size(&c, -1.0, &need), SMS_ERR_SAMPLE_PERIOD);
    c.kind = SMS_SHAPER_EI;
    CHECK_STATUS(sms_scheduled_buffer_size(&c, Ts, &need), SMS_ERR_KIND);
    c.kind = SMS_SHAPER_ZVN;
    c.order = 9;
    CHECK_STATUS(sms_scheduled_buffer_size(&c, Ts, &need), SMS_ERR_ORDER);
    c = config_of(SMS_SHAPER_ZV, 0);
    CHECK_STATUS(sms_scheduled_buffer_size(&c, Ts, &need), SMS_ERR_MULTIPLE);
    c = config_of(SMS_SHAPER_ZV, 1);
    c.points = bad;
    c.n_points = 2;
    CHECK_STATUS(sms_scheduled_buffer_size(&c, Ts, &need), SMS_ERR_STATE);
    bad[1].value = 1.0;
    bad[1].wn = 4000.0;
    CHECK_STATUS(sms_scheduled_buffer_size(&c, Ts, &need), SMS_ERR_ABOVE_NYQUIST);
    bad[1].wn = 120.0;
    bad[1].zeta = 1.0;
    CHECK_STATUS(sms_scheduled_buffer_size(&c, Ts, &need), SMS_ERR_ZETA);
    bad[1].zeta = 0.1;
    CHECK_STATUS(sms_scheduled_buffer_size(&c, Ts, &need), SMS_OK);
    CHECK_STATUS(sms_scheduled_init(&f, &c, Ts, ring, need - 1), SMS_ERR_BUFFER_TOO_SMALL);
    c.n_points = 0;
    CHECK_STATUS(sms_scheduled_buffer_size(&c, Ts, &need), SMS_ERR_ORDER);
}

int main(void)
{
    test_taps_are_the_fixed_shapers();
    test_zero_on_the_mode();
    test_taps_continuous();
    test_output();
    test_refusals();
    return check_summary("test_scheduled");
}
