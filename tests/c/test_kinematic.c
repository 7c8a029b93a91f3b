/* SPDX-License-Identifier: Apache-2.0 */
/* Kinematic design: seed check values, time-optimal double-S duration from the textbook
 * closed form, structure and bounds of every design, bad input. */
#include <stdlib.h>
#include "check.h"
#include "double_s.h"

#define PI 3.14159265358979323846

static double urand(unsigned *s)
{
    *s = *s * 1103515245u + 12345u;
    return ((*s >> 8) & 0xFFFFFFu) / 16777216.0;
}

static double log_uniform(unsigned *s, double lo, double hi)
{
    return exp(log(lo) + (log(hi) - log(lo)) * urand(s));
}

/* Chain structure T[k] >= T[k+1] + ... and the peak of every derivative (header formula). */
static void check_structure_and_bounds(double h, const double *L, size_t n, const double *T,
                                       double last_gain)
{
    size_t k;
    double prod = 1.0;
    for (k = 0; k + 1 < n; ++k) {
        double rest = 0.0;
        size_t i;
        for (i = k + 1; i < n; ++i)
            rest += T[i];
        CHECK(T[k] >= rest * (1.0 - 1e-12));
    }
    for (k = 0; k < n; ++k) {
        double peak;
        prod *= T[k];
        peak = fabs(h) / prod * (k + 1 == n ? last_gain : 1.0);
        CHECK(peak <= L[k] * (1.0 + 1e-12));
    }
}

static void test_seed_values(void)
{
    double L[3] = {250.0, 5000.0, 200000.0}, T[4];
    size_t n = 0;
    CHECK_STATUS(sms_kinematic_design(40.0, L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 0.0, T, 4, &n), SMS_OK);
    CHECK(n == 3);
    CHECK_CLOSE(T[0], 0.16, 1e-14, 1.0);
    CHECK_CLOSE(T[1], 0.05, 1e-14, 1.0);
    CHECK_CLOSE(T[2], 0.025, 1e-14, 1.0);
    /* seed 001: harmonic alone, modified trapezoid, modified double-S */
    CHECK_STATUS(sms_kinematic_design(40.0, L, 1, SMS_PROFILE_TRIGONOMETRIC, 0.0, 0.0, 0.0, T, 4, &n), SMS_OK);
    CHECK_CLOSE(T[0], PI * 40.0 / 500.0, 1e-14, 1.0);
    CHECK(fabs(T[0] - 0.2513) < 5e-5);
    CHECK_STATUS(sms_kinematic_design(40.0, L, 2, SMS_PROFILE_TRIGONOMETRIC, 0.0, 0.0, 0.0, T, 4, &n), SMS_OK);
    CHECK_CLOSE(T[0], 0.16, 1e-14, 1.0);
    CHECK(fabs(T[1] - 0.0785) < 5e-5);
    CHECK_STATUS(sms_kinematic_design(40.0, L, 3, SMS_PROFILE_TRIGONOMETRIC, 0.0, 0.0, 0.0, T, 4, &n), SMS_OK);
    CHECK_CLOSE(T[0], 0.16, 1e-14, 1.0);
    CHECK_CLOSE(T[1], 0.05, 1e-14, 1.0);
    CHECK(fabs(T[2] - 0.0393) < 5e-5);
    check_structure_and_bounds(40.0, L, 3, T, PI / 2.0);
}

static double sampled_excess(double h, const double *L, size_t n, const sms_stage_config *cfg,
                             double Ts, size_t *samples_out);

static void test_mode_tuned(void)
{
    /* seed 001 sec. 5.2: T1 = h/v, T2 = v/a, T3 = 2 pi / 260.4 = 0.0241 s (not 0.0209) */
    double L[3] = {250.0, 5000.0, 1e6}, T[3];
    sms_stage_config cfg[3];
    size_t n;
    CHECK_STATUS(sms_kinematic_design(40.0, L, 3, SMS_PROFILE_POLYNOMIAL, 260.4, 0.0, 0.0, T, 3, &n), SMS_OK);
    CHECK_CLOSE(T[0], 0.16, 1e-14, 1.0);
    CHECK_CLOSE(T[1], 0.05, 1e-14, 1.0);
    CHECK_CLOSE(T[2], 2.0 * PI / 260.4, 1e-14, 1.0);
    CHECK(fabs(T[2] - 0.0241) < 5e-5);
    /* Damped-Jerk: exponential jerk stage, T_J = k Td with the jerk bound met */
    L[2] = 200000.0;
    CHECK_STATUS(sms_kinematic_configs(40.0, L, 3, SMS_PROFILE_DAMPED, 122.0, 0.1, 1e-4, cfg, 3, &n), SMS_OK);
    CHECK(cfg[2].kind == SMS_EXPONENTIAL);
    CHECK_CLOSE(cfg[2].sigma, -12.2, 1e-14, 12.2);
    {
        double wd = 122.0 * sqrt(1.0 - 0.01), Td = 2.0 * PI / wd, rho, excess;
        CHECK_CLOSE(cfg[2].T, cfg[2].k * Td, 1e-14, cfg[2].T);
        rho = -cfg[2].sigma / -expm1(cfg[2].sigma * cfg[2].T);
        /* acceleration level times peak jerk density within the jerk bound; the stages
         * need not keep "each at least the ones after it" (the overlap search's exact tests
         * let copies overlap), but every sampled difference keeps its bound */
        CHECK(40.0 / (cfg[0].T * cfg[1].T) * rho <= 200000.0 * (1.0 + 1e-12));
        CHECK(cfg[2].timing == SMS_TIMING_BOUNDED);
        excess = sampled_excess(40.0, L, 3, cfg, 1e-4, NULL);
        CHECK(excess > -1.5 && excess <= 1e-9); /* -2, -3: not simulated */
    }
    /* the chain builds directly from the configs */
    {
        sms_stage stages[3];
        sms_chain chain;
        size_t need;
        CHECK_STATUS(sms_chain_memory_size(cfg, 3, 1e-4, &need), SMS_OK);
        if (need < 100000) {
            static sms_memory_cell buf[100000];
            CHECK_STATUS(sms_chain_init(&chain, stages, cfg, 3, 1e-4, buf, need), SMS_OK);
        }
    }
    /* one bound, a tuned half sine whose sampled peak exceeds vmax: the next odd multiple */
    {
        double L1 = 1.0, T1 = 0.5 * PI, excess; /* h = 1, vmax = 1: T = pi/2 h/vmax */
        sms_stage_config one[1];
        size_t c1;
        CHECK_STATUS(sms_kinematic_configs(1.0, &L1, 1, SMS_PROFILE_TRIGONOMETRIC, 3.0 * PI / T1,
                                           0.0, T1 / 23.7, one, 1, &c1), SMS_OK);
        CHECK(one[0].k == 3u);
        excess = sampled_excess(1.0, &L1, 1, one, T1 / 23.7, NULL);
        CHECK(excess > -1.5 && excess <= 1e-9);
    }
    /* trigonometric tuned: odd multiples of 3 pi / wd only */
    CHECK_STATUS(sms_kinematic_configs(40.0, L, 3, SMS_PROFILE_TRIGONOMETRIC, 300.0, 0.0, 1e-4, cfg, 3, &n), SMS_OK);
    CHECK(cfg[2].kind == SMS_HARMONIC);
    CHECK(cfg[2].k % 2u == 1u);
    CHECK_CLOSE(cfg[2].T, cfg[2].k * 3.0 * PI / 300.0, 1e-14, 1.0);
}

static void test_double_s_random(void)
{
    unsigned seed = 12345u;
    int trial;
    for (trial = 0; trial < 20000; ++trial) {
        double L[3], T[3], h;
        size_t n;
        h = log_uniform(&seed, 1e-4, 1e4);
        L[0] = log_uniform(&seed, 1e-3, 1e3);
        L[1] = log_uniform(&seed, 1e-3, 1e5);
        L[2] = log_uniform(&seed, 1e-3, 1e7);
        CHECK_STATUS(sms_kinematic_design(trial % 2 ? h : -h, L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 0.0, T, 3, &n), SMS_OK);
        CHECK_CLOSE(T[0] + T[1] + T[2], double_s_duration(h, L[0], L[1], L[2]), 1e-12,
                    T[0] + T[1] + T[2]);
        check_structure_and_bounds(h, L, 3, T, 1.0);
    }
}

static void test_higher_orders(void)
{
    unsigned seed = 777u;
    int trial;
    for (trial = 0; trial < 300; ++trial) {
        double L[6], T[6], h = log_uniform(&seed, 1e-3, 1e3);
        size_t n, i, order = 1 + (size_t)(urand(&seed) * 6.0);
        for (i = 0; i < order; ++i)
            L[i] = log_uniform(&seed, 1e-2, 1e4);
        if (order > 6)
            order = 6;
        CHECK_STATUS(sms_kinematic_design(h, L, order, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 0.0, T, 6, &n), SMS_OK);
        check_structure_and_bounds(h, L, order, T, 1.0);
        CHECK_STATUS(sms_kinematic_design(h, L, order, SMS_PROFILE_TRIGONOMETRIC, 0.0, 0.0, 0.0, T, 6, &n), SMS_OK);
        check_structure_and_bounds(h, L, order, T, PI / 2.0);
    }
    /* n = 2: short move gives the triangular profile T1 = T2 = sqrt(h/a) */
    {
        double L[2] = {10.0, 1.0}, T[2];
        size_t n;
        CHECK_STATUS(sms_kinematic_design(4.0, L, 2, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 0.0, T, 2, &n), SMS_OK);
        CHECK_CLOSE(T[0], 2.0, 1e-14, 1.0);
        CHECK_CLOSE(T[1], 2.0, 1e-14, 1.0);
    }
}

static void test_bad_input(void)
{
    double L[3] = {250.0, 5000.0, 200000.0}, T[3] = {-1.0, -1.0, -1.0};
    size_t n = 99;
    sms_stage_config cfg[3];
    CHECK_STATUS(sms_kinematic_design(0.0, L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 0.0, T, 3, &n), SMS_ERR_LIMIT);
    CHECK_STATUS(sms_kinematic_design(NAN, L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 0.0, T, 3, &n), SMS_ERR_LIMIT);
    L[1] = -1.0;
    CHECK_STATUS(sms_kinematic_design(1.0, L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 0.0, T, 3, &n), SMS_ERR_LIMIT);
    L[1] = INFINITY;
    CHECK_STATUS(sms_kinematic_design(1.0, L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 0.0, T, 3, &n), SMS_ERR_LIMIT);
    L[1] = 5000.0;
    CHECK_STATUS(sms_kinematic_design(1.0, L, 0, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 0.0, T, 3, &n), SMS_ERR_ORDER);
    CHECK_STATUS(sms_kinematic_design(1.0, L, SMS_KINEMATIC_MAX_ORDER + 1, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 0.0, T, 3, &n), SMS_ERR_ORDER);
    CHECK_STATUS(sms_kinematic_design(1.0, L, 3, (sms_profile)7, 0.0, 0.0, 0.0, T, 3, &n), SMS_ERR_KIND);
    CHECK_STATUS(sms_kinematic_design(1.0, L, 3, SMS_PROFILE_DAMPED, 0.0, 0.0, 0.0, T, 3, &n), SMS_ERR_WN);
    CHECK_STATUS(sms_kinematic_design(1.0, L, 3, SMS_PROFILE_POLYNOMIAL, -5.0, 0.0, 0.0, T, 3, &n), SMS_ERR_WN);
    CHECK_STATUS(sms_kinematic_design(1.0, L, 3, SMS_PROFILE_POLYNOMIAL, 50.0, 1.0, 0.0, T, 3, &n), SMS_ERR_ZETA);
    CHECK_STATUS(sms_kinematic_design(1.0, L, 1, SMS_PROFILE_DAMPED, 50.0, 0.1, 0.0, T, 3, &n), SMS_ERR_ORDER);
    CHECK_STATUS(sms_kinematic_design(1.0, L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 0.0, T, 2, &n), SMS_ERR_BUFFER_TOO_SMALL);
    CHECK_STATUS(sms_kinematic_design(1.0, NULL, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 0.0, T, 3, &n), SMS_ERR_NULL);
    CHECK_STATUS(sms_kinematic_configs(1.0, L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 1e-4, NULL, 3, &n), SMS_ERR_NULL);
    CHECK_STATUS(sms_kinematic_configs(1.0, L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 1e-4, cfg, 1, &n), SMS_ERR_BUFFER_TOO_SMALL);
    CHECK(T[0] == -1.0 && T[1] == -1.0 && T[2] == -1.0 && n == 99); /* untouched */
}


#ifdef SMS_USE_FLOAT
#define SAMPLE_EPS 5.96e-8
#else
#define SAMPLE_EPS 1.11e-16
#endif

/* Largest |D^i q| / Ts^i / limits[i-1] - 1 over a step of h through the chain the configs
 * describe, beyond the rounding of the samples themselves (2^i 8 eps max|q| / Ts^i). */
static double sampled_excess(double h, const double *L, size_t n, const sms_stage_config *cfg,
                             double Ts, size_t *samples_out)
{
    sms_stage stages[SMS_KINEMATIC_MAX_ORDER];
    sms_chain chain;
    size_t need, len = 0, m, i;
    sms_memory_cell *buf;
    sms_real *x;
    double worst = -1.0, d[SMS_KINEMATIC_MAX_ORDER + 1];
    for (i = 0; i < n; ++i)
        len += (size_t)ceil(cfg[i].T / Ts) + 1u;
    len += 4u;
    if (sms_chain_memory_size(cfg, n, Ts, &need) != SMS_OK || need > 2000000u || len > 2000000u)
        return -2.0;
    buf = (sms_memory_cell *)malloc(need * sizeof(sms_memory_cell));
    x = (sms_real *)malloc(len * sizeof(sms_real));
    if (buf == NULL || x == NULL || sms_chain_init(&chain, stages, cfg, n, Ts, buf, need) != SMS_OK) {
        free(buf);
        free(x);
        return -3.0;
    }
    for (m = 0; m < len; ++m)
        x[m] = (sms_real)h;
    sms_chain_process(&chain, x, x, len);
    for (i = 0; i <= n; ++i)
        d[i] = 0.0;
    for (m = 0; m < len; ++m) {
        /* e[i] = D^i q[m] from d[i] = D^i q[m-1] (q = 0 before the step) */
        double e[SMS_KINEMATIC_MAX_ORDER + 1];
        e[0] = (double)x[m];
        for (i = 1; i <= n; ++i) {
            double floor_ = ldexp(8.0 * SAMPLE_EPS * fabs(h), (int)i) / pow(Ts, (double)i);
            double excess;
            e[i] = e[i - 1] - d[i - 1];
            excess = (fabs(e[i]) / pow(Ts, (double)i) - floor_) / L[i - 1] - 1.0;
            if (excess > worst)
                worst = excess;
        }
        for (i = 0; i <= n; ++i)
            d[i] = e[i];
    }
    if (samples_out != NULL)
        *samples_out = len;
    free(buf);
    free(x);
    return worst;
}

/* Checks the chain's sampled differences (reporting the trial on failure); 1 if it was run,
 * 0 if the chain is too long to simulate here. */
static int check_sampled(double h, const double *L, size_t n, const sms_stage_config *cfg,
                         double Ts, int trial, sms_profile profile, double wn)
{
    double excess = sampled_excess(h, L, n, cfg, Ts, NULL);
    if (excess == -2.0)
        return 0;
    CHECK(excess <= 1e-9);
    if (excess > 1e-9)
        fprintf(stderr, "trial %d: n %lu profile %d wn %g h %g Ts %g: excess %g\n", trial,
                (unsigned long)n, (int)profile, wn, h, Ts, excess);
    return 1;
}

/* The sampled output keeps every bound for any Ts: limits spanning 6 orders of magnitude,
 * every profile, with and without a mode. */
static void test_sampled_limits_random(void)
{
    unsigned seed = 4242u;
    int trial, tested = 0;
    for (trial = 0; trial < 600; ++trial) {
        double L[4], Tc[4], h = log_uniform(&seed, 1e-3, 1e3), total = 0.0, Ts;
        size_t n = 1u + (size_t)(urand(&seed) * 4.0), i, cnt;
        sms_profile profile = (sms_profile)(trial % 3);
        double wn = 0.0, zeta = 0.0;
        sms_stage_config cfg[4];
        sms_status st;
        if (n > 4u)
            n = 4u;
        for (i = 0; i < n; ++i)
            L[i] = log_uniform(&seed, 1e-3, 1e3) * pow(10.0, (double)i);
        if (profile == SMS_PROFILE_DAMPED && n < 2u)
            n = 2u, L[1] = log_uniform(&seed, 1e-3, 1e4);
        if (profile == SMS_PROFILE_DAMPED || (trial % 5 == 0 && n >= 2u)) {
            zeta = profile == SMS_PROFILE_DAMPED ? 0.3 * urand(&seed) : 0.0;
        }
        CHECK_STATUS(sms_kinematic_design(h, L, n, profile == SMS_PROFILE_DAMPED ?
                     SMS_PROFILE_POLYNOMIAL : profile, 0.0, 0.0, 0.0, Tc, 4, &cnt), SMS_OK);
        for (i = 0; i < n; ++i)
            total += Tc[i];
        if (profile == SMS_PROFILE_DAMPED || (trial % 5 == 0 && n >= 2u))
            wn = 2.0 * PI / (Tc[n - 1] * (0.5 + urand(&seed)));
        /* between 3 and 3000 samples in all, off the grid */
        Ts = total / log_uniform(&seed, 3.0, 3000.0);
        st = sms_kinematic_configs(trial % 2 ? h : -h, L, n, profile, wn, zeta, Ts, cfg, 4, &cnt);
        if (wn > 0.0 && (st == SMS_ERR_ABOVE_NYQUIST || st == SMS_ERR_DURATION_BELOW_TS))
            continue;
        CHECK_STATUS(st, SMS_OK);
        if (st != SMS_OK)
            continue;
        for (i = 0; i + 1 < n || (i + 1 == n && wn == 0.0); ++i) {
            double nu = cfg[i].T / Ts;
            CHECK(fabs(nu - floor(nu + 0.5)) <= 1e-9 * nu); /* on the grid */
        }
        if (wn > 0.0) {
            /* a tuned bound stage: bounded taps (a half sine: exact timing); the price, its
             * taps counted: under 2 samples for the stage, under one per other stage, for the
             * half sine (no overlap search) the doubled rounding of tight stages above it */
            double Tcm[4], grid = 0.0, cont = 0.0;
            size_t taps, c2;
            CHECK(cfg[n - 1].timing == (cfg[n - 1].kind == SMS_HARMONIC ? SMS_TIMING_EXACT
                                                                          : SMS_TIMING_BOUNDED));
            CHECK_STATUS(sms_kinematic_design(h, L, n, profile, wn, zeta, 0.0, Tcm, 4, &c2),
                         SMS_OK);
            CHECK_STATUS(sms_smoother_length(&cfg[n - 1], Ts, &taps), SMS_OK);
            for (i = 0; i < n; ++i) {
                grid += i + 1 < n ? cfg[i].T : (double)taps * Ts;
                cont += Tcm[i];
            }
            CHECK((grid - cont) / Ts < (cfg[n - 1].kind == SMS_HARMONIC
                                        ? ldexp(1.0, (int)n - 1) + 1.0 : (double)n + 1.0) + 1e-9);
        }
        tested += check_sampled(h, L, n, cfg, Ts, trial, profile, wn);
    }
    CHECK(tested > 300);
}

/* Five to eight bounds (the search that lets copies of stages overlap where they cancel),
 * both profiles: every sampled difference within its bound, and the chain at most a sample
 * per stage over the continuous optimum; a trigonometric chain up to the floor of sampled
 * half sines more (one sample when a continuous stage is shorter than a sample, else
 * 2 - pi/2: a sampled half sine starts with a zero tap; docs/sampled-limits.md proves that
 * floor and gives the measured prices). Measured, the search being bounded. */
static void test_sampled_limits_high_orders(void)
{
    unsigned seed = 977u;
    int trial, tested = 0;
    for (trial = 0; trial < 600; ++trial) {
        double L[8], Tc[8], h = log_uniform(&seed, 1e-3, 1e3), total = 0.0, shortest = HUGE_VAL;
        double Ts, grid = 0.0, bar;
        size_t n = 5u + (size_t)(trial % 4), i, cnt;
        sms_profile profile = trial % 3 == 2 ? SMS_PROFILE_TRIGONOMETRIC : SMS_PROFILE_POLYNOMIAL;
        sms_stage_config cfg[8];
        for (i = 0; i < n; ++i)
            L[i] = log_uniform(&seed, 1e-3, 1e3) * pow(10.0, (double)i);
        if (sms_kinematic_design(h, L, n, profile, 0.0, 0.0, 0.0, Tc, 8, &cnt) != SMS_OK)
            continue;
        for (i = 0; i < n; ++i) {
            total += Tc[i];
            if (Tc[i] < shortest)
                shortest = Tc[i];
        }
        Ts = total / log_uniform(&seed, 3.0, 3000.0);
        CHECK_STATUS(sms_kinematic_configs(h, L, n, profile, 0.0, 0.0, Ts, cfg, 8, &cnt), SMS_OK);
        for (i = 0; i < n; ++i)
            grid += cfg[i].T;
        bar = (double)n;
        if (profile == SMS_PROFILE_TRIGONOMETRIC)
            bar += shortest < Ts ? 1.0 : 2.0 - 0.5 * PI;
        CHECK((grid - total) / Ts <= bar + 1e-9);
        tested += check_sampled(h, L, n, cfg, Ts, trial, profile, 0.0);
    }
    CHECK(tested > 450);
}

/* The reported cases: h = 40, v = 250, a = 5000, j = 2e5 at T/Ts = 10.5 and 1000.5. */
static void test_sampled_limits_examples(void)
{
    double L[3] = {250.0, 5000.0, 200000.0}, Tc[3], T[3], Ts[3] = {0.025 / 10.5, 0.16 / 10.5,
                                                                   0.16 / 1000.5};
    sms_stage_config cfg[3];
    size_t n, i, k;
    for (k = 0; k < 3; ++k) {
        CHECK_STATUS(sms_kinematic_configs(40.0, L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, Ts[k], cfg, 3, &n), SMS_OK);
        CHECK(sampled_excess(40.0, L, 3, cfg, Ts[k], NULL) <= 1e-9);
        /* price: less than one sample per stage over the continuous optimum */
        CHECK_STATUS(sms_kinematic_design(40.0, L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 0.0, Tc, 3, &n), SMS_OK);
        CHECK_STATUS(sms_kinematic_design(40.0, L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, Ts[k], T, 3, &n), SMS_OK);
        for (i = 0; i < 3; ++i)
            CHECK(cfg[i].T == T[i]);
        CHECK((T[0] + T[1] + T[2] - (Tc[0] + Tc[1] + Tc[2])) / Ts[k] < 3.0);
        CHECK(T[0] + T[1] + T[2] >= Tc[0] + Tc[1] + Tc[2]);
    }
}

/* Scaling positions and every bound by the same factor leaves the durations unchanged. A
 * factor of 1e40 moves a moderate problem (solved in plain arithmetic) out of that range
 * (solved in logarithms): both solutions agree, in every regime, tuned or not. */
static void test_position_scaling(void)
{
    const double s = 1e40;
    int trial;
    srand(29);
    for (trial = 0; trial < 3000; ++trial) {
        double L[4], Ls[4], T[4], Tb[4], h = pow(10.0, -3.0 + 5.0 * rand() / RAND_MAX), total = 0;
        size_t n = 1 + (size_t)(rand() % 4), cnt, i;
        sms_profile profile = (sms_profile)(rand() % 2);
        double wn = (rand() % 3 == 0 && n >= 2) ? 20.0 + 200.0 * rand() / RAND_MAX : 0.0;
        for (i = 0; i < n; ++i) {
            L[i] = pow(10.0, (double)i + 3.0 * rand() / RAND_MAX);
            Ls[i] = L[i] * s;
        }
        if (sms_kinematic_design(h, L, n, profile, wn, 0.0, 0.0, T, 4, &cnt) != SMS_OK)
            continue;
        CHECK_STATUS(sms_kinematic_design(h * s, Ls, n, profile, wn, 0.0, 0.0, Tb, 4, &cnt), SMS_OK);
        for (i = 0; i < n; ++i)
            total += T[i];
        for (i = 0; i < n; ++i)
            CHECK_CLOSE(Tb[i], T[i], 1e-12, total);
    }
}

/* Finite but extreme bounds: a status in O(1), never OK with a non-finite length. */
static void test_extreme_bounds(void)
{
    double L[8], T[8];
    size_t n, order, i;
    for (order = 1; order <= 8; ++order) {
        for (i = 0; i < order; ++i)
            L[i] = (i % 2) ? 1e-300 : 1e300;
        CHECK(sms_kinematic_design(1.0, L, order, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 0.0, T, 8, &n) != SMS_OK);
        for (i = 0; i < order; ++i)
            L[i] = pow(10.0, 7.0 * (double)i);
        CHECK_STATUS(sms_kinematic_design(1e-20, L, order, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 0.0, T, 8, &n), SMS_OK);
        for (i = 0; i < order; ++i)
            CHECK(isfinite(T[i]) && T[i] > 0.0);
    }
    L[0] = 1e-10;
    CHECK_STATUS(sms_kinematic_design(1e308, L, 1, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 0.0, T, 8, &n), SMS_ERR_TOO_LONG);
    L[0] = 250.0; L[1] = 5000.0; L[2] = 1e7;
    CHECK_STATUS(sms_kinematic_design(40.0, L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 1e-300, T, 8, &n), SMS_ERR_TOO_LONG);
    CHECK_STATUS(sms_kinematic_design(40.0, L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, -1.0, T, 8, &n), SMS_ERR_SAMPLE_PERIOD);
    {
        sms_stage_config cfg[3];
        CHECK_STATUS(sms_kinematic_configs(40.0, L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 0.0, cfg, 3, &n), SMS_ERR_SAMPLE_PERIOD);
    }
}

/* Whole samples of T/Ts as the grid design rounds them: the nearest integer when within 1e-9
 * (relative) of it, else the ceiling; at least 1. */
static double grid_ceil_ref(double nu)
{
    double r = floor(nu + 0.5);
    if (fabs(nu - r) <= 1e-9 * (nu > 1.0 ? nu : 1.0))
        return r < 1.0 ? 1.0 : r;
    return ceil(nu);
}

/* The grid design of a rectangular chain of n <= 3 bounds written out as its documentation
 * states it (docs/sampled-limits.md): every chain N_i = ceil(T_i/Ts) + {-1, 0, 1} tested for
 * the structure and, in logarithms with the 1e-12 margin, every level; the shortest feasible
 * total wins (ties: longer early stages), the greedy rounding when none is shorter. Returns the
 * reference's excess over the continuous total in samples (its searches beyond the
 * neighbourhood start past n samples). */
static double grid_reference(double h, const double *L, size_t n, double Ts, double *best_N)
{
    double T[3], base[3], N[3], cont = 0.0, best, below, lh = log(h), lTs = log(Ts), rhs[3];
    size_t count, i, c, combos = 1;
    CHECK(sms_kinematic_design(h, L, n, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 0.0, T, 3, &count) ==
          SMS_OK);
    for (i = 0; i < n; ++i) {
        base[i] = grid_ceil_ref(T[i] / Ts);
        cont += T[i] / Ts;
        rhs[i] = lh - log(L[i]) - (double)(i + 1) * lTs - 1e-12;
        combos *= 3u;
    }
    below = 0.0;
    best = 0.0;
    for (i = n; i-- > 0;) {
        best_N[i] = base[i] < below ? below : base[i];
        below += best_N[i];
        best += best_N[i];
    }
    for (c = 0; c < combos; ++c) {
        size_t code = c;
        double sum = 0.0, lp = 0.0;
        int ok = 1, better;
        for (i = 0; i < n; ++i, code /= 3u) {
            N[i] = base[i] + (double)(code % 3u) - 1.0;
            ok = ok && N[i] >= 1.0;
            sum += N[i];
        }
        for (below = N[n - 1], i = n - 1; ok && i-- > 0; below += N[i])
            ok = N[i] >= below;
        for (i = 0; ok && i < n; ++i) {
            lp += log(N[i]);
            ok = lp >= rhs[i];
        }
        if (!ok || sum > best)
            continue;
        better = sum < best;
        for (i = 0; i < n && !better; ++i)
            if (N[i] != best_N[i]) {
                better = N[i] > best_N[i];
                break;
            }
        if (better) {
            best = sum;
            for (i = 0; i < n; ++i)
                best_N[i] = N[i];
        }
    }
    return best - cont;
}

/* The grid design decides most level tests on the product of the lengths and takes the
 * logarithms only near the 1e-12 margin: its chains equal the reference's, on limits that put
 * a level exactly on the grid (h/vmax, vmax/amax, amax/jmax whole multiples of Ts, the case a
 * product meets its bound to the last bit), a few 1e-12 to either side of it (the margin
 * itself) and at random. */
static void test_grid_neighbourhood(void)
{
    const double nudges[] = {0.0, 0.5e-12, 0.9e-12, 1.1e-12, 2e-12, -0.5e-12, -1e-12, -3e-12};
    unsigned seed = 20261204u;
    int c, compared = 0;
    for (c = 0; c < 6000; ++c) {
        size_t n = 1u + (size_t)c % 3u, count, i;
        double Ts = c % 2 ? 1e-3 : 2.5e-4, h, L[3], T[3], Nref[3], over;
        double nudge = nudges[(size_t)(c / 12) % (sizeof nudges / sizeof nudges[0])];
        if (c % 4 != 3) {
            /* whole samples: h/vmax = a Ts, vmax/amax = b Ts, amax/jmax = d Ts */
            double a = floor(10.0 + 3000.0 * urand(&seed)), b = floor(2.0 + 200.0 * urand(&seed));
            double d = floor(1.0 + 60.0 * urand(&seed));
            h = 0.1 + urand(&seed);
            L[0] = h / (a * Ts);
            L[1] = L[0] / (b * Ts);
            L[2] = L[1] / (d * Ts);
            L[c % 3] *= 1.0 + nudge;
        } else {
            h = log_uniform(&seed, 1e-3, 10.0);
            L[0] = log_uniform(&seed, 0.05, 5.0);
            L[1] = L[0] * log_uniform(&seed, 1.0, 500.0);
            L[2] = L[1] * log_uniform(&seed, 1.0, 2000.0);
        }
        over = grid_reference(h, L, n, Ts, Nref);
        if (over > (double)n)
            continue; /* beyond the neighbourhood: other searches decide */
        CHECK(sms_kinematic_design(h, L, n, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, Ts, T, 3,
                                   &count) == SMS_OK);
        for (i = 0; i < n; ++i)
            CHECK(floor(T[i] / Ts + 0.5) == Nref[i]);
        ++compared;
    }
    CHECK(compared > 5000);
}

int main(void)
{
    test_grid_neighbourhood();
    test_position_scaling();
    test_sampled_limits_examples();
    test_sampled_limits_random();
    test_sampled_limits_high_orders();
    test_extreme_bounds();
    test_seed_values();
    test_mode_tuned();
    test_double_s_random();
    test_higher_orders();
    test_bad_input();
    return check_summary("test_kinematic");
}
