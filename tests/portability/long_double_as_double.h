/* SPDX-License-Identifier: Apache-2.0 */
/*
 * Force-included (-include) with -mlong-double-64 by the SMS_LONG_DOUBLE_AS_DOUBLE build: it
 * makes this machine a platform whose long double is a double, as MSVC on x64, Apple arm64 and
 * the Cortex-M toolchains have it. -mlong-double-64 makes the type 64 bits wide; the C library
 * here still implements the long double functions for the 80-bit type, so their calls go to
 * the double functions, as they do where long double is a double.
 */
#ifndef SMS_LONG_DOUBLE_AS_DOUBLE_H
#define SMS_LONG_DOUBLE_AS_DOUBLE_H

#include <math.h>

typedef char sms_long_double_is_double[(sizeof(long double) == sizeof(double)) ? 1 : -1];

#define expl exp
#define expm1l expm1
#define log1pl log1p
#define sinl sin
#define cosl cos
#define fabsl fabs
#define floorl floor
#define fmodl fmod
#define sqrtl sqrt
#define logl log
#define powl pow
#define ceill ceil
#define roundl round
#define truncl trunc

#endif
