/* SPDX-License-Identifier: Apache-2.0 */
/* Drift benchmark (docs/numerics.md): runs each smoother for many samples of 1e3 + uniform noise and
 * prints, at decade checkpoints, the max |error| against the direct convolution with the
 * taps (over a window of max(1e4, 4L) samples after the checkpoint) and the running max.
 *
 * usage: drift_bench_double [samples [family [white]]]  samples default 1e9; family 0..3, or
 * -1 for all; "white" feeds 1e3 U(-1, 1) instead (no offset for the copies' reference to
 * absorb: the harder case for rounding).
 * Built by CMake (tests/bench), never run by ctest. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <time.h>
#include "smoothshaper/smoothshaper.h"
#include "compensated_sum.h"
#include "smoother_fixtures.h"

#ifdef SMS_USE_FLOAT
#define PRECISION "float"
#else
#define PRECISION "double"
#endif

#define MAX_LEN 10100

static sms_real ring[MAX_LEN], naive_in[MAX_LEN + 2];
static double taps[MAX_LEN], recent[MAX_LEN];

static unsigned long long rng = 88172645463325252ull;
static double noise(void)
{
    return 2.0 * xorshift_uniform(&rng) - 1.0; /* [-1, 1) */
}

static int white_input = 0;

static void run(sms_kind kind, double T, double sigma, double total)
{
    const double Ts = 1e-3;
    sms_stage_config c = sms_stage_config_default(kind);
    sms_smoother f;
    size_t L, head = 0, i, window;
    double n, checkpoint = 1e4, window_end = -1.0, worst = 0.0, worst_window = 0.0;
    double naive_window = 0.0;
    /* For an integer harmonic: the seed's recursion of S(z) (docs/numerics.md) side by side. */
    int naive = 0;
    size_t naive_len = 0, naive_head = 0;
    sms_real naive_a = 0, naive_b = 0, naive_y1 = 0, naive_y2 = 0, naive_y = 0;
    clock_t start;
    c.T = T;
    c.sigma = sigma;
    if (sms_smoother_init(&f, &c, Ts, ring, MAX_LEN) != SMS_OK
        || sms_smoother_taps(&c, Ts, taps, MAX_LEN) != SMS_OK) {
        printf("%s: configuration rejected\n", sms_kind_name(kind));
        return;
    }
    L = f.length;
    window = 4 * L > 10000 ? 4 * L : 10000;
    for (i = 0; i < L; ++i)
        recent[i] = 0.0;
    if (kind == SMS_HARMONIC && f.n_corrections == 0) {
        naive = 1;
        naive_len = L + 2;
        naive_a = (sms_real)(2.0 * cos(3.14159265358979323846 / (double)L));
        naive_b = (sms_real)(1.0 - cos(3.14159265358979323846 / (double)L));
        for (i = 0; i < naive_len; ++i)
            naive_in[i] = (sms_real)0;
    }
    printf("%s [%s] T/Ts = %.4g, L = %zu, sigma = %g, input %s\n",
           sms_kind_name(kind), PRECISION, T / Ts, L, sigma,
           white_input ? "1e3 U(-1, 1)" : "1e3 + U(-1, 1)");
    start = clock();
    for (n = 0.0; n < total; n += 1.0) {
        sms_real x = (sms_real)(white_input ? 1e3 * noise() : 1e3 + noise());
        recent[head] = (double)x;
        if (naive) {
            /* y = 2 cos(pi/N) y1 - y2 + (1 - cos(pi/N)) (x[n-1] + x[n-N-1]) */
            naive_in[naive_head] = x;
            naive_y = naive_a * naive_y1 - naive_y2
                      + naive_b * (naive_in[(naive_head + naive_len - 1) % naive_len]
                                   + naive_in[(naive_head + 1) % naive_len]);
            naive_y2 = naive_y1;
            naive_y1 = naive_y;
            naive_head = (naive_head + 1) % naive_len;
        }
        sms_smoother_step(&f, &x);
        /* The last checkpoint is the end of the run: its window is the final samples. */
        if (checkpoint + (double)window > total && checkpoint <= total * 10.0)
            checkpoint = total - (double)window > 0.0 ? total - (double)window : 0.0;
        if (n >= checkpoint && window_end < 0.0) {
            window_end = n + (double)window;
            worst_window = 0.0;
            naive_window = 0.0;
        }
        if (window_end >= 0.0) {
            compensated_sum y = { 0.0, 0.0 }; /* its own rounding stays below the engine's */
            double e;
            size_t idx = head;
            for (i = 0; i < L; ++i) {
                compensated_add_product(&y, taps[i], recent[idx]);
                idx = idx == 0 ? L - 1 : idx - 1;
            }
            e = fabs(((double)x - y.sum) - y.err);
            if (!(e <= worst_window))
                worst_window = e;
            if (naive && !(fabs((naive_y - y.sum) - y.err) <= naive_window))
                naive_window = fabs((naive_y - y.sum) - y.err);
            if (n + 1.0 >= window_end || n + 1.0 >= total) {
                if (worst_window > worst || worst_window != worst_window)
                    worst = worst_window;
                printf("  samples %.10g..%.10g: max |error| %.3e (relative %.3e), running max %.3e\n",
                       checkpoint, n + 1.0, worst_window, worst_window / 1e3, worst);
                if (naive)
                    printf("    (seed's recursion of S(z), same input: max |error| %.3e)\n",
                           naive_window);
                fflush(stdout);
                window_end = -1.0;
                checkpoint = n + 1.0 >= total ? total * 100.0 : checkpoint * 10.0;
            }
        }
        head = head + 1 == L ? 0 : head + 1;
    }
    printf("  %s: max |error| bound observed %.3e (relative %.3e) over %.0e samples, %.1f ns/sample\n",
           sms_kind_name(kind), worst, worst / 1e3, total,
           1e9 * (double)(clock() - start) / CLOCKS_PER_SEC / total);
}

int main(int argc, char **argv)
{
    double total = argc > 1 ? atof(argv[1]) : 1e9;
    int only = argc > 2 ? atoi(argv[2]) : -1;
    white_input = argc > 3 && strcmp(argv[3], "white") == 0;
    if (!(total >= 1.0)) {
        fprintf(stderr, "usage: %s [samples >= 1 [family 0..3]]\n", argv[0]);
        return 2;
    }
    if (only < 0 || only == 0) {
        run(SMS_RECTANGULAR, 0.1003, 0.0, total);
        run(SMS_RECTANGULAR, 10.0, 0.0, total);
    }
    if (only < 0 || only == 1) {
        run(SMS_HARMONIC, 0.1, 0.0, total);
        run(SMS_HARMONIC, 10.0037, 0.0, total);
    }
    if (only < 0 || only == 2) {
        run(SMS_DAMPED_HARMONIC, 3.0 * 3.14159265358979323846 / 122.7185 * 0.9, -15.6539, total);
        run(SMS_DAMPED_HARMONIC, 10.0, -0.3, total);
    }
    if (only < 0 || only == 3) {
        run(SMS_EXPONENTIAL, 0.1, -3.0, total);
        run(SMS_EXPONENTIAL, 10.0, -0.1, total);
    }
    return 0;
}
