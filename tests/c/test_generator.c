/* Online generator: bounds under adversarial staircases (fixed seeds), exact arrival,
 * q/v/a/j consistency, the right-limit jerk at jumps on the grid, time-optimal single moves,
 * state save/load, bad input. */
#include <stdlib.h>
#include "check.h"

#define MAX_TABLE 40000
static sms_real table[MAX_TABLE];
static sms_real table2[MAX_TABLE];

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
    double target = 0.0, peak[4] = {0, 0, 0, 0};
    long k, next = 0, hold;
    if (!build(&g, c, Ts))
        return;
    rng = seed;
    for (k = 0; k < 20000; ++k) {
        int i;
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
    }
    CHECK(peak[1] <= c->vmax * (1.0 + BOUND_TOL));
    CHECK(peak[2] <= c->amax * (1.0 + BOUND_TOL));
    CHECK(peak[3] <= c->jmax * (1.0 + BOUND_TOL));
    /* hold: the output ends exactly on the last target */
    hold = (long)(4.0 * c->vmax / (c->vmax * Ts)) + 4 * (long)g.n_tail + 10;
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
    sms_generator_config c = make_config(1.0, 10.0, 100.0, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0);
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
        double wn = cases[i].damped ? 2.0 * 3.14159265358979323846 / ((double)n3 * Ts) /
                                          sqrt(1.0 - zeta * zeta) : 0.0;
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
    CHECK_CLOSE(g.T2, 0.05, 1e-14, 1.0);
    CHECK_CLOSE(g.T3, 0.025, 1e-14, 1.0);
    for (k = 0; k < 4000; ++k) {
        int i;
        sms_generator_step(&g, 40, out);
        for (i = 0; i < 4; ++i)
            if (fabs((double)out[i]) > peak[i])
                peak[i] = fabs((double)out[i]);
        if (arrive < 0 && out[0] == 40 && out[1] == 0)
            arrive = k;
    }
    /* 0.16 s at vmax (1600 samples) + 0.075 s tail (750 samples): 0.235 s, the optimum */
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
    size_t need, i;
    long k;
    if (!build(&g, &c, 1e-3))
        return;
    for (k = 0; k < 150; ++k)
        sms_generator_step(&g, 1, a);
    CHECK(sms_generator_state_count(&g) == 9u);
    sms_generator_get_state(&g, state);
    h = g;
    for (i = 0; i < 4u * (g.n_tail + 1u); ++i)
        table2[i] = table[i];
    sms_generator_rebind(&h, table2);
    sms_generator_reset(&h, 5);
    CHECK_STATUS(sms_generator_set_state(&h, state, 9), SMS_OK);
    for (k = 0; k < 500; ++k) {
        sms_generator_step(&g, k < 300 ? 1 : -2, a);
        sms_generator_step(&h, k < 300 ? 1 : -2, b);
        CHECK(a[0] == b[0] && a[3] == b[3]);
    }
    for (i = 0; i < 9; ++i)
        bad[i] = state[i];
    bad[6] = 1.5;
    CHECK_STATUS(sms_generator_set_state(&h, bad, 9), SMS_ERR_STATE);
    bad[6] = state[6];
    bad[4] = NAN;
    CHECK_STATUS(sms_generator_check_state(&h, bad, 9), SMS_ERR_STATE);
    CHECK_STATUS(sms_generator_set_state(&h, state, 8), SMS_ERR_STATE);
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
    CHECK_STATUS(sms_generator_buffer_size(&c, 0.5, &need), SMS_ERR_DURATION_BELOW_TS);
    CHECK_STATUS(sms_generator_buffer_size(NULL, 1e-3, &need), SMS_ERR_NULL);
    c.profile = SMS_PROFILE_DAMPED;
    CHECK_STATUS(sms_generator_buffer_size(&c, 1e-3, &need), SMS_ERR_WN);
    c.wn = 5000.0;
    CHECK_STATUS(sms_generator_buffer_size(&c, 1e-3, &need), SMS_ERR_ABOVE_NYQUIST);
    c.wn = 50.0;
    c.zeta = 1.0;
    CHECK_STATUS(sms_generator_buffer_size(&c, 1e-3, &need), SMS_ERR_ZETA);
    c = make_config(1.0, 10.0, 100.0, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0);
    h = g;
    CHECK_STATUS(sms_generator_init(&g, &c, 1e-3, table, 10), SMS_ERR_BUFFER_TOO_SMALL);
    CHECK(g.n_tail == h.n_tail && g.r == h.r && g.target == h.target);
}

int main(void)
{
    test_bounds_random();
    test_consistency();
    test_jerk_right_limit_on_grid();
    test_single_move();
    test_state_and_bad_input();
    return check_summary("test_generator");
}
