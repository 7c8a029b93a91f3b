/* SPDX-License-Identifier: Apache-2.0 */
/* The input smoothers, SI shapers and user-defined impulses in the lag (align.h) and the
 * retunable stage (tunable.h): an input smoother's lag is its taps' centroid; SI and the input
 * smoothers come back from a saved identity with every field they read, so they retune and
 * restore like the other shapers; user-defined impulses (their identity holds a checksum) are
 * refused a retune to or from them and a state names them only by that checksum. */
#include <string.h>
#include "check.h"

#define PI 3.14159265358979323846
#define CELLS 16384u
#define MAX_LEN 8192u

static sms_memory_cell mem_a[CELLS], mem_b[CELLS];
static double taps[MAX_LEN];
static double state_a[MAX_LEN], state_b[MAX_LEN];

static const sms_kind smoothers[] = {SMS_SMOOTH_ZV, SMS_SMOOTH_MZV, SMS_SMOOTH_EI,
                                     SMS_SMOOTH_EI2, SMS_SMOOTH_ZVD_EI, SMS_SMOOTH_SI};

static sms_stage_config shaper(sms_kind kind, double f, double zeta)
{
    sms_stage_config c = sms_stage_config_default(kind);
    c.wn = 2.0 * PI * f;
    c.zeta = zeta;
    return c;
}

static sms_stage_config si(unsigned n, double D, double V, double f)
{
    sms_stage_config c = shaper(SMS_SHAPER_SI, f, 0.05);
    c.order = n;
    c.duration = D;
    c.tolerance = V;
    return c;
}

static sms_stage_config user(void)
{
    static const double A[4] = {0.3, 0.4, -0.1, 0.4}, t[4] = {0.0, 0.0041, 0.0063, 0.0117};
    sms_stage_config c = sms_stage_config_default(SMS_SHAPER_IMPULSES);
    c.order = 4;
    memcpy(c.amplitudes, A, sizeof A);
    memcpy(c.times, t, sizeof t);
    return c;
}

/* An input smoother has no sparse design: its lag is the centroid its correction pins, which
 * the realised taps carry. The taps' moment sums L terms of size <= L h_max, so it agrees to
 * a few L eps of the lag. */
static void test_input_smoother_lag(void)
{
    static const double Ts_list[] = {1e-4, 1.7e-3};
    size_t ik, it, i;
    for (ik = 0; ik < sizeof smoothers / sizeof smoothers[0]; ++ik)
        for (it = 0; it < 2; ++it) {
            const double Ts = Ts_list[it];
            sms_stage_config c = shaper(smoothers[ik], 37.0, 0.12);
            sms_stage stage;
            size_t L = 0, cells = 0;
            double lag = 0.0, sum = 0.0, moment = 0.0;
            CHECK_STATUS(sms_shaper_buffer_size(&c, Ts, &L), SMS_OK);
            CHECK(L <= MAX_LEN);
            CHECK_STATUS(sms_shaper_taps(&c, Ts, taps, MAX_LEN), SMS_OK);
            for (i = 0; i < L; ++i) {
                sum += taps[i];
                moment += (double)i * taps[i];
            }
            CHECK_STATUS(sms_stage_config_lag(&c, Ts, &lag), SMS_OK);
            CHECK_CLOSE(lag, moment / sum, 16.0 * (double)L * 2.2e-16, lag);
            /* a built stage's lag comes from its identity: the same number */
            CHECK_STATUS(sms_stage_memory_size(&c, Ts, &cells), SMS_OK);
            CHECK(cells <= CELLS);
            CHECK_STATUS(sms_stage_init(&stage, &c, Ts, mem_a, CELLS), SMS_OK);
            CHECK(sms_stage_lag(&stage) == lag);
        }
}

/* The fields of an SI shaper (order, tolerance, duration) and of an input smoother survive
 * the identity: the tunable reports the configuration it was built with. */
static void test_identity_configs(void)
{
    const double Ts = 2e-4;
    sms_stage_config list[3];
    size_t i, cells = 0;
    list[0] = si(7, 2.3, 0.03, 41.0);
    list[1] = shaper(SMS_SMOOTH_MZV, 29.0, 0.2);
    list[2] = shaper(SMS_SMOOTH_ZVD_EI, 29.0, 0.0);
    CHECK_STATUS(sms_tunable_slot_cells(list, 3, Ts, &cells), SMS_OK);
    CHECK(2u * cells <= CELLS);
    for (i = 0; i < 3; ++i) {
        sms_tunable t;
        sms_stage_config back;
        double lag = 0.0;
        CHECK_STATUS(sms_tunable_init(&t, &list[i], Ts, cells, mem_a, 2u * cells), SMS_OK);
        back = sms_tunable_config(&t);
        CHECK(back.kind == list[i].kind && back.wn == list[i].wn);
        if (list[i].kind == SMS_SHAPER_SI)
            CHECK(back.order == 7u && back.duration == 2.3 && back.tolerance == 0.03
                  && back.zeta == list[i].zeta);
        if (list[i].kind == SMS_SMOOTH_MZV)
            CHECK(back.zeta == 0.2);
        CHECK_STATUS(sms_stage_config_lag(&list[i], Ts, &lag), SMS_OK);
        CHECK(sms_stage_lag(sms_tunable_active(&t)) == lag);
    }
}

/* Retune between the new FIR kinds: once both lengths have passed, the output is the new
 * filter's alone to rounding; a state saved during the switch names both configurations and
 * a tunable brought there continues it bit for bit. */
static void test_retune_new_kinds(void)
{
    const double Ts = 2e-4;
    sms_stage_config from = shaper(SMS_SMOOTH_EI, 31.0, 0.1), to = si(5, 1.4, 0.05, 47.0);
    sms_stage_config seq[2], active, old;
    sms_tunable t, u;
    sms_stage alone;
    size_t cells = 0, n, k, L_from = 0, L_to = 0, count;
    int switching = 0;
    seq[0] = from;
    seq[1] = to;
    CHECK_STATUS(sms_tunable_slot_cells(seq, 2, Ts, &cells), SMS_OK);
    CHECK(2u * cells <= CELLS);
    CHECK_STATUS(sms_tunable_init(&t, &from, Ts, cells, mem_a, 2u * cells), SMS_OK);
    CHECK_STATUS(sms_stage_init(&alone, &to, Ts, mem_b, CELLS), SMS_OK);
    CHECK_STATUS(sms_stage_buffer_size(&from, Ts, &L_from), SMS_OK);
    CHECK_STATUS(sms_stage_buffer_size(&to, Ts, &L_to), SMS_OK);
    sms_tunable_reset(&t, (sms_real)1);
    sms_stage_reset(&alone, (sms_real)0);
    for (n = 0; n < 40; ++n) {   /* a ramp through the old filter */
        sms_real x = (sms_real)(1.0 + 0.01 * (double)n);
        sms_tunable_step(&t, &x);
    }
    CHECK_STATUS(sms_tunable_retune(&t, &to), SMS_OK);
    CHECK(sms_tunable_switching(&t));
    for (k = 0; k < 400; ++k) {   /* the new filter from the switch on: another ramp */
        sms_real x = (sms_real)(1.39 + 0.02 * (double)k), y = x;
        sms_real z = (sms_real)(0.02 * (double)k);
        if (k == 10) {   /* mid-switch: save, rebuild from the state's configurations */
            count = sms_tunable_state_count(&t);
            CHECK(count <= MAX_LEN);
            sms_tunable_get_state(&t, state_a);
            CHECK_STATUS(sms_tunable_state_configs(state_a, count, &active, &old, &switching),
                         SMS_OK);
            CHECK(switching == 1 && old.kind == SMS_SMOOTH_EI && old.zeta == 0.1
                  && active.kind == SMS_SHAPER_SI && active.order == 5u
                  && active.duration == 1.4 && active.tolerance == 0.05);
            CHECK_STATUS(sms_tunable_init(&u, &old, Ts, cells, mem_b + CELLS / 2u, 2u * cells),
                         SMS_OK);
            CHECK_STATUS(sms_tunable_retune(&u, &active), SMS_OK);
            CHECK_STATUS(sms_tunable_set_state(&u, state_a, count), SMS_OK);
        }
        sms_tunable_step(&t, &y);
        if (k >= 10) {
            sms_real yu = x;
            sms_tunable_step(&u, &yu);
            CHECK(yu == y);
        }
        /* B alone on the increments since the switch, plus the held value */
        sms_stage_step(&alone, &z);
        if (k + 2u >= (L_from > L_to ? L_from : L_to))
            CHECK_CLOSE(y, (double)z + 1.39, 16.0 * SMS_TEST_REL_TOL, 10.0);
    }
    CHECK(!sms_tunable_switching(&t));
}

/* User-defined impulses: a retune to or from them is refused and nothing changes; their
 * state's configuration is refused with SMS_ERR_KIND (the identity holds a checksum), the
 * caller's own configuration restores it, and other impulses are refused. */
static void test_impulses_refused(void)
{
    const double Ts = 1e-4;
    sms_stage_config imp = user(), zv = shaper(SMS_SHAPER_ZV, 50.0, 0.05), other = user();
    sms_stage_config seq[2], active;
    sms_tunable t, before, u;
    size_t cells = 0, n, count;
    int switching = 0;
    double lag = 0.0;
    seq[0] = imp;
    seq[1] = zv;
    CHECK_STATUS(sms_tunable_slot_cells(seq, 2, Ts, &cells), SMS_OK);
    CHECK(2u * cells <= CELLS);
    CHECK_STATUS(sms_tunable_init(&t, &imp, Ts, cells, mem_a, 2u * cells), SMS_OK);
    for (n = 0; n < 30; ++n) {
        sms_real x = (sms_real)(0.1 * (double)n);
        sms_tunable_step(&t, &x);
    }
    before = t;
    CHECK_STATUS(sms_tunable_retune(&t, &zv), SMS_ERR_KIND);
    CHECK_STATUS(sms_tunable_retune(&t, &other), SMS_ERR_KIND);
    CHECK(memcmp(&t, &before, sizeof t) == 0);
    /* the lag of the built stage: its taps' centroid, the config's lag to their rounding */
    CHECK_STATUS(sms_stage_config_lag(&imp, Ts, &lag), SMS_OK);
    CHECK_CLOSE(sms_stage_lag(sms_tunable_active(&t)), lag, 4.0 * SMS_TEST_REL_TOL, lag);
    /* the state */
    count = sms_tunable_state_count(&t);
    sms_tunable_get_state(&t, state_a);
    CHECK_STATUS(sms_tunable_state_configs(state_a, count, &active, NULL, &switching), SMS_ERR_KIND);
    CHECK_STATUS(sms_tunable_init(&u, &imp, Ts, cells, mem_b, 2u * cells), SMS_OK);
    CHECK_STATUS(sms_tunable_set_state(&u, state_a, count), SMS_OK);
    sms_tunable_get_state(&u, state_b);
    CHECK(memcmp(state_a, state_b, count * sizeof(double)) == 0);
    other.amplitudes[1] = 0.41;   /* other impulses: their checksum differs (in the head's
                                   * identity, so the tunable refuses it as no state of its own) */
    CHECK_STATUS(sms_tunable_init(&u, &other, Ts, cells, mem_b, 2u * cells), SMS_OK);
    CHECK_STATUS(sms_tunable_set_state(&u, state_a, count), SMS_ERR_STATE);
    CHECK_STATUS(sms_stage_check_state(sms_tunable_active(&u), state_a + SMS_TUNABLE_STATE_HEAD
                                       + 2u * SMS_STATE_IDENTITY_COUNT,
                                       sms_stage_state_count(sms_tunable_active(&u))),
                 SMS_ERR_STATE_DURATION);   /* the stage names the checksum's field */
    /* and a ZV tunable is refused a retune to impulses */
    CHECK_STATUS(sms_tunable_init(&u, &zv, Ts, cells, mem_b, 2u * cells), SMS_OK);
    before = u;
    CHECK_STATUS(sms_tunable_retune(&u, &imp), SMS_ERR_KIND);
    CHECK(memcmp(&u, &before, sizeof u) == 0);
}

int main(void)
{
    test_input_smoother_lag();
    test_identity_configs();
    test_retune_new_kinds();
    test_impulses_refused();
    return check_summary("test_families_retune");
}
