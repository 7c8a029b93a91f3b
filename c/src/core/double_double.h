/* SPDX-License-Identifier: Apache-2.0 */
/* Internal: double-double arithmetic for the designs that need more than double (init only).
 *
 * A value is hi + lo with |lo| <= ulp(hi)/2, about 106 bits, built from the error-free
 * transformations TwoSum (Knuth) and TwoProduct (one fma): T. J. Dekker, "A floating-point
 * technique for extending the available precision", 1971; D. H. Bailey, Y. Hida, X. S. Li,
 * "Algorithms for quad-double precision floating point arithmetic", 2001. Every operation rounds
 * each double result on its own (assignments under C99's FLT_EVAL_METHOD rules), so it gives the
 * same digits whatever the platform's long double is (80-bit x87, 128-bit or a plain double). */
#ifndef SMS_DOUBLE_DOUBLE_INTERNAL_H
#define SMS_DOUBLE_DOUBLE_INTERNAL_H

typedef struct sms_dd {
    double hi, lo;
} sms_dd;

sms_dd sms_dd_of(double a);
sms_dd sms_dd_add(sms_dd a, sms_dd b);
sms_dd sms_dd_sub(sms_dd a, sms_dd b);
sms_dd sms_dd_neg(sms_dd a);
sms_dd sms_dd_mul(sms_dd a, sms_dd b);
sms_dd sms_dd_div(sms_dd a, sms_dd b);
/* a * 2^e, exact */
sms_dd sms_dd_scale(sms_dd a, int e);

/* e^x and e^x - 1 (both to about 2^-100 relative; 0 below e^-745, not for x above 700) */
sms_dd sms_dd_exp(sms_dd x);
sms_dd sms_dd_expm1(sms_dd x);

/* sin(pi x), cos(pi x) for any finite x, exact zeros (and +-1) at multiples of 1/2 */
sms_dd sms_dd_sin_pi(sms_dd x);
sms_dd sms_dd_cos_pi(sms_dd x);

#endif
