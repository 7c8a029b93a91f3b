/* SPDX-License-Identifier: Apache-2.0 */
/* Multi-axis generator: phase-synchronised rest-to-rest moves (common arrival sample, straight
 * line, limits at every sample, time-optimal duration on the grid), staircases with reversals
 * and mid-motion changes (limits, exact arrival), independent axes, bad input. Fixed seeds. */
#include <stdlib.h>
#include <string.h>
#include <float.h>
#include "check.h"
#include "multi_config.h"

#ifdef SMS_USE_FLOAT
#define LINE_TOL 1e-5
#define UNIT_ROUNDOFF 5.9604644775390625e-8
#else
#define LINE_TOL 1e-12
#define UNIT_ROUNDOFF 1.1102230246251565e-16
#endif
/* reported v, a, j (docs/multi-axis.md): every plan keeps the limits in its own arithmetic but
 * for the arrival's rounding onto a sample at most 2 eps of the move earlier (W grows by up to
 * 4 eps = 8 u) and the roundings of the plan and of the evaluation (at most 23 u): 32 u */
#define LIMIT_TOL (32.0 * UNIT_ROUNDOFF)
#define DIFF_TOL 1e-9
#define HIGHER_DIFFS 1

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

/* Limits log-uniform over four decades each, amax/vmax and jmax/amax too. */
static void random_limits(size_t axis, double lim[3])
{
    (void)axis;
    lim[0] = log_uniform(0.1, 1000.0);
    lim[1] = log_uniform(0.1, 1000.0) * lim[0];
    lim[2] = log_uniform(0.1, 1000.0) * lim[1];
}

static sms_multi_generator_config random_config(size_t n, sms_sync sync)
{
    return multi_config(n, sync, random_limits);
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
        /* rounding of q per sample (docs/multi-axis.md): 8 u of the largest term a sample
         * sums, |p| + |V| t + |W - V| T1 G with t <= T1 <= T(2 vmax) <= 2 vmax/amax + amax/jmax
         * (a reversal's terms exceed the positions themselves) */
        e = 8.0 * UNIT_ROUNDOFF * (qmax + 3.0 * lim[0] * (2.0 * lim[0] / lim[1] + lim[1] / lim[2]));
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
    CHECK_STATUS(sms_multi_generator_init(&g, &c, Ts, NULL, 0, NULL, 0, NULL), SMS_OK);
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
    CHECK_STATUS(sms_multi_generator_init(&g, &c, Ts, NULL, 0, NULL, 0, NULL), SMS_OK);
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

/* The last jerk phase of a transition on a sample. The S-curve's jerk phases span the fractions
 * rho, 1 - 2 rho, rho of the transition; the last starts at 1 - rho, which rounds by up to half
 * an ulp of 1, u/(2 rho) of that phase. A sample on (or snapped onto) the rounded breakpoint
 * reported the acceleration ap (1 - fl(1 - rho))/rho instead of at most the peak ap: 4.8e-5
 * (400 eps) above amax in float on a blended reversal. Here a move from rest with vmax = 1,
 * amax = 10, jmax = 100 R and Ts = amax/jmax, the jerk phase, so rho = 1/(R + 1): the first
 * transition's last jerk phase starts on sample R and the stop's one sample before the
 * arrival; the move lasts a whole number of samples less 8 u, so the arrival's rounding onto
 * the grid leaves no slack. R is the first of 1000 .. 1063 whose planned rho1 and rho2 both have
 * 1 - fl(1 - rho) at least 64 u above rho (what the old evaluation exceeded amax by: R = 1001,
 * 130 eps in float, 112 eps in double). */
static void last_jerk_phase_on_a_sample(void)
{
    const size_t N = 12000;
    size_t R, found = 0;
    for (R = 1000; R < 1064 && !found; ++R) {
        sms_multi_generator_config c;
        sms_multi_generator g;
        sms_multi_move m;
        const double Ts = 10.0 / (100.0 * (double)R), q0 = 0.0;
        double D, x, y, over1, over2;
        sms_real target = 1;
        size_t k;
        memset(&c, 0, sizeof c);
        c.n_axes = 1;
        c.sync = SMS_SYNC_PHASE;
        c.vmax[0] = 1.0;
        c.amax[0] = 10.0;
        c.jmax[0] = 100.0 * (double)R;
        CHECK_STATUS(sms_multi_generator_init(&g, &c, Ts, NULL, 0, NULL, 0, NULL), SMS_OK);
        sms_multi_generator_step(&g, &target, out_buf); /* the plan's T1 (= T2) */
        D = ((double)N * Ts - (double)g.move[0].T1) * (1.0 - 8.0 * UNIT_ROUNDOFF);
        target = (sms_real)D;
        CHECK_STATUS(sms_multi_generator_init(&g, &c, Ts, NULL, 0, NULL, 0, NULL), SMS_OK);
        for (k = 0; k < N + 2; ++k) {
            sms_multi_generator_step(&g, &target, out_buf + 4 * k);
            if (k == 0)
                m = g.move[0];
        }
        /* the old evaluation's excess at each breakpoint, relative */
        over1 = (1.0 - (double)(sms_real)(1 - m.rho1)) / (double)m.rho1 - 1.0;
        over2 = (1.0 - (double)(sms_real)(1 - m.rho2)) / (double)m.rho2 - 1.0;
        if (!(over1 >= 64.0 * UNIT_ROUNDOFF && over2 >= 64.0 * UNIT_ROUNDOFF))
            continue;
        found = R;
        /* the samples are on the breakpoints: sample R at x = 1 - rho1 and sample k_end - 1
         * at the fraction left y = rho2 (to the snap of 64 eps); no slack from the grid */
        x = (double)((sms_real)R * g.Ts_signal / m.T1);
        y = (double)(g.Ts_signal / m.T2);
        CHECK(fabs(x - (1.0 - (double)m.rho1)) <= 128.0 * UNIT_ROUNDOFF);
        CHECK(fabs(y - (double)m.rho2) <= 128.0 * UNIT_ROUNDOFF);
        CHECK(m.k_end == N);
        CHECK(fabs((double)out_buf[4 * R + 2]) >= 10.0 * (1.0 - 1e-6)); /* at the peak */
        CHECK(fabs((double)out_buf[4 * (N - 1) + 2]) >= 10.0 * (1.0 - 1e-6));
        (void)check_limits(&c, out_buf, N + 2, Ts, &q0);
    }
    CHECK(found != 0);
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
    CHECK_STATUS(sms_multi_generator_init(&g, &c, Ts, NULL, 0, NULL, 0, NULL), SMS_OK);
    for (i = 0; i < 3; ++i) {
        memset(&c1, 0, sizeof c1);
        c1.n_axes = 1;
        c1.vmax[0] = c.vmax[i];
        c1.amax[0] = c.amax[i];
        c1.jmax[0] = c.jmax[i];
        CHECK_STATUS(sms_multi_generator_init(&g1, &c1, Ts, NULL, 0, NULL, 0, NULL), SMS_OK);
        CHECK_STATUS(sms_multi_generator_init(&g, &c, Ts, NULL, 0, NULL, 0, NULL), SMS_OK);
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
    CHECK_STATUS(sms_multi_generator_init(&g, &c, 1e-3, NULL, 0, NULL, 0, &bad), SMS_ERR_LIMIT);
    CHECK(bad == 1);
    c.amax[1] = 1.0;
    c.jmax[2] = NAN;
    CHECK_STATUS(sms_multi_generator_init(&g, &c, 1e-3, NULL, 0, NULL, 0, &bad), SMS_ERR_LIMIT);
    CHECK(bad == 2);
    c.jmax[2] = 1.0;
    CHECK_STATUS(sms_multi_generator_init(&g, &c, 0.0, NULL, 0, NULL, 0, NULL), SMS_ERR_SAMPLE_PERIOD);
    /* 2^53 Ts must stay finite (a state's durations are held to it): the largest double and
     * anything above SMS_TS_MAX are refused, SMS_TS_MAX itself builds */
    /* (the float build refuses a Ts above its largest float first, as the Generator does) */
    CHECK_STATUS(sms_multi_generator_init(&g, &c, DBL_MAX, NULL, 0, NULL, 0, NULL),
                 sizeof(sms_real) == sizeof(double) ? SMS_ERR_SAMPLE_PERIOD_RANGE
                                                    : SMS_ERR_SAMPLE_PERIOD);
    CHECK_STATUS(sms_multi_generator_init(&g, &c, nextafter(SMS_TS_MAX, HUGE_VAL), NULL, 0, NULL,
                                          0, NULL),
                 sizeof(sms_real) == sizeof(double) ? SMS_ERR_SAMPLE_PERIOD_RANGE
                                                    : SMS_ERR_SAMPLE_PERIOD);
    {   /* Ts above SMS_TS_MAX is named before limits that would be refused too */
        sms_generator_reach_info info;
        size_t axis = 9;
        c.jmax[1] = 1e308;
        CHECK_STATUS(sms_multi_generator_reach(&c, nextafter(SMS_TS_MAX, HUGE_VAL), &info, &axis),
                     sizeof(sms_real) == sizeof(double) ? SMS_ERR_SAMPLE_PERIOD_RANGE
                                                        : SMS_ERR_SAMPLE_PERIOD);
        CHECK(info.quantity != NULL && strcmp(info.quantity, "Ts") == 0 && axis == 0);
        c.jmax[1] = 1.0;
    }
    CHECK(isfinite(9007199254740992.0 * 8.0 * SMS_TS_MAX));
    {   /* the float build: the generators take a Ts its floats hold, the tighter bound */
        sms_multi_generator big;
        CHECK_STATUS(sms_multi_generator_init(&big, &c, sizeof(sms_real) == sizeof(double)
                                              ? SMS_TS_MAX : 1e30, NULL, 0, NULL, 0, NULL),
                     SMS_OK);
    }
    c.n_axes = 0;
    CHECK_STATUS(sms_multi_generator_init(&g, &c, 1e-3, NULL, 0, NULL, 0, NULL), SMS_ERR_ORDER);
    c.n_axes = SMS_MULTI_MAX_AXES + 1;
    CHECK_STATUS(sms_multi_generator_init(&g, &c, 1e-3, NULL, 0, NULL, 0, NULL), SMS_ERR_ORDER);
    c.n_axes = 3;
    c.sync = (sms_sync)7;
    CHECK_STATUS(sms_multi_generator_init(&g, &c, 1e-3, NULL, 0, NULL, 0, NULL), SMS_ERR_KIND);
    CHECK(g.n_axes != 3); /* untouched */
    CHECK_STATUS(sms_multi_generator_init(NULL, &c, 1e-3, NULL, 0, NULL, 0, NULL), SMS_ERR_NULL);
}

/* Non-finite targets are ignored. */
static void non_finite_target(void)
{
    sms_multi_generator_config c = random_config(2, SMS_SYNC_PHASE);
    sms_multi_generator g;
    sms_real t[2] = {1, 1}, o[8];
    size_t k;
    CHECK_STATUS(sms_multi_generator_init(&g, &c, 1e-2, NULL, 0, NULL, 0, NULL), SMS_OK);
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
    CHECK_STATUS(sms_multi_generator_init(&g, &c, 1e-2, NULL, 0, NULL, 0, NULL), SMS_OK);
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
    double state[128 + SMS_MULTI_IDENTITY_COUNT], bad[128 + SMS_MULTI_IDENTITY_COUNT];
    sms_real t[3] = {1, -2, 3}, a[12], b[12];
    size_t k, n;
    int sync, same = 1;
    for (sync = 0; sync < 2; ++sync) {
        c.sync = (sms_sync)sync;
        CHECK_STATUS(sms_multi_generator_init(&g, &c, 1e-3, NULL, 0, NULL, 0, NULL), SMS_OK);
        CHECK_STATUS(sms_multi_generator_init(&h, &c, 1e-3, NULL, 0, NULL, 0, NULL), SMS_OK);
        n = sms_multi_generator_state_count(&g);
        CHECK(n == SMS_MULTI_IDENTITY_COUNT + 15 + (sync == 0 ? 12u : 36u));
        for (k = 0; k < 137; ++k)
            sms_multi_generator_step(&g, t, a);
        t[1] = 5; /* pending change */
        sms_multi_generator_step(&g, t, a);
        sms_multi_generator_get_state(&g, state);
        CHECK_STATUS(sms_multi_generator_set_state(&h, state, n), SMS_OK);
        for (k = 0; k < 3000; ++k) {
            sms_multi_generator_step(&g, t, a);
            sms_multi_generator_step(&h, t, b);
            if (memcmp(a, b, sizeof a) != 0)
                same = 0;
        }
        memcpy(bad, state, n * sizeof(double));
        bad[n - 1] = 2.0; /* a flag that is not 0/1 */
        CHECK_STATUS(sms_multi_generator_set_state(&h, bad, n), SMS_ERR_STATE);
        memcpy(bad, state, n * sizeof(double));
        bad[SMS_MULTI_IDENTITY_COUNT] = NAN;
        CHECK_STATUS(sms_multi_generator_set_state(&h, bad, n), SMS_ERR_STATE);
        CHECK_STATUS(sms_multi_generator_set_state(&h, state, n - 1), SMS_ERR_STATE);
        t[1] = -2;
    }
    CHECK(same);
}

/* Vibration stages: each axis's q, v, a, j equal the stage-free generator's outputs through a
 * separate chain of the same configs (bit for bit); same stages on every axis keep a phase
 * move on its straight line; state round trip, copy + rebind, size query and bad stages. */
static void stages_filter_every_signal(void)
{
    sms_multi_generator_config c = random_config(3, SMS_SYNC_PHASE), plain;
    sms_stage_config zv, m, bad_wn, cfg[3][2];
    sms_multi_generator g, h, raw;
    static sms_stage mem[64], mem_h[64], chain_mem[3][4][2];
    static sms_memory_cell buf[4096], buf_h[4096], chain_buf[3][4][1024];
    static double state[4096]; /* two vectors of up to 2048 */
    sms_chain ref[3][4];
    size_t n_structs = 0, n_cells = 0, bad = 99, i, k, sig, n;
    sms_real t[3] = {0.4, -0.3, 0.25}, a[12], b[12], r[12];
    const double Ts = 1e-3;
    int same = 1, copy_same = 1;
    double line = 0.0;
    zv = sms_stage_config_default(SMS_SHAPER_ZV);
    zv.wn = 60.0;
    zv.zeta = 0.05;
    m = sms_stage_config_default(SMS_RECTANGULAR);
    m.T = 0.0123;
    for (i = 0; i < 3; ++i) {
        c.vmax[i] = 0.5 + 0.2 * (double)i;
        c.amax[i] = 5.0 + (double)i;
        c.jmax[i] = 100.0 + 30.0 * (double)i;
        cfg[i][0] = zv;
        cfg[i][1] = m;
        c.stages[i] = cfg[i];
        c.n_stages[i] = 2;
    }
    plain = c;
    memset(plain.n_stages, 0, sizeof plain.n_stages);
    CHECK_STATUS(sms_multi_generator_memory(&c, Ts, &n_structs, &n_cells, &bad), SMS_OK);
    CHECK(n_structs == 3 * 4 * 2 && bad == 0);
    CHECK(n_cells > 0 && n_cells <= sizeof buf / sizeof buf[0]);
    CHECK_STATUS(sms_multi_generator_init(&g, &c, Ts, mem, n_structs - 1, buf, n_cells, NULL),
                 SMS_ERR_BUFFER_TOO_SMALL);
    CHECK_STATUS(sms_multi_generator_init(&g, &c, Ts, mem, n_structs, buf, n_cells - 1, NULL),
                 SMS_ERR_BUFFER_TOO_SMALL);
    CHECK_STATUS(sms_multi_generator_init(&g, &c, Ts, NULL, 0, buf, n_cells, NULL), SMS_ERR_NULL);
    CHECK_STATUS(sms_multi_generator_init(&g, &c, Ts, mem, n_structs, buf, n_cells, NULL), SMS_OK);
    CHECK_STATUS(sms_multi_generator_init(&raw, &plain, Ts, NULL, 0, NULL, 0, NULL), SMS_OK);
    for (i = 0; i < 3; ++i)
        for (sig = 0; sig < 4; ++sig) {
            size_t need = 0;
            CHECK_STATUS(sms_chain_memory_size(cfg[i], 2, Ts, &need), SMS_OK);
            CHECK_STATUS(sms_chain_init(&ref[i][sig], chain_mem[i][sig], cfg[i], 2, Ts,
                                        chain_buf[i][sig], need), SMS_OK);
        }
    for (k = 0; k < 3000; ++k) {
        if (k == 150)
            t[0] = -0.2; /* mid-motion change: the corner is cut, not straight */
        if (k == 1500) {
            t[0] = 0.1; /* from rest: a straight move */
            t[1] = 0.2;
            t[2] = -0.35;
        }
        if (k == 1600) { /* copy mid-motion: the copy continues identically after rebind */
            h = g;
            memcpy(mem_h, mem, sizeof mem);
            memcpy(buf_h, buf, sizeof buf);
            sms_multi_generator_rebind(&h, mem_h, buf_h);
        }
        sms_multi_generator_step(&g, t, a);
        sms_multi_generator_step(&raw, t, r);
        for (i = 0; i < 3; ++i)
            for (sig = 0; sig < 4; ++sig)
                sms_chain_step(&ref[i][sig], &r[4 * i + sig]);
        if (memcmp(a, r, sizeof a) != 0)
            same = 0;
        if (k >= 1600) {
            sms_multi_generator_step(&h, t, b);
            if (memcmp(a, b, sizeof a) != 0)
                copy_same = 0;
        }
        if (k >= 1500) { /* filtered q stays on the segment from the rest point to the target */
            const double p0[3] = {-0.2, -0.3, 0.25}, d[3] = {0.3, 0.5, -0.6};
            double s = ((double)a[8] - p0[2]) / d[2];
            for (i = 0; i < 3; ++i) {
                double dev = fabs((double)a[4 * i] - p0[i] - s * d[i]) / 0.6;
                if (dev > line)
                    line = dev;
            }
        }
    }
    CHECK(same);
    CHECK(copy_same);
    CHECK(line <= LINE_TOL);
    /* state round trip with stages: restored into a fresh generator, continues bit for bit */
    n = sms_multi_generator_state_count(&g);
    CHECK(n > SMS_MULTI_IDENTITY_COUNT + 15 + 12 && n <= 2048);
    t[2] = 0.3;
    for (k = 0; k < 40; ++k)
        sms_multi_generator_step(&g, t, a);
    sms_multi_generator_get_state(&g, state);
    CHECK_STATUS(sms_multi_generator_init(&h, &c, Ts, mem_h, n_structs, buf_h, n_cells, NULL),
                 SMS_OK);
    CHECK_STATUS(sms_multi_generator_set_state(&h, state, n), SMS_OK);
    same = 1;
    for (k = 0; k < 800; ++k) {
        sms_multi_generator_step(&g, t, a);
        sms_multi_generator_step(&h, t, b);
        if (memcmp(a, b, sizeof a) != 0)
            same = 0;
    }
    CHECK(same);
    /* the head of axis 0's first shaper (after its stage identity, kind, L): not in its history */
    state[SMS_MULTI_IDENTITY_COUNT + 15 + 12 + SMS_STATE_IDENTITY_COUNT + 2] = -1.0;
    sms_multi_generator_get_state(&h, state + 2048);
    CHECK_STATUS(sms_multi_generator_set_state(&h, state, n), SMS_ERR_STATE);
    sms_multi_generator_get_state(&h, state);
    CHECK(memcmp(state, state + 2048, n * sizeof(double)) == 0); /* nothing written */
    /* a bad stage on axis 2: its status and axis, nothing built */
    bad_wn = zv;
    bad_wn.wn = -1.0;
    cfg[2][0] = bad_wn;
    CHECK_STATUS(sms_multi_generator_memory(&c, Ts, &n_structs, &n_cells, &bad), SMS_ERR_WN);
    CHECK(bad == 2);
    CHECK_STATUS(sms_multi_generator_init(&h, &c, Ts, mem_h, 64, buf_h, 4096, &bad), SMS_ERR_WN);
    CHECK(bad == 2);
    c.n_stages[1] = SMS_CHAIN_MAX_STAGES + 1;
    CHECK_STATUS(sms_multi_generator_memory(&c, Ts, &n_structs, &n_cells, &bad), SMS_ERR_ORDER);
    CHECK(bad == 1);
}

/* Within feasible limits, a move that cannot be planned (|d| = 1e300 with vmax = 1: a cruise
 * of 1e300 s, beyond 2^52 samples) is dropped at rest and mid-motion: outputs stay finite and
 * within the limits, the previous target is kept, and a representable target moves as usual. */
static void unrepresentable_move_dropped(void)
{
#ifdef SMS_USE_FLOAT
    const double big = 1e38;
#else
    const double big = 1e300;
#endif
    sms_multi_generator_config c = random_config(2, SMS_SYNC_PHASE);
    sms_multi_generator g;
    sms_real t[2], o[8];
    size_t k;
    int finite_ok = 1, within = 1;
    c.vmax[0] = 1.0;
    c.amax[0] = 1e-3;
    c.jmax[0] = 1e-3;
    c.vmax[1] = c.amax[1] = c.jmax[1] = 1.0;
    CHECK_STATUS(sms_multi_generator_init(&g, &c, 1e-3, NULL, 0, NULL, 0, NULL), SMS_OK);
    for (k = 0; k < 3000; ++k) {
        t[0] = (sms_real)(k < 30 || (k >= 40 && k < 60) ? big : 0.0);
        t[1] = (sms_real)(k < 30 ? -big : k < 100 ? 0.5 : 0.25);
        sms_multi_generator_step(&g, t, o);
        if (!(o[0] - o[0] == 0 && o[1] - o[1] == 0 && o[2] - o[2] == 0 && o[3] - o[3] == 0 &&
              o[4] - o[4] == 0 && o[5] - o[5] == 0 && o[6] - o[6] == 0 && o[7] - o[7] == 0))
            finite_ok = 0;
        if (k < 30 && (o[0] != 0 || o[4] != 0 || sms_multi_generator_busy(&g)))
            within = 0; /* dropped at rest: still at 0, not waiting to try it again */
        if (k < 30)
            CHECK(g.move[0].refused == 1 && g.dropped == 1); /* once, not per sample */
        if (k >= 30 && k < 40)
            CHECK(g.move[0].refused == 0);
        if (fabs((double)o[1]) > 1.0 * (1 + LIMIT_TOL) || fabs((double)o[5]) > 1.0 * (1 + LIMIT_TOL))
            within = 0;
    }
    CHECK(finite_ok);
    CHECK(within);
    /* counted once: the second target 1e300 (k = 40 .. 59) arrives in the first velocity
     * transition of axis 1's move and changes before the move may blend, so it is never
     * tried (nor dropped) */
    CHECK(g.dropped == 1);
    sms_multi_generator_reset(&g, NULL);
    CHECK(g.dropped == 0 && g.move[0].refused == 0);
}

/* A move far beyond the distance to reach vmax whose unit limit jmax/|d| underflows to 0 but
 * which lasts about 1e10 (double) or 2e8 (float) samples: planned, at vmax after the first
 * transition, in both sync modes (it was dropped while the landing formed the unit limits
 * before trying the cruise bound). */
static void long_move_planned(void)
{
#ifdef SMS_USE_FLOAT
    const double jmax = 1e-7, Ts = 1e30, far = 2e38;
#else
    const double jmax = 1e-190, Ts = 1e130, far = 1e140;
#endif
    sms_multi_generator_config c = random_config(2, SMS_SYNC_PHASE);
    sms_multi_generator g;
    sms_real t[2], o[8];
    int sync;
    for (sync = 0; sync < 2; ++sync) {
        c.sync = sync ? SMS_SYNC_INDEPENDENT : SMS_SYNC_PHASE;
        c.vmax[0] = 1.0;
        c.vmax[1] = 2.0;
        c.amax[0] = c.amax[1] = 1.0;
        c.jmax[0] = c.jmax[1] = jmax;
        CHECK_STATUS(sms_multi_generator_init(&g, &c, Ts, NULL, 0, NULL, 0, NULL), SMS_OK);
        t[0] = (sms_real)far;
        t[1] = (sms_real)-far;
        sms_multi_generator_step(&g, t, o);
        sms_multi_generator_step(&g, t, o);
        CHECK(g.dropped == 0 && g.move[0].refused == 0 && sms_multi_generator_busy(&g));
        CHECK(o[1] == 1 && o[5] == (sync ? -2 : -1)); /* cruising at vmax (phase: axis 0's) */
    }
}

/* The largest and smallest normal numbers and the epsilon of sms_real (the test's own copy of
 * the documented region, trajectory.h sms_generator_reach()). */
#ifdef SMS_USE_FLOAT
#define R_MAX 3.4028234663852886e38
#define R_MIN 1.1754943508222875e-38
#define R_EPS 1.1920928955078125e-7
#define R_SPAN 37.0
#define R_TINY 1.7e-10 /* about 4 eps^1.5 */
#else
#define R_MAX 1.7976931348623157e308
#define R_MIN 2.2250738585072014e-308
#define R_EPS 2.220446049250313e-16
#define R_SPAN 300.0
#define R_TINY 1.3e-23
#endif
#define REACH_SAMPLES 1125899906842624.0 /* 2^50 */
#define RATIO_BOUND 72057594037927936.0    /* 2^56 */

/* One sample towards `target` from rest at 0; 1 when no target was dropped. */
static int plans_from_rest(sms_multi_generator *g, const double *target)
{
    sms_real t[SMS_MULTI_MAX_AXES], o[4 * SMS_MULTI_MAX_AXES];
    size_t i, k;
    int finite = 1;
    sms_multi_generator_reset(g, NULL);
    for (i = 0; i < g->n_axes; ++i)
        t[i] = (sms_real)target[i];
    for (k = 0; k < 3; ++k)
        sms_multi_generator_step(g, t, o);
    for (i = 0; i < 4 * g->n_axes; ++i)
        finite &= o[i] - o[i] == 0;
    return g->dropped == 0 && finite;
}

/* Cruising towards 2 h (every axis), the target jumps to -2 h: the move is put into its
 * cruise through a saved state (sample k in the middle of the cruise), then re-planned. */
static int plans_reversal(sms_multi_generator *g, const double *h)
{
    static double st[SMS_MULTI_IDENTITY_COUNT + 17 * SMS_MULTI_MAX_AXES];
    double target[SMS_MULTI_MAX_AXES];
    sms_real t[SMS_MULTI_MAX_AXES], o[4 * SMS_MULTI_MAX_AXES];
    size_t i, n = g->n_axes, moves = g->sync == SMS_SYNC_PHASE ? 1 : n, count;
    for (i = 0; i < n; ++i)
        target[i] = 2.0 * h[i];
    if (!plans_from_rest(g, target))
        return 0;
    count = sms_multi_generator_state_count(g);
    CHECK(count <= sizeof st / sizeof st[0]);
    sms_multi_generator_get_state(g, st);
    for (i = 0; i < moves; ++i) {
        double *m = st + SMS_MULTI_IDENTITY_COUNT + 5 * n + 12 * i;
        double k = floor((m[0] + m[2] / 2.0 - m[5]) / g->Ts);
        if (m[9] == 1.0 && k > m[7] && k < m[8])
            m[7] = k;
    }
    CHECK_STATUS(sms_multi_generator_set_state(g, st, count), SMS_OK);
    for (i = 0; i < n; ++i)
        t[i] = (sms_real)(-2.0 * h[i]);
    for (i = 0; i < 3; ++i)
        sms_multi_generator_step(g, t, o);
    for (i = 0; i < 4 * n; ++i)
        if (!(o[i] - o[i] == 0))
            return 0;
    return g->dropped == 0;
}

/* The generator's own states load again: over random moves that cruise at vmax (from rest and
 * retargeted while moving, both sync modes, up to 1e7 samples to reach vmax), the state saved
 * after every sample passes check_state and set_state, and the generator reloaded from it
 * runs on bit for bit like one never reloaded. The cruise velocity W = u/kappa of a move at
 * vmax rounds over vmax, by up to 2 GRID_TOL when its arrival is rounded onto the grid; the
 * check must follow that. */
static void own_states_reload(void)
{
    static double st[SMS_MULTI_IDENTITY_COUNT + 17 * SMS_MULTI_MAX_AXES];
    size_t trial, move, i, k, reloads = 0;
    double worst = 0.0;
    int same = 1;
    for (trial = 0; trial < 40; ++trial) {
        size_t n = 1 + (size_t)(urand() * 6.0), count;
        sms_multi_generator_config c = random_config(n, urand() < 0.5 ? SMS_SYNC_PHASE
                                                                      : SMS_SYNC_INDEPENDENT);
        sms_multi_generator g, h;
        sms_real target[SMS_MULTI_MAX_AXES], a[4 * SMS_MULTI_MAX_AXES], b[4 * SMS_MULTI_MAX_AXES];
        double reach = 0.0, Ts;
        for (i = 0; i < n; ++i) { /* the longest time to reach vmax from rest */
            double t = c.vmax[i] / c.amax[i] + c.amax[i] / c.jmax[i];
            if (t > reach)
                reach = t;
        }
        Ts = reach / log_uniform(3.0, 1e7); /* long moves: a larger grid rounding */
        CHECK_STATUS(sms_multi_generator_init(&g, &c, Ts, NULL, 0, NULL, 0, NULL), SMS_OK);
        CHECK_STATUS(sms_multi_generator_init(&h, &c, Ts, NULL, 0, NULL, 0, NULL), SMS_OK);
        count = sms_multi_generator_state_count(&g);
        CHECK(count <= sizeof st / sizeof st[0]);
        for (move = 0; move < 100; ++move) {
            for (i = 0; i < n; ++i) /* up to 20 times the distance to reach vmax */
                target[i] = (sms_real)((2.0 * urand() - 1.0) * 20.0 * c.vmax[i] * reach);
            for (k = 0; k < 4; ++k) {
                sms_multi_generator_step(&g, target, a);
                sms_multi_generator_step(&h, target, b);
                if (memcmp(a, b, sizeof(sms_real) * 4 * n) != 0)
                    same = 0;
                sms_multi_generator_get_state(&h, st);
                for (i = 0; i < n; ++i) {
                    double W = fabs(st[SMS_MULTI_IDENTITY_COUNT + 4 * n + i]) / (double)h.vmax[i];
                    if (W - 1.0 > worst)
                        worst = W - 1.0;
                }
                CHECK_STATUS(sms_multi_generator_check_state(&h, st, count), SMS_OK);
                CHECK_STATUS(sms_multi_generator_set_state(&h, st, count), SMS_OK);
                ++reloads;
            }
            if (urand() < 0.5) { /* from rest, else retargeted while moving */
                sms_multi_generator_reset(&g, NULL);
                sms_multi_generator_reset(&h, NULL);
            }
        }
    }
    CHECK(same);
    printf("own states reloaded: %lu, largest |W|/vmax - 1 = %.3g (%.1f eps)\n",
           (unsigned long)reloads, worst, worst / R_EPS);
}

/* Random limit sets over the build's whole range (log-uniform per axis, so the axes' limits
 * and their moves' durations differ by up to the whole range), both sync modes: whenever init
 * accepts them, every axis's move that reaches vmax (h_i), h_i/2, 3 h_i, 1e-9 h_i and about
 * eps^1.5 h_i, all axes together and each alone, mixed sizes, and the reversal from full
 * speed are planned (no target dropped). Each axis is drawn until sms_generator_reach()
 * accepts it alone; the set is then accepted as a whole (the region is per axis). */
static void feasible_random(void)
{
    size_t trial, accepted = 0;
    for (trial = 0; trial < 1500; ++trial) {
        sms_multi_generator_config c;
        sms_multi_generator g;
        sms_generator_reach_info r;
        double h[SMS_MULTI_MAX_AXES], x[SMS_MULTI_MAX_AXES], Ts = pow(10.0, R_SPAN * (2.0 * urand() - 1.0));
        size_t i, j, axis = 99, tries = 0;
        int ok = 1;
        memset(&c, 0, sizeof c);
        c.n_axes = 1 + trial % 3;
        c.sync = urand() < 0.5 ? SMS_SYNC_PHASE : SMS_SYNC_INDEPENDENT;
        for (i = 0; i < c.n_axes; ++i) {
            sms_multi_generator_config one;
            memset(&one, 0, sizeof one);
            one.n_axes = 1;
            do {
                one.vmax[0] = pow(10.0, R_SPAN * (2.0 * urand() - 1.0));
                one.amax[0] = pow(10.0, R_SPAN * (2.0 * urand() - 1.0));
                one.jmax[0] = pow(10.0, R_SPAN * (2.0 * urand() - 1.0));
            } while (sms_multi_generator_reach(&one, Ts, &r, NULL) != SMS_OK && ++tries < 100000);
            c.vmax[i] = one.vmax[0];
            c.amax[i] = one.amax[0];
            c.jmax[i] = one.jmax[0];
            h[i] = r.distance;
        }
        if (sms_multi_generator_reach(&c, Ts, &r, &axis) != SMS_OK)
            continue; /* Ts itself out of range, or an axis not found feasible */
        CHECK(axis == 0);
        CHECK_STATUS(sms_multi_generator_init(&g, &c, Ts, NULL, 0, NULL, 0, NULL), SMS_OK);
        ++accepted;
        {
            static const double part[] = {1.0, 0.5, 3.0, 1e-9, R_TINY};
            for (j = 0; j < sizeof part / sizeof part[0]; ++j) {
                for (i = 0; i < c.n_axes; ++i)
                    x[i] = part[j] * h[i];
                ok &= plans_from_rest(&g, x);
                for (i = 0; i < c.n_axes; ++i) { /* mixed: one axis at this size, others h */
                    size_t k;
                    for (k = 0; k < c.n_axes; ++k)
                        x[k] = k == i ? part[j] * h[k] : (k % 2 ? -h[k] : h[k]);
                    ok &= plans_from_rest(&g, x);
                    for (k = 0; k < c.n_axes; ++k) /* alone */
                        x[k] = k == i ? part[j] * h[k] : 0.0;
                    ok &= plans_from_rest(&g, x);
                }
            }
            ok &= plans_reversal(&g, h);
        }
        CHECK(ok);
        if (!ok)
            fprintf(stderr, "dropped: n %u sync %d Ts %g axis0 %g %g %g axis1 %g %g %g\n",
                    (unsigned)c.n_axes, (int)c.sync, Ts, c.vmax[0], c.amax[0], c.jmax[0],
                    c.vmax[1], c.amax[1], c.jmax[1]);
    }
    CHECK(accepted > 500);
}

/* Expect init (and the memory query) to refuse axis `axis` naming `quantity`. */
static void check_refused(const sms_multi_generator_config *c, double Ts, size_t axis,
                          const char *quantity)
{
    sms_multi_generator g;
    sms_generator_reach_info r;
    size_t bad = 99, n_structs, n_cells;
    memset(&g, 0x5a, sizeof g);
    CHECK_STATUS(sms_multi_generator_reach(c, Ts, &r, &bad), SMS_ERR_LIMIT);
    CHECK(bad == axis);
    CHECK(r.quantity != NULL && strcmp(r.quantity, quantity) == 0);
    if (r.quantity == NULL || strcmp(r.quantity, quantity) != 0 || bad != axis)
        fprintf(stderr, "refused axis %u for %s, expected axis %u, %s\n", (unsigned)bad,
                r.quantity != NULL ? r.quantity : "nothing", (unsigned)axis, quantity);
    bad = 99;
    CHECK_STATUS(sms_multi_generator_init(&g, c, Ts, NULL, 0, NULL, 0, &bad), SMS_ERR_LIMIT);
    CHECK(bad == axis);
    CHECK(g.n_axes == (size_t)0x5a5a5a5a5a5a5a5aull); /* untouched on error */
    CHECK_STATUS(sms_multi_generator_memory(c, Ts, &n_structs, &n_cells, &bad), SMS_ERR_LIMIT);
}

/* Expect init to accept the limits and plan h and the reversal for every axis. */
static void check_accepted(const sms_multi_generator_config *c, double Ts)
{
    sms_multi_generator g;
    sms_generator_reach_info r;
    sms_generator_config one;
    double h[SMS_MULTI_MAX_AXES];
    size_t i;
    memset(&one, 0, sizeof one);
    CHECK_STATUS(sms_multi_generator_reach(c, Ts, &r, NULL), SMS_OK);
    CHECK_STATUS(sms_multi_generator_init(&g, c, Ts, NULL, 0, NULL, 0, NULL), SMS_OK);
    if (r.quantity != NULL) {
        fprintf(stderr, "refused for %s (axis 1: %g %g %g, Ts %g)\n", r.quantity, c->vmax[1],
                c->amax[1], c->jmax[1], Ts);
        return;
    }
    for (i = 0; i < c->n_axes; ++i) {
        one.vmax = c->vmax[i];
        one.amax = c->amax[i];
        one.jmax = c->jmax[i];
        CHECK_STATUS(sms_generator_reach(&one, Ts, &r), SMS_OK);
        h[i] = r.distance;
    }
    CHECK(plans_from_rest(&g, h));
    CHECK(plans_reversal(&g, h));
}

/* Both sides of every bound of the region, on axis 1 of two (axis 0 an ordinary machine),
 * both sync modes: just inside, h and the reversal are planned; just outside, init refuses
 * axis 1 and names the quantity. */
static void feasible_limits(void)
{
    const double in = 1.0 - 1e-6, out = 1.0 + 1e-6, big = R_MAX / 16.0;
    sms_multi_generator_config c;
    double T, x;
    int sync;
    for (sync = 0; sync < 2; ++sync) {
        memset(&c, 0, sizeof c);
        c.n_axes = 2;
        c.sync = sync ? SMS_SYNC_INDEPENDENT : SMS_SYNC_PHASE;
        c.vmax[0] = 1.0;
        c.amax[0] = 100.0;
        c.jmax[0] = 1e4;
        /* the duration to reach vmax: 2 (vmax/amax + amax/jmax) against 2^50 samples */
        c.vmax[1] = 1.0;
        c.amax[1] = 5.0;
        c.jmax[1] = 100.0;
        T = 2.0 * (1.0 / 5.0 + 5.0 / 100.0);
        check_accepted(&c, T / REACH_SAMPLES * out);
        check_refused(&c, T / REACH_SAMPLES * in, 1, "vmax/amax");
        c.amax[1] = 1e10; /* amax not reached: 4 sqrt(vmax/jmax) */
        T = 4.0 * sqrt(1.0 / 100.0);
        check_accepted(&c, T / REACH_SAMPLES * out);
        check_refused(&c, T / REACH_SAMPLES * in, 1, "sqrt(vmax/jmax)");
        /* the velocity changes: 16 vmax jmax <= MAX (jmax = 2^40 vmax, amax 1, Ts = vmax):
         * outside, refused; inside, the unit limits of the displacement already fail */
        x = sqrt(R_MAX / 16.0 / 1099511627776.0);
        c.vmax[1] = x;
        c.amax[1] = 1.0;
        c.jmax[1] = x * 1099511627776.0 * out;
        check_refused(&c, x, 1, "vmax*jmax");
        /* the planner's ratios limit/|dv| (capped at 2^60): amax/vmax, jmax/vmax <= 2^56 */
        c.vmax[1] = 1.0;
        c.jmax[1] = 1.0;
        c.amax[1] = RATIO_BOUND * in;
        check_accepted(&c, 1e-3);
        c.amax[1] = RATIO_BOUND * out;
        check_refused(&c, 1e-3, 1, "amax/vmax");
        c.amax[1] = 1.0;
        c.jmax[1] = RATIO_BOUND * in;
        check_accepted(&c, 1e-3);
        c.jmax[1] = RATIO_BOUND * out;
        check_refused(&c, 1e-3, 1, "jmax/vmax");
        /* the ratios limit/|d| of the displacement h to reach vmax: amax/h, jmax/h <= 2^56 */
        c.vmax[1] = 1.0;
        c.jmax[1] = 1e10;
        x = 2.0 * sqrt(1.0 / 1e10); /* h = 2 vmax sqrt(vmax/jmax): amax not reached */
        c.amax[1] = RATIO_BOUND * x * in;
        check_accepted(&c, 1e-3);
        c.amax[1] = RATIO_BOUND * x * out;
        check_refused(&c, 1e-3, 1, "amax/h");
        c.amax[1] = 100.0;
        c.jmax[1] = RATIO_BOUND * 0.01;
        x = 0.01 + 100.0 / c.jmax[1]; /* h = vmax (vmax/amax + amax/jmax) */
        c.jmax[1] = RATIO_BOUND * x * in;
        check_accepted(&c, 1e-3);
        c.jmax[1] = RATIO_BOUND * x * out;
        check_refused(&c, 1e-3, 1, "jmax/h");
        /* the unit accelerations' squares: (amax/(16 h))^2 >= MIN/eps, with vmax = jmax = 1,
         * h = 1/amax + amax: amax^2 = 16 s/(1 - 16 s), s = sqrt(MIN/eps) */
        x = 16.0 * sqrt(R_MIN / R_EPS);
        x = sqrt(x / (1.0 - x));
        c.vmax[1] = 1.0;
        c.jmax[1] = 1.0;
        c.amax[1] = x * out;
        T = 2.0 * (1.0 / c.amax[1] + c.amax[1]);
        check_accepted(&c, T * 1e-6);
        c.amax[1] = x * in;
        check_refused(&c, T * 1e-6, 1, "(amax/h)^2");
        /* each limit in [MIN, MAX/16] */
        c.vmax[1] = 1.0;
        c.amax[1] = 10.0;
        c.jmax[1] = big * out;
        check_refused(&c, 1e-3, 1, "jmax");
        c.jmax[1] = 100.0;
        c.vmax[1] = R_MIN * in;
        check_refused(&c, 1e-3, 1, "vmax");
    }
    /* the documented example, on axis 1: reaching vmax takes 4e150 s */
    memset(&c, 0, sizeof c);
    c.n_axes = 2;
    c.vmax[0] = c.amax[0] = c.jmax[0] = 1.0;
    c.vmax[1] = 1.0;
    c.amax[1] = 1e-30;
    c.jmax[1] = 1e-300; /* in float jmax itself is below MIN */
    check_refused(&c, 1e-3, 1, sizeof(sms_real) == sizeof(double) ? "sqrt(vmax/jmax)" : "jmax");
}

/* A saved start or cruise velocity beyond vmax by 1.25 or 2 times the tolerance of the
 * reported values (SMS_LIMIT_RTOL, 32 u) is refused, writing nothing; one at the tolerance
 * loads. */
static void state_beyond_vmax(void)
{
    static double st[SMS_MULTI_IDENTITY_COUNT + 17 * SMS_MULTI_MAX_AXES];
    static double before[SMS_MULTI_IDENTITY_COUNT + 17 * SMS_MULTI_MAX_AXES];
    static double after[SMS_MULTI_IDENTITY_COUNT + 17 * SMS_MULTI_MAX_AXES];
    sms_multi_generator_config c = random_config(3, SMS_SYNC_PHASE);
    sms_multi_generator g;
    sms_real t[3] = {1, -2, 3}, o[12];
    size_t k, count, field, axis;
    c.vmax[1] = 2.0; /* a power of two: vmax (1 + tol) is exact in float too */
    CHECK_STATUS(sms_multi_generator_init(&g, &c, 1e-3, NULL, 0, NULL, 0, NULL), SMS_OK);
    CHECK(SMS_LIMIT_RTOL == 32.0 * UNIT_ROUNDOFF);
    for (k = 0; k < 50; ++k)
        sms_multi_generator_step(&g, t, o);
    count = sms_multi_generator_state_count(&g);
    CHECK(count <= sizeof st / sizeof st[0]);
    sms_multi_generator_get_state(&g, before);
    axis = 1;
    for (field = 3; field <= 4; ++field) { /* V (start), W (cruise) */
        double sign, *v = st + SMS_MULTI_IDENTITY_COUNT + field * 3 + axis;
        for (sign = -1.0; sign <= 1.0; sign += 2.0) {
            double over;
            memcpy(st, before, count * sizeof(double));
            for (over = 1.25; over <= 2.0; over += 0.75) { /* 40 u: 48 u was allowed before */
                *v = sign * 2.0 * (1.0 + over * SMS_LIMIT_RTOL);
                CHECK_STATUS(sms_multi_generator_check_state(&g, st, count), SMS_ERR_STATE);
                CHECK_STATUS(sms_multi_generator_set_state(&g, st, count), SMS_ERR_STATE);
                sms_multi_generator_get_state(&g, after);
                CHECK(memcmp(after, before, count * sizeof(double)) == 0);
            }
            *v = sign * 2.0 * (1.0 + SMS_LIMIT_RTOL);
            CHECK_STATUS(sms_multi_generator_check_state(&g, st, count), SMS_OK);
        }
    }
}

/* Put g (one group) into a cruise at V0 with p = 0 at the next sample's blend, and step it
 * towards target: the move planned from (0, V0) with zero acceleration. Returns its first
 * sample in out (4 n values). */
static void plan_from_cruise(sms_multi_generator *g, const double *V0, const sms_real *target,
                             sms_real *out)
{
    static double st[SMS_MULTI_IDENTITY_COUNT + 17 * SMS_MULTI_MAX_AXES];
    const size_t n = g->n_axes, count = sms_multi_generator_state_count(g);
    double *axis = st + SMS_MULTI_IDENTITY_COUNT, *m = axis + 5 * n;
    size_t i;
    CHECK(count <= sizeof st / sizeof st[0]);
    sms_multi_generator_get_state(g, st);
    for (i = 0; i < n; ++i) {
        const sms_real v = (sms_real)V0[i];
        const double p0 = -(double)(v * g->Ts_signal); /* the blend adds V0 Ts: p = 0 */
        axis[i] = (double)target[i];
        axis[n + i] = axis[2 * n + i] = p0; /* goal (differs from the target) and p */
        axis[3 * n + i] = axis[4 * n + i] = (double)v;
    }
    /* a cruise at V0: T1 = 0, rho1, tau, T2 = 0, rho2, off, seen, k, k_end, active, ... */
    m[0] = 0.0, m[1] = 0.5, m[2] = 1e9, m[3] = 0.0, m[4] = 0.5, m[5] = 0.0, m[6] = 0.0;
    m[7] = 0.0, m[8] = 1125899906842624.0, m[9] = 1.0, m[10] = 0.0, m[11] = 0.0;
    CHECK_STATUS(sms_multi_generator_set_state(g, st, count), SMS_OK);
    sms_multi_generator_step(g, target, out);
}

/* The arrival rounded onto an earlier sample (a planned end within GRID_TOL = 2 eps after
 * it) raises the cruise velocity W by up to 2 GRID_TOL, and with it the first transition's
 * change W - V. From a cruise at V0 = vmax/2 to a cruise at vmax, V0 and W - V0 both need the
 * whole first transition (T1 = T(V0) = T(W - V0)), so the change grows by twice as much, and
 * the stretched jerk fraction raised the jerk by the square of that: 40 u over jmax in both
 * precisions (1 axis, vmax 1, amax 1, jmax 1000, 42 u reported in double and 39 u in float;
 * docs/multi-axis.md). The targets here put the candidate's cruise a few ulps long and Ts so
 * that its end lies just after sample N; every reported v, a, j of the first transition stays
 * within the limits to 32 u, the best-fitting jerk fraction bounding a and j by 2 (s - 1)
 * <= 4 GRID_TOL = 16 u over their limits (s - 1 the rise of W). */
static void snapped_arrival_from_a_cruise(void)
{
    const double V0 = 0.5, eps = 2.0 * UNIT_ROUNDOFF;
    sms_multi_generator_config c;
    sms_multi_generator g;
    double worst[4] = {0, 0, 0, 0};
    size_t snapped = 0, N, k, f, i;
    static const double fracs[4] = {0.3, 0.6, 0.9, 0.99};
    memset(&c, 0, sizeof c);
    c.n_axes = 1;
    c.sync = SMS_SYNC_PHASE;
    c.vmax[0] = 1.0;
    c.amax[0] = 1.0;
    c.jmax[0] = 1000.0;
    for (N = 1000; N <= 10000; N *= 10)
        for (k = 0; k < 24; ++k) {
            sms_real target, T1, T2, u, tau_c, total, base;
            sms_real out[4];
            /* the candidate's T1, T2 from a probe; the target k ulps beyond the one with no
             * cruise, V0 T1/2 + T1/2 + T2/2 */
            CHECK_STATUS(sms_multi_generator_init(&g, &c, 1e-3, NULL, 0, NULL, 0, NULL), SMS_OK);
            target = (sms_real)(V0 * (0.501 / 2.0) + 0.501 / 2.0 + 1.001 / 2.0);
            plan_from_cruise(&g, &V0, &target, out);
            T1 = g.move[0].T1;
            T2 = g.move[0].T2;
            base = (sms_real)V0 * (T1 / 2) + T1 / 2 + T2 / 2;
            target = base + (sms_real)k * (sms_real)(2.0 * eps) * base;
            u = target - (sms_real)V0 * (T1 / 2);
            tau_c = u / (sms_real)c.vmax[0] - T1 / 2 - T2 / 2; /* plan(): kappa = |u|/vmax */
            if (!(tau_c > 0))
                continue;
            total = T1 + tau_c + T2;
            for (f = 0; f < 4; ++f) {
                const double Ts = (double)total / ((double)N * (1.0 + fracs[f] * 4.0 * eps));
                size_t n_first;
                CHECK_STATUS(sms_multi_generator_init(&g, &c, Ts, NULL, 0, NULL, 0, NULL),
                             SMS_OK);
                plan_from_cruise(&g, &V0, &target, out);
                if (g.move[0].k_end == N && g.move[0].tau < tau_c)
                    ++snapped; /* the arrival moved onto the earlier sample N */
                n_first = (size_t)((double)g.move[0].T1 / Ts) + 1;
                for (i = 0; i < n_first; ++i) {
                    const double limit[4] = {0.0, (double)(sms_real)c.vmax[0],
                                             (double)(sms_real)c.amax[0],
                                             (double)(sms_real)c.jmax[0]};
                    int o;
                    if (i > 0)
                        sms_multi_generator_step(&g, &target, out);
                    for (o = 1; o < 4; ++o)
                        if (fabs((double)out[o]) / limit[o] > worst[o])
                            worst[o] = fabs((double)out[o]) / limit[o];
                }
            }
        }
    CHECK(snapped >= 10);
    CHECK(worst[1] <= 1.0 + LIMIT_TOL);
    CHECK(worst[2] <= 1.0 + LIMIT_TOL);
    CHECK(worst[3] <= 1.0 + LIMIT_TOL);
    printf("snapped arrival from a cruise: %lu snapped moves; first transition v, a, j at most "
           "%.1f, %.1f, %.1f u over the limits\n", (unsigned long)snapped,
           (worst[1] - 1.0) / UNIT_ROUNDOFF, (worst[2] - 1.0) / UNIT_ROUNDOFF,
           (worst[3] - 1.0) / UNIT_ROUNDOFF);
}

int main(void)
{
    unsigned trial;
    for (trial = 0; trial < 300; ++trial)
        rest_to_rest(trial);
    for (trial = 0; trial < 60; ++trial)
        staircase(trial, trial % 3 == 2 ? SMS_SYNC_INDEPENDENT : SMS_SYNC_PHASE);
    last_jerk_phase_on_a_sample();
    independent_equals_single();
    bad_input();
    non_finite_target();
    tiny_moves();
    state_round_trip();
    stages_filter_every_signal();
    unrepresentable_move_dropped();
    long_move_planned();
    feasible_limits();
    feasible_random();
    own_states_reload();
    state_beyond_vmax();
    snapped_arrival_from_a_cruise();
    return check_summary("test_multi_generator");
}
