/* SPDX-License-Identifier: Apache-2.0 */
/* Minimal test harness: CHECK macros count failures; a test's main returns check_summary(). */
#ifndef SMS_TEST_CHECK_H
#define SMS_TEST_CHECK_H

#include <math.h>
#include <stdio.h>
#include "smoothshaper/smoothshaper.h"

#ifdef SMS_USE_FLOAT
#define SMS_TEST_REL_TOL 1e-5   /* float: docs/numerics.md */
#define SMS_TEST_PRECISION "float"
#else
#define SMS_TEST_REL_TOL 1e-12  /* double: docs/numerics.md */
#define SMS_TEST_PRECISION "double"
#endif

static int check_failures = 0;
static int check_count = 0;

#define CHECK(cond) do { ++check_count; if (!(cond)) { ++check_failures; \
    fprintf(stderr, "%s:%d: CHECK(%s) failed\n", __FILE__, __LINE__, #cond); } } while (0)

#define CHECK_STATUS(expr, expected) do { sms_status st_ = (expr); ++check_count; \
    if (st_ != (expected)) { ++check_failures; fprintf(stderr, "%s:%d: %s returned %d (%s), expected %d\n", \
    __FILE__, __LINE__, #expr, (int)st_, sms_status_string(st_), (int)(expected)); } } while (0)

/* |a - b| <= tol * max(|scale|, tiny) */
#define CHECK_CLOSE(a, b, tol, scale) do { double a_ = (double)(a), b_ = (double)(b); \
    double s_ = fabs((double)(scale)); if (s_ < 1e-300) s_ = 1e-300; ++check_count; \
    if (!(fabs(a_ - b_) <= (tol) * s_)) { ++check_failures; \
    fprintf(stderr, "%s:%d: %s = %.17g vs %s = %.17g (rel %.3g > %.3g)\n", __FILE__, __LINE__, \
    #a, a_, #b, b_, fabs(a_ - b_) / s_, (double)(tol)); } } while (0)

static int check_summary(const char *name)
{
    printf("%s [%s]: %d checks, %d failed\n", name, SMS_TEST_PRECISION, check_count, check_failures);
    return check_failures == 0 ? 0 : 1;
}

#endif
