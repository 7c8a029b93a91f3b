/* SPDX-License-Identifier: Apache-2.0 */
/* The multi-axis generator with per-axis position limits [qmin[i], qmax[i]], every sync mode:
 * every sample's q within them exactly and v, a, j within their bounds (1 + SMS_LIMIT_RTOL)
 * on random staircases that change mid-motion, the rest on the last target exactly; the
 * refusals (configuration, targets, start states) naming the axis with the generator
 * untouched; hold equal to steps. */
#include <string.h>
#include "check.h"
#include "xorshift.h"
#include "smoothshaper/multi_generator.h"

static uint64_t rng = 0x2545F4914F6CDD1Dull;

static double urand(void) { return xorshift_uniform(&rng); }

static const double VMAX[3] = {1.0, 2.0, 0.5}, AMAX[3] = {10.0, 4.0, 5.0},
                    JMAX[3] = {100.0, 50.0, 40.0};

static sms_multi_generator_config config(sms_sync sync, const double *lo, const double *hi)
{
    sms_multi_generator_config c;
    size_t i;
    memset(&c, 0, sizeof c);
    c.n_axes = 3;
    c.sync = sync;
    for (i = 0; i < 3; ++i) {
        c.vmax[i] = VMAX[i];
        c.amax[i] = AMAX[i];
        c.jmax[i] = JMAX[i];
        c.qmin[i] = lo[i];
        c.qmax[i] = hi[i];
    }
    return c;
}

static void test_staircases_stay_inside(sms_sync sync)
{
    int run;
    for (run = 0; run < 6; ++run) {
        double lo[3], hi[3];
        sms_multi_generator g;
        sms_multi_generator_config c;
        sms_real target[3], out[12];
        size_t i, k, step;
        for (i = 0; i < 3; ++i) {
            lo[i] = -urand();
            hi[i] = lo[i] + 0.05 + 1.5 * urand();
        }
        c = config(sync, lo, hi);
        CHECK_STATUS(sms_multi_generator_init(&g, &c, 1e-3, NULL, 0, NULL, 0, NULL), SMS_OK);
        for (step = 0; step < 6; ++step) {
            const size_t hold = step == 5 ? 6000 : 50 + (size_t)(urand() * 300);
            for (i = 0; i < 3; ++i)
                target[i] = (sms_real)(lo[i] + (hi[i] - lo[i]) * urand());
            for (k = 0; k < hold; ++k) {
                sms_multi_generator_step(&g, target, out);
                for (i = 0; i < 3; ++i) {
                    CHECK(out[4 * i] >= (sms_real)lo[i] && out[4 * i] <= (sms_real)hi[i]);
                    CHECK(fabs((double)out[4 * i + 1]) <= VMAX[i] * (1 + SMS_LIMIT_RTOL));
                    CHECK(fabs((double)out[4 * i + 2]) <= AMAX[i] * (1 + SMS_LIMIT_RTOL));
                    CHECK(fabs((double)out[4 * i + 3]) <= JMAX[i] * (1 + SMS_LIMIT_RTOL));
                }
            }
        }
        for (i = 0; i < 3; ++i)
            CHECK(out[4 * i] == target[i] && out[4 * i + 1] == 0 && out[4 * i + 2] == 0);
    }
}

static void test_refusals(void)
{
    const double lo[3] = {-1.0, 0.0, -1.0}, hi[3] = {1.0, 1.0, 1.0};
    sms_multi_generator_config c = config(SMS_SYNC_TIME, lo, hi);
    sms_multi_generator g;
    sms_multi_target t;
    sms_generator_reach_info r;
    sms_real q[3] = {0, (sms_real)0.9, 0}, v[3] = {0, 2, 0}, a[3] = {0, 0, 0};
    double before[512], after[512];
    size_t axis = 9, n;
    c.qmax[2] = -2.0; /* out of order on axis 2 */
    CHECK_STATUS(sms_multi_generator_reach(&c, 1e-3, &r, &axis), SMS_ERR_LIMIT);
    CHECK(axis == 2 && strcmp(r.quantity, "qmax") == 0);
    c.qmax[2] = 1.0;
    CHECK_STATUS(sms_multi_generator_init(&g, &c, 1e-3, NULL, 0, NULL, 0, NULL), SMS_OK);
    n = sms_multi_generator_state_count(&g);
    CHECK(n <= 512);
    sms_multi_generator_get_state(&g, before);
    memset(&t, 0, sizeof t);
    t.position[1] = (sms_real)1.5;
    CHECK_STATUS(sms_multi_generator_check_target(&g, &t, &axis), SMS_ERR_POSITION_LIMIT);
    CHECK(axis == 1);
    t.position[1] = (sms_real)0.5;
    t.velocity[2] = (sms_real)0.1;
    CHECK_STATUS(sms_multi_generator_check_target(&g, &t, &axis), SMS_ERR_TARGET_VELOCITY);
    CHECK(axis == 2);
    t.velocity[2] = 0;
    /* axis 1 at 0.9 moving up at 2 (amax 4, jmax 50): its brake passes qmax = 1 */
    CHECK_STATUS(sms_multi_generator_start(&g, q, v, a, &t, &axis), SMS_ERR_POSITION_LIMIT);
    CHECK(axis == 1);
    CHECK_STATUS(sms_multi_generator_start(&g, q, v, a, NULL, &axis), SMS_ERR_POSITION_LIMIT);
    q[1] = (sms_real)1.5;
    v[1] = 0;
    CHECK_STATUS(sms_multi_generator_start(&g, q, v, a, &t, &axis), SMS_ERR_POSITION_LIMIT);
    CHECK(axis == 1);
    sms_multi_generator_reset(&g, q); /* outside: nothing changes */
    sms_multi_generator_get_state(&g, after);
    CHECK(memcmp(before, after, n * sizeof(double)) == 0);
}

/* Time: a stretched synchronised motion that would cross brakes, rests and moves; hold() of
 * the same run equals its steps bit for bit. */
static void test_hold_equals_steps(void)
{
    const double lo[3] = {-5.0, -1.0, -1.0}, hi[3] = {5.0, 0.95, 1.0};
    sms_multi_generator_config c = config(SMS_SYNC_TIME, lo, hi);
    sms_multi_generator g, h;
    sms_multi_target t;
    sms_real q[3] = {0, (sms_real)0.5, 0}, v[3] = {0, (sms_real)1.5, 0}, a[3] = {0, 0, 0};
    sms_real out[12], held[12], pos[3] = {3, (sms_real)0.9, 0};
    size_t k, i;
    sms_real top = 0;
    CHECK_STATUS(sms_multi_generator_init(&g, &c, 1e-3, NULL, 0, NULL, 0, NULL), SMS_OK);
    memset(&t, 0, sizeof t);
    for (i = 0; i < 3; ++i)
        t.position[i] = pos[i];
    CHECK_STATUS(sms_multi_generator_start(&g, q, v, a, &t, NULL), SMS_OK);
    h = g;
    for (k = 0; k < 3300; ++k) {
        sms_multi_generator_step(&g, pos, out);
        if (out[4] > top)
            top = out[4];
    }
    CHECK(top <= (sms_real)0.95 && top > (sms_real)0.8);
    CHECK(out[0] == pos[0] && out[4] == pos[1]);
    CHECK(sms_multi_generator_hold(&h, pos, 3300, held) == 3300);
    CHECK(memcmp(out, held, sizeof out) == 0);
}

int main(void)
{
    test_staircases_stay_inside(SMS_SYNC_PHASE);
    test_staircases_stay_inside(SMS_SYNC_INDEPENDENT);
    test_staircases_stay_inside(SMS_SYNC_TIME);
    test_staircases_stay_inside(SMS_SYNC_TIME_IF_NECESSARY);
    test_staircases_stay_inside(SMS_SYNC_NONE);
    test_refusals();
    test_hold_equals_steps();
    return check_summary("test_multi_position");
}
