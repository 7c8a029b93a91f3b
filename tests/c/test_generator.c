/* SPDX-License-Identifier: Apache-2.0 */
/* Online generator: bounds under adversarial staircases (fixed seeds), exact arrival,
 * time-optimal single moves for every profile, the tuned stage (convolution, arrival, the
 * mode's zero), state save/load, bad input. */
#include <float.h>
#include <stdlib.h>
#include <string.h>
#include "check.h"
#include "double_s.h"
#include "generator_campaign.h"

#define MAX_TABLE 40000
static sms_real table[MAX_TABLE];
static sms_real table2[MAX_TABLE];

#ifdef SMS_USE_FLOAT
#define SAMPLE_EPS 5.96e-8
#else
#define SAMPLE_EPS 1.11e-16
#endif

/* Reported v, a, j: within the limits to 32 u, the rounding of the plan's own values and of
 * the tuned stage's average (docs/sampled-limits.md, "What rounding adds"; at most 20.6 u in
 * float and 10 u in double over 38,626 cases of tests/bench/generator_rounding_bench.c). */
#define BOUND_TOL (32.0 * SAMPLE_EPS)

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
    c.vmin = 0.0; /* symmetric */
    c.amin = 0.0;
    c.qmin = c.qmax = 0.0; /* no position limits */
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
           4 * (long)g.stage_length + 10;
    for (k = 0; k < hold; ++k)
        sms_generator_step(&g, (sms_real)target, out);
    CHECK(out[0] == (sms_real)target);
    CHECK(out[1] == 0 && out[2] == 0 && out[3] == 0);
}

/* The random cases of generator_campaign.h (random limits, Ts coarse, fine and on the phase
 * grid, every profile, a mode on about half, adversarial targets): every reported v, a, j
 * within 32 u of its limit and every backward difference within its limit (1 + 1e-9) beyond
 * the positions' rounding, 2^i 16 u S / Ts^i (docs/sampled-limits.md, "What rounding adds";
 * tests/bench/generator_rounding_bench.c runs 100 times as many). */
static void test_bounds_random_limits(int trials)
{
    int trial, i;
    rng = 4242u;
    for (trial = 0; trial < trials; ++trial) {
        campaign_case k;
        double reported[4], beyond[4];
        campaign_draw(&k, urand, trial % 2);
        if (!campaign_run(&k, urand, SAMPLE_EPS, table, MAX_TABLE, reported, beyond, NULL,
                          NULL))
            continue;
        for (i = 1; i < 4; ++i) {
            CHECK(reported[i] <= 1.0 + BOUND_TOL);
            CHECK(beyond[i] <= 1.0 + 1e-9);
            if (!(reported[i] <= 1.0 + BOUND_TOL && beyond[i] <= 1.0 + 1e-9))
                fprintf(stderr, "random limits, trial %d, order %d: reported %.17g, sampled %.17g"
                                " of the limit (profile %d wn %g style %d)\n", trial, i,
                        reported[i], beyond[i], (int)k.config.profile, k.config.wn, k.style);
        }
    }
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

/* Random rest-to-rest moves (limits over four decades, lengths over five, Ts = T/20 ..
 * T/2020): the output rests exactly on the target from the first sample at or after the
 * profile's time-optimal duration, the textbook double-S at jerk jmax (polynomial) or at the
 * mean jerk (2/pi) jmax (trigonometric, which is also the trigonometric kinematic design's
 * duration, checked here). */
static void check_rest_to_rest_arrivals(sms_profile profile, unsigned seed, int trials)
{
    int trial;
    rng = seed;
    for (trial = 0; trial < trials; ++trial) {
        double v = exp(log(1e-2) + urand() * log(1e4)), a = v * exp(log(1e-1) + urand() * log(1e3));
        double j = a * exp(log(1e-1) + urand() * log(1e3)), T, h, Ts;
        int trig = profile == SMS_PROFILE_TRIGONOMETRIC;
        sms_generator g;
        sms_generator_config c;
        sms_real out[4];
        long k, arrive = -1, expect;
        h = v * (v / a + a / j) * exp(log(1e-4) + urand() * log(1e5));
        T = double_s_duration(h, v, a, trig ? j * 2.0 / 3.14159265358979323846 : j);
        if (trig) {
            double lim[3], Tk[3];
            size_t cnt;
            lim[0] = v;
            lim[1] = a;
            lim[2] = j;
            CHECK_STATUS(sms_kinematic_design(h, lim, 3, SMS_PROFILE_TRIGONOMETRIC, 0.0, 0.0, 0.0,
                                              Tk, 3, &cnt), SMS_OK);
            CHECK_CLOSE(Tk[0] + Tk[1] + Tk[2], T, 1e-9, T);
        }
        Ts = T / (20.0 + 2000.0 * urand());
        c = make_config(v, a, j, profile, 0.0, 0.0);
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
}

/* The trigonometric profile: half-cosine transitions of the acceleration. A rest-to-rest move
 * arrives on the first sample at or after the textbook double-S duration at jerk (2/pi) jmax,
 * which is also the trigonometric kinematic design's duration; the jerk peaks at jmax and is
 * continuous (it changes by at most jmax pi Ts / d per sample, d = (pi/2) amax/jmax the
 * shortest full transition), where the polynomial profile jumps by jmax. */
static void test_trigonometric(void)
{
    check_rest_to_rest_arrivals(SMS_PROFILE_TRIGONOMETRIC, 77u, 200);
    {
        /* h = 40, v = 250, a = 5000, j = 2e5 (reaches every bound): peaks and continuity */
        sms_generator g;
        sms_generator_config c = make_config(250.0, 5000.0, 200000.0, SMS_PROFILE_TRIGONOMETRIC,
                                             0.0, 0.0);
        double Ts = 1e-5, d = 0.5 * 3.14159265358979323846 * 5000.0 / 200000.0, peak[4] = {0};
        double dj = 0.0, prevj = 0.0;
        sms_real out[4];
        long k;
        if (build(&g, &c, Ts)) {
            for (k = 0; k < 40000; ++k) {
                int i;
                sms_generator_step(&g, 40, out);
                for (i = 0; i < 4; ++i)
                    if (fabs((double)out[i]) > peak[i])
                        peak[i] = fabs((double)out[i]);
                if (fabs((double)out[3] - prevj) > dj)
                    dj = fabs((double)out[3] - prevj);
                prevj = (double)out[3];
            }
            CHECK(out[0] == 40 && out[3] == 0);
            CHECK_CLOSE(peak[1], 250.0, 100 * SMS_TEST_REL_TOL, 250.0);
            CHECK_CLOSE(peak[2], 5000.0, 100 * SMS_TEST_REL_TOL, 5000.0);
            CHECK_CLOSE(peak[3], 200000.0, 1e-6, 200000.0);
            /* (plus the rounding of two jerk values from their series, ~40 ulps of jmax) */
            CHECK(dj <= 200000.0 * 3.14159265358979323846 * Ts / d * (1.0 + 1e-6) +
                            40.0 * SAMPLE_EPS * 200000.0);
        }
    }
}

/* With a mode, the output is the plan without the mode through the stage tuned to it: q, v, a
 * and j equal the convolution of the mode-free generator's outputs with the stage's taps
 * (sms_smoother_taps, in double), the output rests exactly on the target L - 1 samples after
 * the plan does, and the stage's zero cancels the mode: the transform of the output's
 * differences at z* = e^(s* Ts), s* = -zeta wn + j wd, vanishes. */
static void test_mode_stage(void)
{
    static const struct {
        sms_profile profile;
        sms_kind kind;
        double wn, zeta, Ts;
    } cases[] = {
        {SMS_PROFILE_POLYNOMIAL, SMS_RECTANGULAR, 40.0, 0.0, 1e-3},
        {SMS_PROFILE_POLYNOMIAL, SMS_RECTANGULAR, 61.3, 0.0, 0.37e-3},
        {SMS_PROFILE_DAMPED, SMS_EXPONENTIAL, 60.0, 0.05, 1e-3},
        {SMS_PROFILE_TRIGONOMETRIC, SMS_DAMPED_HARMONIC, 90.0, 0.02, 0.53e-3},
        {SMS_PROFILE_TRIGONOMETRIC, SMS_HARMONIC, 70.0, 0.0, 1e-3},
    };
    static double taps[4000], plain[4 * 3000];
    size_t ci;
    for (ci = 0; ci < sizeof cases / sizeof cases[0]; ++ci) {
        double Ts = cases[ci].Ts, wn = cases[ci].wn, zeta = cases[ci].zeta;
        double wd = wn * sqrt(1.0 - zeta * zeta), H = 0.37;
        sms_generator_config c = make_config(1.0, 10.0, 300.0, cases[ci].profile, wn, zeta);
        sms_generator_config c0 = make_config(1.0, 10.0, 300.0, cases[ci].profile, 0.0, 0.0);
        sms_stage_config sc = sms_stage_config_default(cases[ci].kind);
        sms_generator g, g0;
        sms_real out[4];
        size_t L = 0, need;
        long k, n = 3000, arrive = -1, arrive0 = -1, close = -1;
        double zr = 0.0, zi = 0.0, mag = 0.0, prev = 0.0, err = 0.0;
        if (cases[ci].profile == SMS_PROFILE_DAMPED)
            c0.profile = SMS_PROFILE_POLYNOMIAL; /* the damped profile's plan: linear ramps */
        sc.T = (cases[ci].profile == SMS_PROFILE_TRIGONOMETRIC ? 3.0 : 2.0) *
               3.14159265358979323846 / wd;
        sc.sigma = cases[ci].kind == SMS_RECTANGULAR ? 0.0 : -zeta * wn;
        sc.timing = SMS_TIMING_EXACT;
        CHECK_STATUS(sms_smoother_length(&sc, Ts, &L), SMS_OK);
        CHECK_STATUS(sms_smoother_taps(&sc, Ts, taps, L), SMS_OK);
        for (k = 0; k < (long)L; ++k)
            CHECK(taps[k] >= 0.0); /* an average: every bound carries over */
        CHECK_STATUS(sms_generator_buffer_size(&c0, Ts, &need), SMS_OK);
        CHECK(need == 0u);
        CHECK_STATUS(sms_generator_init(&g0, &c0, Ts, NULL, 0), SMS_OK);
        if (!build(&g, &c, Ts))
            continue;
        CHECK(g.stage_length == L);
        CHECK_CLOSE(sms_generator_tail_duration(&g), sc.T, 1e-15, sc.T);
        for (k = 0; k < n; ++k) {
            sms_generator_step(&g0, (sms_real)H, out);
            plain[4 * k] = out[0];
            plain[4 * k + 1] = out[1];
            plain[4 * k + 2] = out[2];
            plain[4 * k + 3] = out[3];
            if (arrive0 < 0 && out[0] == (sms_real)H && out[1] == 0 && out[2] == 0 &&
                out[3] == 0)
                arrive0 = k;
        }
        for (k = 0; k < n; ++k) {
            int ch;
            double ang = -wd * (double)k * Ts, grow = exp(zeta * wn * (double)k * Ts);
            sms_generator_step(&g, (sms_real)H, out);
            for (ch = 0; ch < 4; ++ch) {
                double conv = 0.0, scale = ch == 0 ? H : ch == 1 ? 1.0 : ch == 2 ? 10.0 : 300.0;
                size_t i;
                for (i = 0; i < L; ++i)
                    conv += taps[i] * (k >= (long)i ? plain[4 * (k - (long)i) + ch] : 0.0);
                if (fabs((double)out[ch] - conv) / scale > err)
                    err = fabs((double)out[ch] - conv) / scale;
                if (ch == 0 && fabs(conv - H) > (sizeof(sms_real) == sizeof(float) ? FLT_EPSILON : DBL_EPSILON) * H)
                    close = -1; /* the exact output is not yet within an ulp of the target */
                else if (ch == 0 && close < 0)
                    close = k;
            }
            /* at rest: j too (in float the stage's v and a can round to 0 a sample before
             * its j does) */
            if (arrive < 0 && out[0] == (sms_real)H && out[1] == 0 && out[2] == 0 &&
                out[3] == 0)
                arrive = k;
            /* sum of dq[k] z*^-k (dq[0] = q[0] - 0) */
            zr += ((double)out[0] - prev) * grow * cos(ang);
            zi += ((double)out[0] - prev) * grow * sin(ang);
            mag += fabs((double)out[0] - prev) * grow;
            prev = (double)out[0];
        }
#ifdef SMS_USE_FLOAT
        CHECK(err <= 1e-5);
        CHECK(hypot(zr, zi) <= 1e-5 * mag);
#else
        CHECK(err <= 1e-12);
        CHECK(hypot(zr, zi) <= 1e-12 * mag);
#endif
#ifdef SMS_USE_FLOAT
        /* In float the output may land on the target before the stage's length has passed: from
         * the first sample whose exact output is within an ulp of it (the last taps weigh a
         * remaining difference far below float's resolution), never later than that length. */
        CHECK(arrive0 > 0 && close >= 0 && arrive >= close && arrive <= arrive0 + (long)L - 1);
#else
        CHECK(arrive0 > 0 && arrive == arrive0 + (long)L - 1);
#endif
    }
}

/* A target just beyond the direct stop, from a state whose acceleration opposes the move
 * (v = 0.5, a = -2 with vmax 1, amax 10, jmax 100: the stop from `after` = v + a|a|/(2 J)):
 * the planner's peak velocity vp lies just above `after`, where the distance covered grows
 * like the square root of vp - after, so neighbouring vp differ in distance by up to
 * 2 after sqrt(ulp(vp)/J) (1.7e-5 in float, 7e-10 in double here), far more than the rounding
 * of the positions. The stop is anchored on the target, so the plan jumped there (in float by
 * 100 ulps of q on random staircases), or, beyond 256 eps of the move, refused the target.
 * Now a cruise at vp covers what vp leaves: every target ratio below is planned, every sample
 * keeps the reported and sampled bounds (docs/sampled-limits.md) and lands on the target. */
static void replan_beyond_the_direct_stop(void)
{
    const double V = 1.0, A = 10.0, J = 100.0, v0 = 0.5, a0 = -2.0, Ts = 1e-3;
    int profile, k;
    for (profile = 0; profile < 2; ++profile) {
        /* the direct stop from (v0, a0): a to zero at the mean jerk Jm (a ramp, or a half
         * cosine whose position term has 1/4 - 1/pi^2 for 1/6), then the stop from `after`,
         * symmetric: after times half its duration 2 ap/Jm */
        const int trig = profile == 1;
        const double Jm = trig ? J * 2.0 / 3.14159265358979323846 : J;
        const double c3 = trig ? 0.25 - 1.0 / (3.14159265358979323846 * 3.14159265358979323846)
                               : 1.0 / 6.0;
        const double d = -a0 / Jm, after = v0 + a0 * fabs(a0) / (2.0 * Jm);
        const double dA = v0 * d + a0 * d * d / 2.0 + c3 * Jm * d * d * d +
                          after * sqrt(Jm * after) / Jm;
        sms_generator_config c = make_config(V, A, J, trig ? SMS_PROFILE_TRIGONOMETRIC
                                                          : SMS_PROFILE_POLYNOMIAL, 0.0, 0.0);
        for (k = 8; k <= (sizeof(sms_real) == sizeof(double) ? 52 : 24); k += 2) {
            sms_generator g;
            double st[SMS_GENERATOR_IDENTITY_COUNT + SMS_GENERATOR_PLAN_STATE_COUNT], *plan = st + SMS_GENERATOR_IDENTITY_COUNT;
            double prev[4] = {0, 0, 0, 0}, L[4], S, peak[4] = {0, 0, 0, 0}, over = 0.0;
            const sms_real target = (sms_real)(dA * (1.0 + ldexp(1.0, -k)));
            sms_real out[4];
            long m;
            int i;
            CHECK_STATUS(sms_generator_init(&g, &c, Ts, NULL, 0), SMS_OK);
            sms_generator_get_state(&g, st);
            /* heading for the direct stop */
            plan[SMS_GENERATOR_STATE_TARGET] = plan[SMS_GENERATOR_STATE_GOAL] = (double)(sms_real)dA;
            plan[SMS_GENERATOR_STATE_Q] = 0.0;
            plan[SMS_GENERATOR_STATE_V] = v0;
            plan[SMS_GENERATOR_STATE_A] = a0;
            plan[SMS_GENERATOR_STATE_K] = 0.0;
            CHECK_STATUS(sms_generator_set_state(&g, st, SMS_GENERATOR_IDENTITY_COUNT + SMS_GENERATOR_PLAN_STATE_COUNT),
                         SMS_OK);
            prev[0] = 0.0;
            prev[1] = -v0 * Ts; /* the samples before: q - v Ts, q - 2 v Ts + a Ts^2 ... */
            prev[2] = -2.0 * v0 * Ts + a0 * Ts * Ts;
            prev[3] = -3.0 * v0 * Ts + 4.5 * a0 * Ts * Ts;
            L[1] = V;
            L[2] = A;
            L[3] = J;
            S = 2.0 * fabs((double)target);
            for (m = 0; m < 2000; ++m) {
                double e[4], q;
                sms_generator_step(&g, target, out);
                CHECK(g.refused == 0);
                q = (double)out[0];
                /* backward differences over the samples q[m], q[m-1], q[m-2], q[m-3] */
                e[0] = q;
                e[1] = q - prev[0];
                e[2] = q - 2.0 * prev[0] + prev[1];
                e[3] = q - 3.0 * prev[0] + 3.0 * prev[1] - prev[2];
                for (i = 1; i < 4; ++i) {
                    double floor_ = ldexp(8.0 * SAMPLE_EPS * S, i) / pow(Ts, (double)i);
                    double r = (fabs(e[i]) / pow(Ts, (double)i) - floor_) / L[i];
                    if (m >= 3 && r > over)
                        over = r;
                    if (fabs((double)out[i]) / L[i] > peak[i])
                        peak[i] = fabs((double)out[i]) / L[i];
                }
                prev[2] = prev[1];
                prev[1] = prev[0];
                prev[0] = q;
            }
            CHECK(over <= 1.0 + 1e-9);
            if (!(over <= 1.0 + 1e-9))
                fprintf(stderr, "beyond the direct stop (profile %d, 2^-%d): a sampled difference"
                                " %.9g of its bound\n", profile, k, over);
            CHECK(peak[1] <= 1.0 + BOUND_TOL && peak[2] <= 1.0 + BOUND_TOL &&
                  peak[3] <= 1.0 + BOUND_TOL);
            CHECK(out[0] == target && out[1] == 0 && out[2] == 0 && out[3] == 0);
        }
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
    static double state[1000], bad[1000];
    size_t need, i, n_state;
    long k;
    int realisation;
    for (realisation = 0; realisation < 2; ++realisation) {
        /* a count that must be whole: 0: no mode (k is the last value); 1: a mode (the quiet
         * count follows k, then the four stage states) */
        size_t count_index = SMS_GENERATOR_IDENTITY_COUNT +
                             (realisation == 0 ? (size_t)SMS_GENERATOR_STATE_K
                                               : (size_t)SMS_GENERATOR_PLAN_STATE_COUNT);
        c.profile = realisation == 0 ? SMS_PROFILE_POLYNOMIAL : SMS_PROFILE_TRIGONOMETRIC;
        c.wn = realisation == 0 ? 0.0 : 90.0;
        if (!build(&g, &c, 1e-3))
            return;
        for (k = 0; k < 150; ++k)
            sms_generator_step(&g, 1, a);
        n_state = sms_generator_state_count(&g);
        CHECK(n_state <= sizeof state / sizeof state[0]);
        CHECK(n_state == SMS_GENERATOR_IDENTITY_COUNT + SMS_GENERATOR_PLAN_STATE_COUNT
                         + (realisation == 0 ? 0u
                                             : 1u + 4u * sms_smoother_state_count(&g.stage[0])));
        sms_generator_get_state(&g, state);
        h = g;
        for (i = 0; realisation == 1 && i < 4u * g.stage_window; ++i)
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
        bad[SMS_GENERATOR_IDENTITY_COUNT + SMS_GENERATOR_STATE_A] = NAN;
        CHECK_STATUS(sms_generator_check_state(&h, bad, n_state), SMS_ERR_STATE);
        CHECK_STATUS(sms_generator_set_state(&h, state, n_state - 1u), SMS_ERR_STATE);
    }
    c.profile = SMS_PROFILE_POLYNOMIAL;
    c.wn = 0.0;
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
    /* Ts up to SMS_TS_MAX (2^53 Ts must stay finite); the float build takes a Ts its floats
     * hold, the tighter bound there */
    CHECK_STATUS(sms_generator_buffer_size(&c, nextafter(SMS_TS_MAX, HUGE_VAL), &need),
                 sizeof(sms_real) == sizeof(double) ? SMS_ERR_SAMPLE_PERIOD_RANGE
                                                    : SMS_ERR_SAMPLE_PERIOD);
    CHECK_STATUS(sms_generator_buffer_size(&c, DBL_MAX, &need),
                 sizeof(sms_real) == sizeof(double) ? SMS_ERR_SAMPLE_PERIOD_RANGE
                                                    : SMS_ERR_SAMPLE_PERIOD);
    CHECK_STATUS(sms_generator_buffer_size(&c, sizeof(sms_real) == sizeof(double) ? SMS_TS_MAX
                                                                                  : 1e30, &need),
                 SMS_OK);
    CHECK_STATUS(sms_generator_buffer_size(&c, 0.5, &need), SMS_OK); /* any Ts: no stage */
    CHECK(need == 0u);
    c.profile = SMS_PROFILE_TRIGONOMETRIC;
    CHECK_STATUS(sms_generator_buffer_size(&c, 0.5, &need), SMS_OK);
    CHECK(need == 0u);
    c.profile = (sms_profile)7;
    CHECK_STATUS(sms_generator_buffer_size(&c, 1e-3, &need), SMS_ERR_KIND);
    c.profile = SMS_PROFILE_POLYNOMIAL;
    c.wn = -1.0;
    CHECK_STATUS(sms_generator_buffer_size(&c, 1e-3, &need), SMS_ERR_WN);
    c.wn = 0.0;
    CHECK_STATUS(sms_generator_buffer_size(NULL, 1e-3, &need), SMS_ERR_NULL);
    c.profile = SMS_PROFILE_DAMPED;
    CHECK_STATUS(sms_generator_buffer_size(&c, 1e-3, &need), SMS_ERR_WN);
    c.wn = 5000.0;
    CHECK_STATUS(sms_generator_buffer_size(&c, 1e-3, &need), SMS_ERR_ABOVE_NYQUIST);
    c.wn = 50.0;
    c.zeta = 1.0;
    CHECK_STATUS(sms_generator_buffer_size(&c, 1e-3, &need), SMS_ERR_ZETA);
    c = make_config(1.0, 10.0, 100.0, SMS_PROFILE_TRIGONOMETRIC, 90.0, 0.0);
    h = g;
    CHECK_STATUS(sms_generator_init(&g, &c, 1e-3, table, 10), SMS_ERR_BUFFER_TOO_SMALL);
    CHECK_STATUS(sms_generator_init(&g, &c, 1e-3, NULL, 0), SMS_ERR_NULL);
    CHECK(g.stage_length == h.stage_length && g.plan_q == h.plan_q && g.target.position == h.target.position);
}

/* A rest-to-rest move of any length arrives on the first sample at or after the
 * time-optimal duration, and stays there exactly. */
static void test_time_optimal_arrival(void)
{
    check_rest_to_rest_arrivals(SMS_PROFILE_POLYNOMIAL, 2024u, 300);
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

/* Float (and double) on moves of 2^24 and 2^30 samples, polynomial and trigonometric (half-
 * cosine transitions evaluated from their own start like any segment): the plan is sampled at its start,
 * around the arrival and in the cruise, jumping there through a saved state (a state carries
 * the samples since the plan's start): position within the rounding of the positions of the
 * exact closed form, mean speed over 1 s windows within vmax, arrival on time to the
 * rounding of the duration. */
static void test_long_moves(void)
{
    static const double n_samples[2] = {16777216.0, 1073741824.0};
    int m;
    for (m = 0; m < 4; ++m) {
        /* m = 0, 1: polynomial; 2, 3: trigonometric (transitions (pi/2) a/j long) */
        int trig = m >= 2;
        double Ts = 1e-4, v = 1.0, a = 10.0, j = 1000.0;
        double rise = v / a + (trig ? 0.5 * 3.14159265358979323846 : 1.0) * a / j;
        double T = n_samples[m % 2] * Ts, h = v * (T - rise); /* arrives at T */
        sms_generator g;
        sms_generator_config c = make_config(v, a, j, trig ? SMS_PROFILE_TRIGONOMETRIC
                                                           : SMS_PROFILE_POLYNOMIAL, 0.0, 0.0);
        double state[SMS_GENERATOR_IDENTITY_COUNT + SMS_GENERATOR_PLAN_STATE_COUNT], start_k;
        sms_real out[4], prev = 0;
        long k, arrive = -1;
        int probe;
        if (!build(&g, &c, Ts))
            continue;
        sms_generator_step(&g, (sms_real)h, out); /* the plan starts at sample 0 */
        CHECK(sms_generator_state_count(&g) == SMS_GENERATOR_IDENTITY_COUNT + SMS_GENERATOR_PLAN_STATE_COUNT);
        sms_generator_get_state(&g, state);
        for (probe = 0; probe < 3; ++probe) {
            /* probes: 1 s windows mid-cruise, a window 1 s before arrival, the arrival */
            start_k = probe == 0 ? floor(0.5 * n_samples[m % 2])
                                 : n_samples[m % 2] - (probe == 1 ? 20000.0 : 10000.0);
            state[SMS_GENERATOR_IDENTITY_COUNT + SMS_GENERATOR_STATE_K] = start_k;
            CHECK_STATUS(sms_generator_set_state(&g, state, SMS_GENERATOR_IDENTITY_COUNT + SMS_GENERATOR_PLAN_STATE_COUNT),
                         SMS_OK);
            sms_generator_step(&g, (sms_real)h, out);
            prev = out[0];
            for (k = 1; k <= (probe == 2 ? 20000 : 10000); ++k) {
                double t = (start_k + 1.0 + (double)k) * Ts, exact;
                sms_generator_step(&g, (sms_real)h, out);
                /* cruise: q = v (t - rise/2) after the velocity rise */
                if (probe < 2) {
                    exact = v * (t - 0.5 * rise);
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
        CHECK(fabs((double)arrive - n_samples[m % 2]) <= 1.0 + 8.0 * SAMPLE_EPS * n_samples[m % 2]);
        if (fabs((double)arrive - n_samples[m % 2]) > 1.0 + 8.0 * SAMPLE_EPS * n_samples[m % 2])
            fprintf(stderr, "long move %g: arrival %ld\n", n_samples[m % 2], arrive);
    }
}

/* A mode on a long move, float and double: the plan jumps (through a saved state) to 2^24 and
 * 2^30 samples into a cruise at vmax; after the tuned stage's rings have refilled (L + 5
 * samples) the output is the plan through the stage's taps, in a cruise the line
 * v (t - Ts sum i h_i) - v rise/2: within 64 ulps of the move (the drift-free smoother's
 * error stays at the rounding of its input's variation, whatever the run length). */
static void test_long_moves_through_the_stage(void)
{
    static const double n_samples[2] = {16777216.0, 1073741824.0};
    static double taps[2000];
    int m;
    for (m = 0; m < 2; ++m) {
        double Ts = 1e-4, v = 1.0, a = 10.0, j = 1000.0, wn = 40.0;
        double rise = v / a + a / j, T = n_samples[m] * Ts, h = v * (T - rise), lag = 0.0;
        sms_generator g;
        sms_generator_config c = make_config(v, a, j, SMS_PROFILE_POLYNOMIAL, wn, 0.0);
        sms_stage_config sc = sms_stage_config_default(SMS_RECTANGULAR);
        static double state[8000];
        sms_real out[4];
        size_t L = 0, i, n_state;
        long k, start_k;
        double err = 0.0;
        sc.T = 2.0 * 3.14159265358979323846 / wn;
        CHECK_STATUS(sms_smoother_length(&sc, Ts, &L), SMS_OK);
        CHECK_STATUS(sms_smoother_taps(&sc, Ts, taps, L), SMS_OK);
        for (i = 0; i < L; ++i)
            lag += (double)i * taps[i] * Ts;
        if (!build(&g, &c, Ts))
            continue;
        sms_generator_step(&g, (sms_real)h, out); /* the plan starts at sample 0 */
        n_state = sms_generator_state_count(&g);
        CHECK(n_state <= sizeof state / sizeof state[0]);
        sms_generator_get_state(&g, state);
        start_k = (long)floor(0.5 * n_samples[m]);
        state[SMS_GENERATOR_IDENTITY_COUNT + SMS_GENERATOR_STATE_K] = (double)(start_k - (long)L - 5);
        CHECK_STATUS(sms_generator_set_state(&g, state, n_state), SMS_OK);
        for (k = 0; k < (long)L + 5; ++k)
            sms_generator_step(&g, (sms_real)h, out);
        for (k = 0; k < 10000; ++k) {
            double t = (double)(start_k + 1 + k) * Ts, exact = v * (t - lag - 0.5 * rise);
            sms_generator_step(&g, (sms_real)h, out);
            if (fabs((double)out[0] - exact) > err)
                err = fabs((double)out[0] - exact);
            CHECK_CLOSE(out[1], v, 64 * SAMPLE_EPS, v);
        }
        CHECK(err <= 64.0 * SAMPLE_EPS * h);
        if (err > 64.0 * SAMPLE_EPS * h)
            fprintf(stderr, "long move through the stage %g: error %g\n", n_samples[m], err);
    }
}

/* Extreme but finite limits and targets (found by the FMI fuzzer): limits with which no plan
 * can reach vmax are refused at init (sms_generator_reach() says which quantity); within
 * feasible limits a move whose plan cannot be represented (a value overflowing, or more than
 * 2^52 samples long) is dropped. Every output stays finite, within vmax, amax, jmax and the
 * sampled velocity bound at every sample, and every saved state loads again and continues bit
 * for bit. */
static void test_extreme_limits_and_targets(void)
{
    static const double limits[][3] = {
        {1.7976931348623157e308, 9e-16, 3e-14}, /* vmax = DBL_MAX, tiny amax, jmax */
        {1.0, 10.0, 9e307},                     /* jmax near DBL_MAX */
        {1e300, 1e100, 1e5},                    /* vmax 1e300, targets 1e305 */
        {1.0, 1e-30, 1e-300},                   /* a move to 1e300 would jump 1e149 a sample */
        {1e-100, 1e-100, 1e-100},
        {1e150, 1e-150, 1e150},
    };
    static const double targets[] = {1e305, 1.0, -1e305, 1e300, 1.7976931348623157e308,
                                     -1.7976931348623157e308, 1e-300, 0.0, 3.5};
    static double state[64];
    size_t ci, ti, i, n_state;
    const double Ts = 1e-3;
    for (ci = 0; ci < sizeof limits / sizeof limits[0]; ++ci) {
        sms_generator g, h;
        sms_real out[4], prev = 0, o2[4];
        size_t need = 1;
        int profile;
        for (profile = 0; profile < 2; ++profile) {
            sms_generator_config c = make_config(limits[ci][0], limits[ci][1], limits[ci][2],
                                                 profile ? SMS_PROFILE_TRIGONOMETRIC
                                                         : SMS_PROFILE_POLYNOMIAL, 0.0, 0.0);
            sms_status st = sms_generator_buffer_size(&c, Ts, &need);
            sms_generator_reach_info r;
            CHECK_STATUS(sms_generator_reach(&c, Ts, &r), st);
            CHECK(st == SMS_OK || st == SMS_ERR_LIMIT);
            CHECK((st == SMS_OK) == (r.quantity == NULL));
            if (st != SMS_OK) {
                g.refused = 7; /* untouched on error */
                CHECK_STATUS(sms_generator_init(&g, &c, Ts, NULL, 0), SMS_ERR_LIMIT);
                CHECK(g.refused == 7);
                continue;
            }
            CHECK_STATUS(sms_generator_init(&g, &c, Ts, NULL, 0), SMS_OK);
            h = g;
            prev = 0;
            for (ti = 0; ti < sizeof targets / sizeof targets[0]; ++ti) {
                sms_real x = (sms_real)targets[ti];
                if (x - x != 0)
                    continue; /* beyond a float build's range: ignored anyway */
                for (i = 0; i < 40; ++i) {
                    double dq, q;
                    sms_generator_step(&g, x, out);
                    q = (double)out[0];
                    CHECK(out[0] - out[0] == 0 && out[1] - out[1] == 0 &&
                          out[2] - out[2] == 0 && out[3] - out[3] == 0);
                    CHECK(fabs((double)out[1]) <= c.vmax * (1.0 + BOUND_TOL));
                    CHECK(fabs((double)out[2]) <= c.amax * (1.0 + BOUND_TOL));
                    CHECK(fabs((double)out[3]) <= c.jmax * (1.0 + BOUND_TOL));
                    dq = fabs(q - (double)prev);
                    CHECK(dq <= c.vmax * Ts * (1.0 + BOUND_TOL) +
                                    4.0 * SAMPLE_EPS * (fabs(q) + fabs((double)prev)));
                    prev = out[0];
                    /* save, load into a copy, and both go on bit for bit */
                    if (i % 7 == 3) {
                        n_state = sms_generator_state_count(&g);
                        CHECK(n_state <= sizeof state / sizeof state[0]);
                        sms_generator_get_state(&g, state);
                        CHECK_STATUS(sms_generator_set_state(&h, state, n_state), SMS_OK);
                        sms_generator_step(&g, x, out);
                        sms_generator_step(&h, x, o2);
                        CHECK(out[0] == o2[0] && out[1] == o2[1] && out[2] == o2[2] &&
                              out[3] == o2[3]);
                        CHECK(fabs((double)out[0] - (double)prev) <=
                              c.vmax * Ts * (1.0 + BOUND_TOL) +
                                  4.0 * SAMPLE_EPS * (fabs((double)out[0]) + fabs((double)prev)));
                        prev = out[0];
                    }
                }
            }
        }
    }
    {
        /* feasible limits, a target 1e300 units away: a cruise of 1e294 s, more than 2^52
         * samples; it is dropped (counted once, the output rests), then a move to 1000 runs */
        sms_generator g;
        sms_generator_config c2 = make_config(1e6, 1e8, 1e10, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0);
        sms_real out[4] = {0, 0, 0, 0};
        CHECK_STATUS(sms_generator_init(&g, &c2, Ts, NULL, 0), SMS_OK);
        for (i = 0; i < 10; ++i) {
            sms_generator_step(&g, (sms_real)1e30, out); /* 1e30: also a float's */
            CHECK(out[0] == 0 && out[1] == 0 && out[2] == 0 && out[3] == 0);
            CHECK(g.refused == 1 && g.dropped == 1);
        }
        for (i = 0; i < 2000 && !(out[0] == 1000 && out[1] == 0); ++i) {
            sms_generator_step(&g, 1000, out);
            CHECK(g.refused == 0 && g.dropped == 1);
            CHECK(fabs((double)out[3]) <= c2.jmax * (1.0 + BOUND_TOL));
        }
        CHECK(out[0] == 1000 && out[1] == 0 && i > 10);
        /* a second dropped target counts again; reset clears both */
        sms_generator_step(&g, (sms_real)-1e30, out);
        CHECK(g.refused == 1 && g.dropped == 2 && out[0] == 1000);
        sms_generator_reset(&g, 0);
        CHECK(g.refused == 0 && g.dropped == 0);
    }
}

/* The largest and smallest normal numbers and the epsilon of sms_real (the test's own copy of
 * the documented region, trajectory.h sms_generator_reach()). */
#ifdef SMS_USE_FLOAT
#define R_MAX 3.4028234663852886e38
#define R_MIN 1.1754943508222875e-38
#define R_EPS 1.1920928955078125e-7
#else
#define R_MAX 1.7976931348623157e308
#define R_MIN 2.2250738585072014e-308
#define R_EPS 2.220446049250313e-16
#endif

/* Plan the move that reaches vmax from rest (and a reversal from full speed): both must be
 * planned (not dropped) with limits just inside the region. */
static void check_plans(const sms_generator_config *c, double Ts)
{
    sms_generator g;
    sms_generator_reach_info r;
    sms_real out[4];
    double st[SMS_GENERATOR_IDENTITY_COUNT + SMS_GENERATOR_PLAN_STATE_COUNT], *plan = st + SMS_GENERATOR_IDENTITY_COUNT;
    CHECK_STATUS(sms_generator_reach(c, Ts, &r), SMS_OK);
    CHECK_STATUS(sms_generator_init(&g, c, Ts, NULL, 0), SMS_OK);
    sms_generator_step(&g, (sms_real)r.distance, out);
    CHECK(g.refused == 0 && g.dropped == 0);
    /* it lasts its duration: the plan's end sample is duration/Ts rounded up (to rounding) */
    CHECK(fabs((double)g.plan.end + (double)g.plan.end_f / Ts - r.samples) <=
          1.0 + 1e-3 * r.samples);
    sms_generator_reset(&g, 0);
    sms_generator_step(&g, (sms_real)(r.distance * (sizeof(sms_real) == sizeof(float) ? 1.7e-10
                                                                                       : 1.3e-23)),
                       out); /* about 4 eps^1.5 h */
    CHECK(g.refused == 0);
    /* cruising at +vmax towards 2 h, the target jumps to -2 h (a state of this generator: its
     * identity, then the plan fields) */
    CHECK(sms_generator_state_count(&g) == SMS_GENERATOR_IDENTITY_COUNT + SMS_GENERATOR_PLAN_STATE_COUNT);
    sms_generator_get_state(&g, st);
    plan[SMS_GENERATOR_STATE_TARGET] = plan[SMS_GENERATOR_STATE_GOAL] =
        2.0 * (double)(sms_real)r.distance;
    plan[SMS_GENERATOR_STATE_Q] = 0.0;
    plan[SMS_GENERATOR_STATE_V] = (double)g.limits.vmax;
    plan[SMS_GENERATOR_STATE_A] = plan[SMS_GENERATOR_STATE_K] = 0.0;
    CHECK_STATUS(sms_generator_set_state(&g, st, SMS_GENERATOR_IDENTITY_COUNT + SMS_GENERATOR_PLAN_STATE_COUNT), SMS_OK);
    sms_generator_step(&g, (sms_real)(-2.0 * r.distance), out);
    CHECK(g.refused == 0);
}

/* Random limits and sample periods over the build's whole range (log-uniform): whenever init
 * accepts them, the move that reaches vmax, h/2, 3 h, 1e-9 h, eps^1.5 h and the reversal from
 * full speed are all planned (the documented promise of the region). */
static void test_feasible_random(void)
{
    const double span = sizeof(sms_real) == sizeof(double) ? 300.0 : 37.0;
    size_t i, accepted = 0;
    for (i = 0; i < 4000; ++i) {
        double e[4];
        size_t k;
        sms_generator_config c;
        sms_generator_reach_info r;
        for (k = 0; k < 4; ++k)
            e[k] = pow(10.0, span * (2.0 * urand() - 1.0));
        c = make_config(e[0], e[1], e[2], urand() < 0.5 ? SMS_PROFILE_TRIGONOMETRIC
                                                         : SMS_PROFILE_POLYNOMIAL, 0.0, 0.0);
        if (sms_generator_reach(&c, e[3], &r) != SMS_OK)
            continue;
        ++accepted;
        check_plans(&c, e[3]);
        {
            static const double part[] = {0.5, 3.0, 1e-9};
            sms_generator g;
            sms_real out[4];
            CHECK_STATUS(sms_generator_init(&g, &c, e[3], NULL, 0), SMS_OK);
            for (k = 0; k < 3; ++k) {
                sms_generator_reset(&g, 0);
                sms_generator_step(&g, (sms_real)(part[k] * r.distance), out);
                CHECK(g.refused == 0);
            }
        }
    }
    CHECK(accepted > 200);
}

/* Expect a refusal naming `quantity`. */
static void check_refused(const sms_generator_config *c, double Ts, const char *quantity)
{
    sms_generator g;
    sms_generator_reach_info r;
    size_t need;
    CHECK_STATUS(sms_generator_reach(c, Ts, &r), SMS_ERR_LIMIT);
    CHECK(r.quantity != NULL && strcmp(r.quantity, quantity) == 0);
    if (r.quantity == NULL || strcmp(r.quantity, quantity) != 0)
        fprintf(stderr, "refused for %s, expected %s (vmax %g amax %g jmax %g Ts %g)\n",
                r.quantity != NULL ? r.quantity : "nothing", quantity, c->vmax, c->amax, c->jmax,
                Ts);
    CHECK_STATUS(sms_generator_init(&g, c, Ts, NULL, 0), SMS_ERR_LIMIT);
    CHECK_STATUS(sms_generator_buffer_size(c, Ts, &need), SMS_ERR_LIMIT);
}

/* The feasible region on both sides of each of its bounds, in this build's precision: just
 * inside, the move that reaches vmax and a reversal are planned; just outside, init refuses
 * and names the quantity. */
static void test_feasible_limits(void)
{
    const double in = 1.0 - 1e-6, out = 1.0 + 1e-6, big = R_MAX / 16.0;
    sms_generator_config c = make_config(1.0, 10.0, 100.0, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0);
    double T, x;
    int profile;
    for (profile = 0; profile < 2; ++profile) {
        double J = profile ? 100.0 * 2.0 / 3.14159265358979323846 : 100.0;
        c.profile = profile ? SMS_PROFILE_TRIGONOMETRIC : SMS_PROFILE_POLYNOMIAL;
        c.vmax = 1.0;
        c.amax = 5.0;
        c.jmax = 100.0;
        /* the duration to reach vmax: 2 (vmax/amax + amax/J) against 2^50 samples of Ts */
        T = 2.0 * (c.vmax / c.amax + c.amax / J);
        check_plans(&c, T / 1125899906842624.0 * out);
        check_refused(&c, T / 1125899906842624.0 * in, "vmax/amax");
        c.amax = 7.9; /* just reached, amax/J close to vmax/amax */
        T = 2.0 * (c.vmax / c.amax + c.amax / J);
        check_plans(&c, T / 1125899906842624.0 * out);
        check_refused(&c, T / 1125899906842624.0 * in, "vmax/amax");
        c.amax = 1e10; /* amax not reached: 4 sqrt(vmax/J) */
        T = 4.0 * sqrt(c.vmax / J);
        check_plans(&c, T / 1125899906842624.0 * out);
        check_refused(&c, T / 1125899906842624.0 * in,
                      profile ? "sqrt(pi vmax/(2 jmax))" : "sqrt(vmax/jmax)");
        /* the velocity changes: 16 vmax J <= MAX */
        c.vmax = 4.0;
        c.amax = 1.0;
        c.jmax = R_MAX / 64.0 / (J / 100.0) * in;
        check_plans(&c, 1e-3);
        c.jmax = R_MAX / 64.0 / (J / 100.0) * out;
        check_refused(&c, 1e-3, "vmax*jmax");
        /* the squares of accelerations: amax^2 >= MIN/eps (Ts long enough for vmax/amax) */
        x = sqrt(R_MIN / R_EPS);
        c.vmax = 1.0;
        c.jmax = 1.0;
        c.amax = x * out;
        T = 2.0 * (c.vmax / c.amax + c.amax / (J / 100.0));
        check_plans(&c, T * 1e-6);
        c.amax = x * in;
        check_refused(&c, T * 1e-6, "amax^2");
        /* the distance: vmax (vmax/amax + amax/J) <= MAX/16 (vmax = sqrt(MAX/16), amax = 1) */
        x = sqrt(big);
        c.amax = 1.0;
        c.jmax = 1e3;
        c.vmax = x * in * in;
        T = 2.0 * (c.vmax / c.amax + c.amax / (J * 10.0));
        check_plans(&c, T * 1e-6);
        c.vmax = x * out;
        check_refused(&c, T * 1e-6, "the distance to reach vmax");
        /* each limit within [MIN, MAX/16] */
        c = make_config(1.0, 10.0, 100.0, c.profile, 0.0, 0.0);
        c.jmax = big * out;
        check_refused(&c, 1e-3, "jmax");
        c.jmax = 100.0;
        c.vmax = R_MIN * in;
        check_refused(&c, 1e-3, "vmax");
    }
    /* the example of the documentation: vmax 1, amax 1e-30, jmax 1e-300 (amax never reached:
     * vmax takes 4 sqrt(vmax/jmax) = 4e150 s); in float jmax itself is below MIN */
    c = make_config(1.0, 1e-30, 1e-300, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0);
    check_refused(&c, 1e-3, sizeof(sms_real) == sizeof(double) ? "sqrt(vmax/jmax)" : "jmax");
    c = make_config(1.0, 1e-30, 1e-20, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0); /* vmax/amax 1e30 s */
    check_refused(&c, 1e-3, "vmax/amax");
    /* Ts itself */
    c = make_config(1.0, 10.0, 100.0, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0);
    CHECK_STATUS(sms_generator_reach(&c, 1e-300, NULL), sizeof(sms_real) == sizeof(double)
                                                          ? SMS_ERR_LIMIT : SMS_ERR_SAMPLE_PERIOD);
    CHECK_STATUS(sms_generator_reach(NULL, 1e-3, NULL), SMS_ERR_NULL);
}

/* ------------------------------------------------------------ saved states and the limits */

/* The tolerance of a saved state's v, a and brake velocity: the one of the reported values,
 * 32 u of the limits as the generator holds them (trajectory.h, SMS_LIMIT_RTOL). */
#define STATE_TOL (32.0 * SAMPLE_EPS)

/* What a saved state's plan fields are, relative to the limits as sms_real, minus 1, in u:
 * |v|/vmax, |a|/amax, |v + a|a|/(2 J)|/vmax with J the shape's mean jerk. */
typedef struct own_states {
    double *state;
    size_t capacity;
    long samples, saved, refused;
    double worst[3];
} own_states;

static void plan_excess(const sms_generator *g, const double *plan, double excess[3])
{
    const double V = (double)g->limits.vmax, A = (double)g->limits.amax;
    const double J = g->shape == 1 ? (double)(g->limits.jmax * (sms_real)0.63661977236758134)
                                   : (double)g->limits.jmax;
    const double v = plan[SMS_GENERATOR_STATE_V], a = plan[SMS_GENERATOR_STATE_A];
    excess[0] = (fabs(v) / V - 1.0) / SAMPLE_EPS;
    excess[1] = (fabs(a) / A - 1.0) / SAMPLE_EPS;
    excess[2] = (fabs(v + a * fabs(a) / (2.0 * J)) / V - 1.0) / SAMPLE_EPS;
}

/* Save the state on every re-plan (the plan's start moves to the sample's q, v, a, often
 * mid-transition or at the peak velocity) and on every 61st sample otherwise; each must pass
 * check_state. */
static void observe_own_state(const sms_generator *g, void *context)
{
    own_states *o = (own_states *)context;
    size_t n = sms_generator_state_count(g);
    double e[3];
    int i;
    ++o->samples;
    if ((g->k != 0 && o->samples % 61 != 0) || n > o->capacity)
        return;
    sms_generator_get_state(g, o->state);
    ++o->saved;
    if (sms_generator_check_state(g, o->state, n) != SMS_OK) {
        ++o->refused;
        plan_excess(g, o->state + SMS_GENERATOR_IDENTITY_COUNT, e);
        if (o->refused <= 5)
            fprintf(stderr, "own state refused: v %.3g u, a %.3g u, brake %.3g u over the limits"
                            " (vmax %.17g amax %.17g jmax %.17g Ts %.17g)\n", e[0], e[1], e[2],
                    (double)g->limits.vmax, (double)g->limits.amax, (double)g->limits.jmax,
                    g->Ts_signal);
    }
    plan_excess(g, o->state + SMS_GENERATOR_IDENTITY_COUNT, e);
    for (i = 0; i < 3; ++i)
        if (e[i] > o->worst[i])
            o->worst[i] = e[i];
}

/* Every state the generator saves over the random campaign (random limits and Ts, all
 * profiles, modes, reversals, targets every 1 to 200 samples, tiny steps) loads again: the
 * state check is not tighter than the generator's own rounding. Prints the worst v, a and
 * brake velocity of those states over the limits in u. */
static void test_own_states_are_accepted(int trials)
{
    static double buffer[MAX_TABLE + 1000];
    own_states o;
    int trial;
    memset(&o, 0, sizeof o);
    o.state = buffer;
    o.capacity = sizeof buffer / sizeof buffer[0];
    o.worst[0] = o.worst[1] = o.worst[2] = -1e300;
    rng = 777u;
    for (trial = 0; trial < trials; ++trial) {
        campaign_case k;
        double reported[4], beyond[4];
        campaign_draw(&k, urand, trial % 2);
        (void)campaign_run(&k, urand, SAMPLE_EPS, table, MAX_TABLE, reported, beyond,
                           observe_own_state, &o);
    }
    CHECK(o.saved > 1000);
    CHECK(o.refused == 0);
    CHECK(o.worst[0] <= 32.0 && o.worst[1] <= 32.0 && o.worst[2] <= 32.0);
    printf("own states [%s]: %ld saved, %ld refused; worst over the limits: v %.3g u, a %.3g u,"
           " brake velocity %.3g u\n", SMS_TEST_PRECISION, o.saved, o.refused, o.worst[0],
           o.worst[1], o.worst[2]);
}

/* Set the plan fields (v, a) of a state saved at rest, expect `want` from check_state and
 * set_state; refused: the generator (struct and saved state) untouched. Accepted: the restored
 * generator reports v, a within the limits (1 + STATE_TOL) on its way to a far target. */
static void restore_plan_state(sms_generator *g, double v, double a, sms_status want)
{
    enum { n = SMS_GENERATOR_IDENTITY_COUNT + SMS_GENERATOR_PLAN_STATE_COUNT };
    static double state[n], before[n];
    sms_generator copy;
    sms_real out[4];
    double peak[2] = {0.0, 0.0};
    long k;
    CHECK(sms_generator_state_count(g) == n);
    sms_generator_reset(g, 0);
    sms_generator_get_state(g, before);
    sms_generator_get_state(g, state);
    state[SMS_GENERATOR_IDENTITY_COUNT + SMS_GENERATOR_STATE_V] = v;
    state[SMS_GENERATOR_IDENTITY_COUNT + SMS_GENERATOR_STATE_A] = a;
    copy = *g;
    CHECK_STATUS(sms_generator_check_state(g, state, n), want);
    CHECK_STATUS(sms_generator_set_state(g, state, n), want);
    if (want != SMS_OK) {
        CHECK(memcmp(&copy, g, sizeof copy) == 0);
        sms_generator_get_state(g, state);
        CHECK(memcmp(state, before, sizeof state) == 0);
        return;
    }
    for (k = 0; k < 4000; ++k) {
        sms_generator_step(g, (sms_real)(v >= 0 ? 5.0 : -5.0), out);
        peak[0] = fabs((double)out[1]) > peak[0] ? fabs((double)out[1]) : peak[0];
        peak[1] = fabs((double)out[2]) > peak[1] ? fabs((double)out[2]) : peak[1];
    }
    CHECK(peak[0] <= (double)g->limits.vmax * (1.0 + STATE_TOL));
    CHECK(peak[1] <= (double)g->limits.amax * (1.0 + STATE_TOL));
}

/* A state beyond the limits by twice the tolerance is refused (v, a, brake velocity, each
 * sign), one at the tolerance is accepted and keeps the limits. The limits are powers of two,
 * so every value below is exact in float too: a = amax/2 brakes over amax^2/(8 jmax) = 1/8. */
static void test_state_beyond_the_limits(void)
{
    sms_generator g;
    const sms_generator_config c = make_config(1.0, 8.0, 64.0, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0);
    int sign;
    CHECK(SMS_LIMIT_RTOL == ldexp(32.0, sizeof(sms_real) == sizeof(double) ? -53 : -24));
    CHECK_STATUS(sms_generator_init(&g, &c, 1e-3, NULL, 0), SMS_OK);
    for (sign = -1; sign <= 1; sign += 2) {
        const double s = sign, tol = SMS_LIMIT_RTOL;
        restore_plan_state(&g, s * (1.0 + 2.0 * tol), 0.0, SMS_ERR_STATE);
        restore_plan_state(&g, 0.0, s * 8.0 * (1.0 + 2.0 * tol), SMS_ERR_STATE);
        restore_plan_state(&g, s * (0.875 + 2.0 * tol), s * 4.0, SMS_ERR_STATE);
        restore_plan_state(&g, s * (1.0 + tol), 0.0, SMS_OK);
        restore_plan_state(&g, 0.0, s * 8.0 * (1.0 + tol), SMS_OK);
        restore_plan_state(&g, s * (0.875 + tol), s * 4.0, SMS_OK);
    }
}

int main(void)
{
    test_feasible_limits();
    test_feasible_random();
    test_extreme_limits_and_targets();
    test_time_optimal_arrival();
    test_long_moves();
    test_long_moves_through_the_stage();
    test_bounds_random();
    test_bounds_random_limits(400);
    test_trigonometric();
    test_mode_stage();
    test_single_move();
    replan_beyond_the_direct_stop();
    test_state_and_bad_input();
    test_own_states_are_accepted(400);
    test_state_beyond_the_limits();
    return check_summary("test_generator");
}
