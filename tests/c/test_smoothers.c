/* SPDX-License-Identifier: Apache-2.0 */
/* The four FIR smoothers' responses: taps against the sampled continuous responses, step
 * responses against closed forms, exact-timing zeros, paper timing. (Streams, state, invalid
 * configurations: test_smoother_stream.c.) Tolerances: SMS_TEST_REL_TOL (check.h). */
#include "check.h"
#include "smoother_fixtures.h"

#define PI 3.14159265358979323846
#define MAX_LEN 12000

static sms_real ring_a[MAX_LEN];
static double taps[MAX_LEN], expect[MAX_LEN];

static int is_damped(sms_kind kind)
{
    return kind == SMS_DAMPED_HARMONIC || kind == SMS_EXPONENTIAL;
}

/* Unnormalised continuous impulse response at t for duration T (docs/filters.md). */
static double continuous(sms_kind kind, double t, double T, double sigma)
{
    double g = is_damped(kind) ? exp(sigma * t) : 1.0;
    return is_harmonic(kind) ? g * sin(PI * t / T) : g;
}

static double max_abs(const double *v, size_t n)
{
    double m = 0.0;
    size_t i;
    for (i = 0; i < n; ++i)
        if (fabs(v[i]) > m)
            m = fabs(v[i]);
    return m;
}

/* Impulse response of an initialised smoother into out[0..n-1]. */
static void impulse_response(sms_smoother *f, double *out, size_t n)
{
    size_t i;
    sms_smoother_reset(f, (sms_real)0);
    for (i = 0; i < n; ++i) {
        sms_real x = (sms_real)(i == 0 ? 1.0 : 0.0);
        sms_smoother_step(f, &x);
        out[i] = (double)x;
    }
}

/* Integer N: realised impulse response == sampled continuous response, normalised. */
static void test_integer_impulse(sms_kind kind, size_t N, double sigma)
{
    const double Ts = 1e-3;
    sms_stage_config c = smoother(kind, (double)N * Ts, sigma, 1u, SMS_TIMING_EXACT);
    sms_smoother f;
    double sum = 0.0, scale;
    size_t i, len;
    CHECK_STATUS(sms_smoother_init(&f, &c, Ts, ring_a, MAX_LEN), SMS_OK);
    CHECK(f.length == N);
    CHECK_STATUS(sms_smoother_length(&c, Ts, &len), SMS_OK);
    CHECK(len == N);
    for (i = 0; i < N; ++i)
        sum += continuous(kind, (double)i * Ts, c.T, sigma);
    for (i = 0; i < N + 8; ++i)
        expect[i] = i < N ? continuous(kind, (double)i * Ts, c.T, sigma) / sum : 0.0;
    impulse_response(&f, taps, N + 8);
    scale = max_abs(expect, N);
    for (i = 0; i < N + 8; ++i)
        CHECK_CLOSE(taps[i], expect[i], SMS_TEST_REL_TOL, scale);
    /* sms_smoother_taps() describes the same filter, in double. */
    CHECK_STATUS(sms_smoother_taps(&c, Ts, taps, MAX_LEN), SMS_OK);
    for (i = 0; i < N; ++i)
        CHECK_CLOSE(taps[i], expect[i], 1e-12, scale);
}

/* Any timing: the realised impulse response == sms_smoother_taps(), and nothing after L. */
static void test_realised_equals_taps(const sms_stage_config *c, double Ts)
{
    sms_smoother f;
    double scale;
    size_t i, L;
    CHECK_STATUS(sms_smoother_init(&f, c, Ts, ring_a, MAX_LEN), SMS_OK);
    L = f.length;
    CHECK(L + 8 <= MAX_LEN);
    CHECK_STATUS(sms_smoother_taps(c, Ts, expect, L), SMS_OK);
    CHECK_STATUS(sms_smoother_taps(c, Ts, expect, L - 1), SMS_ERR_BUFFER_TOO_SMALL);
    impulse_response(&f, taps, L + 8);
    scale = max_abs(expect, L);
    for (i = 0; i < L + 8; ++i)
        CHECK_CLOSE(taps[i], i < L ? expect[i] : 0.0, SMS_TEST_REL_TOL, scale);
}

/* H(z) = sum h[i] z^-i at z = e^{(sigma + j w) Ts}, returned as |H|; also H(1). */
static double response_at(const double *h, size_t L, double sigma, double w, double Ts, double *dc)
{
    double re = 0.0, im = 0.0, sum = 0.0;
    size_t i;
    for (i = 0; i < L; ++i) {
        double mag = exp(-sigma * Ts * (double)i);
        re += h[i] * mag * cos(w * Ts * (double)i);
        im -= h[i] * mag * sin(w * Ts * (double)i);
        sum += h[i];
    }
    *dc = sum;
    return sqrt(re * re + im * im);
}

/* Exact timing: H(1) = 1 and H(z*) = 0 at the pinned zero, for T/Ts off the grid. */
static void test_exact_zero(sms_kind kind, double T, double sigma, unsigned k, double Ts)
{
    sms_stage_config c = smoother(kind, T, sigma, k, SMS_TIMING_EXACT);
    double w = (double)k * (is_harmonic(kind) ? 3.0 : 2.0) * PI / T, dc, residual;
    double s = is_damped(kind) ? sigma : 0.0;
    size_t L;
    CHECK_STATUS(sms_smoother_length(&c, Ts, &L), SMS_OK);
    CHECK(L == (size_t)floor(T / Ts) + 1u);
    CHECK_STATUS(sms_smoother_taps(&c, Ts, taps, MAX_LEN), SMS_OK);
    residual = response_at(taps, L, s, w, Ts, &dc);
    CHECK_CLOSE(dc, 1.0, 1e-12, 1.0);
    CHECK(residual <= 1e-9);
    test_realised_equals_taps(&c, Ts);
}

/* docs/errata.md: the seed 000 experiment with paper timing keeps N = round(153.6) = 154 and leaves
 * ~0.27 % residual at the nominal mode; exact timing removes it. */
static void test_paper_timing(void)
{
    const double sigma = -15.6539, wd = 122.7185, Ts = 500e-6, T = 3.0 * PI / wd;
    sms_stage_config c = smoother(SMS_DAMPED_HARMONIC, T, sigma, 1u, SMS_TIMING_PAPER);
    double dc, residual, sum = 0.0, scale;
    size_t L, i;
    CHECK_STATUS(sms_smoother_length(&c, Ts, &L), SMS_OK);
    CHECK(L == 154u);
    CHECK_STATUS(sms_smoother_taps(&c, Ts, taps, MAX_LEN), SMS_OK);
    for (i = 0; i < L; ++i)
        sum += continuous(SMS_DAMPED_HARMONIC, (double)i * Ts, 154.0 * Ts, sigma);
    for (i = 0; i < L; ++i)
        expect[i] = continuous(SMS_DAMPED_HARMONIC, (double)i * Ts, 154.0 * Ts, sigma) / sum;
    scale = max_abs(expect, L);
    for (i = 0; i < L; ++i)
        CHECK_CLOSE(taps[i], expect[i], 1e-12, scale);
    residual = response_at(taps, L, sigma, wd, Ts, &dc);
    printf("paper timing, T/Ts = %.4f: residual at the mode %.4f %%\n", T / Ts, 100.0 * residual);
    CHECK(residual >= 0.0026 && residual <= 0.0028);
    test_realised_equals_taps(&c, Ts);
    c.timing = SMS_TIMING_EXACT;
    CHECK_STATUS(sms_smoother_taps(&c, Ts, taps, MAX_LEN), SMS_OK);
    CHECK_STATUS(sms_smoother_length(&c, Ts, &L), SMS_OK);
    CHECK(L == 154u);
    residual = response_at(taps, L, sigma, wd, Ts, &dc);
    CHECK(residual <= 1e-9);
    /* Paper timing rounds half up: 10.5 -> 11 (harmonic), 2.4 -> 2 (rectangular). */
    c = smoother(SMS_HARMONIC, 10.5 * Ts, 0.0, 1u, SMS_TIMING_PAPER);
    CHECK_STATUS(sms_smoother_length(&c, Ts, &L), SMS_OK);
    CHECK(L == 11u);
    c = smoother(SMS_RECTANGULAR, 2.4 * Ts, 0.0, 1u, SMS_TIMING_PAPER);
    CHECK_STATUS(sms_smoother_length(&c, Ts, &L), SMS_OK);
    CHECK(L == 2u);
}

/* Exact timing keeps the taps non-negative, so a step rises monotonically to 1 without
 * overshoot (docs/exact-mode.md), over a sweep of non-integer T/Ts, multiples and damping. */
static void test_exact_no_overshoot(void)
{
    static const double ratios[9] = {3.1, 3.7, 6.5, 10.25, 33.3, 100.9, 257.77, 1000.5, 2999.3};
    static const sms_kind kinds[4] = {SMS_RECTANGULAR, SMS_HARMONIC, SMS_DAMPED_HARMONIC, SMS_EXPONENTIAL};
    static const double sigmas[3] = {-0.5, -20.0, -200.0};
    const double Ts = 1e-3;
    int f, r, s;
    unsigned k;
    for (f = 0; f < 4; ++f)
        for (r = 0; r < 9; ++r)
            for (k = 1u; k <= 3u; ++k)
                for (s = 0; s < 3; ++s) {
                    sms_stage_config c = smoother(kinds[f], ratios[r] * Ts, sigmas[s], k, SMS_TIMING_EXACT);
                    double step = 0.0, lowest = 0.0, highest = 0.0;
                    size_t L, i;
                    if (is_harmonic(kinds[f]) && k == 2u)
                        continue;
                    if ((double)k * (is_harmonic(kinds[f]) ? 3.0 : 2.0) >= ratios[r])
                        continue; /* above Nyquist: rejected, see test_smoother_stream.c */
                    CHECK_STATUS(sms_smoother_length(&c, Ts, &L), SMS_OK);
                    CHECK_STATUS(sms_smoother_taps(&c, Ts, taps, MAX_LEN), SMS_OK);
                    for (i = 0; i < L; ++i) {
                        step += taps[i];
                        if (taps[i] < lowest)
                            lowest = taps[i];
                        if (step > highest)
                            highest = step;
                    }
                    CHECK(lowest >= 0.0);
                    CHECK(highest <= 1.0 + 1e-13);
                }
}

/* Unit step through an initialised smoother into taps[0..n-1]. */
static void step_response(sms_smoother *f, double *out, size_t n)
{
    size_t i;
    sms_smoother_reset(f, (sms_real)0);
    for (i = 0; i < n; ++i) {
        sms_real x = (sms_real)1;
        sms_smoother_step(f, &x);
        out[i] = (double)x;
    }
}

/* Continuous peak density of a real-pole smoother over [0, T): the largest value of its
 * normalised impulse response, 1/T (rectangular) or -sigma/(1 - e^{sigma T}) at t = 0. */
static double peak_density(double T, double sigma)
{
    return sigma * T > -1e-15 ? 1.0 / T : -sigma / -expm1(sigma * T); /* 1/T to rounding */
}

/* Bounded timing (docs/exact-mode.md) over random T/Ts off the grid, multiples and damping:
 * L = floor(nu) + 2 taps, all in [0, peak density Ts (1 + 1e-12)], summing to 1, the zero
 * pinned as exact timing pins it, the realisation equal to the taps; on the grid the same
 * filter as exact timing; refused where it has no meaning. */
static void test_bounded_timing(void)
{
    unsigned long long rng = 0x9e3779b97f4a7c15ull;
    const double Ts = 1e-3;
    double worst = -1.0;
    int trial;
    for (trial = 0; trial < 400; ++trial) {
        const sms_kind kind = trial % 2 ? SMS_EXPONENTIAL : SMS_RECTANGULAR;
        const unsigned k = 1u + (unsigned)(4.0 * xorshift_uniform(&rng));
        /* nu from just above 2k (a mode near Nyquist) to about 2k + 3000 */
        const double nu = 2.0 * k + 1e-3 + pow(10.0, 3.5 * xorshift_uniform(&rng));
        const double zeta = kind == SMS_EXPONENTIAL ? 0.9 * xorshift_uniform(&rng) : 0.0;
        const double w = (double)k * 2.0 * PI / (nu * Ts);
        const double sigma = -zeta / sqrt(1.0 - zeta * zeta) * w / (double)k;
        sms_stage_config c = smoother(kind, nu * Ts, sigma, k, SMS_TIMING_BOUNDED);
        double dc, residual, top, bound, lowest = 1.0;
        size_t L, M, i;
        if (fabs(nu - floor(nu + 0.5)) <= 1e-9 * nu)
            continue;
        CHECK_STATUS(sms_smoother_length(&c, Ts, &L), SMS_OK);
        CHECK_STATUS(sms_smoother_buffer_size(&c, Ts, &M), SMS_OK);
        CHECK(L == (size_t)floor(nu) + 2u && M == L - 1u);
        CHECK_STATUS(sms_smoother_taps(&c, Ts, taps, MAX_LEN), SMS_OK);
        top = max_abs(taps, L);
        for (i = 0; i < L; ++i)
            if (taps[i] < lowest)
                lowest = taps[i];
        bound = peak_density(c.T, sigma) * Ts;
        CHECK(lowest >= 0.0);
        CHECK(top <= bound * (1.0 + 1e-12));
        if (top / bound - 1.0 > worst)
            worst = top / bound - 1.0;
        residual = response_at(taps, L, sigma, w, Ts, &dc);
        CHECK_CLOSE(dc, 1.0, 1e-12, 1.0);
        CHECK(residual <= 1e-9);
        if (L + 8 <= MAX_LEN)
            test_realised_equals_taps(&c, Ts);
    }
    printf("bounded timing: largest tap / (peak density Ts) - 1 = %.3g (400 designs)\n", worst);
    /* one sample off a mode near Nyquist, and the limits of u: f -> 0 and f -> 1 */
    {
        static const double ratios[5] = {2.08, 10.5, 20.000001, 20.999999, 1000.5};
        int r;
        for (r = 0; r < 5; ++r) {
            sms_stage_config c = smoother(SMS_RECTANGULAR, ratios[r] * Ts, 0.0, 1u,
                                          SMS_TIMING_BOUNDED);
            double dc;
            size_t L;
            CHECK_STATUS(sms_smoother_length(&c, Ts, &L), SMS_OK);
            CHECK_STATUS(sms_smoother_taps(&c, Ts, taps, MAX_LEN), SMS_OK);
            CHECK(max_abs(taps, L) <= (1.0 + 1e-12) / ratios[r]);
            /* symmetric: the undamped end taps are equal */
            CHECK_CLOSE(taps[0], taps[L - 1u], 1e-12, taps[1]);
            CHECK(response_at(taps, L, 0.0, 2.0 * PI / (ratios[r] * Ts), Ts, &dc) <= 1e-9);
            test_realised_equals_taps(&c, Ts);
        }
    }
    /* on the grid: the integer-N filter, as exact timing gives */
    {
        sms_stage_config c = smoother(SMS_EXPONENTIAL, 40.0 * Ts, -7.0, 1u, SMS_TIMING_BOUNDED);
        size_t L, i;
        CHECK_STATUS(sms_smoother_taps(&c, Ts, taps, MAX_LEN), SMS_OK);
        c.timing = SMS_TIMING_EXACT;
        CHECK_STATUS(sms_smoother_taps(&c, Ts, expect, MAX_LEN), SMS_OK);
        CHECK_STATUS(sms_smoother_length(&c, Ts, &L), SMS_OK);
        CHECK(L == 40u);
        for (i = 0; i < L; ++i)
            CHECK(taps[i] == expect[i]);
    }
    /* refused: a half sine (its peak is mid-window), above Nyquist */
    {
        sms_stage_config c = smoother(SMS_HARMONIC, 10.5 * Ts, 0.0, 1u, SMS_TIMING_BOUNDED);
        size_t L;
        CHECK_STATUS(sms_smoother_length(&c, Ts, &L), SMS_ERR_KIND);
        c = smoother(SMS_DAMPED_HARMONIC, 10.0 * Ts, -1.0, 1u, SMS_TIMING_BOUNDED);
        CHECK_STATUS(sms_smoother_length(&c, Ts, &L), SMS_ERR_KIND);
        c = smoother(SMS_RECTANGULAR, 3.9 * Ts, 0.0, 2u, SMS_TIMING_BOUNDED);
        CHECK_STATUS(sms_smoother_length(&c, Ts, &L), SMS_ERR_ABOVE_NYQUIST);
    }
}

/* Step responses: discrete closed forms (exact) and the continuous trajectories (O(Ts)). */
static void test_step_rectangular(void)
{
    const double Ts = 1e-3;
    const size_t N = 250;
    sms_stage_config c = smoother(SMS_RECTANGULAR, (double)N * Ts, 0.0, 1u, SMS_TIMING_EXACT);
    sms_smoother f;
    size_t n;
    CHECK_STATUS(sms_smoother_init(&f, &c, Ts, ring_a, MAX_LEN), SMS_OK);
    step_response(&f, taps, N + 10);
    /* sum_{i<=n} 1/N = (n+1)/N: the continuous ramp t/T sampled at t = (n+1) Ts, exactly. */
    for (n = 0; n < N + 10; ++n)
        CHECK_CLOSE(taps[n], n + 1 < N ? (double)(n + 1) / (double)N : 1.0, SMS_TEST_REL_TOL, 1.0);
}

static void test_step_exponential(void)
{
    const double Ts = 1e-3, sigma = -7.0;
    const size_t N = 300;
    sms_stage_config c = smoother(SMS_EXPONENTIAL, (double)N * Ts, sigma, 1u, SMS_TIMING_EXACT);
    sms_smoother f;
    double r = exp(sigma * Ts);
    size_t n;
    CHECK_STATUS(sms_smoother_init(&f, &c, Ts, ring_a, MAX_LEN), SMS_OK);
    step_response(&f, taps, N + 10);
    /* sum_{i<=n} r^i / sum_{i<N} r^i = (1 - r^{n+1})/(1 - r^N). */
    for (n = 0; n < N + 10; ++n) {
        double m = n + 1 < N ? (double)(n + 1) : (double)N;
        CHECK_CLOSE(taps[n], (1.0 - pow(r, m)) / (1.0 - pow(r, (double)N)), SMS_TEST_REL_TOL, 1.0);
    }
}

/* Continuous damped harmonic trajectory, docs/filters.md (sigma = 0: h/2 (1 - cos(pi t/T))). */
static double trajectory(double t, double T, double sigma)
{
    if (t >= T)
        return 1.0;
    return (1.0 + exp(sigma * t) * (sigma * T / PI * sin(PI * t / T) - cos(PI * t / T)))
           / (1.0 + exp(sigma * T));
}

/* Max of the normalised continuous impulse response q'(t) (dense sampling, 1 % margin). */
static double impulse_peak(double T, double sigma)
{
    double c = ((PI / T) * (PI / T) + sigma * sigma) * T / (PI * (1.0 + exp(sigma * T)));
    double peak = 0.0;
    int i;
    for (i = 0; i <= 100000; ++i) {
        double t = T * (double)i / 100000.0, v = c * exp(sigma * t) * sin(PI * t / T);
        if (v > peak)
            peak = v;
    }
    return 1.01 * peak;
}

static void test_step_harmonic(double sigma, size_t N)
{
    const double Ts = 1e-3, T = (double)N * Ts, theta = PI / (double)N;
    const sms_kind kind = sigma == 0.0 ? SMS_HARMONIC : SMS_DAMPED_HARMONIC;
    sms_stage_config c = smoother(kind, T, sigma, 1u, SMS_TIMING_EXACT);
    sms_smoother f;
    double r = exp(sigma * Ts), q_re = r * cos(theta), q_im = r * sin(theta);
    double full_re, full_im, den, variation, bound, worst = 0.0;
    size_t n;
    CHECK_STATUS(sms_smoother_init(&f, &c, Ts, ring_a, MAX_LEN), SMS_OK);
    step_response(&f, taps, N + 10);
    /* Discrete: sum_{i<=n} Im q^i = Im (1 - q^{n+1})/(1 - q), normalised by its value at N-1. */
    den = (1.0 - q_re) * (1.0 - q_re) + q_im * q_im;
    full_re = 1.0 - pow(r, (double)N) * cos(theta * (double)N);
    full_im = -pow(r, (double)N) * sin(theta * (double)N);
    for (n = 0; n < N + 10; ++n) {
        double m = n + 1 < N ? (double)(n + 1) : (double)N;
        double a_re = 1.0 - pow(r, m) * cos(theta * m), a_im = -pow(r, m) * sin(theta * m);
        double part = (a_im * (1.0 - q_re) + a_re * q_im) / den;
        double whole = (full_im * (1.0 - q_re) + full_re * q_im) / den;
        CHECK_CLOSE(taps[n], part / whole, SMS_TEST_REL_TOL, 1.0);
    }
    /* Continuous: y[n] is a left Riemann sum of the impulse response f up to (n+1) Ts,
     * normalised by the full sum. For a non-negative f of total variation V (= 2 max f, f
     * rises from 0 and falls back), each sum is within Ts V of its integral, so
     * |y[n] - q((n+1) Ts)| <= 2 Ts V / (1 - Ts V). */
    variation = 2.0 * impulse_peak(T, sigma);
    bound = 2.0 * Ts * variation / (1.0 - Ts * variation);
    for (n = 0; n < N + 10; ++n) {
        double e = fabs(taps[n] - trajectory((double)(n + 1) * Ts, T, sigma));
        if (e > worst)
            worst = e;
    }
    CHECK(worst <= bound + SMS_TEST_REL_TOL);
    CHECK(worst >= 0.05 * bound); /* the bound is of the right order, not vacuous */
    if (sigma == 0.0) {
        /* Undamped: sum_{i<=n} sin(i theta)/cot(theta/2) = (1 - cos((n+1/2) theta)/cos(theta/2))/2,
         * so the half-sample-shifted trajectory is within (1/cos(theta/2) - 1)/2 = O(Ts^2). */
        double tight = (1.0 / cos(theta / 2.0) - 1.0) / 2.0;
        for (n = 0; n + 1 < N; ++n)
            CHECK(fabs(taps[n] - trajectory(((double)n + 0.5) * Ts, T, 0.0))
                  <= tight + SMS_TEST_REL_TOL);
    }
}

int main(void)
{
    const double Ts = 1e-3;
    static const sms_kind kinds[4] = {SMS_RECTANGULAR, SMS_HARMONIC, SMS_DAMPED_HARMONIC, SMS_EXPONENTIAL};
    static const double ratios[5] = {7.3, 25.5, 100.0, 153.6, 1001.7};
    const double sigma = -15.6539, wd = 122.7185;
    int f, r;
    size_t sizes[4] = {2, 7, 100, 1500};

    for (f = 0; f < 4; ++f) {
        for (r = 0; r < 4; ++r) {
            if (sizes[r] < 2 && is_harmonic(kinds[f]))
                continue;
            test_integer_impulse(kinds[f], sizes[r], -4.0);
        }
    }
    test_integer_impulse(SMS_RECTANGULAR, 1, 0.0);
    test_integer_impulse(SMS_EXPONENTIAL, 1, -3.0);
    test_integer_impulse(SMS_EXPONENTIAL, 50, 0.0);
    test_integer_impulse(SMS_DAMPED_HARMONIC, 400, -40.0);
    /* Long windows: the split pole keeps tap i accurate although q^i takes i steps. */
    test_integer_impulse(SMS_HARMONIC, 10000, 0.0);
    test_integer_impulse(SMS_DAMPED_HARMONIC, 10000, -0.3);
    test_integer_impulse(SMS_EXPONENTIAL, 10000, -0.1);

    /* Exact timing: the seed 000 mode (T/Ts = 153.6) and other ratios and multiples. */
    test_exact_zero(SMS_DAMPED_HARMONIC, 3.0 * PI / wd, sigma, 1u, 500e-6);
    test_exact_zero(SMS_HARMONIC, 3.0 * PI / wd, 0.0, 1u, 500e-6);
    for (f = 0; f < 4; ++f) {
        for (r = 0; r < 5; ++r) {
            double T = ratios[r] * Ts;
            if (ratios[r] == 100.0)
                T = 100.37 * Ts;
            test_exact_zero(kinds[f], T, -9.0, 1u, Ts);
        }
        test_exact_zero(kinds[f], 77.77 * Ts, -20.0, 3u, Ts);
        test_exact_zero(kinds[f], 11.01 * Ts, -1.0, 1u, Ts);
    }
    test_exact_zero(SMS_RECTANGULAR, 5.0001 * Ts, 0.0, 2u, Ts);
    test_exact_zero(SMS_EXPONENTIAL, 2.5 * Ts, -100.0, 1u, Ts);
    test_paper_timing();
    test_exact_no_overshoot();
    test_bounded_timing();

    test_step_rectangular();
    test_step_exponential();
    test_step_harmonic(0.0, 200);
    test_step_harmonic(0.0, 31);
    test_step_harmonic(sigma, 154);
    test_step_harmonic(-60.0, 80);

    for (f = 0; f < 4; ++f) {
        sms_stage_config paper = smoother(kinds[f], 0.0614, -9.0, 1u, SMS_TIMING_PAPER);
        sms_stage_config tiny = smoother(kinds[f], is_harmonic(kinds[f]) ? 3.5e-3 : 2.5e-3,
                                         -9.0, 1u, SMS_TIMING_EXACT);
        test_realised_equals_taps(&paper, Ts);
        test_realised_equals_taps(&tiny, Ts);
    }
    return check_summary("test_smoothers");
}

