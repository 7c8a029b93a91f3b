/* SPDX-License-Identifier: Apache-2.0 */
/*
 * CPU time of the process and the median of timed rounds, shared by the C benchmarks
 * (tests/bench/, tests/fmu/bench_*.c): CPU time, so other processes on the machine do not
 * count, and the median of interleaved rounds, so one disturbed round does not either.
 */
#ifndef SMS_BENCH_CPU_TIME_H
#define SMS_BENCH_CPU_TIME_H

#include <stdlib.h>
#include <time.h>

static inline double cpu_seconds(void)
{
#if defined(CLOCK_PROCESS_CPUTIME_ID)
    struct timespec t;
    if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t) == 0)
        return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
#endif
    return (double)clock() / CLOCKS_PER_SEC;
}

static inline int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/** The median of v[0..n-1] (sorts v). */
static inline double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, compare_doubles);
    return v[n / 2];
}

#endif
