/* Kinematic design: seed check values, time-optimal double-S duration from the textbook
 * closed form, structure and bounds of every design, bad input. */
#include <stdlib.h>
#include "check.h"

#define PI 3.14159265358979323846

/* Time-optimal rest-to-rest jerk-limited duration (Biagiotti & Melchiorri, Trajectory
 * Planning for Automatic Machines and Robots, sec. 3.4), written independently of the design. */
static double double_s_duration(double h, double v, double a, double j)
{
    double Tj, Ta, Tv;
    if (v * j >= a * a) {
        Tj = a / j;
        Ta = Tj + v / a;
    } else {
        Tj = sqrt(v / j);
        Ta = 2.0 * Tj;
    }
    Tv = h / v - Ta;
    if (Tv >= 0.0)
        return 2.0 * Ta + Tv;
    if (h >= 2.0 * a * a * a / (j * j)) {
        Tj = a / j;
        Ta = 0.5 * Tj + sqrt(0.25 * Tj * Tj + h / a);
        return 2.0 * Ta;
    }
    Tj = cbrt(h / (2.0 * j));
    return 4.0 * Tj;
}

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
    CHECK_STATUS(sms_kinematic_design(40.0, L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, T, 4, &n), SMS_OK);
    CHECK(n == 3);
    CHECK_CLOSE(T[0], 0.16, 1e-14, 1.0);
    CHECK_CLOSE(T[1], 0.05, 1e-14, 1.0);
    CHECK_CLOSE(T[2], 0.025, 1e-14, 1.0);
    /* seed 001: harmonic alone, modified trapezoid, modified double-S */
    CHECK_STATUS(sms_kinematic_design(40.0, L, 1, SMS_PROFILE_TRIGONOMETRIC, 0.0, 0.0, T, 4, &n), SMS_OK);
    CHECK_CLOSE(T[0], PI * 40.0 / 500.0, 1e-14, 1.0);
    CHECK(fabs(T[0] - 0.2513) < 5e-5);
    CHECK_STATUS(sms_kinematic_design(40.0, L, 2, SMS_PROFILE_TRIGONOMETRIC, 0.0, 0.0, T, 4, &n), SMS_OK);
    CHECK_CLOSE(T[0], 0.16, 1e-14, 1.0);
    CHECK(fabs(T[1] - 0.0785) < 5e-5);
    CHECK_STATUS(sms_kinematic_design(40.0, L, 3, SMS_PROFILE_TRIGONOMETRIC, 0.0, 0.0, T, 4, &n), SMS_OK);
    CHECK_CLOSE(T[0], 0.16, 1e-14, 1.0);
    CHECK_CLOSE(T[1], 0.05, 1e-14, 1.0);
    CHECK(fabs(T[2] - 0.0393) < 5e-5);
    check_structure_and_bounds(40.0, L, 3, T, PI / 2.0);
}

static void test_mode_tuned(void)
{
    /* seed 001 sec. 5.2: T1 = h/v, T2 = v/a, T3 = 2 pi / 260.4 = 0.0241 s (not 0.0209) */
    double L[3] = {250.0, 5000.0, 1e6}, T[3];
    sms_stage_config cfg[3];
    size_t n;
    CHECK_STATUS(sms_kinematic_design(40.0, L, 3, SMS_PROFILE_POLYNOMIAL, 260.4, 0.0, T, 3, &n), SMS_OK);
    CHECK_CLOSE(T[0], 0.16, 1e-14, 1.0);
    CHECK_CLOSE(T[1], 0.05, 1e-14, 1.0);
    CHECK_CLOSE(T[2], 2.0 * PI / 260.4, 1e-14, 1.0);
    CHECK(fabs(T[2] - 0.0241) < 5e-5);
    /* Damped-Jerk: exponential jerk stage, T_J = k Td with the jerk bound met */
    L[2] = 200000.0;
    CHECK_STATUS(sms_kinematic_configs(40.0, L, 3, SMS_PROFILE_DAMPED, 122.0, 0.1, cfg, 3, &n), SMS_OK);
    CHECK(cfg[2].kind == SMS_EXPONENTIAL);
    CHECK_CLOSE(cfg[2].sigma, -12.2, 1e-14, 12.2);
    {
        double wd = 122.0 * sqrt(1.0 - 0.01), Td = 2.0 * PI / wd, rho;
        CHECK_CLOSE(cfg[2].T, cfg[2].k * Td, 1e-14, cfg[2].T);
        rho = -cfg[2].sigma / -expm1(cfg[2].sigma * cfg[2].T);
        /* acceleration level times peak jerk density within the jerk bound */
        CHECK(40.0 / (cfg[0].T * cfg[1].T) * rho <= 200000.0 * (1.0 + 1e-12));
        CHECK(cfg[1].T >= cfg[2].T);
        CHECK(cfg[0].T >= cfg[1].T + cfg[2].T);
    }
    /* the chain builds directly from the configs */
    {
        sms_stage stages[3];
        sms_chain chain;
        size_t need;
        CHECK_STATUS(sms_chain_buffer_size(cfg, 3, 1e-4, &need), SMS_OK);
        if (need < 100000) {
            static sms_real buf[100000];
            CHECK_STATUS(sms_chain_init(&chain, stages, cfg, 3, 1e-4, buf, need), SMS_OK);
        }
    }
    /* trigonometric tuned: odd multiples of 3 pi / wd only */
    CHECK_STATUS(sms_kinematic_configs(40.0, L, 3, SMS_PROFILE_TRIGONOMETRIC, 300.0, 0.0, cfg, 3, &n), SMS_OK);
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
        CHECK_STATUS(sms_kinematic_design(trial % 2 ? h : -h, L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, T, 3, &n), SMS_OK);
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
        CHECK_STATUS(sms_kinematic_design(h, L, order, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, T, 6, &n), SMS_OK);
        check_structure_and_bounds(h, L, order, T, 1.0);
        CHECK_STATUS(sms_kinematic_design(h, L, order, SMS_PROFILE_TRIGONOMETRIC, 0.0, 0.0, T, 6, &n), SMS_OK);
        check_structure_and_bounds(h, L, order, T, PI / 2.0);
    }
    /* n = 2: short move gives the triangular profile T1 = T2 = sqrt(h/a) */
    {
        double L[2] = {10.0, 1.0}, T[2];
        size_t n;
        CHECK_STATUS(sms_kinematic_design(4.0, L, 2, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, T, 2, &n), SMS_OK);
        CHECK_CLOSE(T[0], 2.0, 1e-14, 1.0);
        CHECK_CLOSE(T[1], 2.0, 1e-14, 1.0);
    }
}

static void test_bad_input(void)
{
    double L[3] = {250.0, 5000.0, 200000.0}, T[3] = {-1.0, -1.0, -1.0};
    size_t n = 99;
    sms_stage_config cfg[3];
    CHECK_STATUS(sms_kinematic_design(0.0, L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, T, 3, &n), SMS_ERR_LIMIT);
    CHECK_STATUS(sms_kinematic_design(NAN, L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, T, 3, &n), SMS_ERR_LIMIT);
    L[1] = -1.0;
    CHECK_STATUS(sms_kinematic_design(1.0, L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, T, 3, &n), SMS_ERR_LIMIT);
    L[1] = INFINITY;
    CHECK_STATUS(sms_kinematic_design(1.0, L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, T, 3, &n), SMS_ERR_LIMIT);
    L[1] = 5000.0;
    CHECK_STATUS(sms_kinematic_design(1.0, L, 0, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, T, 3, &n), SMS_ERR_ORDER);
    CHECK_STATUS(sms_kinematic_design(1.0, L, SMS_KINEMATIC_MAX_ORDER + 1, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, T, 3, &n), SMS_ERR_ORDER);
    CHECK_STATUS(sms_kinematic_design(1.0, L, 3, (sms_profile)7, 0.0, 0.0, T, 3, &n), SMS_ERR_KIND);
    CHECK_STATUS(sms_kinematic_design(1.0, L, 3, SMS_PROFILE_DAMPED, 0.0, 0.0, T, 3, &n), SMS_ERR_WN);
    CHECK_STATUS(sms_kinematic_design(1.0, L, 3, SMS_PROFILE_POLYNOMIAL, -5.0, 0.0, T, 3, &n), SMS_ERR_WN);
    CHECK_STATUS(sms_kinematic_design(1.0, L, 3, SMS_PROFILE_POLYNOMIAL, 50.0, 1.0, T, 3, &n), SMS_ERR_ZETA);
    CHECK_STATUS(sms_kinematic_design(1.0, L, 1, SMS_PROFILE_DAMPED, 50.0, 0.1, T, 3, &n), SMS_ERR_ORDER);
    CHECK_STATUS(sms_kinematic_design(1.0, L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, T, 2, &n), SMS_ERR_BUFFER_TOO_SMALL);
    CHECK_STATUS(sms_kinematic_design(1.0, NULL, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, T, 3, &n), SMS_ERR_NULL);
    CHECK_STATUS(sms_kinematic_configs(1.0, L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, NULL, 3, &n), SMS_ERR_NULL);
    CHECK_STATUS(sms_kinematic_configs(1.0, L, 3, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, cfg, 1, &n), SMS_ERR_BUFFER_TOO_SMALL);
    CHECK(T[0] == -1.0 && T[1] == -1.0 && T[2] == -1.0 && n == 99); /* untouched */
}

int main(void)
{
    test_seed_values();
    test_mode_tuned();
    test_double_s_random();
    test_higher_orders();
    test_bad_input();
    return check_summary("test_kinematic");
}
