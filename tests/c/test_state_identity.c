/* SPDX-License-Identifier: Apache-2.0 */
/* Saved stage states carry their configuration's identity (config.h, SMS_STATE_IDENTITY_COUNT):
 * loading a state saved by another configuration is refused, writing nothing, with the status
 * that names the first field that differs; a field the kind does not read does not matter. */
#include <string.h>
#include "check.h"

#define CELLS 4096
static sms_memory_cell mem_a[CELLS], mem_b[CELLS], mem_b_before[CELLS];
static double state[CELLS];
static const double Ts = 1e-3;

/* Save a state of config a (after some input), load it into config b: expect `want`, and on
 * an error b (instance and memory) untouched. */
static void load_across(const sms_stage_config *a, double Ts_a, const sms_stage_config *b,
                        double Ts_b, sms_status want)
{
    sms_stage sa, sb, sb_before;
    size_t ca, cb, n, i;
    CHECK_STATUS(sms_stage_memory_size(a, Ts_a, &ca), SMS_OK);
    CHECK_STATUS(sms_stage_memory_size(b, Ts_b, &cb), SMS_OK);
    if (ca > CELLS || cb > CELLS) {
        CHECK(0);
        return;
    }
    CHECK_STATUS(sms_stage_init(&sa, a, Ts_a, mem_a, ca), SMS_OK);
    CHECK_STATUS(sms_stage_init(&sb, b, Ts_b, mem_b, cb), SMS_OK);
    for (i = 0; i < 50; ++i) {
        sms_real x = (sms_real)(i % 7);
        sms_stage_step(&sa, &x);
    }
    n = sms_stage_state_count(&sa);
    CHECK(n <= CELLS && n > SMS_STATE_IDENTITY_COUNT);
    sms_stage_get_state(&sa, state);
    sb_before = sb;
    memcpy(mem_b_before, mem_b, cb * sizeof mem_b[0]);
    CHECK_STATUS(sms_stage_check_state(&sb, state, n), want);
    CHECK_STATUS(sms_stage_set_state(&sb, state, n), want);
    if (want != SMS_OK) {
        CHECK(memcmp(&sb, &sb_before, sizeof sb) == 0);
        CHECK(memcmp(mem_b, mem_b_before, cb * sizeof mem_b[0]) == 0);
    }
}

static void smoothers(void)
{
    sms_stage_config a = sms_stage_config_default(SMS_DAMPED_HARMONIC), b;
    a.T = 0.0375;
    a.sigma = -20.0;
    b = a; load_across(&a, Ts, &b, Ts, SMS_OK);
    b = a; b.wn = 40.0; b.tolerance = 0.2; load_across(&a, Ts, &b, Ts, SMS_OK); /* not read */
    b = a; b.T = 0.0376; load_across(&a, Ts, &b, Ts, SMS_ERR_STATE_T);
    b = a; b.T = 0.04; load_across(&a, Ts, &b, Ts, SMS_ERR_STATE_T);         /* another size too */
    b = a; b.sigma = -21.0; load_across(&a, Ts, &b, Ts, SMS_ERR_STATE_SIGMA);
    b = a; b.k = 3u; load_across(&a, Ts, &b, Ts, SMS_ERR_STATE_K);
    b = a; b.timing = SMS_TIMING_PAPER; load_across(&a, Ts, &b, Ts, SMS_ERR_STATE_TIMING);
    b = a; b.kind = SMS_HARMONIC; load_across(&a, Ts, &b, Ts, SMS_ERR_STATE_KIND);
    b = a; load_across(&a, Ts, &b, 1.001e-3, SMS_ERR_STATE_TS);
    /* sigma is not read by the undamped families */
    a.kind = b.kind = SMS_RECTANGULAR;
    b.sigma = -5.0;
    load_across(&a, Ts, &b, Ts, SMS_OK);
}

static void shapers_and_notches(void)
{
    sms_stage_config a = sms_stage_config_default(SMS_SHAPER_GMZV), b;
    a.wn = 60.0;
    a.zeta = 0.05;
    a.order = 4u;
    a.duration = 1.0;
    b = a; load_across(&a, Ts, &b, Ts, SMS_OK);
    b = a; b.wn = 61.0; load_across(&a, Ts, &b, Ts, SMS_ERR_STATE_WN);
    b = a; b.zeta = 0.06; load_across(&a, Ts, &b, Ts, SMS_ERR_STATE_ZETA);
    b = a; b.order = 5u; load_across(&a, Ts, &b, Ts, SMS_ERR_STATE_ORDER);
    b = a; b.duration = 1.1; load_across(&a, Ts, &b, Ts, SMS_ERR_STATE_DURATION);
    b = a; b.tolerance = 0.01; load_across(&a, Ts, &b, Ts, SMS_OK);      /* not read by GMZV */
    a.kind = b.kind = SMS_SHAPER_EI2;
    b = a; b.tolerance = 0.06; load_across(&a, Ts, &b, Ts, SMS_ERR_STATE_TOLERANCE);
    b = a; b.order = 2u; load_across(&a, Ts, &b, Ts, SMS_OK);             /* not read by EI2 */
    a = sms_stage_config_default(SMS_NOTCH_TUSTIN);
    a.wn = 80.0;
    a.zeta = 0.02;
    b = a; b.notch_pole_zeta = 0.8; load_across(&a, Ts, &b, Ts, SMS_ERR_STATE_NOTCH_POLE_ZETA);
    b = a; b.kind = SMS_NOTCH_MATCHED; load_across(&a, Ts, &b, Ts, SMS_ERR_STATE_KIND);
    b = a; b.kind = SMS_SHAPER_ZV; load_across(&a, Ts, &b, Ts, SMS_ERR_STATE_KIND);
}

/* Tag, version and precision: a vector that is not a state of this build. */
static void format_and_precision(void)
{
    sms_stage_config c = sms_stage_config_default(SMS_HARMONIC);
    sms_stage s;
    size_t cells, n;
    static double bad[CELLS];
    c.T = 0.02;
    CHECK_STATUS(sms_stage_memory_size(&c, Ts, &cells), SMS_OK);
    CHECK_STATUS(sms_stage_init(&s, &c, Ts, mem_a, cells), SMS_OK);
    n = sms_stage_state_count(&s);
    sms_stage_get_state(&s, state);
    CHECK(state[0] == SMS_STATE_TAG && state[1] == SMS_STATE_VERSION);
    CHECK(state[2] == (double)sizeof(sms_real));
    memcpy(bad, state, n * sizeof *state);
    bad[2] = sizeof(sms_real) == sizeof(double) ? 4.0 : 8.0;
    CHECK_STATUS(sms_stage_set_state(&s, bad, n), SMS_ERR_STATE_PRECISION);
    bad[2] = state[2];
    bad[1] = SMS_STATE_VERSION + 1.0;
    CHECK_STATUS(sms_stage_set_state(&s, bad, n), SMS_ERR_STATE_FORMAT);
    bad[1] = state[1];
    bad[0] = 0.0;
    CHECK_STATUS(sms_stage_set_state(&s, bad, n), SMS_ERR_STATE_FORMAT);
    CHECK_STATUS(sms_stage_set_state(&s, state, n), SMS_OK);
    CHECK(strstr(sms_status_string(SMS_ERR_STATE_SIGMA), "sigma") != NULL);
}

/* A chain names the field of the first stage whose identity differs. */
static void chain_names_the_field(void)
{
    sms_stage_config c[3], d[3];
    sms_chain a, b;
    sms_stage sa[3], sb[3];
    size_t ca, cb;
    c[0] = sms_stage_config_default(SMS_RECTANGULAR);
    c[0].T = 0.01;
    c[1] = sms_stage_config_default(SMS_EXPONENTIAL);
    c[1].T = 0.02;
    c[1].sigma = -10.0;
    c[2] = sms_stage_config_default(SMS_SHAPER_ZVD);
    c[2].wn = 70.0;
    memcpy(d, c, sizeof c);
    d[1].sigma = -11.0;
    CHECK_STATUS(sms_chain_memory_size(c, 3, Ts, &ca), SMS_OK);
    CHECK_STATUS(sms_chain_memory_size(d, 3, Ts, &cb), SMS_OK);
    CHECK_STATUS(sms_chain_init(&a, sa, c, 3, Ts, mem_a, ca), SMS_OK);
    CHECK_STATUS(sms_chain_init(&b, sb, d, 3, Ts, mem_b, cb), SMS_OK);
    sms_chain_get_state(&a, state);
    CHECK_STATUS(sms_chain_set_state(&b, state, sms_chain_state_count(&a)), SMS_ERR_STATE_SIGMA);
    /* another length too: the field is still named */
    d[1].sigma = c[1].sigma;
    d[1].T = 0.03;
    CHECK_STATUS(sms_chain_memory_size(d, 3, Ts, &cb), SMS_OK);
    CHECK_STATUS(sms_chain_init(&b, sb, d, 3, Ts, mem_b, cb), SMS_OK);
    CHECK(sms_chain_state_count(&b) != sms_chain_state_count(&a));
    CHECK_STATUS(sms_chain_set_state(&b, state, sms_chain_state_count(&a)), SMS_ERR_STATE_T);
}

int main(void)
{
    smoothers();
    shapers_and_notches();
    format_and_precision();
    chain_names_the_field();
    return check_summary("test_state_identity");
}
