/* Online generator: bounds under adversarial staircases (fixed seeds), exact arrival,
 * q/v/a/j consistency, the right-limit jerk at jumps on the grid, time-optimal single moves,
 * state save/load, bad input. */
#include <stdlib.h>
#include "check.h"
#include "double_s.h"

#define MAX_TABLE 40000
static sms_real table[MAX_TABLE];
static sms_real table2[MAX_TABLE];

#ifdef SMS_USE_FLOAT
#define SAMPLE_EPS 5.96e-8
#else
#define SAMPLE_EPS 1.11e-16
#endif

/* Rounding allowance on the bounds: a few ulps of the signal type. */
#ifdef SMS_USE_FLOAT
#define BOUND_TOL 1e-5
#else
#define BOUND_TOL 1e-11
#endif

static unsigned rng = 1u;
static double urand(void)
{
    rng = rng * 1103515245u + 12345u;
    return ((rng >> 8) & 0xFFFFFFu) / 16777216.0;
}

static sms_generator_config make_config(double v, double a, double j, sms_profile profile,
                                        double wn, double zeta)
{
    sms_generator_config c;
    c.vmax = v;
    c.amax = a;
    c.jmax = j;
    c.profile = profile;
    c.wn = wn;
    c.zeta = zeta;
    return c;
}

static int build(sms_generator *g, const sms_generator_config *c, double Ts)
{
    size_t need = 0;
    sms_status st = sms_generator_buffer_size(c, Ts, &need);
    CHECK_STATUS(st, SMS_OK);
    if (st != SMS_OK || need > MAX_TABLE)
        return 0;
    CHECK_STATUS(sms_generator_init(g, c, Ts, table, need), SMS_OK);
    return 1;
}

/* Feed a random staircase; check every bound at every sample; hold the last target and check
 * exact arrival. style 0: steps every 1..5 samples; 1: every 1..200; 2: mixed tiny/huge. */
static void staircase(const sms_generator_config *c, double Ts, int style, unsigned seed)
{
    sms_generator g;
    sms_real out[4];
    double target = 0.0, peak[4] = {0, 0, 0, 0}, d[4] = {0, 0, 0, 0}, dpeak[4] = {0, 0, 0, 0};
    double L[4];
    long k, next = 0, hold;
    if (!build(&g, c, Ts))
        return;
    L[1] = c->vmax;
    L[2] = c->amax;
    L[3] = c->jmax;
    rng = seed;
    for (k = 0; k < 20000; ++k) {
        int i;
        double e[4];
        if (k == next) {
            double u = urand();
            if (style == 2 && u < 0.3)
                target += (urand() - 0.5) * 1e-6; /* tiny steps */
            else
                target = (urand() - 0.5) * 4.0 * c->vmax; /* reversals included */
            next = k + 1 + (long)(urand() * (style == 0 ? 5 : 200));
        }
        sms_generator_step(&g, (sms_real)target, out);
        for (i = 0; i < 4; ++i)
            if (fabs((double)out[i]) > peak[i])
                peak[i] = fabs((double)out[i]);
        /* backward differences of the samples over Ts^i, beyond their own rounding
         * (2^i 8 eps max|q| / Ts^i), relative to the bound: at most 1 + 1e-9 */
        e[0] = (double)out[0];
        for (i = 1; i < 4; ++i) {
            double floor_ = ldexp(8.0 * SAMPLE_EPS * (4.0 * c->vmax + 1.0), i) / pow(Ts, i), r;
            e[i] = e[i - 1] - d[i - 1];
            r = k >= i ? (fabs(e[i]) / pow(Ts, i) - floor_) / L[i] : 0.0;
            if (r > dpeak[i])
                dpeak[i] = r;
        }
        for (i = 0; i < 4; ++i)
            d[i] = e[i];
    }
    CHECK(dpeak[1] <= 1.0 + 1e-9);
    CHECK(dpeak[2] <= 1.0 + 1e-9);
    CHECK(dpeak[3] <= 1.0 + 1e-9);
    CHECK(peak[1] <= c->vmax * (1.0 + BOUND_TOL));
    CHECK(peak[2] <= c->amax * (1.0 + BOUND_TOL));
    CHECK(peak[3] <= c->jmax * (1.0 + BOUND_TOL));
    /* hold: the output ends exactly on the last target */
    hold = (long)((4.0 + 2.0 * c->vmax / c->amax + 2.0 * c->amax / c->jmax) / Ts) +
           4 * (long)g.n_tail + 10;
    for (k = 0; k < hold; ++k)
        sms_generator_step(&g, (sms_real)target, out);
    CHECK(out[0] == (sms_real)target);
    CHECK(out[1] == 0 && out[2] == 0 && out[3] == 0);
}

static void test_bounds_random(void)
{
    sms_generator_config c[7];
    int i, style;
    c[0] = make_config(1.0, 10.0, 100.0, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0);
    c[1] = make_config(250.0, 5000.0, 200000.0, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0);
    c[2] = make_config(2.0, 3.0, 50.0, SMS_PROFILE_TRIGONOMETRIC, 0.0, 0.0);
    c[3] = make_config(1.0, 10.0, 300.0, SMS_PROFILE_DAMPED, 60.0, 0.05);
    c[4] = make_config(0.5, 100.0, 300.0, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0); /* amax unreachable */
    c[5] = make_config(1.0, 10.0, 300.0, SMS_PROFILE_POLYNOMIAL, 40.0, 0.0);  /* jerk stage on a mode */
    c[6] = make_config(1.0, 10.0, 300.0, SMS_PROFILE_TRIGONOMETRIC, 90.0, 0.02);
    for (i = 0; i < 7; ++i)
        for (style = 0; style < 3; ++style) {
            staircase(&c[i], 1e-3, style, 17u + 31u * (unsigned)(i * 3 + style));
            staircase(&c[i], 0.37e-3, style, 99u + 7u * (unsigned)(i * 3 + style)); /* off-grid */
        }
}

/* With every breakpoint on the grid (T2, T3, segments multiples of Ts), q is a cubic with
 * constant jerk on each sample interval: q, v, a, j must satisfy Taylor's formula exactly. */
static void test_consistency(void)
{
    sms_generator g;
    /* the tail realisation: a rectangular last stage tuned to a mode of period 0.1 s */
    sms_generator_config c = make_config(1.0, 10.0, 100.0, SMS_PROFILE_POLYNOMIAL,
                                         2.0 * 3.14159265358979323846 / 0.1, 0.0);
    double Ts = 1e-3;
    sms_real prev[4], out[4];
    double err = 0.0, target = 0.0;
    long k;
    if (!build(&g, &c, Ts))
        return;
    CHECK(g.n_tail == 200u);
    sms_generator_step(&g, 0, prev);
    rng = 5u;
    for (k = 1; k < 20000; ++k) {
        double pred;
        if (k % 137 == 0)
            target = (double)(int)((urand() - 0.5) * 8000.0) * 1e-3; /* whole segments */
        sms_generator_step(&g, (sms_real)target, out);
        pred = prev[0] + prev[1] * Ts + prev[2] * Ts * Ts / 2 + prev[3] * Ts * Ts * Ts / 6;
        if (fabs(pred - out[0]) > err)
            err = fabs(pred - out[0]);
        pred = prev[1] + prev[2] * Ts + prev[3] * Ts * Ts / 2;
        CHECK_CLOSE(out[1], pred, 100 * SMS_TEST_REL_TOL, 1.0);
        pred = prev[2] + prev[3] * Ts;
        CHECK_CLOSE(out[2], pred, 100 * SMS_TEST_REL_TOL, 10.0);
        prev[0] = out[0]; prev[1] = out[1]; prev[2] = out[2]; prev[3] = out[3];
    }
    CHECK(err <= 100 * SMS_TEST_REL_TOL * 4.0);
}

/* Density of the tail's last stage at s in [0, T3]: rectangular 1/T3, exponential
 * sigma e^(sigma s) / (e^(sigma T3) - 1). */
static double last_density(double s, double T3, double sigma)
{
    return sigma == 0.0 ? 1.0 / T3 : sigma * exp(sigma * s) / expm1(sigma * T3);
}

/* Jerk response of the tail at sample m after a unit change, from the closed form
 * (l(s) - l(s - T2)) / T2 with the breakpoints n3 = T3/Ts, n2 = T2/Ts on the grid. right = 1:
 * the right limit at a jump (the documented convention), 0: the left limit. */
static double jerk_shape(long m, long n2, long n3, double Ts, double sigma, int right)
{
    double T2 = (double)n2 * Ts, T3 = (double)n3 * Ts, j = 0.0;
    int first = right ? (m >= 0 && m < n3) : (m > 0 && m <= n3);
    int second = right ? (m >= n2 && m < n2 + n3) : (m > n2 && m <= n2 + n3);
    if (first)
        j += last_density((double)m * Ts, T3, sigma);
    if (second)
        j -= last_density((double)(m - n2) * Ts, T3, sigma);
    return j / T2;
}

/* Stage lengths whole multiples of Ts (the FMU validation's limits among them): a single move
 * of D from rest changes r' by +V at tick 0 and by -V at tick K = ceil(D / (vmax Ts)); the jerk
 * must equal the closed form at every tick, and at the jump ticks the right limit, which there
 * differs from the left limit by a sizeable fraction of jmax (so the check can fail). */
static void test_jerk_right_limit_on_grid(void)
{
    /* limits {vmax, amax, jmax} with T2 = vmax/amax = n2 Ts and T3 = amax/jmax = n3 Ts; amax,
     * jmax 0: set as vmax / (n2 Ts), amax / (n3 Ts), which round so that T2 or T3 lands an ulp
     * off n Ts (those jumps fell on the wrong side before the sample-index comparison) */
    static const struct {
        double vmax, amax, jmax, Ts;
        long n2, n3;
        int damped;
    } cases[] = {
        {1.0, 10.0, 200.0, 1e-3, 100, 50, 0},           /* validation.TRAJECTORY_LIMITS */
        {1.0, 10.0, 100.0, 1e-3, 100, 100, 0},          /* T2 = T3: l ends as its copy starts */
        {2.0, 8.0, 64.0, 1e-3, 250, 125, 0},
        {250.0, 5000.0, 200000.0, 1e-4, 500, 250, 0},
        {1.0, 10.0, 0.0, 1e-3, 100, 7, 0},
        {1.0, 0.0, 0.0, 1e-4, 76, 25, 0},
        {0.3, 30.0, 0.0, 1e-4, 100, 33, 0},
        {1.0, 10.0, 400.0, 1e-3, 100, 50, 1},           /* exponential of one mode period */
    };
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        sms_generator g;
        double Ts = cases[i].Ts, zeta = cases[i].damped ? 0.05 : 0.0;
        long n2 = cases[i].n2, n3 = cases[i].n3, K, k, n_jumps = 0;
        double amax = cases[i].amax > 0.0 ? cases[i].amax : cases[i].vmax / ((double)n2 * Ts);
        double jmax = cases[i].jmax > 0.0 ? cases[i].jmax : amax / ((double)n3 * Ts);
        /* mode period 2 pi / wd = n3 Ts */
        /* (the tail realisation: with a mode, also for the polynomial profile) */
        double wn = 2.0 * 3.14159265358979323846 / ((double)n3 * Ts) / sqrt(1.0 - zeta * zeta);
        double sigma = -zeta * wn, D = 0.7 * cases[i].vmax, V;
        sms_generator_config c = make_config(cases[i].vmax, amax, jmax,
                                             cases[i].damped ? SMS_PROFILE_DAMPED
                                                             : SMS_PROFILE_POLYNOMIAL, wn, zeta);
        sms_real out[4];
        if (!build(&g, &c, Ts))
            continue;
        CHECK_CLOSE(g.T2, (double)n2 * Ts, 1e-12, 1.0);
        CHECK_CLOSE(g.T3, (double)n3 * Ts, 1e-12, 1.0);
        CHECK(g.n_tail == (size_t)(n2 + n3));
        K = (long)ceil(D / (cases[i].vmax * Ts)); /* as the generator rounds */
        CHECK(K >= n2 + n3);
        V = D / ((double)K * Ts);
        for (k = 0; k < K + n2 + n3 + 20; ++k) {
            double right = V * jerk_shape(k, n2, n3, Ts, sigma, 1) -
                           V * jerk_shape(k - K, n2, n3, Ts, sigma, 1);
            double left = V * jerk_shape(k, n2, n3, Ts, sigma, 0) -
                          V * jerk_shape(k - K, n2, n3, Ts, sigma, 0);
            sms_generator_step(&g, (sms_real)D, out);
            CHECK_CLOSE(out[3], right, SMS_TEST_REL_TOL, jmax);
            if (fabs(right - left) > 0.1 * jmax)
                ++n_jumps;
        }
        /* ticks 0, n3, n2, n2 + n3 after each change (n2 = n3 merges two) */
        CHECK(n_jumps == (n2 == n3 ? 6 : 8));
    }
}

/* A single long move from rest lasts D/vmax + Tc (on the grid) and reaches the bounds. */
static void test_single_move(void)
{
    sms_generator g;
    sms_generator_config c = make_config(250.0, 5000.0, 200000.0, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0);
    sms_real out[4];
    double Ts = 1e-4, peak[4] = {0, 0, 0, 0};
    long k, arrive = -1;
    if (!build(&g, &c, Ts))
        return;
    CHECK(g.time_optimal == 1);
    for (k = 0; k < 4000; ++k) {
        int i;
        sms_generator_step(&g, 40, out);
        for (i = 0; i < 4; ++i)
            if (fabs((double)out[i]) > peak[i])
                peak[i] = fabs((double)out[i]);
        if (arrive < 0 && out[0] == 40 && out[1] == 0)
            arrive = k;
    }
    /* 0.235 s, the optimum, on the grid: 2350 samples */
    CHECK(arrive == 2350);
    CHECK_CLOSE(peak[1], 250.0, 1e-9, 250.0);
    CHECK_CLOSE(peak[2], 5000.0, 1e-9, 5000.0);
    CHECK_CLOSE(peak[3], 200000.0, 1e-9, 200000.0);
}

static void test_state_and_bad_input(void)
{
    sms_generator g, h;
    sms_generator_config c = make_config(1.0, 10.0, 100.0, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0);
    sms_real a[4], b[4];
    double state[9], bad[9];
    size_t need, i, n_state;
    long k;
    int realisation;
    for (realisation = 0; realisation < 2; ++realisation) {
        /* 0: time-optimal (6 values: k is index 5); 1: tail (9 values: seg_len is index 6) */
        size_t count_index = realisation == 0 ? 5u : 6u;
        c.profile = realisation == 0 ? SMS_PROFILE_POLYNOMIAL : SMS_PROFILE_TRIGONOMETRIC;
        if (!build(&g, &c, 1e-3))
            return;
        for (k = 0; k < 150; ++k)
            sms_generator_step(&g, 1, a);
        n_state = sms_generator_state_count(&g);
        CHECK(n_state == (realisation == 0 ? 6u : 9u));
        sms_generator_get_state(&g, state);
        h = g;
        for (i = 0; realisation == 1 && i < 4u * (g.n_tail + 1u); ++i)
            table2[i] = table[i];
        sms_generator_rebind(&h, table2);
        sms_generator_reset(&h, 5);
        CHECK_STATUS(sms_generator_set_state(&h, state, n_state), SMS_OK);
        for (k = 0; k < 500; ++k) {
            sms_generator_step(&g, k < 300 ? 1 : -2, a);
            sms_generator_step(&h, k < 300 ? 1 : -2, b);
            CHECK(a[0] == b[0] && a[3] == b[3]);
        }
        for (i = 0; i < n_state; ++i)
            bad[i] = state[i];
        bad[count_index] = 1.5;
        CHECK_STATUS(sms_generator_set_state(&h, bad, n_state), SMS_ERR_STATE);
        bad[count_index] = state[count_index];
        bad[4] = NAN;
        CHECK_STATUS(sms_generator_check_state(&h, bad, n_state), SMS_ERR_STATE);
        CHECK_STATUS(sms_generator_set_state(&h, state, n_state - 1u), SMS_ERR_STATE);
    }
    c.profile = SMS_PROFILE_POLYNOMIAL;
    build(&g, &c, 1e-3);
    /* non-finite targets are ignored */
    sms_generator_reset(&g, 0);
    for (k = 0; k < 2000; ++k)
        sms_generator_step(&g, k % 3 ? (sms_real)NAN : (sms_real)0.5, a);
    CHECK(a[0] == (sms_real)0.5);
    sms_generator_step(&g, (sms_real)INFINITY, a);
    CHECK(a[0] == (sms_real)0.5);

    c.vmax = 0.0;
    CHECK_STATUS(sms_generator_buffer_size(&c, 1e-3, &need), SMS_ERR_LIMIT);
    c.vmax = 1.0;
    c.jmax = NAN;
    CHECK_STATUS(sms_generator_buffer_size(&c, 1e-3, &need), SMS_ERR_LIMIT);
    c.jmax = 100.0;
    CHECK_STATUS(sms_generator_buffer_size(&c, 0.0, &need), SMS_ERR_SAMPLE_PERIOD);
    CHECK_STATUS(sms_generator_buffer_size(&c, 0.5, &need), SMS_OK); /* any Ts: no tail */
    CHECK(need == 0u);
    c.profile = SMS_PROFILE_TRIGONOMETRIC;
    CHECK_STATUS(sms_generator_buffer_size(&c, 0.5, &need), SMS_ERR_DURATION_BELOW_TS);
    c.profile = SMS_PROFILE_POLYNOMIAL;
    CHECK_STATUS(sms_generator_buffer_size(NULL, 1e-3, &need), SMS_ERR_NULL);
    c.profile = SMS_PROFILE_DAMPED;
    CHECK_STATUS(sms_generator_buffer_size(&c, 1e-3, &need), SMS_ERR_WN);
    c.wn = 5000.0;
    CHECK_STATUS(sms_generator_buffer_size(&c, 1e-3, &need), SMS_ERR_ABOVE_NYQUIST);
    c.wn = 50.0;
    c.zeta = 1.0;
    CHECK_STATUS(sms_generator_buffer_size(&c, 1e-3, &need), SMS_ERR_ZETA);
    c = make_config(1.0, 10.0, 100.0, SMS_PROFILE_TRIGONOMETRIC, 0.0, 0.0);
    h = g;
    CHECK_STATUS(sms_generator_init(&g, &c, 1e-3, table, 10), SMS_ERR_BUFFER_TOO_SMALL);
    CHECK(g.n_tail == h.n_tail && g.r == h.r && g.target == h.target);
}

/* A rest-to-rest move of any length arrives on the first sample at or after the
 * time-optimal duration, and stays there exactly. */
static void test_time_optimal_arrival(void)
{
    int trial;
    rng = 2024u;
    for (trial = 0; trial < 300; ++trial) {
        double v = exp(log(1e-2) + urand() * log(1e4)), a = v * exp(log(1e-1) + urand() * log(1e3));
        double j = a * exp(log(1e-1) + urand() * log(1e3)), T, h, Ts;
        sms_generator g;
        sms_generator_config c;
        sms_real out[4];
        long k, arrive = -1, expect;
        h = v * (v / a + a / j) * exp(log(1e-4) + urand() * log(1e5));
        T = double_s_duration(h, v, a, j);
        Ts = T / (20.0 + 2000.0 * urand());
        c = make_config(v, a, j, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0);
        if (!build(&g, &c, Ts))
            continue;
        for (k = 0; k < 2100 + 30; ++k) {
            sms_generator_step(&g, (sms_real)h, out);
            if (arrive < 0 && out[0] == (sms_real)h && out[1] == 0 && out[2] == 0)
                arrive = k;
        }
        CHECK(out[0] == (sms_real)h);
        /* sample k is at time k Ts after the step: the first with k Ts >= T (float: the
         * duration is known to a few ulps, allow one sample) */
        expect = (long)ceil(T / Ts * (1.0 - 1e-12));
#ifdef SMS_USE_FLOAT
        CHECK(labs(arrive - expect) <= 1);
#else
        CHECK(arrive == expect || (arrive == expect + 1 && fabs(T / Ts - floor(T / Ts + 0.5)) < 1e-9));
        if (arrive != expect)
            fprintf(stderr, "arrive %ld expect %ld (T/Ts = %.17g)\n", arrive, expect, T / Ts);
#endif
    }
    /* the short move: 0.1 with v = 1, a = 10, j = 1000 (reaches neither v nor a) */
    {
        sms_generator g;
        sms_generator_config c = make_config(1.0, 10.0, 1000.0, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0);
        sms_real out[4];
        long k, arrive = -1;
        double T = double_s_duration(0.1, 1.0, 10.0, 1000.0);
        if (build(&g, &c, 1e-3)) {
            for (k = 0; k < 1000; ++k) {
                sms_generator_step(&g, (sms_real)0.1, out);
                if (arrive < 0 && out[0] == (sms_real)0.1 && out[1] == 0 && out[2] == 0)
                    arrive = k;
            }
            CHECK(arrive == (long)ceil(T / 1e-3));
        }
    }
}

/* Float (and double) on moves of 2^24 and 2^30 samples: the plan is sampled at its start,
 * around the arrival and in the cruise, jumping there through a saved state (a state carries
 * the samples since the plan's start): position within the rounding of the positions of the
 * exact closed form, mean speed over 1 s windows within vmax, arrival on time to the
 * rounding of the duration. */
static void test_long_moves(void)
{
    static const double n_samples[2] = {16777216.0, 1073741824.0};
    int m;
    for (m = 0; m < 2; ++m) {
        double Ts = 1e-4, v = 1.0, a = 10.0, j = 1000.0;
        double T = n_samples[m] * Ts, h = v * (T - v / a - a / j); /* arrives at T */
        sms_generator g;
        sms_generator_config c = make_config(v, a, j, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0);
        double state[6], start_k;
        sms_real out[4], prev = 0;
        long k, arrive = -1;
        int probe;
        if (!build(&g, &c, Ts))
            continue;
        sms_generator_step(&g, (sms_real)h, out); /* the plan starts at sample 0 */
        CHECK(sms_generator_state_count(&g) == 6u);
        sms_generator_get_state(&g, state);
        for (probe = 0; probe < 3; ++probe) {
            /* probes: 1 s windows mid-cruise, a window 1 s before arrival, the arrival */
            start_k = probe == 0 ? floor(0.5 * n_samples[m]) : n_samples[m] - (probe == 1 ? 20000.0 : 10000.0);
            state[5] = start_k;
            CHECK_STATUS(sms_generator_set_state(&g, state, 6), SMS_OK);
            sms_generator_step(&g, (sms_real)h, out);
            prev = out[0];
            for (k = 1; k <= (probe == 2 ? 20000 : 10000); ++k) {
                double t = (start_k + 1.0 + (double)k) * Ts, exact;
                sms_generator_step(&g, (sms_real)h, out);
                /* cruise: q = v (t - (v/a + a/j)/2) after the velocity rise */
                if (probe < 2) {
                    exact = v * (t - 0.5 * (v / a + a / j));
                    CHECK(fabs((double)out[0] - exact) <= 64.0 * SAMPLE_EPS * h);
                }
                if (probe == 2 && arrive < 0 && out[0] == (sms_real)h && out[1] == 0 &&
                    out[2] == 0)
                    arrive = (long)(start_k + 1.0 + (double)k);
            }
            if (probe < 2)
                /* 1 s of motion: at most vmax, to the rounding of two positions */
                CHECK(((double)out[0] - (double)prev) / (10000.0 * Ts) <= v + 4.0 * SAMPLE_EPS * h);
        }
        CHECK(out[0] == (sms_real)h && out[1] == 0);
        /* on time: the duration to its rounding (float: 2^30 samples carry ~64 samples) */
        CHECK(fabs((double)arrive - n_samples[m]) <= 1.0 + 8.0 * SAMPLE_EPS * n_samples[m]);
        if (fabs((double)arrive - n_samples[m]) > 1.0 + 8.0 * SAMPLE_EPS * n_samples[m])
            fprintf(stderr, "long move %g: arrival %ld\n", n_samples[m], arrive);
    }
}

int main(void)
{
    test_time_optimal_arrival();
    test_long_moves();
    test_bounds_random();
    test_consistency();
    test_jerk_right_limit_on_grid();
    test_single_move();
    test_state_and_bad_input();
    return check_summary("test_generator");
}
