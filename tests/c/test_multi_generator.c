/* Multi-axis generator: phase-synchronised rest-to-rest moves (common arrival sample, straight
 * line, limits at every sample, time-optimal duration on the grid), staircases with reversals
 * and mid-motion changes (limits, exact arrival), independent axes, bad input. Fixed seeds. */
#include <stdlib.h>
#include <string.h>
#include "check.h"

#ifdef SMS_USE_FLOAT
#define LIMIT_TOL 1e-4   /* float rounding of q differences over a few samples */
#define LINE_TOL 1e-5
#define DIFF_TOL 1e-2
/* second and third differences of float positions are rounding, not motion: not checked */
#define HIGHER_DIFFS 0
#else
#define LIMIT_TOL 1e-9
#define LINE_TOL 1e-12
#define DIFF_TOL 1e-9
#define HIGHER_DIFFS 1
#endif

#define MAX_SAMPLES 60000
static sms_real out_buf[MAX_SAMPLES * SMS_MULTI_MAX_AXES * 4];

static unsigned long rng_state = 88172645463325252ul & 0xFFFFFFFFul;
static double urand(void)
{
    rng_state ^= (rng_state << 13) & 0xFFFFFFFFul;
    rng_state ^= rng_state >> 17;
    rng_state ^= (rng_state << 5) & 0xFFFFFFFFul;
    return (double)(rng_state & 0xFFFFFFul) / 16777216.0;
}
static double log_uniform(double lo, double hi)
{
    return lo * pow(hi / lo, urand());
}

static sms_multi_generator_config random_config(size_t n, sms_sync sync)
{
    sms_multi_generator_config c;
    size_t i;
    memset(&c, 0, sizeof c);
    c.n_axes = n;
    c.sync = sync;
    for (i = 0; i < n; ++i) {
        c.vmax[i] = log_uniform(0.1, 1000.0);
        c.amax[i] = log_uniform(0.1, 1000.0) * c.vmax[i];
        c.jmax[i] = log_uniform(0.1, 1000.0) * c.amax[i];
    }
    return c;
}

/* Every reported v, a, j and every backward difference within the limits; returns the
 * largest ratio seen (1 = at a limit). */
static double check_limits(const sms_multi_generator_config *c, const sms_real *out, size_t n,
                           double Ts, const double *q_before)
{
    size_t k, i, m, na = c->n_axes;
    double worst = 0.0;
    for (i = 0; i < na; ++i) {
        const double lim[3] = {c->vmax[i], c->amax[i], c->jmax[i]};
        double hist[4] = {q_before[i], q_before[i], q_before[i], q_before[i]};
        double qmax = fabs(q_before[i]), e;
        for (k = 0; k < n; ++k)
            if (fabs((double)out[4 * (k * na + i)]) > qmax)
                qmax = fabs((double)out[4 * (k * na + i)]);
        /* rounding of q (a few ulps of the largest position the record reaches) */
        e = 4.0 * qmax * (SMS_TEST_PRECISION[0] == 'f' ? 6e-8 : 1.2e-16);
        for (k = 0; k < n; ++k) {
            const sms_real *o = out + 4 * (k * na + i);
            double d1, d2, d3;
            for (m = 0; m < 3; ++m) {
                double r = fabs((double)o[m + 1]) / lim[m];
                if (r > worst)
                    worst = r;
                if (!(r <= 1.0 + LIMIT_TOL)) {
                    CHECK(r <= 1.0 + LIMIT_TOL);
                    fprintf(stderr, "  axis %zu sample %zu derivative %zu ratio %.17g\n", i, k,
                            m + 1, r);
                    return worst;
                }
            }
            hist[0] = hist[1];
            hist[1] = hist[2];
            hist[2] = hist[3];
            hist[3] = (double)o[0];
            d1 = (hist[3] - hist[2]) / Ts;
            d2 = (hist[3] - 2 * hist[2] + hist[1]) / (Ts * Ts);
            d3 = (hist[3] - 3 * hist[2] + 3 * hist[1] - hist[0]) / (Ts * Ts * Ts);
            {
                if (!(fabs(d1) <= lim[0] * (1 + DIFF_TOL) + 2 * e / Ts &&
                      (!HIGHER_DIFFS ||
                       (fabs(d2) <= lim[1] * (1 + DIFF_TOL) + 4 * e / (Ts * Ts) &&
                        fabs(d3) <= lim[2] * (1 + DIFF_TOL) + 8 * e / (Ts * Ts * Ts))))) {
                    CHECK(0);
                    fprintf(stderr, "  axis %zu sample %zu differences %.17g %.17g %.17g limits %g %g %g q %g\n",
                            i, k, d1, d2, d3, lim[0], lim[1], lim[2], hist[3]);
                    return worst;
                }
            }
        }
    }
    return worst;
}

static void rest_to_rest(unsigned trial)
{
    size_t n = 2 + (size_t)(urand() * 5.0), i, k, N, first_all = 0, k_arrive[SMS_MULTI_MAX_AXES];
    sms_multi_generator_config c = random_config(n, SMS_SYNC_PHASE);
    sms_multi_generator g;
    sms_real start[SMS_MULTI_MAX_AXES], target[SMS_MULTI_MAX_AXES];
    double delta[SMS_MULTI_MAX_AXES], q0[SMS_MULTI_MAX_AXES], T, Ts, nu, dmax = 0.0, dev = 0.0;
    for (i = 0; i < n; ++i) {
        start[i] = (sms_real)(urand() * 20.0 - 10.0);
        target[i] = (sms_real)(urand() * 20.0 - 10.0);
        delta[i] = (double)target[i] - (double)start[i];
        q0[i] = (double)start[i];
        if (fabs(delta[i]) > dmax)
            dmax = fabs(delta[i]);
    }
    CHECK_STATUS(sms_multi_phase_duration(&c, delta, &T), SMS_OK);
    Ts = T / log_uniform(3.0, 3000.0);
    nu = T / Ts;
    N = (size_t)ceil(nu - 1e-9 * nu);
    if (N + 2 > MAX_SAMPLES / n)
        return;
    CHECK_STATUS(sms_multi_generator_init(&g, &c, Ts, NULL), SMS_OK);
    sms_multi_generator_reset(&g, start);
    for (k = 0; k < N + 2; ++k)
        sms_multi_generator_step(&g, target, out_buf + 4 * k * n);
    /* every axis lands on its target exactly on the same sample, N after the step */
    for (i = 0; i < n; ++i) {
        k_arrive[i] = N + 2;
        for (k = 0; k < N + 2; ++k)
            if (out_buf[4 * (k * n + i)] == target[i] && out_buf[4 * (k * n + i) + 1] == 0 &&
                out_buf[4 * (k * n + i) + 2] == 0) {
                k_arrive[i] = k;
                break;
            }
        if (i == 0)
            first_all = k_arrive[0];
        CHECK(k_arrive[i] == first_all);
    }
    CHECK(first_all == N || (fabs(nu - floor(nu + 0.5)) < 1e-6 * nu &&
                             (first_all + 1 == N || first_all == N + 1)));
    if (first_all != N)
        fprintf(stderr, "  trial %u: arrival %zu, expected %zu (T/Ts = %.17g)\n", trial,
                first_all, N, nu);
    /* straight line: q - start parallel to delta */
    {
        size_t imax = 0;
        for (i = 1; i < n; ++i)
            if (fabs(delta[i]) > fabs(delta[imax]))
                imax = i;
        for (k = 0; k < N + 2; ++k) {
            double s = ((double)out_buf[4 * (k * n + imax)] - q0[imax]) / delta[imax];
            for (i = 0; i < n; ++i) {
                double e = fabs((double)out_buf[4 * (k * n + i)] - q0[i] - s * delta[i]) / dmax;
                if (e > dev)
                    dev = e;
            }
        }
    }
    CHECK(dev <= LINE_TOL);
    if (!(dev <= LINE_TOL))
        fprintf(stderr, "  trial %u: deviation from the line %g\n", trial, dev);
    (void)check_limits(&c, out_buf, N + 2, Ts, q0);
}

/* Random staircase with reversals and changes every 1 .. 400 samples; held at the end. */
static void staircase(unsigned trial, sms_sync sync)
{
    size_t n = 1 + (size_t)(urand() * 6.0), i, k, total = 0, hold_start;
    sms_multi_generator_config c = random_config(n, sync);
    sms_multi_generator g;
    sms_real target[SMS_MULTI_MAX_AXES];
    double q0[SMS_MULTI_MAX_AXES] = {0}, Ts = log_uniform(1e-4, 1e-2), scale[SMS_MULTI_MAX_AXES];
    sms_real *o;
    CHECK_STATUS(sms_multi_generator_init(&g, &c, Ts, NULL), SMS_OK);
    for (i = 0; i < n; ++i)
        scale[i] = c.vmax[i] * Ts * log_uniform(1.0, 300.0);
    while (total < 4000) {
        size_t hold = 1 + (size_t)(urand() * 400.0);
        for (i = 0; i < n; ++i)
            if (urand() < 0.7)
                target[i] = (sms_real)((urand() * 2.0 - 1.0) * scale[i]);
        for (k = 0; k < hold && total < MAX_SAMPLES * SMS_MULTI_MAX_AXES / n; ++k, ++total)
            sms_multi_generator_step(&g, target, out_buf + 4 * total * n);
    }
    /* hold until arrival */
    hold_start = total;
    while (sms_multi_generator_busy(&g) && total < MAX_SAMPLES * SMS_MULTI_MAX_AXES / n) {
        sms_multi_generator_step(&g, target, out_buf + 4 * total * n);
        ++total;
    }
    CHECK(!sms_multi_generator_busy(&g));
    o = out_buf + 4 * (total - 1) * n;
    for (i = 0; i < n; ++i) {
        CHECK(o[4 * i] == target[i]);
        CHECK(o[4 * i + 1] == 0 && o[4 * i + 2] == 0 && o[4 * i + 3] == 0);
    }
    (void)hold_start;
    (void)check_limits(&c, out_buf, total, Ts, q0);
    (void)trial;
}

/* Independent axes: each equals a one-axis generator with that axis's limits. */
static void independent_equals_single(void)
{
    sms_multi_generator_config c = random_config(3, SMS_SYNC_INDEPENDENT), c1;
    sms_multi_generator g, g1;
    sms_real target[3] = {2, -1, 0.5}, o3[12], o1[4];
    size_t i, k;
    int same = 1;
    double Ts = 1e-3;
    CHECK_STATUS(sms_multi_generator_init(&g, &c, Ts, NULL), SMS_OK);
    for (i = 0; i < 3; ++i) {
        memset(&c1, 0, sizeof c1);
        c1.n_axes = 1;
        c1.vmax[0] = c.vmax[i];
        c1.amax[0] = c.amax[i];
        c1.jmax[0] = c.jmax[i];
        CHECK_STATUS(sms_multi_generator_init(&g1, &c1, Ts, NULL), SMS_OK);
        CHECK_STATUS(sms_multi_generator_init(&g, &c, Ts, NULL), SMS_OK);
        for (k = 0; k < 5000; ++k) {
            sms_real t1 = target[i];
            if (k == 700) {
                target[i] = -target[i];
                t1 = target[i];
            }
            sms_multi_generator_step(&g, target, o3);
            sms_multi_generator_step(&g1, &t1, o1);
            if (memcmp(o3 + 4 * i, o1, sizeof o1) != 0)
                same = 0;
        }
    }
    CHECK(same);
}

static void bad_input(void)
{
    sms_multi_generator_config c = random_config(3, SMS_SYNC_PHASE);
    sms_multi_generator g;
    size_t bad = 99;
    memset(&g, 0x5a, sizeof g);
    c.amax[1] = 0.0;
    CHECK_STATUS(sms_multi_generator_init(&g, &c, 1e-3, &bad), SMS_ERR_LIMIT);
    CHECK(bad == 1);
    c.amax[1] = 1.0;
    c.jmax[2] = NAN;
    CHECK_STATUS(sms_multi_generator_init(&g, &c, 1e-3, &bad), SMS_ERR_LIMIT);
    CHECK(bad == 2);
    c.jmax[2] = 1.0;
    CHECK_STATUS(sms_multi_generator_init(&g, &c, 0.0, NULL), SMS_ERR_SAMPLE_PERIOD);
    c.n_axes = 0;
    CHECK_STATUS(sms_multi_generator_init(&g, &c, 1e-3, NULL), SMS_ERR_ORDER);
    c.n_axes = SMS_MULTI_MAX_AXES + 1;
    CHECK_STATUS(sms_multi_generator_init(&g, &c, 1e-3, NULL), SMS_ERR_ORDER);
    c.n_axes = 3;
    c.sync = (sms_sync)7;
    CHECK_STATUS(sms_multi_generator_init(&g, &c, 1e-3, NULL), SMS_ERR_KIND);
    CHECK(g.n_axes != 3); /* untouched */
    CHECK_STATUS(sms_multi_generator_init(NULL, &c, 1e-3, NULL), SMS_ERR_NULL);
}

/* Non-finite targets are ignored. */
static void non_finite_target(void)
{
    sms_multi_generator_config c = random_config(2, SMS_SYNC_PHASE);
    sms_multi_generator g;
    sms_real t[2] = {1, 1}, o[8];
    size_t k;
    CHECK_STATUS(sms_multi_generator_init(&g, &c, 1e-2, NULL), SMS_OK);
    for (k = 0; k < 100000 && (k < 10 || sms_multi_generator_busy(&g)); ++k) {
        t[1] = (k % 3 == 0) ? (sms_real)NAN : (sms_real)1;
        sms_multi_generator_step(&g, t, o);
        CHECK(o[0] - o[0] == 0 && o[4] - o[4] == 0);
    }
    CHECK(o[0] == 1 && o[4] == 1);
}

/* Tiny and subnormal moves: finite outputs, exact arrival. */
static void tiny_moves(void)
{
    sms_multi_generator_config c = random_config(2, SMS_SYNC_PHASE);
    sms_multi_generator g;
    const double sizes[] = {1e-30, 1e-300, 2.2250738585072014e-311};
    sms_real t[2], o[8];
    size_t s, k;
    CHECK_STATUS(sms_multi_generator_init(&g, &c, 1e-2, NULL), SMS_OK);
    for (s = 0; s < sizeof sizes / sizeof sizes[0]; ++s) {
        t[0] = (sms_real)sizes[s];
        t[1] = -(sms_real)sizes[s];
        for (k = 0; k < 100000 && (k < 2 || sms_multi_generator_busy(&g)); ++k) {
            sms_multi_generator_step(&g, t, o);
            CHECK(o[0] - o[0] == 0 && o[1] - o[1] == 0 && o[4] - o[4] == 0);
        }
        CHECK(!sms_multi_generator_busy(&g));
        CHECK(o[0] == t[0] && o[4] == t[1]);
    }
}

/* Save mid-motion, run on, restore (also into a second generator): identical outputs. */
static void state_round_trip(void)
{
    sms_multi_generator_config c = random_config(3, SMS_SYNC_PHASE);
    sms_multi_generator g, h;
    double state[128], bad[128];
    sms_real t[3] = {1, -2, 3}, a[12], b[12];
    size_t k, n;
    int sync, same = 1;
    for (sync = 0; sync < 2; ++sync) {
        c.sync = (sms_sync)sync;
        CHECK_STATUS(sms_multi_generator_init(&g, &c, 1e-3, NULL), SMS_OK);
        CHECK_STATUS(sms_multi_generator_init(&h, &c, 1e-3, NULL), SMS_OK);
        n = sms_multi_generator_state_count(&g);
        CHECK(n == 15 + (sync == 0 ? 11u : 33u));
        for (k = 0; k < 137; ++k)
            sms_multi_generator_step(&g, t, a);
        t[1] = 5; /* pending change */
        sms_multi_generator_step(&g, t, a);
        sms_multi_generator_save_state(&g, state);
        CHECK_STATUS(sms_multi_generator_load_state(&h, state, n), SMS_OK);
        for (k = 0; k < 3000; ++k) {
            sms_multi_generator_step(&g, t, a);
            sms_multi_generator_step(&h, t, b);
            if (memcmp(a, b, sizeof a) != 0)
                same = 0;
        }
        memcpy(bad, state, n * sizeof(double));
        bad[n - 1] = 2.0; /* a flag that is not 0/1 */
        CHECK_STATUS(sms_multi_generator_load_state(&h, bad, n), SMS_ERR_STATE);
        memcpy(bad, state, n * sizeof(double));
        bad[0] = NAN;
        CHECK_STATUS(sms_multi_generator_load_state(&h, bad, n), SMS_ERR_STATE);
        CHECK_STATUS(sms_multi_generator_load_state(&h, state, n - 1), SMS_ERR_STATE);
        t[1] = -2;
    }
    CHECK(same);
}

int main(void)
{
    unsigned trial;
    for (trial = 0; trial < 300; ++trial)
        rest_to_rest(trial);
    for (trial = 0; trial < 60; ++trial)
        staircase(trial, trial % 3 == 2 ? SMS_SYNC_INDEPENDENT : SMS_SYNC_PHASE);
    independent_equals_single();
    bad_input();
    non_finite_target();
    tiny_moves();
    state_round_trip();
    return check_summary("test_multi_generator");
}
