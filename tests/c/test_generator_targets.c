/* SPDX-License-Identifier: Apache-2.0 */
/* Online generator, targets beyond rest: a position reached with a velocity and an
 * acceleration (exactly on a sample, then the acceleration back to zero and the velocity
 * held), the velocity interface, the stop, sms_generator_start from any state; every sample
 * within every limit (reported values and backward differences), refusals named and
 * harmless, hold and the saved state bit for bit. */
#include <stdlib.h>
#include <string.h>
#include "check.h"

#ifdef SMS_USE_FLOAT
#define U 5.9604644775390625e-8
#else
#define U 1.1102230246251565e-16
#endif
/* Reported |v|, |a|, |j| within the limits to 32 u (SMS_LIMIT_RTOL, docs/sampled-limits.md). */
#define BOUND_TOL (32.0 * U)

static unsigned rng = 7u;
static double urand(void)
{
    rng = rng * 1103515245u + 12345u;
    return ((rng >> 8) & 0xFFFFFFu) / 16777216.0;
}

static sms_generator_config config(double v, double a, double j, sms_profile profile)
{
    sms_generator_config c;
    c.vmax = v;
    c.amax = a;
    c.jmax = j;
    c.profile = profile;
    c.wn = 0.0;
    c.zeta = 0.0;
    c.vmin = 0.0; /* symmetric */
    c.amin = 0.0;
    c.qmin = c.qmax = 0.0; /* no position limits */
    return c;
}

static sms_target target(int interface, double q, double v, double a)
{
    sms_target t;
    t.interface = interface;
    t.position = (sms_real)q;
    t.velocity = (sms_real)v;
    t.acceleration = (sms_real)a;
    t.minimum_duration = 0;
    return t;
}

/* A state (v, a) whose acceleration returns to zero within +-V, and for a target was zero
 * within +-V on the way in too. */
static void random_state(double V, double A, double J, int is_target, double *v, double *a)
{
    for (;;) {
        double r;
        *v = (2.0 * urand() - 1.0) * V;
        *a = (2.0 * urand() - 1.0) * A;
        r = *a * fabs(*a) / (2.0 * J);
        if (fabs(*v + r) <= V && (!is_target || fabs(*v - r) <= V))
            return;
    }
}

/* Bounds over a run: reported values to 32 u, backward differences of the samples to 1e-9
 * after the rounding floor 2^i 16 u S / Ts^i (S the largest |q| of the run). */
typedef struct watch {
    double L[4], Ts, prev[3], worst[4], over[4], S;
    long n;
} watch;

static void watch_start(watch *w, const sms_generator *g, double q0)
{
    memset(w, 0, sizeof *w);
    w->L[1] = (double)g->limits.vmax;
    w->L[2] = (double)g->limits.amax;
    w->L[3] = (double)g->limits.jmax;
    w->Ts = g->Ts;
    w->prev[0] = w->prev[1] = w->prev[2] = q0;
}

static void watch_sample(watch *w, const sms_real out[4])
{
    double q = (double)out[0], d[4];
    int i;
    if (fabs(q) > w->S)
        w->S = fabs(q);
    d[1] = q - w->prev[0];
    d[2] = q - 2.0 * w->prev[0] + w->prev[1];
    d[3] = q - 3.0 * w->prev[0] + 3.0 * w->prev[1] - w->prev[2];
    for (i = 1; i < 4; ++i) {
        double r = fabs((double)out[i]) / w->L[i];
        if (r > w->worst[i])
            w->worst[i] = r;
        if (w->n >= 3) {
            double floor_ = ldexp(16.0 * U * (w->S + 1e-300), i) / pow(w->Ts, (double)i);
            double e = (fabs(d[i]) / pow(w->Ts, (double)i) - floor_) / w->L[i];
            if (e > w->over[i])
                w->over[i] = e;
        }
    }
    w->prev[2] = w->prev[1];
    w->prev[1] = w->prev[0];
    w->prev[0] = q;
    ++w->n;
}

static void watch_check(const watch *w)
{
    int i;
    for (i = 1; i < 4; ++i) {
        CHECK(w->worst[i] <= 1.0 + BOUND_TOL);
        CHECK(w->over[i] <= 1.0 + 1e-9);
    }
}

/* From a random state to a random moving target: the target state exactly on the sample the
 * plan reports (arrival), then the acceleration back to zero at jmax and the velocity held. */
static void test_moving_targets(int trials)
{
    int trial, landed = 0;
    for (trial = 0; trial < trials; ++trial) {
        const double V = pow(10.0, 2.0 * urand() - 1.0), A = V * pow(10.0, 3.0 * urand() - 1.0);
        const double J = A * pow(10.0, 3.0 * urand() - 1.0), scale = V * (V / A + A / J);
        const double Ts = (V / A + A / J + V / (V + 1.0)) / (20.0 + 400.0 * urand());
        sms_generator_config c = config(V, A, J, SMS_PROFILE_POLYNOMIAL);
        sms_generator g;
        sms_target t;
        sms_real out[4];
        double v0, a0, vf, af, q0 = (urand() - 0.5) * scale;
        uint64_t n, k, after;
        watch w;
        random_state(V, A, J, 0, &v0, &a0);
        random_state(V, A, J, 1, &vf, &af);
        t = target(SMS_INTERFACE_POSITION, q0 + (urand() - 0.5) * 6.0 * scale, vf, af);
        CHECK_STATUS(sms_generator_init(&g, &c, Ts, NULL, 0), SMS_OK);
        CHECK_STATUS(sms_generator_start(&g, (sms_real)q0, (sms_real)v0, (sms_real)a0, &t),
                     SMS_OK);
        n = sms_generator_arrival(&g);
        CHECK(n > 0 && n < 100000u);
        watch_start(&w, &g, q0);
        after = (uint64_t)(fabs(af) / J / Ts) + 3u; /* the acceleration back to zero */
        for (k = 1; k <= n + after; ++k) {
            sms_generator_step_target(&g, &t, out);
            watch_sample(&w, out);
            if (k == n) {
                int exact = out[0] == t.position && out[1] == t.velocity &&
                            out[2] == t.acceleration;
                CHECK(exact);
                landed += exact;
                CHECK(sms_generator_arrival(&g) == 0u);
            }
        }
        /* moving on: zero acceleration and the velocity it left, held */
        CHECK(out[2] == 0 && out[3] == 0);
        CHECK_CLOSE(out[1], vf + af * fabs(af) / (2.0 * J), 64.0 * U, V);
        watch_check(&w);
    }
    printf("moving targets [%s]: %d of %d exactly on their arrival sample\n",
           SMS_TEST_PRECISION, landed, trials);
}

/* A move stretched to a minimum duration Tmin (a random fraction of up to 3x the optimum):
 * the target state exactly on the arrival sample N, N Ts >= Tmin and N at least the
 * optimum's; a target at rest with Tmin at most the optimum arrives as without it; every
 * bound at every sample. The velocity interface too (its velocity reached on sample N). */
static void test_minimum_duration(int trials)
{
    int trial, landed = 0, beyond = 0;
    for (trial = 0; trial < trials; ++trial) {
        const double V = pow(10.0, 2.0 * urand() - 1.0), A = V * pow(10.0, 3.0 * urand() - 1.0);
        const double J = A * pow(10.0, 3.0 * urand() - 1.0), scale = V * (V / A + A / J);
        const double Ts = (V / A + A / J + V / (V + 1.0)) / (20.0 + 400.0 * urand());
        const int kind = trial % 3; /* 0: at rest, 1: moving, 2: velocity interface */
        sms_generator_config c = config(V, A, J, SMS_PROFILE_POLYNOMIAL);
        sms_generator g;
        sms_target t;
        sms_real out[4];
        double v0, a0, vf = 0, af = 0, q0 = (urand() - 0.5) * scale, Tmin;
        uint64_t n, n0, k, after;
        watch w;
        random_state(V, A, J, 0, &v0, &a0);
        if (kind > 0)
            random_state(V, A, J, 1, &vf, &af);
        t = target(kind == 2 ? SMS_INTERFACE_VELOCITY : SMS_INTERFACE_POSITION,
                   kind == 2 ? 0.0 : q0 + (urand() - 0.5) * 6.0 * scale, vf, af);
        CHECK_STATUS(sms_generator_init(&g, &c, Ts, NULL, 0), SMS_OK);
        CHECK_STATUS(sms_generator_start(&g, (sms_real)q0, (sms_real)v0, (sms_real)a0, &t),
                     SMS_OK);
        n0 = sms_generator_arrival(&g);
        Tmin = 3.0 * urand() * (double)(n0 + 1u) * Ts;
        t.minimum_duration = (sms_real)Tmin;
        CHECK_STATUS(sms_generator_start(&g, (sms_real)q0, (sms_real)v0, (sms_real)a0, &t),
                     SMS_OK);
        n = sms_generator_arrival(&g);
        CHECK(n >= n0 && n < 1000000u);
        CHECK((double)n * Ts >= (double)t.minimum_duration * (1.0 - 64.0 * U));
        if (!((double)n * Ts >= (double)t.minimum_duration * (1.0 - 64.0 * U)))
            printf("kind %d n %lu n0 %lu Tmin/Ts %.17g v0 %.17g a0 %.17g vf %.17g af %.17g V %.17g A %.17g J %.17g Ts %.17g\n", kind,
                   (unsigned long)n, (unsigned long)n0, Tmin / Ts, v0, a0, vf, af, V, A, J, Ts);
        if ((double)t.minimum_duration <= (double)(n0 - 1u) * Ts && kind == 0)
            CHECK(n == n0);
        if ((double)n * Ts > (double)t.minimum_duration + 2.0 * Ts &&
            (double)n * Ts > (double)n0 * Ts + 2.0 * Ts)
            ++beyond; /* past a blocked interval */
        watch_start(&w, &g, q0);
        after = (uint64_t)(fabs(af) / J / Ts) + 3u;
        for (k = 1; k <= n + after; ++k) {
            sms_generator_step_target(&g, &t, out);
            watch_sample(&w, out);
            if (k == n) {
                /* (the velocity interface not stretched arrives between samples) */
                int exact = out[1] == t.velocity && out[2] == t.acceleration &&
                            (kind == 2 || out[0] == t.position);
                int stretched = kind < 2 || (double)t.minimum_duration > (double)n0 * Ts;
                CHECK(exact || !stretched);
                landed += exact;
            }
        }
        CHECK(out[2] == 0 && out[3] == 0);
        watch_check(&w);
    }
    printf("minimum duration [%s]: %d of %d exactly on their arrival sample, %d past a "
           "blocked duration\n", SMS_TEST_PRECISION, landed, trials, beyond);
}

/* A minimum duration given on the ramp into the cruise (or on the cruise itself): the start's
 * acceleration returns to zero on vmax to the rounding of the running plan, the farthest
 * motion back cruises from there, so the stretched motion exists and the target rests on its
 * sample N (the first with N Ts at or after the minimum), never on the time-optimal one. */
static void test_minimum_duration_into_the_cruise(void)
{
    static const double lim[][4] = {/* vmax, amax, jmax, target */
                                    {1.0, 10.0, 100.0, -0.5}, {2.0, 10.0, 50.0, -1.0},
                                    {2.0, 5.0, 300.0, 1.0},   {3.0, 10.0, 100.0, -2.0},
                                    {3.0, 20.0, 300.0, 1.0},  {2.0, 10.0, 300.0, -0.5}};
    const double Ts = 1e-3;
    size_t i;
    int cases = 0;
    for (i = 0; i < sizeof lim / sizeof lim[0]; ++i) {
        const double V = lim[i][0], A = lim[i][1], J = lim[i][2];
        sms_generator_config c = config(V, A, J, SMS_PROFILE_POLYNOMIAL);
        sms_target t = target(SMS_INTERFACE_POSITION, lim[i][3], 0, 0);
        sms_generator g;
        sms_real out[4];
        /* the first sample of the cruise: the ramps up and down to a = amax, then the
         * velocity's rest on amax (every case here reaches amax and vmax) */
        const uint64_t cruise = (uint64_t)((2.0 * A / J + (V - A * A / J) / A) / Ts + 0.5);
        uint64_t k, m, n, opt;
        for (k = cruise - 6u; k <= cruise + 2u; ++k) {
            CHECK_STATUS(sms_generator_init(&g, &c, Ts, NULL, 0), SMS_OK);
            t.minimum_duration = 0;
            for (m = 0; m < k; ++m)
                sms_generator_step_target(&g, &t, out);
            opt = sms_generator_arrival(&g);
            t.minimum_duration = (sms_real)((double)(opt + 500u) * Ts);
            sms_generator_step_target(&g, &t, out);
            n = sms_generator_arrival(&g);
            /* N = opt + 500 samples after the one before this (within a sample of rounding
             * of N Ts), this sample being the first */
            CHECK(n + 1u >= opt + 500u && n + 1u <= opt + 501u);
            if (!(n + 1u >= opt + 500u && n + 1u <= opt + 501u))
                printf("into the cruise: vmax %g amax %g jmax %g at sample %lu: arrival %lu, "
                       "the minimum asks %lu\n", V, A, J, (unsigned long)k, (unsigned long)n,
                       (unsigned long)(opt + 499u));
            for (m = 0; m < n; ++m)
                sms_generator_step_target(&g, &t, out);
            CHECK(out[0] == t.position && out[1] == 0 && out[2] == 0);
            ++cases;
        }
    }
    printf("minimum duration into the cruise [%s]: %d cases\n", SMS_TEST_PRECISION, cases);
}

/* Invalid minimum durations are refused naming the field (SMS_ERR_DURATION), nothing changed;
 * a stop ignores it; the trigonometric profile takes 0 only. */
static void test_minimum_duration_refusals(void)
{
    static const double bad[] = {-1e-9, 1e300};
    sms_generator_config c = config(1.0, 10.0, 100.0, SMS_PROFILE_POLYNOMIAL);
    sms_generator_config ct = config(1.0, 10.0, 100.0, SMS_PROFILE_TRIGONOMETRIC);
    sms_generator g, copy;
    sms_target t = target(SMS_INTERFACE_POSITION, 0.5, 0, 0);
    sms_real out[4];
    size_t i;
    CHECK_STATUS(sms_generator_init(&g, &c, 1e-3, NULL, 0), SMS_OK);
    for (i = 0; i < 4; ++i) {
        t.minimum_duration = i < 2 ? (sms_real)bad[i] : i == 2 ? (sms_real)NAN : (sms_real)INFINITY;
        CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_ERR_DURATION);
        copy = g;
        CHECK_STATUS(sms_generator_start(&g, 0, 0, 0, &t), SMS_ERR_DURATION);
        CHECK(memcmp(&copy, &g, sizeof g) == 0);
        sms_generator_step_target(&g, &t, out); /* ignored: at rest on 0 */
        CHECK(out[0] == 0 && out[1] == 0);
    }
    t.interface = SMS_INTERFACE_STOP;
    CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_OK);
    t.interface = SMS_INTERFACE_POSITION;
    t.minimum_duration = 0.25;
    CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_OK);
    CHECK_STATUS(sms_generator_init(&g, &ct, 1e-3, NULL, 0), SMS_OK);
    CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_ERR_DURATION);
    t.minimum_duration = 0;
    CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_OK);
}

/* A staircase of every kind of target, changed every 1 to 120 samples: every bound at every
 * sample; the last (a position at rest) is rested on exactly. */
static void test_mixed_staircase(sms_profile profile, unsigned seed)
{
    const double V = 1.3, A = 7.0, J = 90.0, Ts = 1.7e-3;
    sms_generator_config c = config(V, A, J, profile);
    sms_generator g;
    sms_target t = target(SMS_INTERFACE_POSITION, 0, 0, 0);
    sms_real out[4];
    long k, next = 0;
    watch w;
    rng = seed;
    CHECK_STATUS(sms_generator_init(&g, &c, Ts, NULL, 0), SMS_OK);
    watch_start(&w, &g, 0.0);
    for (k = 0; k < 20000; ++k) {
        if (k == next) {
            double u = urand(), v, a;
            int trig = profile == SMS_PROFILE_TRIGONOMETRIC;
            random_state(V, A, J, 1, &v, &a);
            if (trig)
                a = 0.0;
            if (u < 0.5)
                t = target(SMS_INTERFACE_POSITION, (urand() - 0.5) * 4.0, trig ? 0.0 : v, a);
            else if (u < 0.85)
                t = target(SMS_INTERFACE_VELOCITY, 0.0, v, a);
            else
                t = target(SMS_INTERFACE_STOP, 0.0, 0.0, 0.0);
            CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_OK);
            next = k + 1 + (long)(urand() * 120.0);
        }
        sms_generator_step_target(&g, &t, out);
        watch_sample(&w, out);
    }
    t = target(SMS_INTERFACE_POSITION, 0.25, 0, 0);
    for (k = 0; k < 4000; ++k) {
        sms_generator_step_target(&g, &t, out);
        watch_sample(&w, out);
    }
    CHECK(out[0] == t.position && out[1] == 0 && out[2] == 0 && out[3] == 0);
    CHECK(g.dropped == 0);
    watch_check(&w);
}

/* The velocity interface reaches its velocity and holds it exactly; a stop rests exactly. */
static void test_velocity_and_stop(void)
{
    sms_generator_config c = config(2.0, 5.0, 40.0, SMS_PROFILE_POLYNOMIAL);
    sms_generator g;
    sms_target t = target(SMS_INTERFACE_VELOCITY, 123.0, 1.5, 0.0); /* position ignored */
    sms_real out[4];
    uint64_t n;
    int k;
    CHECK_STATUS(sms_generator_init(&g, &c, 1e-3, NULL, 0), SMS_OK);
    sms_generator_step_target(&g, &t, out);
    n = sms_generator_arrival(&g);
    CHECK(n > 0);
    for (k = 0; k < (int)n + 100; ++k)
        sms_generator_step_target(&g, &t, out);
    CHECK(out[1] == (sms_real)1.5 && out[2] == 0 && out[3] == 0);
    t = target(SMS_INTERFACE_STOP, 0.0, 0.7, 0.3); /* velocity and acceleration ignored */
    for (k = 0; k < 2000; ++k)
        sms_generator_step_target(&g, &t, out);
    CHECK(out[1] == 0 && out[2] == 0 && out[3] == 0);
    {
        /* the stop lasts ruckig's braking duration: from (1.5, 0) with 5, 40 it brakes through
         * -amax: 1.5 = 5 t2 + 25/40, t = 2 (5/40) + 0.175 = 0.425 s: 425 samples */
        sms_generator h;
        sms_real q;
        CHECK_STATUS(sms_generator_init(&h, &c, 1e-3, NULL, 0), SMS_OK);
        CHECK_STATUS(sms_generator_start(&h, 0, (sms_real)1.5, 0, NULL), SMS_OK);
        CHECK(sms_generator_arrival(&h) == 425u);
        for (k = 0; k < 425; ++k)
            sms_generator_step_target(&h, &t, out);
        CHECK(out[1] == 0 && out[2] == 0);
        q = out[0];
        sms_generator_step_target(&h, &t, out);
        CHECK(out[0] == q);
    }
}

/* Every refusal names its field, in O(1), and leaves the generator as it was. */
static void test_refusals(void)
{
    sms_generator_config c = config(1.0, 10.0, 100.0, SMS_PROFILE_POLYNOMIAL);
    sms_generator_config ct = config(1.0, 10.0, 100.0, SMS_PROFILE_TRIGONOMETRIC);
    sms_generator g, copy, trig;
    sms_target t, list[3];
    sms_real out[4];
    size_t index;
    int k;
    CHECK_STATUS(sms_generator_init(&g, &c, 1e-3, NULL, 0), SMS_OK);
    CHECK_STATUS(sms_generator_init(&trig, &ct, 1e-3, NULL, 0), SMS_OK);
    t = target(SMS_INTERFACE_POSITION, 0.5, 0, 0);
    for (k = 0; k < 100; ++k)
        sms_generator_step_target(&g, &t, out);
    t = target(7, 0, 0, 0);
    CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_ERR_INTERFACE);
    t = target(SMS_INTERFACE_POSITION, NAN, 0, 0);
    CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_ERR_TARGET_POSITION);
    t = target(SMS_INTERFACE_VELOCITY, NAN, 0.5, 0); /* position ignored */
    CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_OK);
    t = target(SMS_INTERFACE_POSITION, 0, 1.01, 0);
    CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_ERR_TARGET_VELOCITY);
    t = target(SMS_INTERFACE_POSITION, 0, INFINITY, 0);
    CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_ERR_TARGET_VELOCITY);
    t = target(SMS_INTERFACE_VELOCITY, 0, 0, 10.5);
    CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_ERR_TARGET_ACCELERATION);
    /* a = 4 adds 16/200 = 0.08 either way: v = 0.93 passes vmax after, v = -0.93 before */
    t = target(SMS_INTERFACE_POSITION, 0, 0.93, 4.0);
    CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_ERR_TARGET_ACCELERATION);
    t = target(SMS_INTERFACE_POSITION, 0, -0.93, 4.0);
    CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_ERR_TARGET_ACCELERATION);
    t = target(SMS_INTERFACE_POSITION, 0, 0.91, 4.0);
    CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_OK);
    t = target(SMS_INTERFACE_STOP, NAN, NAN, NAN); /* a stop takes nothing else */
    CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_OK);
    /* the trigonometric profile: position targets at rest, velocity targets at a = 0 */
    t = target(SMS_INTERFACE_POSITION, 0, 0.5, 0);
    CHECK_STATUS(sms_generator_check_target(&trig, &t), SMS_ERR_TARGET_VELOCITY);
    t = target(SMS_INTERFACE_VELOCITY, 0, 0.5, 0);
    CHECK_STATUS(sms_generator_check_target(&trig, &t), SMS_OK);
    t = target(SMS_INTERFACE_VELOCITY, 0, 0.5, 1.0);
    CHECK_STATUS(sms_generator_check_target(&trig, &t), SMS_ERR_TARGET_ACCELERATION);
    list[0] = target(SMS_INTERFACE_POSITION, 1, 0, 0);
    list[1] = target(SMS_INTERFACE_VELOCITY, 0, 0.2, 0);
    list[2] = target(SMS_INTERFACE_POSITION, 1, 0, 11.0);
    CHECK_STATUS(sms_generator_check_targets(&g, list, 3, &index), SMS_ERR_TARGET_ACCELERATION);
    CHECK(index == 2);
    CHECK_STATUS(sms_generator_check_targets(&g, list, 2, &index), SMS_OK);
    CHECK(index == 2);
    CHECK_STATUS(sms_generator_check_targets(&g, NULL, 1, &index), SMS_ERR_NULL);
    /* an invalid target on the per-sample path is ignored: the previous one is kept */
    copy = g;
    {
        sms_generator twin = g;
        sms_real o2[4];
        sms_target bad = target(SMS_INTERFACE_POSITION, 0, 3.0, 0);
        t = target(SMS_INTERFACE_POSITION, 0.5, 0, 0);
        for (k = 0; k < 50; ++k) {
            sms_generator_step_target(&g, &bad, out);
            sms_generator_step_target(&twin, &t, o2);
            CHECK(memcmp(out, o2, sizeof out) == 0);
        }
    }
    g = copy;
    /* start: the state's velocity and acceleration named, nothing changed */
    CHECK_STATUS(sms_generator_start(&g, 0, (sms_real)1.5, 0, NULL), SMS_ERR_TARGET_VELOCITY);
    CHECK_STATUS(sms_generator_start(&g, 0, 0, 20, NULL), SMS_ERR_TARGET_ACCELERATION);
    CHECK_STATUS(sms_generator_start(&g, 0, (sms_real)0.9, 5, NULL), SMS_ERR_TARGET_ACCELERATION);
    CHECK_STATUS(sms_generator_start(&g, NAN, 0, 0, NULL), SMS_ERR_TARGET_POSITION);
    t = target(SMS_INTERFACE_POSITION, 0, 2.0, 0);
    CHECK_STATUS(sms_generator_start(&g, 0, 0, 0, &t), SMS_ERR_TARGET_VELOCITY);
    t = target(SMS_INTERFACE_POSITION, 1e30, 0, 0); /* beyond 2^52 samples at vmax 1 */
    CHECK_STATUS(sms_generator_start(&g, 0, 0, 0, &t), SMS_ERR_TOO_LONG);
    CHECK(memcmp(&copy, &g, sizeof g) == 0);
}

/* hold_target equals its steps, and a state saved mid-motion continues bit for bit, for a
 * moving target and a velocity target, with and without a tuned stage. */
static void test_hold_and_state(void)
{
    static sms_real ring[40000];
    static double state[4 * 40000];
    int mode;
    for (mode = 0; mode < 2; ++mode) {
        sms_generator_config c = config(1.0, 10.0, 100.0, SMS_PROFILE_POLYNOMIAL);
        sms_generator a, b;
        sms_target t[3];
        sms_real oa[4], ob[4];
        size_t need = 0, n;
        int which, k;
        c.wn = mode ? 40.0 : 0.0;
        CHECK_STATUS(sms_generator_buffer_size(&c, 1e-3, &need), SMS_OK);
        CHECK(2 * need <= sizeof ring / sizeof ring[0]);
        CHECK_STATUS(sms_generator_init(&a, &c, 1e-3, ring, need), SMS_OK);
        CHECK_STATUS(sms_generator_init(&b, &c, 1e-3, ring + need, need), SMS_OK);
        t[0] = target(SMS_INTERFACE_POSITION, 0.6, -0.4, 2.0);
        t[1] = target(SMS_INTERFACE_POSITION, -0.3, 0, 0);
        t[1].minimum_duration = (sms_real)1.2345; /* saved with the target, not re-planned */
        t[2] = target(SMS_INTERFACE_VELOCITY, 0, -0.7, 0);
        for (which = 0; which < 3; ++which) {
            for (k = 0; k < 37; ++k)
                sms_generator_step_target(&a, &t[which], oa);
            n = sms_generator_state_count(&a);
            CHECK(n <= sizeof state / sizeof state[0]);
            sms_generator_get_state(&a, state);
            CHECK_STATUS(sms_generator_set_state(&b, state, n), SMS_OK);
            for (k = 0; k < 3000; ++k)
                sms_generator_step_target(&a, &t[which], oa);
            sms_generator_hold_target(&b, &t[which], 3000u, ob);
            CHECK(memcmp(oa, ob, sizeof oa) == 0);
        }
        /* a saved target not in canonical form is refused */
        sms_generator_get_state(&a, state);
        state[SMS_GENERATOR_IDENTITY_COUNT + SMS_GENERATOR_STATE_TARGET] = 5.0; /* velocity: position 0 */
        CHECK_STATUS(sms_generator_check_state(&a, state, sms_generator_state_count(&a)),
                     SMS_ERR_STATE);
        sms_generator_get_state(&a, state);
        state[SMS_GENERATOR_IDENTITY_COUNT + SMS_GENERATOR_STATE_TARGET + 3] = 2.0; /* a stop */
        CHECK_STATUS(sms_generator_check_state(&a, state, sms_generator_state_count(&a)),
                     SMS_ERR_STATE);
    }
}

/* Asymmetric limits (vmin, amin): refusals at init naming the bound, targets and start states
 * beyond a lower bound refused with the generator unchanged, a random sequence of every kind
 * of target with every sample within [vmin, vmax], [amin, amax], |j| <= jmax (v and a held
 * to their bounds exactly; j to 32 u), hold equal to stepping bit for bit, and the saved
 * state refused by the symmetric generator naming the velocity bound. */
static void test_asymmetric(unsigned seed)
{
    sms_generator g, h, s;
    sms_generator_config c = config(1.0, 10.0, 100.0, SMS_PROFILE_POLYNOMIAL), bad;
    sms_generator_reach_info r;
    sms_target t;
    sms_real out[4], out2[4];
    double state[64], before[64], vmin = -0.25, amin = -2.5;
    int i, k, worst_v = 0, worst_a = 0, worst_j = 0;
    size_t n;
    rng = seed;
    c.vmin = vmin;
    c.amin = amin;
    /* refusals at init, O(1), naming the bound */
    bad = c;
    bad.vmin = 0.5;
    CHECK_STATUS(sms_generator_reach(&bad, 1e-3, &r), SMS_ERR_LIMIT);
    CHECK(r.quantity != NULL && strcmp(r.quantity, "vmin") == 0);
    bad = c;
    bad.amin = NAN;
    CHECK_STATUS(sms_generator_init(&g, &bad, 1e-3, NULL, 0), SMS_ERR_LIMIT);
    CHECK_STATUS(sms_generator_reach(&bad, 1e-3, &r), SMS_ERR_LIMIT);
    CHECK(r.quantity != NULL && strcmp(r.quantity, "amin") == 0);
    bad = c;
    bad.profile = SMS_PROFILE_TRIGONOMETRIC;
    CHECK_STATUS(sms_generator_reach(&bad, 1e-3, &r), SMS_ERR_LIMIT);
    CHECK(r.quantity != NULL && strcmp(r.quantity, "vmin") == 0 &&
          strcmp(r.arguments, "vmin, profile") == 0);
    bad.vmin = -bad.vmax;
    bad.amin = -bad.amax;
    CHECK_STATUS(sms_generator_reach(&bad, 1e-3, NULL), SMS_OK); /* explicit symmetric bounds */
    bad = c;
    bad.vmin = -1e-200; /* double: reaching vmin covers a distance below the smallest normal
                         * over eps; float: vmin itself below the smallest normal */
    CHECK_STATUS(sms_generator_reach(&bad, 1e-3, &r), SMS_ERR_LIMIT);
    CHECK(r.quantity != NULL &&
          strcmp(r.quantity, sizeof(sms_real) == 4 ? "vmin" : "the distance to reach vmin") == 0);

    CHECK_STATUS(sms_generator_init(&g, &c, 1e-3, NULL, 0), SMS_OK);
    CHECK(g.asymmetric == 1 && g.vmin == (sms_real)vmin && g.amin == (sms_real)amin);
    /* targets and states beyond a lower bound: refused, nothing changed */
    for (k = 0; k < 300; ++k)
        sms_generator_step(&g, (sms_real)0.4, out);
    n = sms_generator_state_count(&g);
    CHECK(n <= 64);
    sms_generator_get_state(&g, before);
    t = target(SMS_INTERFACE_VELOCITY, 0.0, -0.3, 0.0);
    CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_ERR_TARGET_VELOCITY);
    t = target(SMS_INTERFACE_POSITION, 0.0, 0.0, -3.0);
    CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_ERR_TARGET_ACCELERATION);
    t = target(SMS_INTERFACE_POSITION, 0.0, -0.2, 5.0); /* way in at -0.325 */
    CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_ERR_TARGET_ACCELERATION);
    t = target(SMS_INTERFACE_POSITION, 0.0, 0.0, 0.0);
    CHECK_STATUS(sms_generator_start(&g, 0, (sms_real)-0.3, 0, &t), SMS_ERR_TARGET_VELOCITY);
    CHECK_STATUS(sms_generator_start(&g, 0, (sms_real)-0.24, (sms_real)-2.4, &t),
                 SMS_ERR_TARGET_ACCELERATION); /* braking passes -0.2688 */
    CHECK_STATUS(sms_generator_start(&g, 0, 0, (sms_real)-3.0, &t), SMS_ERR_TARGET_ACCELERATION);
    sms_generator_get_state(&g, state);
    CHECK(memcmp(state, before, n * sizeof(double)) == 0);

    /* every kind of target, held 1..150 samples: every sample within the bounds */
    sms_generator_reset(&g, 0);
    h = g;
    for (i = 0; i < 40; ++i) {
        int kind = (int)(urand() * 3.0), hold = 1 + (int)(urand() * 150.0);
        double v, a;
        for (;;) {
            double rr;
            v = vmin + (1.0 - vmin) * urand();
            a = amin + (10.0 - amin) * urand();
            rr = a * fabs(a) / 200.0;
            if (v - rr >= vmin && v - rr <= 1.0 && v + rr >= vmin && v + rr <= 1.0)
                break;
        }
        t = target(kind == 1 ? SMS_INTERFACE_VELOCITY : kind == 2 ? SMS_INTERFACE_STOP
                                                                   : SMS_INTERFACE_POSITION,
                   4.0 * urand() - 2.0, v, a);
        CHECK_STATUS(sms_generator_check_target(&g, &t), SMS_OK);
        for (k = 0; k < hold; ++k) {
            sms_generator_step_target(&g, &t, out);
            if (!(out[1] >= (sms_real)vmin && out[1] <= (sms_real)1.0))
                ++worst_v;
            if (!(out[2] >= (sms_real)amin && out[2] <= (sms_real)10.0))
                ++worst_a;
            if (!(fabs((double)out[3]) <= 100.0 * (1.0 + BOUND_TOL)))
                ++worst_j;
        }
        sms_generator_hold_target(&h, &t, (uint64_t)hold, out2);
        CHECK(memcmp(out, out2, sizeof out) == 0);
    }
    CHECK(worst_v == 0);
    CHECK(worst_a == 0);
    CHECK(worst_j == 0);
    /* to rest, far below: the descent cruises at vmin exactly */
    t = target(SMS_INTERFACE_POSITION, -5.0, 0.0, 0.0);
    for (k = 0; k < 40000; ++k) { /* at most 7 units at 0.25 unit/s, and the stop */
        sms_generator_step_target(&g, &t, out);
        if (k == 6000)
            CHECK(out[1] == (sms_real)vmin && out[2] == 0);
    }
    CHECK(out[0] == (sms_real)-5.0 && out[1] == 0 && out[2] == 0 && out[3] == 0);

    /* the saved state: the symmetric generator refuses it naming the velocity bound; the
     * same configuration continues bit for bit */
    sms_generator_get_state(&g, state);
    n = sms_generator_state_count(&g);
    CHECK_STATUS(sms_generator_init(&s, &bad, 1e-3, NULL, 0), SMS_ERR_LIMIT);
    c.vmin = 0.0;
    CHECK_STATUS(sms_generator_init(&s, &c, 1e-3, NULL, 0), SMS_OK);
    CHECK_STATUS(sms_generator_set_state(&s, state, n), SMS_ERR_STATE_VMAX);
    c.vmin = vmin;
    c.amin = 0.0;
    CHECK_STATUS(sms_generator_init(&s, &c, 1e-3, NULL, 0), SMS_OK);
    CHECK_STATUS(sms_generator_set_state(&s, state, n), SMS_ERR_STATE_AMAX);
    c.amin = amin;
    CHECK_STATUS(sms_generator_init(&s, &c, 1e-3, NULL, 0), SMS_OK);
    CHECK_STATUS(sms_generator_set_state(&s, state, n), SMS_OK);
    t = target(SMS_INTERFACE_POSITION, 0.7, 0.0, 0.0);
    for (k = 0; k < 3000; ++k) {
        sms_generator_step_target(&g, &t, out);
        sms_generator_step_target(&s, &t, out2);
        CHECK(memcmp(out, out2, sizeof out) == 0);
    }
    printf("asymmetric limits [%s]: every sample within [vmin, vmax], [amin, amax], jmax\n",
           sizeof(sms_real) == 4 ? "float" : "double");
}

int main(void)
{
    test_moving_targets(300);
    test_mixed_staircase(SMS_PROFILE_POLYNOMIAL, 11u);
    test_mixed_staircase(SMS_PROFILE_TRIGONOMETRIC, 12u);
    test_velocity_and_stop();
    test_refusals();
    test_minimum_duration(300);
    test_minimum_duration_into_the_cruise();
    test_minimum_duration_refusals();
    test_hold_and_state();
    test_asymmetric(31u);
    return check_summary("test_generator_targets");
}
