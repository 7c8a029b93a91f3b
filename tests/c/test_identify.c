/* SPDX-License-Identifier: Apache-2.0 */
/* Mode identification: exact on noise-free data, accurate with noise and an offset, and every
 * bad record rejected. */
#include <string.h>
#include "check.h"

#define PI 3.14159265358979323846
#define MAX_N 20000

static double rec[MAX_N];

/* Deterministic standard normal samples (LCG + Box-Muller): the test must be reproducible. */
static unsigned long lcg_state = 12345u;
static double uniform01(void)
{
    lcg_state = (lcg_state * 1103515245u + 12345u) & 0x7fffffffu;
    return ((double)lcg_state + 0.5) / 2147483648.0;
}
static double gauss(void)
{
    return sqrt(-2.0 * log(uniform01())) * cos(2.0 * PI * uniform01());
}

/* x[k] = offset + e^{sigma t}(A cos wd t + B sin wd t) + noise * N(0,1) */
static void make_record(size_t n, double Ts, double sigma, double wd, double offset, double noise)
{
    size_t k;
    for (k = 0; k < n; ++k) {
        double t = (double)k * Ts;
        rec[k] = offset + exp(sigma * t) * (2.0 * cos(wd * t) + 0.5 * sin(wd * t)) + noise * gauss();
    }
}

static void test_peaks(void)
{
    const double sigmas[] = {0.0, -0.8, -15.6539}, wds[] = {3.0, 122.7185};
    size_t i, j;
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 2; ++j) {
            double sigma = sigmas[i], wd = wds[j], Td = 2 * PI / wd;
            /* peaks of e^{sigma t} cos(wd t): tan(wd t) = sigma/wd, one period apart */
            double t1 = atan(sigma / wd) / wd + Td, t2 = t1 + Td;
            double p1 = exp(sigma * t1) * cos(wd * t1), p2 = exp(sigma * t2) * cos(wd * t2);
            sms_mode m;
            if (sigma == 0.0) {
                CHECK_STATUS(sms_identify_from_peaks(t1, p1, t2, p2, &m), SMS_ERR_RECORD);
                continue;
            }
            CHECK_STATUS(sms_identify_from_peaks(t1, p1, t2, p2, &m), SMS_OK);
            CHECK_CLOSE(m.sigma, sigma, 1e-12, sigma);
            CHECK_CLOSE(m.wd, wd, 1e-12, wd);
            CHECK_CLOSE(m.wn, sqrt(sigma * sigma + wd * wd), 1e-12, wd);
            CHECK_CLOSE(m.zeta, -sigma / m.wn, 1e-12, 1.0);
            {   /* Biagiotti et al. 2020 eq. 16: T = 1.5 T0 for the damped harmonic smoother */
                sms_stage_config c;
                CHECK_STATUS(sms_design_for_mode(SMS_DAMPED_HARMONIC, m.wn, m.zeta, 1, &c), SMS_OK);
                CHECK_CLOSE(c.T, 1.5 * (t2 - t1), 1e-12, c.T);
                CHECK_CLOSE(c.sigma, sigma, 1e-12, sigma);
            }
            /* troughs (negative peaks) give the same mode */
            CHECK_STATUS(sms_identify_from_peaks(t1 + Td / 2, -p1 * exp(sigma * Td / 2), t2 + Td / 2,
                                                 -p2 * exp(sigma * Td / 2), &m), SMS_OK);
            CHECK_CLOSE(m.sigma, sigma, 1e-12, sigma);
        }
    {
        sms_mode m, before;
        memset(&m, 0x11, sizeof m);
        before = m;
        CHECK_STATUS(sms_identify_from_peaks(1.0, 1.0, 1.0, 0.5, &m), SMS_ERR_RECORD);
        CHECK_STATUS(sms_identify_from_peaks(2.0, 1.0, 1.0, 0.5, &m), SMS_ERR_RECORD);
        CHECK_STATUS(sms_identify_from_peaks(1.0, 0.5, 2.0, 1.0, &m), SMS_ERR_RECORD);
        CHECK_STATUS(sms_identify_from_peaks(1.0, 1.0, 2.0, -0.5, &m), SMS_ERR_RECORD);
        CHECK_STATUS(sms_identify_from_peaks(1.0, 1.0, 2.0, 0.0, &m), SMS_ERR_RECORD);
        CHECK_STATUS(sms_identify_from_peaks(1.0, NAN, 2.0, 0.5, &m), SMS_ERR_RECORD);
        CHECK_STATUS(sms_identify_from_peaks(1.0, 1.0, INFINITY, 0.5, &m), SMS_ERR_RECORD);
        CHECK(memcmp(&m, &before, sizeof m) == 0);
        CHECK_STATUS(sms_identify_from_peaks(1.0, 1.0, 2.0, 0.5, NULL), SMS_ERR_NULL);
    }
}

static void test_record_exact(void)
{
    /* noise-free: the least-squares fit is the model itself */
    struct { size_t n; double Ts, sigma, wd; } cases[] = {
        {2000, 1e-3, -1.5, 2 * PI * 5.0},      /* 200 samples per period */
        {400, 500e-6, -15.6539, 122.7185},     /* seed 000 experiment mode */
        {60, 0.1, -0.05, 2.0},                 /* 3 samples per period */
        {5000, 1e-4, 0.0, 2 * PI * 3.0},       /* undamped: not a decay */
    };
    size_t i;
    for (i = 0; i < 4; ++i) {
        sms_mode m;
        make_record(cases[i].n, cases[i].Ts, cases[i].sigma, cases[i].wd, 3.0, 0.0);
        if (cases[i].sigma == 0.0) {
            /* fitted sigma lands at +-rounding: positive is rejected, negative must be ~0 */
            sms_status st = sms_identify_from_record(rec, cases[i].n, cases[i].Ts, &m);
            CHECK(st == SMS_ERR_RECORD || (st == SMS_OK && fabs(m.sigma) < 1e-9));
            continue;
        }
        CHECK_STATUS(sms_identify_from_record(rec, cases[i].n, cases[i].Ts, &m), SMS_OK);
        CHECK_CLOSE(m.wd, cases[i].wd, 1e-9, cases[i].wd);
        CHECK_CLOSE(m.sigma, cases[i].sigma, 1e-9, cases[i].wd);
    }
}

/* Cramer-Rao standard deviations of (sigma, wd) for white noise of std s: the diagonal of
 * s^2 (J^T J)^{-1}, J the Jacobian of c + e^{sigma t}(A cos wd t + B sin wd t) in
 * (c, A, B, sigma, wd) at the true values (the amplitudes and offset are nuisance parameters). */
static void crlb(size_t n, double Ts, double sigma, double wd, double s, double *sd_sigma, double *sd_wd)
{
    double F[25] = {0}, inv[25] = {0};
    size_t k;
    int i, j, c;
    for (k = 0; k < n; ++k) {
        double t = (double)k * Ts, e = exp(sigma * t), co = cos(wd * t), si = sin(wd * t);
        double g[5];
        g[0] = 1; g[1] = e * co; g[2] = e * si; g[3] = t * e * (2.0 * co + 0.5 * si);
        g[4] = t * e * (0.5 * co - 2.0 * si);
        for (i = 0; i < 5; ++i)
            for (j = 0; j < 5; ++j)
                F[i * 5 + j] += g[i] * g[j];
    }
    for (i = 0; i < 5; ++i)
        inv[i * 5 + i] = 1.0;
    for (c = 0; c < 5; ++c) {          /* Gauss-Jordan; F is symmetric positive definite */
        double piv = F[c * 5 + c];
        for (j = 0; j < 5; ++j) { F[c * 5 + j] /= piv; inv[c * 5 + j] /= piv; }
        for (i = 0; i < 5; ++i) {
            double f = F[i * 5 + c];
            if (i == c) continue;
            for (j = 0; j < 5; ++j) { F[i * 5 + j] -= f * F[c * 5 + j]; inv[i * 5 + j] -= f * inv[c * 5 + j]; }
        }
    }
    *sd_sigma = s * sqrt(inv[3 * 5 + 3]);
    *sd_wd = s * sqrt(inv[4 * 5 + 4]);
}

/* With noise and an offset the least-squares (maximum-likelihood) fit must reach the
 * Cramer-Rao bound: every one of 20 draws within 5 standard deviations (a 5-sd miss has
 * probability ~6e-7 per draw), and the figures are printed. */
static void test_record_noise(void)
{
    struct { size_t n; double Ts, sigma, wd, noise; } cases[] = {
        {3000, 1e-3, -1.5, 2 * PI * 5.0, 0.02},
        {3000, 1e-3, -1.5, 2 * PI * 5.0, 0.2},
        {600, 500e-6, -15.6539, 122.7185, 0.05},
        {20000, 1e-4, -0.5, 2 * PI * 2.0, 0.1},
    };
    size_t i, draw;
    for (i = 0; i < 4; ++i) {
        double sd_s, sd_w, worst_w = 0, worst_s = 0;
        crlb(cases[i].n, cases[i].Ts, cases[i].sigma, cases[i].wd, cases[i].noise, &sd_s, &sd_w);
        for (draw = 0; draw < 20; ++draw) {
            sms_mode m;
            make_record(cases[i].n, cases[i].Ts, cases[i].sigma, cases[i].wd, -7.0, cases[i].noise);
            CHECK_STATUS(sms_identify_from_record(rec, cases[i].n, cases[i].Ts, &m), SMS_OK);
            if (fabs(m.wd - cases[i].wd) > worst_w) worst_w = fabs(m.wd - cases[i].wd);
            if (fabs(m.sigma - cases[i].sigma) > worst_s) worst_s = fabs(m.sigma - cases[i].sigma);
        }
        CHECK(worst_w <= 5 * sd_w);
        CHECK(worst_s <= 5 * sd_s);
        printf("  record %u: CRLB sd(wd) %.3g, sd(sigma) %.3g; worst of 20: |dwd| %.3g (%.2f sd), "
               "|dsigma| %.3g (%.2f sd)\n", (unsigned)i, sd_w, sd_s, worst_w, worst_w / sd_w,
               worst_s, worst_s / sd_s);
    }
}

static void test_record_invalid(void)
{
    sms_mode m, before;
    size_t k;
    memset(&m, 0x22, sizeof m);
    before = m;
    make_record(100, 1e-2, -0.5, 2 * PI * 2.0, 0.0, 0.0);
    CHECK_STATUS(sms_identify_from_record(rec, 7, 1e-2, &m), SMS_ERR_RECORD);
    CHECK_STATUS(sms_identify_from_record(rec, 100, 0.0, &m), SMS_ERR_SAMPLE_PERIOD);
    CHECK_STATUS(sms_identify_from_record(rec, 100, NAN, &m), SMS_ERR_SAMPLE_PERIOD);
    CHECK_STATUS(sms_identify_from_record(NULL, 100, 1e-2, &m), SMS_ERR_NULL);
    CHECK_STATUS(sms_identify_from_record(rec, 100, 1e-2, NULL), SMS_ERR_NULL);
    rec[50] = NAN;
    CHECK_STATUS(sms_identify_from_record(rec, 100, 1e-2, &m), SMS_ERR_RECORD);
    /* no oscillation: a constant, a pure exponential, a growing oscillation, less than a period */
    for (k = 0; k < 100; ++k) rec[k] = 4.0;
    CHECK_STATUS(sms_identify_from_record(rec, 100, 1e-2, &m), SMS_ERR_RECORD);
    for (k = 0; k < 100; ++k) rec[k] = 1.0 + exp(-0.03 * (double)k);
    CHECK_STATUS(sms_identify_from_record(rec, 100, 1e-2, &m), SMS_ERR_RECORD);
    make_record(100, 1e-2, +0.5, 2 * PI * 2.0, 0.0, 0.0);
    CHECK_STATUS(sms_identify_from_record(rec, 100, 1e-2, &m), SMS_ERR_RECORD);
    make_record(100, 1e-2, -0.5, 2 * PI * 0.5, 0.0, 0.0);   /* half a period in 1 s */
    CHECK_STATUS(sms_identify_from_record(rec, 100, 1e-2, &m), SMS_ERR_RECORD);
    CHECK(memcmp(&m, &before, sizeof m) == 0);
}

int main(void)
{
    test_peaks();
    test_record_exact();
    test_record_noise();
    test_record_invalid();
    return check_summary("test_identify");
}
