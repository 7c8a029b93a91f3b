/* SPDX-License-Identifier: Apache-2.0 */
/* The multi-axis generator's per-axis plan modes (Time, TimeIfNecessary, None): from random
 * start states to random target states (at rest or moving), 1 to 4 axes with random limits,
 * every reported v, a, j within its axis's limits (1 + SMS_LIMIT_RTOL), the synchronised axes
 * on one arrival sample, each axis exactly on its target state there; hold equals the steps
 * bit for bit; a saved state continues bit for bit; a bad target or start state is refused
 * naming the axis, the generator unchanged. */
#include <math.h>
#include <stdint.h>
#include <string.h>
#include "check.h"
#include "xorshift.h"

#define TS 1e-3
#define MAX_STATE 4096
#define MAX_SAMPLES 20000

static uint64_t rng = 0x2545F4914F6CDD1Dull;
static double uniform(void)
{
    return xorshift_uniform(&rng);
}
static double between(double lo, double hi)
{
    return lo + (hi - lo) * uniform();
}

/* (v, a) within the bounds whose brake velocities (forward; and backward for a target) stay
 * within +-V. */
static void state(double V, double A, double J, int target, sms_real *v, sms_real *a)
{
    for (;;) {
        double x = between(-V, V), y = between(-A, A), r = y * fabs(y) / (2 * J);
        if (fabs(x + r) <= V && (!target || fabs(x - r) <= V)) {
            *v = (sms_real)x;
            *a = (sms_real)y;
            return;
        }
    }
}

static size_t arrival(const sms_multi_generator *g, size_t i)
{
    return (size_t)sms_multi_generator_axis_arrival(g, i);
}

static sms_multi_generator g, twin;
static double saved[MAX_STATE];
static int cases;

static void one_case(void)
{
    sms_multi_generator_config c;
    sms_multi_target t;
    sms_real q[SMS_MULTI_MAX_AXES], v[SMS_MULTI_MAX_AXES], a[SMS_MULTI_MAX_AXES];
    sms_real out[4 * SMS_MULTI_MAX_AXES], held[4 * SMS_MULTI_MAX_AXES];
    size_t i, n = 1 + (size_t)(uniform() * 4), k, N = 0, bad;
    int synced[SMS_MULTI_MAX_AXES];
    sms_status st;
    memset(&c, 0, sizeof c);
    memset(&t, 0, sizeof t);
    c.n_axes = n;
    c.sync = (sms_sync)(SMS_SYNC_TIME + (int)(uniform() * 3));
    for (i = 0; i < n; ++i) {
        double V = pow(10, between(-1, 1)), A = V * pow(10, between(-0.5, 1)),
               J = A * pow(10, between(-0.5, 1)), scale = V * (V / A + A / J);
        c.vmax[i] = V;
        c.amax[i] = A;
        c.jmax[i] = J;
        q[i] = (sms_real)between(-scale, scale);
        state(V, A, J, 0, &v[i], &a[i]);
        t.position[i] = (sms_real)(q[i] + between(-3, 3) * scale);
        if (uniform() < 0.5)
            state(V, A, J, 1, &t.velocity[i], &t.acceleration[i]);
        if (uniform() < 0.3)
            t.sync[i] = SMS_SYNC_TIME + (int)(uniform() * 3);
    }
    CHECK_STATUS(sms_multi_generator_init(&g, &c, TS, NULL, 0, NULL, 0, &bad), SMS_OK);
    CHECK_STATUS(sms_multi_generator_start(&g, q, v, a, &t, &bad), SMS_OK);
    for (i = 0; i < n; ++i) {
        const int mode = t.sync[i] != 0 ? t.sync[i] : (int)c.sync;
        synced[i] = mode == SMS_SYNC_TIME ||
                    (mode == SMS_SYNC_TIME_IF_NECESSARY &&
                     (t.velocity[i] != 0 || t.acceleration[i] != 0));
        if (synced[i]) {
            if (N == 0)
                N = arrival(&g, i);
            CHECK(arrival(&g, i) == N); /* every synchronised axis on one sample */
        }
    }
    if (sms_multi_generator_arrival(&g) + 10 > MAX_SAMPLES)
        return;
    twin = g;
    for (k = 1; k <= sms_multi_generator_arrival(&twin) + 5; ++k) {
        sms_multi_generator_step_target(&g, &t, out);
        if (k == 7 && sms_multi_generator_state_count(&g) <= MAX_STATE)
            sms_multi_generator_get_state(&g, saved);
        for (i = 0; i < n; ++i) {
            CHECK(fabs((double)out[4 * i + 1]) <= c.vmax[i] * (1 + SMS_LIMIT_RTOL));
            CHECK(fabs((double)out[4 * i + 2]) <= c.amax[i] * (1 + SMS_LIMIT_RTOL));
            CHECK(fabs((double)out[4 * i + 3]) <= c.jmax[i] * (1 + SMS_LIMIT_RTOL));
            if (k == arrival(&twin, i) && !(t.acceleration[i] != 0 &&
                                              fabs((double)t.acceleration[i]) / c.jmax[i] <=
                                                  64 * (double)SMS_LIMIT_RTOL * k * TS)) {
                CHECK(out[4 * i] == t.position[i]);
                CHECK(out[4 * i + 1] == t.velocity[i]);
                CHECK(out[4 * i + 2] == t.acceleration[i]);
            }
        }
    }
    /* hold: the same samples at a cost bounded whatever n (the positions at rest) */
    {
        sms_multi_generator x = g, y = g;
        sms_real rest[SMS_MULTI_MAX_AXES];
        uint64_t m = 1 + (uint64_t)(uniform() * 3000);
        for (i = 0; i < n; ++i)
            rest[i] = (sms_real)(t.position[i] + between(-1, 1) * c.vmax[i]);
        CHECK(sms_multi_generator_hold(&x, rest, m, held) == m);
        for (k = 0; k < m; ++k)
            sms_multi_generator_step(&y, rest, out);
        CHECK(memcmp(held, out, 4 * n * sizeof out[0]) == 0);
    }
    /* a saved state loads into a fresh generator and continues bit for bit */
    if (sms_multi_generator_state_count(&twin) <= MAX_STATE) {
        sms_multi_generator z = twin;
        sms_real o1[4 * SMS_MULTI_MAX_AXES], o2[4 * SMS_MULTI_MAX_AXES];
        for (k = 0; k < 7; ++k)
            sms_multi_generator_step_target(&z, &t, o1);
        CHECK_STATUS(sms_multi_generator_init(&twin, &c, TS, NULL, 0, NULL, 0, &bad), SMS_OK);
        CHECK_STATUS(sms_multi_generator_set_state(&twin, saved,
                                                   sms_multi_generator_state_count(&twin)),
                     SMS_OK);
        for (k = 0; k < 50; ++k) {
            sms_multi_generator_step_target(&z, &t, o1);
            sms_multi_generator_step_target(&twin, &t, o2);
        }
        CHECK(memcmp(o1, o2, 4 * n * sizeof o1[0]) == 0);
    }
    /* refusals name the axis and change nothing */
    {
        sms_multi_target b = t;
        sms_multi_generator before = g;
        b.velocity[n - 1] = (sms_real)(2 * c.vmax[n - 1]);
        st = sms_multi_generator_check_target(&g, &b, &bad);
        CHECK(st == SMS_ERR_TARGET_VELOCITY && bad == n - 1);
        b = t;
        b.sync[0] = SMS_SYNC_PHASE + 7;
        CHECK(sms_multi_generator_check_target(&g, &b, &bad) == SMS_ERR_TARGET_SYNC);
        q[n - 1] = (sms_real)NAN;
        CHECK(sms_multi_generator_start(&g, q, v, a, &t, &bad) == SMS_ERR_TARGET_POSITION &&
              bad == n - 1);
        CHECK(memcmp(&before, &g, sizeof g) == 0);
    }
    ++cases;
}

int main(void)
{
    int r;
    for (r = 0; r < 300; ++r)
        one_case();
    CHECK(cases > 200);
    return check_summary("test_multi_sync");
}
