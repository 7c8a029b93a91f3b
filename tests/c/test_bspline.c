/* SPDX-License-Identifier: Apache-2.0 */
/* B-spline filters: exact pass-through of via-points at the documented samples, rest at both
 * ends, spectral zeros at k 2 pi / T, period design, state, bad input. */
#include <stdlib.h>
#include "check.h"

#define PI 3.14159265358979323846
#define MAXBUF 200000
static sms_real buffer[MAXBUF];
static double via[64 * 3], control[64 * 3], work[64 * 10];

static unsigned rng = 3u;
static double urand(void)
{
    rng = rng * 1103515245u + 12345u;
    return ((rng >> 8) & 0xFFFFFFu) / 16777216.0;
}

static void pass_through(unsigned p, size_t N, size_t axes, size_t M)
{
    sms_bspline b;
    size_t need, i, a, k, total, next_pass = 1;
    sms_real in[3], out[3], rest[3];
    double Ts = 1e-3, scale = 0.0;
    CHECK_STATUS(sms_bspline_buffer_size(p, axes, (double)N * Ts, Ts, &need), SMS_OK);
    if (need > MAXBUF)
        return;
    CHECK_STATUS(sms_bspline_init(&b, p, axes, (double)N * Ts, Ts, buffer, need), SMS_OK);
    CHECK(b.N == N);
    for (i = 0; i < M * axes; ++i) {
        via[i] = (urand() - 0.5) * 2.0;
        if (fabs(via[i]) > scale)
            scale = fabs(via[i]);
    }
    CHECK(sms_bspline_work_size(&b, M) <= sizeof work / sizeof work[0]);
    CHECK_STATUS(sms_bspline_control_points(&b, via, M, control, work, sizeof work / sizeof work[0]), SMS_OK);
    for (a = 0; a < axes; ++a)
        rest[a] = (sms_real)via[a];
    sms_bspline_reset(&b, rest);
    total = (M - 2u) * N + p * (N - 1u) + 3u;
    for (k = 0; k < total; ++k) {
        size_t j = k / N + 1u;
        if (j > M - 1u)
            j = M - 1u;
        for (a = 0; a < axes; ++a)
            in[a] = (sms_real)control[j * axes + a];
        sms_bspline_step(&b, in, out);
        if (next_pass <= M - 2u && k == sms_bspline_pass_sample(&b, next_pass)) {
            for (a = 0; a < axes; ++a)
                CHECK_CLOSE(out[a], via[next_pass * axes + a], 10 * SMS_TEST_REL_TOL, scale);
            ++next_pass;
        }
        if (k + 1u == total)
            for (a = 0; a < axes; ++a)
                CHECK_CLOSE(out[a], via[(M - 1u) * axes + a], 10 * SMS_TEST_REL_TOL, scale);
    }
    CHECK(next_pass == M - 1u);
}

static void test_pass_through(void)
{
    unsigned p;
    size_t Ns[4] = {1, 4, 5, 20};
    size_t i;
    for (p = 1; p <= SMS_BSPLINE_MAX_DEGREE; ++p)
        for (i = 0; i < 4; ++i) {
            pass_through(p, Ns[i], 3, 12);
            pass_through(p, Ns[i], 1, 2);
            pass_through(p, Ns[i], 2, 3);
        }
}

/* Frequency response of one axis, from its impulse response, at w = k 2 pi / T. */
static void test_spectrum_zeros(void)
{
    sms_bspline b;
    size_t need, N = 25, k, L;
    unsigned p;
    double Ts = 1e-3;
    for (p = 1; p <= 5; ++p) {
        static double h[2000];
        sms_real rest = 0, x;
        int harm;
        CHECK_STATUS(sms_bspline_buffer_size(p, 1, N * Ts, Ts, &need), SMS_OK);
        CHECK_STATUS(sms_bspline_init(&b, p, 1, N * Ts, Ts, buffer, need), SMS_OK);
        sms_bspline_reset(&b, &rest);
        L = p * (N - 1u) + 1u;
        for (k = 0; k < L + 5u; ++k) {
            x = k == 0 ? (sms_real)1 : (sms_real)0;
            sms_bspline_step(&b, &x, &x);
            if (k < 2000)
                h[k] = (double)x;
        }
        for (harm = 1; harm <= 3; ++harm) {
            double w = harm * 2.0 * PI / (N * Ts), re = 0.0, im = 0.0;
            for (k = 0; k < L; ++k) {
                re += h[k] * cos(w * k * Ts);
                im -= h[k] * sin(w * k * Ts);
            }
            CHECK(sqrt(re * re + im * im) <= 10 * SMS_TEST_REL_TOL);
        }
        /* DC gain 1 */
        {
            double dc = 0.0;
            for (k = 0; k < L; ++k)
                dc += h[k];
            CHECK_CLOSE(dc, 1.0, 10 * SMS_TEST_REL_TOL, 1.0);
        }
    }
}

static void test_period_and_state(void)
{
    double wn[3] = {60.0, 40.0, 60.0}, T = 0.0;
    sms_bspline b, c;
    size_t need, n, k;
    sms_real x[2] = {0, 0}, y[2], z[2];
    static double state[100000];
    CHECK_STATUS(sms_bspline_period_for_modes(wn, 3, 1e-3, &T), SMS_OK);
    CHECK(T >= 2.0 * PI / 40.0);
    CHECK(T - 1e-3 < 2.0 * PI / 40.0);
    CHECK_CLOSE(T / 1e-3, floor(T / 1e-3 + 0.5), 1e-9, 1.0);
    CHECK_STATUS(sms_bspline_buffer_size(3, 2, 0.05, 1e-3, &need), SMS_OK);
    CHECK_STATUS(sms_bspline_init(&b, 3, 2, 0.05, 1e-3, buffer, need), SMS_OK);
    for (k = 0; k < 70; ++k) {
        x[0] = (sms_real)k;
        x[1] = (sms_real)(k % 5);
        sms_bspline_step(&b, x, y);
    }
    n = sms_bspline_state_count(&b);
    if (n <= 100000) {
        sms_bspline_get_state(&b, state);
        CHECK_STATUS(sms_bspline_init(&c, 3, 2, 0.05, 1e-3, buffer + need, need), SMS_OK);
        CHECK_STATUS(sms_bspline_set_state(&c, state, n), SMS_OK);
        for (k = 0; k < 100; ++k) {
            x[0] = (sms_real)(k * 3 % 7);
            sms_bspline_step(&b, x, y);
            sms_bspline_step(&c, x, z);
            CHECK(y[0] == z[0] && y[1] == z[1]);
        }
        CHECK_STATUS(sms_bspline_set_state(&c, state, n - 1), SMS_ERR_STATE);
    }
}

static void test_bad_input(void)
{
    sms_bspline b;
    size_t need = 77;
    double wn[2] = {10.0, -1.0}, T = 5.0;
    CHECK_STATUS(sms_bspline_buffer_size(0, 1, 0.1, 1e-3, &need), SMS_ERR_ORDER);
    CHECK_STATUS(sms_bspline_buffer_size(SMS_BSPLINE_MAX_DEGREE + 1, 1, 0.1, 1e-3, &need), SMS_ERR_ORDER);
    CHECK_STATUS(sms_bspline_buffer_size(3, 4, 0.1, 1e-3, &need), SMS_ERR_ORDER);
    CHECK_STATUS(sms_bspline_buffer_size(3, 0, 0.1, 1e-3, &need), SMS_ERR_ORDER);
    CHECK_STATUS(sms_bspline_buffer_size(3, 1, NAN, 1e-3, &need), SMS_ERR_DURATION);
    CHECK_STATUS(sms_bspline_buffer_size(3, 1, 1e-4, 1e-3, &need), SMS_ERR_DURATION_BELOW_TS);
    CHECK_STATUS(sms_bspline_buffer_size(3, 1, 0.1, -1.0, &need), SMS_ERR_SAMPLE_PERIOD);
    CHECK_STATUS(sms_bspline_buffer_size(3, 1, 1e300, nextafter(SMS_TS_MAX, HUGE_VAL), &need),
                 SMS_ERR_SAMPLE_PERIOD_RANGE);
    CHECK(need == 77);
    CHECK_STATUS(sms_bspline_buffer_size(3, 1, 0.1, 1e-3, &need), SMS_OK);
    CHECK_STATUS(sms_bspline_init(&b, 3, 1, 0.1, 1e-3, buffer, need - 1), SMS_ERR_BUFFER_TOO_SMALL);
    CHECK_STATUS(sms_bspline_init(&b, 3, 1, 0.1, 1e-3, buffer, need), SMS_OK);
    via[0] = 0.0; via[1] = NAN; via[2] = 1.0;
    control[0] = 42.0;
    CHECK_STATUS(sms_bspline_control_points(&b, via, 3, control, work, 64), SMS_ERR_LIMIT);
    CHECK_STATUS(sms_bspline_control_points(&b, via, 1, control, work, 64), SMS_ERR_ORDER);
    via[1] = 0.5;
    CHECK_STATUS(sms_bspline_control_points(&b, via, 3, control, work, 0), SMS_ERR_BUFFER_TOO_SMALL);
    CHECK(control[0] == 42.0);
    CHECK_STATUS(sms_bspline_period_for_modes(wn, 2, 1e-3, &T), SMS_ERR_WN);
    CHECK_STATUS(sms_bspline_period_for_modes(wn, 0, 1e-3, &T), SMS_ERR_ORDER);
    CHECK(T == 5.0);
}

int main(void)
{
    test_pass_through();
    test_spectrum_zeros();
    test_period_and_state();
    test_bad_input();
    return check_summary("test_bspline");
}
