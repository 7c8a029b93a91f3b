/* SPDX-License-Identifier: Apache-2.0 */
/* sms_generator_hold(): n steps with one target give the state and output of n calls of
 * sms_generator_step(), bit for bit, for random limits, every profile, with and without the
 * tuned stage, random histories (moves interrupted by the new target) and every n from one
 * sample through the move and the stage's window to 2^60 samples. Holds longer than the
 * reference can step are compared after reducing n by whole periods 2M of the absorbed
 * stage (the plan at rest): every state value equal, the plan's sample index k larger by
 * exactly the samples removed. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "check.h"
#include "xorshift.h"

#define MAX_RING 2000
#define MAX_STATE (4 * MAX_RING + 200)
#define TS 1e-3

static sms_real buf_a[4 * MAX_RING], buf_b[4 * MAX_RING];
static double st_a[MAX_STATE], st_b[MAX_STATE];

static uint64_t rng = 0x2545F4914F6CDD1Dull;
static double uniform(void)
{
    return xorshift_uniform(&rng);
}

/* The index of k in the saved state (trajectory.h: identity, target, goal, q, v, a, k). */
#define STATE_K (SMS_GENERATOR_IDENTITY_COUNT + SMS_GENERATOR_STATE_K)

static int cases, reduced;

static void one_case(const sms_generator_config *c, uint64_t n, sms_real target)
{
    sms_generator a, b;
    sms_real out_a[4], out_b[4] = {0, 0, 0, 0};
    size_t count, i, hist = (size_t)(uniform() * 600.0);
    uint64_t m = n, period;
    if (sms_generator_init(&a, c, TS, buf_a, 4 * MAX_RING) != SMS_OK
        || sms_generator_init(&b, c, TS, buf_b, 4 * MAX_RING) != SMS_OK)
        return;
    /* the same history in both: a few targets, the last move interrupted */
    for (i = 0; i < hist; ++i) {
        sms_real t = (sms_real)(i < hist / 2 ? 0.3 : -0.2), o[4];
        sms_generator_step(&a, t, o);
        sms_generator_step(&b, t, o);
    }
    period = a.stage_length > 0 ? 2u * (uint64_t)a.stage_window : 1u;
    if (n > 40000u)
        m = 20000u + (n - 20000u) % period;   /* the plan rests and the stage absorbed */
    sms_generator_hold(&a, target, n, out_a);
    for (i = 0; i < m; ++i)
        sms_generator_step(&b, target, out_b);
    count = sms_generator_state_count(&a);
    sms_generator_get_state(&a, st_a);
    sms_generator_get_state(&b, st_b);
    if (m != n) {
        CHECK(st_a[STATE_K] == st_b[STATE_K] + (double)(n - m));
        st_a[STATE_K] = st_b[STATE_K];
        ++reduced;
    }
    CHECK(memcmp(out_a, out_b, sizeof out_a) == 0);
    CHECK(memcmp(st_a, st_b, count * sizeof st_a[0]) == 0);
    if (memcmp(out_a, out_b, sizeof out_a) != 0 || memcmp(st_a, st_b, count * sizeof st_a[0]) != 0)
        fprintf(stderr, "  profile %d wn %g n %llu: q %.17g vs %.17g\n", (int)c->profile, c->wn,
                (unsigned long long)n, (double)out_a[0], (double)out_b[0]);
    ++cases;
}

/* A long move (vmax 5e-3 over 1: about 2e5 samples) through a tuned stage of M = 1000,
 * held to points inside it, at its end and after, against stepping every sample. */
static void long_move(void)
{
    const uint64_t ns[4] = {100000u, 199500u, 200500u, 203300u};
    sms_generator_config c;
    int k;
    c.vmax = 5e-3;
    c.amax = 0.01;
    c.jmax = 0.1;
    c.profile = SMS_PROFILE_POLYNOMIAL;
    c.wn = 2.0 * 3.14159265358979323846;   /* 1 Hz: M = 1000 samples */
    c.zeta = 0.0;
    c.vmin = c.amin = 0.0; /* symmetric */
    c.qmin = c.qmax = 0.0; /* no position limits */
    for (k = 0; k < 4; ++k) {
        sms_generator a, b;
        sms_real out_a[4], out_b[4] = {0, 0, 0, 0};
        uint64_t i;
        size_t count;
        CHECK_STATUS(sms_generator_init(&a, &c, TS, buf_a, 4 * MAX_RING), SMS_OK);
        CHECK_STATUS(sms_generator_init(&b, &c, TS, buf_b, 4 * MAX_RING), SMS_OK);
        sms_generator_hold(&a, (sms_real)1, ns[k], out_a);
        for (i = 0; i < ns[k]; ++i)
            sms_generator_step(&b, (sms_real)1, out_b);
        count = sms_generator_state_count(&a);
        sms_generator_get_state(&a, st_a);
        sms_generator_get_state(&b, st_b);
        CHECK(memcmp(out_a, out_b, sizeof out_a) == 0);
        CHECK(memcmp(st_a, st_b, count * sizeof st_a[0]) == 0);
    }
}

int main(void)
{
    long_move();
    int trial;
    for (trial = 0; trial < 150; ++trial) {
        sms_generator_config c;
        uint64_t ns[10];
        int k;
        c.vmax = 0.5 + uniform();
        c.amax = 5.0 + 20.0 * uniform();
        c.jmax = 100.0 + 900.0 * uniform();
        c.profile = (sms_profile)(trial % 3);
        c.wn = trial % 3 == 2 || uniform() < 0.6 ? 2.0 * 3.14159265358979323846 * (5.0 + 60.0 * uniform())
                                                 : 0.0;
        c.zeta = c.wn > 0.0 && uniform() < 0.5 ? 0.2 * uniform() : 0.0;
        c.vmin = c.amin = 0.0; /* symmetric */
        c.qmin = c.qmax = 0.0; /* no position limits */
        ns[0] = 1;
        ns[1] = 2;
        ns[2] = 3 + (uint64_t)(uniform() * 50.0);
        ns[3] = (uint64_t)(uniform() * 500.0) + 1u;
        ns[4] = (uint64_t)(uniform() * 3000.0) + 1u;
        ns[5] = (uint64_t)(uniform() * 10000.0) + 1u;
        ns[6] = (uint64_t)(uniform() * 15000.0) + 1u;
        ns[7] = 30000u;
        ns[8] = 1000000000u + (uint64_t)(uniform() * 1e6);
        ns[9] = ((uint64_t)1 << 50) + (uint64_t)(uniform() * 1e6);
        for (k = 0; k < 10; ++k)
            one_case(&c, ns[k], (sms_real)(2.0 * uniform() - 1.0));
    }
    CHECK(cases > 1200 && reduced > 250);
    printf("generator hold: %d cases (%d reduced by the absorbed period)\n", cases, reduced);
    return check_summary("test_generator_hold");
}
