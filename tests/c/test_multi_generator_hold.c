/* SPDX-License-Identifier: Apache-2.0 */
/* sms_multi_generator_hold(): n steps with the same targets give the state and output of n calls
 * of sms_multi_generator_step(), bit for bit, for random limits, both synchronisations, 1 to 4
 * axes, no stages, FIR stages (smoothers, shapers) and notches, random histories (moves
 * interrupted by the new targets, some during their stop) and n from one sample through the
 * moves and the stages' windows; a hold that returns 0 (a notch while the profile still
 * moves near the end) changes nothing. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "check.h"
#include "xorshift.h"

#define TS 1e-3
#define MAX_STAGES 64
#define MAX_CELLS 40000
#define MAX_STATE 100000

static sms_stage stages_a[MAX_STAGES], stages_b[MAX_STAGES];
static sms_memory_cell mem_a[MAX_CELLS], mem_b[MAX_CELLS];
static double st_a[MAX_STATE], st_b[MAX_STATE];

static uint64_t rng = 0x853C49E6748FEA9Bull;
static double uniform(void)
{
    return xorshift_uniform(&rng);
}

static int cases, refused_holds;

static void one_case(const sms_multi_generator_config *c, uint64_t n, const sms_real *target,
                     size_t hist)
{
    sms_multi_generator a, b;
    sms_real out_a[32], out_b[32], o[32], t[8];
    size_t i, j, count;
    uint64_t done, k;
    if (sms_multi_generator_init(&a, c, TS, stages_a, MAX_STAGES, mem_a, MAX_CELLS, NULL) != SMS_OK
        || sms_multi_generator_init(&b, c, TS, stages_b, MAX_STAGES, mem_b, MAX_CELLS, NULL)
               != SMS_OK)
        return;
    for (i = 0; i < hist; ++i) {
        for (j = 0; j < c->n_axes; ++j)
            t[j] = (sms_real)(i < hist / 2 ? 0.3 * (double)(j + 1) : -0.2);
        sms_multi_generator_step(&a, t, o);
        sms_multi_generator_step(&b, t, o);
    }
    memset(out_a, 0, sizeof out_a);
    memset(out_b, 0, sizeof out_b);
    done = sms_multi_generator_hold(&a, target, n, out_a);
    CHECK(done == n || done == 0);
    if (done == 0)
        ++refused_holds;
    for (k = 0; k < done; ++k)
        sms_multi_generator_step(&b, target, out_b);
    count = sms_multi_generator_state_count(&a);
    CHECK(count <= MAX_STATE);
    sms_multi_generator_get_state(&a, st_a);
    sms_multi_generator_get_state(&b, st_b);
    CHECK(memcmp(out_a, out_b, sizeof out_a) == 0);
    CHECK(memcmp(st_a, st_b, count * sizeof st_a[0]) == 0);
    if (memcmp(out_a, out_b, sizeof out_a) != 0 || memcmp(st_a, st_b, count * sizeof st_a[0]) != 0)
        fprintf(stderr, "  axes %lu sync %d n %llu: q0 %.17g vs %.17g\n", (unsigned long)c->n_axes,
                (int)c->sync, (unsigned long long)n, (double)out_a[0], (double)out_b[0]);
    ++cases;
}


/* A notch while the profile still moves when the last window starts: the notch enters that
 * window from its stale state, whose transient decays within the window (its settle bound,
 * from the largest state to past the smallest subnormal), so the outputs and state equal n
 * steps to rounding: within 8 eps of each value's scale. */
static double notch_mid_move(int sync, uint64_t n)
{
    sms_multi_generator a, b;
    sms_multi_generator_config c;
    sms_stage_config st[2];
    sms_real out_a[32], out_b[32], target[3] = {40, -25, 60};
    size_t j, count, i;
    uint64_t k;
    double worst = 0.0;
    memset(&c, 0, sizeof c);
    c.n_axes = 3;
    c.sync = sync ? SMS_SYNC_INDEPENDENT : SMS_SYNC_PHASE;
    st[0] = sms_stage_config_default(SMS_RECTANGULAR);
    st[0].T = 20 * TS;
    st[1] = sms_stage_config_default(SMS_NOTCH_TUSTIN);
    st[1].wn = 200.0;
    st[1].zeta = 0.05;
    st[1].notch_pole_zeta = 0.5;
    for (j = 0; j < 3; ++j) {
        c.vmax[j] = 0.5 + 0.1 * (double)j;
        c.amax[j] = 8.0;
        c.jmax[j] = 300.0;
        c.stages[j] = st;
        c.n_stages[j] = 2u;
    }
    CHECK(sms_multi_generator_init(&a, &c, TS, stages_a, MAX_STAGES, mem_a, MAX_CELLS, NULL) == SMS_OK);
    CHECK(sms_multi_generator_init(&b, &c, TS, stages_b, MAX_STAGES, mem_b, MAX_CELLS, NULL) == SMS_OK);
    CHECK(sms_multi_generator_hold(&a, target, n, out_a) == n);
    for (k = 0; k < n; ++k)
        sms_multi_generator_step(&b, target, out_b);
    CHECK(sms_multi_generator_busy(&a));   /* still moving: the case under test */
    CHECK((double)n > sms_chain_settle_bound(&a.chain[0][0]) + 2.0);   /* the jump is taken */
    count = sms_multi_generator_state_count(&a);
    CHECK(count <= MAX_STATE);
    sms_multi_generator_get_state(&a, st_a);
    sms_multi_generator_get_state(&b, st_b);
    for (i = 0; i < 4 * c.n_axes; ++i) {
        const double d = fabs((double)out_a[i] - (double)out_b[i]);
        const double scale = fabs((double)out_b[i]) > 1.0 ? fabs((double)out_b[i]) : 1.0;
        if (d / scale > worst)
            worst = d / scale;
    }
    for (i = 0; i < count; ++i) {
        const double d = fabs(st_a[i] - st_b[i]);
        const double scale = fabs(st_b[i]) > 1.0 ? fabs(st_b[i]) : 1.0;
        if (d / scale > worst)
            worst = d / scale;
    }
    return worst;
}

int main(void)
{
    static const sms_kind kinds[4] = {SMS_RECTANGULAR, SMS_HARMONIC, SMS_SHAPER_ZVD,
                                      SMS_NOTCH_TUSTIN};
    int trial;
    for (trial = 0; trial < 60; ++trial) {
        sms_multi_generator_config c;
        sms_stage_config st[2];
        sms_real target[8];
        size_t j, hist = (size_t)(uniform() * 900.0);
        int k, with = trial % 3;   /* 0: no stages, 1: FIR, 2: with a notch */
        uint64_t ns[6];
        memset(&c, 0, sizeof c);
        c.n_axes = 1u + (size_t)(uniform() * 4.0) % 4u;
        c.sync = uniform() < 0.5 ? SMS_SYNC_PHASE : SMS_SYNC_INDEPENDENT;
        for (j = 0; j < 2; ++j) {
            st[j] = sms_stage_config_default(kinds[with == 2 && j == 1 ? 3 : (size_t)(uniform() * 3.0) % 3u]);
            st[j].T = (5.0 + 40.0 * uniform()) * TS;
            st[j].wn = st[j].kind == SMS_NOTCH_TUSTIN ? 200.0 : 6.283185307179586 / st[j].T;
            st[j].notch_pole_zeta = 0.5;
        }
        for (j = 0; j < c.n_axes; ++j) {
            c.vmax[j] = 0.5 + uniform();
            c.amax[j] = 5.0 + 20.0 * uniform();
            c.jmax[j] = 100.0 + 900.0 * uniform();
            c.stages[j] = with ? st : NULL;
            c.n_stages[j] = with ? 2u : 0u;
            target[j] = (sms_real)(2.0 * uniform() - 1.0);
        }
        ns[0] = 1;
        ns[1] = 2 + (uint64_t)(uniform() * 30.0);
        ns[2] = (uint64_t)(uniform() * 400.0) + 1u;
        ns[3] = (uint64_t)(uniform() * 2000.0) + 1u;
        ns[4] = (uint64_t)(uniform() * 6000.0) + 1u;
        ns[5] = 20000u + (uint64_t)(uniform() * 100.0);
        for (k = 0; k < 6; ++k)
            one_case(&c, ns[k], target, hist);
    }
    {
        const double eps = sizeof(sms_real) == 4 ? 1.1920928955078125e-07 : 2.220446049250313e-16;
        int sync;
        for (sync = 0; sync < 2; ++sync) {
            const uint64_t n[2] = {45000u, 70001u};
            int q;
            for (q = 0; q < 2; ++q) {
                const double w = notch_mid_move(sync, n[q]);
                printf("notch mid-move, sync %d, n %llu: largest difference %.3g of the scale\n",
                       sync, (unsigned long long)n[q], w);
                CHECK(w <= 8.0 * eps);
            }
        }
    }
    CHECK(cases > 300);
    printf("multi-axis generator hold: %d cases (%d left to stepping)\n", cases, refused_holds);
    return check_summary("test_multi_generator_hold");
}
