/* SPDX-License-Identifier: Apache-2.0 */
/* Batch kinematic design: every problem's lengths equal the single design's bit for bit (any
 * order, profile, mode, grid and strides); a refused problem reports its index and status,
 * keeps the rows before it and leaves the rest untouched; bad arguments write nothing. */
#include <stdlib.h>
#include <string.h>
#include "check.h"

#define M 64
#define SENTINEL -7.0

static double urand(unsigned *s)
{
    *s = *s * 1103515245u + 12345u;
    return ((*s >> 8) & 0xFFFFFFu) / 16777216.0;
}

static double decades(unsigned *s, double lo, double hi)
{
    return pow(10.0, lo + (hi - lo) * urand(s));
}

static void fill(double *x, size_t count, double value)
{
    size_t i;
    for (i = 0; i < count; ++i)
        x[i] = value;
}

/* One random batch: per-problem or shared h and bounds; compares with the single design. */
static void check_batch(unsigned *seed, size_t n, sms_profile profile, double wn, int grid,
                        size_t h_stride, size_t limits_stride)
{
    static double h[M], limits[M * SMS_KINEMATIC_MAX_ORDER], T[M * SMS_KINEMATIC_MAX_ORDER + 1];
    double one[SMS_KINEMATIC_MAX_ORDER], Ts = 0.0;
    size_t i, k, index = 12345, count = 0;
    sms_status st;
    for (i = 0; i < M; ++i) {
        h[i] = (urand(seed) < 0.5 ? -1.0 : 1.0) * decades(seed, -3.0, 3.0);
        for (k = 0; k < n; ++k)
            limits[i * n + k] = decades(seed, -2.0, 2.0) * pow(10.0, (double)k);
    }
    if (grid) {
        /* a period a few hundred times shorter than the first problem's duration */
        double total = 0.0;
        CHECK_STATUS(sms_kinematic_design(h[0], limits, n, profile, wn, 0.1, 0.0, one,
                                          SMS_KINEMATIC_MAX_ORDER, &count), SMS_OK);
        for (k = 0; k < n; ++k)
            total += one[k];
        Ts = total / 300.0;
    }
    fill(T, M * SMS_KINEMATIC_MAX_ORDER + 1, SENTINEL);
    st = sms_kinematic_design_batch(M, h, h_stride, limits, limits_stride, n, profile, wn, 0.1,
                                    Ts, T, M * n, &index);
    for (i = 0; i < M; ++i) {
        sms_status single = sms_kinematic_design(h[i * h_stride], limits + i * limits_stride, n,
                                                 profile, wn, 0.1, Ts, one,
                                                 SMS_KINEMATIC_MAX_ORDER, &count);
        if (single != SMS_OK) {
            /* the first refusal stops the batch (a tuned stage on a coarse grid, say) */
            CHECK_STATUS(st, single);
            CHECK(index == i);
            CHECK(T[i * n] == SENTINEL);
            return;
        }
        CHECK(memcmp(T + i * n, one, n * sizeof(double)) == 0);
    }
    CHECK_STATUS(st, SMS_OK);
    CHECK(index == M);
    CHECK(T[M * n] == SENTINEL);
}

static void test_equals_single_design(void)
{
    unsigned seed = 17u;
    size_t n, rep;
    for (n = 1; n <= SMS_KINEMATIC_MAX_ORDER; ++n)
        for (rep = 0; rep < 4; ++rep) {
            /* on a grid from 6 bounds up the design's search takes milliseconds: the loop
             * over problems is the same, so the grid is exercised up to 5 bounds */
            int grid = (int)(rep & 1u) && n <= 5;
            check_batch(&seed, n, SMS_PROFILE_POLYNOMIAL, 0.0, grid, 1, n);
            check_batch(&seed, n, SMS_PROFILE_TRIGONOMETRIC, 0.0, grid, 1, n);
            check_batch(&seed, n, SMS_PROFILE_POLYNOMIAL, 0.0, grid, 0, n);   /* shared h */
            check_batch(&seed, n, SMS_PROFILE_POLYNOMIAL, 0.0, grid, 1, 0);   /* shared bounds */
            if (n >= 2 && n <= 4)   /* a mode's multiple search costs ms at higher orders */
                check_batch(&seed, n, SMS_PROFILE_DAMPED, decades(&seed, 0.0, 3.0), grid, 1, n);
        }
}

static void test_refused_problem(void)
{
    double h[5] = {1.0, -2.0, 3.0, 4.0, 5.0};
    double limits[15] = {1, 10, 100, 2, 20, 200, 3, -30, 300, 4, 40, 400, 5, 50, 500};
    double T[15], one[3];
    size_t index = 0, count, i;
    fill(T, 15, SENTINEL);
    CHECK_STATUS(sms_kinematic_design_batch(5, h, 1, limits, 3, 3, SMS_PROFILE_POLYNOMIAL,
                                            0.0, 0.0, 0.0, T, 15, &index), SMS_ERR_LIMIT);
    CHECK(index == 2);
    for (i = 0; i < 2; ++i) {
        CHECK_STATUS(sms_kinematic_design(h[i], limits + 3 * i, 3, SMS_PROFILE_POLYNOMIAL, 0.0,
                                          0.0, 0.0, one, 3, &count), SMS_OK);
        CHECK(memcmp(T + 3 * i, one, sizeof one) == 0);
    }
    for (i = 6; i < 15; ++i)
        CHECK(T[i] == SENTINEL);
    /* h = 0 in the last problem; NaN in a shared h stops at problem 0 */
    h[4] = 0.0;
    limits[7] = 30.0;
    CHECK_STATUS(sms_kinematic_design_batch(5, h, 1, limits, 3, 3, SMS_PROFILE_POLYNOMIAL,
                                            0.0, 0.0, 0.0, T, 15, &index), SMS_ERR_LIMIT);
    CHECK(index == 4);
    h[0] = NAN;
    CHECK_STATUS(sms_kinematic_design_batch(5, h, 0, limits, 3, 3, SMS_PROFILE_POLYNOMIAL,
                                            0.0, 0.0, 0.0, T, 15, &index), SMS_ERR_LIMIT);
    CHECK(index == 0);
    /* an extreme ratio is refused in the problem where it occurs */
    h[0] = 1.0;
    h[4] = 1e300;
    limits[12] = 1e-250;
    CHECK_STATUS(sms_kinematic_design_batch(5, h, 1, limits, 3, 3, SMS_PROFILE_POLYNOMIAL,
                                            0.0, 0.0, 0.0, T, 15, &index), SMS_ERR_TOO_LONG);
    CHECK(index == 4);
}

static void test_bad_arguments(void)
{
    double h[2] = {1.0, 2.0}, limits[6] = {1, 10, 100, 1, 10, 100}, T[6];
    size_t index = 99;
    fill(T, 6, SENTINEL);
    CHECK_STATUS(sms_kinematic_design_batch(2, h, 1, limits, 3, 3, SMS_PROFILE_POLYNOMIAL, 0.0,
                                            0.0, 0.0, NULL, 6, &index), SMS_ERR_NULL);
    CHECK(index == 99);
    CHECK_STATUS(sms_kinematic_design_batch(2, h, 1, limits, 3, 3, SMS_PROFILE_POLYNOMIAL, 0.0,
                                            0.0, 0.0, T, 6, NULL), SMS_ERR_NULL);
    CHECK_STATUS(sms_kinematic_design_batch(2, NULL, 1, limits, 3, 3, SMS_PROFILE_POLYNOMIAL,
                                            0.0, 0.0, 0.0, T, 6, &index), SMS_ERR_NULL);
    CHECK_STATUS(sms_kinematic_design_batch(2, h, 1, NULL, 3, 3, SMS_PROFILE_POLYNOMIAL, 0.0,
                                            0.0, 0.0, T, 6, &index), SMS_ERR_NULL);
    CHECK_STATUS(sms_kinematic_design_batch(2, h, 1, limits, 3, 0, SMS_PROFILE_POLYNOMIAL, 0.0,
                                            0.0, 0.0, T, 6, &index), SMS_ERR_ORDER);
    CHECK(index == 2);
    CHECK_STATUS(sms_kinematic_design_batch(2, h, 1, limits, 3, SMS_KINEMATIC_MAX_ORDER + 1,
                                            SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 0.0, T, 6, &index),
                 SMS_ERR_ORDER);
    CHECK_STATUS(sms_kinematic_design_batch(2, h, 1, limits, 3, 3, SMS_PROFILE_POLYNOMIAL, 0.0,
                                            0.0, 0.0, T, 5, &index), SMS_ERR_BUFFER_TOO_SMALL);
    /* a count whose product with n overflows size_t is refused, not wrapped */
    CHECK_STATUS(sms_kinematic_design_batch((size_t)-1 / 2, h, 0, limits, 0, 3,
                                            SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 0.0, T, 6, &index),
                 SMS_ERR_BUFFER_TOO_SMALL);
    for (index = 0; index < 6; ++index)
        CHECK(T[index] == SENTINEL);
    /* shared arguments are checked by the design of each problem */
    CHECK_STATUS(sms_kinematic_design_batch(2, h, 1, limits, 3, 3, SMS_PROFILE_POLYNOMIAL, 0.0,
                                            0.0, -1e-3, T, 6, &index), SMS_ERR_SAMPLE_PERIOD);
    CHECK(index == 0);
    /* nothing to do */
    CHECK_STATUS(sms_kinematic_design_batch(0, NULL, 0, NULL, 0, 3, SMS_PROFILE_POLYNOMIAL, 0.0,
                                            0.0, 0.0, T, 0, &index), SMS_OK);
    CHECK(index == 0);
}

int main(void)
{
    test_equals_single_design();
    test_refused_problem();
    test_bad_arguments();
    return check_summary("test_kinematic_batch");
}
