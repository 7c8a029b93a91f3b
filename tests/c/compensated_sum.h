/* SPDX-License-Identifier: Apache-2.0 */
/* The tests' reference sums, as accurate as if computed in twice the working precision
 * whatever the platform's long double is: Dot2 of T. Ogita, S. M. Rump, S. Oishi, "Accurate
 * sum and dot product", SIAM J. Sci. Comput. 26(6), 2005 (TwoSum, and TwoProduct by one fma),
 * written independently of the library's double-double code. */
#ifndef SMS_TEST_COMPENSATED_SUM_H
#define SMS_TEST_COMPENSATED_SUM_H
#include <math.h>

typedef struct compensated_sum {
    double sum, err;   /* the value is sum + err */
} compensated_sum;

/* s += a b: the rounding errors of the product and of the sum go to err. */
static inline void compensated_add_product(compensated_sum *s, double a, double b)
{
    const double p = a * b, pe = fma(a, b, -p);
    const double t = s->sum + p, z = t - s->sum;
    s->err += ((s->sum - (t - z)) + (p - z)) + pe;
    s->sum = t;
}

static inline double compensated_value(const compensated_sum *s)
{
    return s->sum + s->err;
}

#endif
