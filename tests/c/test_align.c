/* SPDX-License-Identifier: Apache-2.0 */
/* Lags and the fractional delay (align.h): the lag of every family is the delay a ramp comes
 * out with; a chain's is the sum; a chain padded with a delay to a whole number of samples and
 * fed A samples early passes a constant-speed segment unchanged (zero lag, to rounding); the
 * delay is a pure delay for whole samples, exact on constants and ramps, block-invariant, and
 * its hold forms and saved state agree with its steps. */
#include <string.h>
#include "check.h"

#define N_RAMP 6000
#define CELLS 8192

static const double Ts = 1e-3;
#ifdef SMS_USE_FLOAT
#define UNIT 5.9604644775390625e-08   /* unit roundoff 2^-24 */
#else
#define UNIT 1.1102230246251565e-16   /* 2^-53 */
#endif
static sms_memory_cell memory[CELLS];
static sms_real ring[CELLS], ring2[CELLS];

static sms_stage_config config_of(int which)
{
    sms_stage_config c;
    switch (which) {
    case 0: c = sms_stage_config_default(SMS_RECTANGULAR); c.T = 40.3 * Ts; break;
    case 1: c = sms_stage_config_default(SMS_HARMONIC); c.T = 31.0 * Ts; break;
    case 2: (void)sms_design_for_mode(SMS_DAMPED_HARMONIC, 123.7, 0.1, 1, &c); break;
    case 3: (void)sms_design_for_mode(SMS_EXPONENTIAL, 300.0, 0.1, 1, &c); break;
    case 4: c = sms_stage_config_default(SMS_RECTANGULAR); c.T = 25.45 * Ts;
            c.timing = SMS_TIMING_BOUNDED; break;
    case 5: (void)sms_design_for_mode(SMS_SHAPER_ZVD, 250.0, 0.05, 1, &c); break;
    case 6: (void)sms_design_for_mode(SMS_SHAPER_EI, 400.0, 0.02, 1, &c); break;
    case 7: (void)sms_design_for_mode(SMS_SHAPER_MZV, 300.0, 0.1, 1, &c); break;
    case 8: (void)sms_design_for_mode(SMS_NOTCH_MATCHED, 500.0, 0.02, 1, &c);
            c.notch_pole_zeta = 0.5; break;
    default: (void)sms_design_for_mode(SMS_NOTCH_TUSTIN, 800.0, 0.0, 1, &c); break;
    }
    return c;
}

/* The lag is what a ramp's output lags by: y[n] = v (n - D) after the transient. */
static void test_lag_is_the_ramps_delay(void)
{
    double worst_ulps = 0.0;
    int which;
    for (which = 0; which < 10; ++which) {
        const sms_stage_config c = config_of(which);
        sms_stage s;
        double lag = -1.0, worst = 0.0;
        const double v = 0.01;
        size_t i;
        CHECK_STATUS(sms_stage_config_lag(&c, Ts, &lag), SMS_OK);
        CHECK_STATUS(sms_stage_init(&s, &c, Ts, memory, CELLS), SMS_OK);
        CHECK(sms_stage_lag(&s) == lag);
        for (i = 0; i < N_RAMP; ++i) {
            sms_real x = (sms_real)(v * (double)i);
            sms_stage_step(&s, &x);
            /* the transient: FIR after its length; a notch's after 5000 samples */
            if (i >= N_RAMP - 500) {
                const double e = fabs((double)x - v * ((double)i - lag));
                if (e > worst)
                    worst = e;
            }
        }
        /* the output's rounding, in ulps of the ramp's largest value (v N = 60): the stage's
         * own sums and the lag's rounding times v */
        CHECK(worst <= 32.0 * UNIT * 60.0);
        if (worst / (UNIT * 60.0) > worst_ulps)
            worst_ulps = worst / (UNIT * 60.0);
        CHECK(lag > 0.0);
    }
    printf("a ramp through every family lags by the stage's lag to %.3g u of its value\n",
           worst_ulps);
    {
        sms_stage_config c[3];
        sms_stage stages[3];
        sms_chain ch;
        double total = 0.0, one;
        int k;
        for (k = 0; k < 3; ++k) {
            c[k] = config_of(k * 4);
            (void)sms_stage_config_lag(&c[k], Ts, &one);
            total += one;
        }
        CHECK_STATUS(sms_chain_config_lag(c, 3, Ts, &one), SMS_OK);
        CHECK_CLOSE(one, total, 1e-15, total);
        CHECK_STATUS(sms_chain_init(&ch, stages, c, 3, Ts, memory, CELLS), SMS_OK);
        CHECK_CLOSE(sms_chain_lag(&ch), total, 1e-15, total);
        CHECK_STATUS(sms_chain_config_lag(c, 0, Ts, &one), SMS_OK);
        CHECK(one == 0.0);
        CHECK_STATUS(sms_chain_config_lag(c, SMS_CHAIN_MAX_STAGES + 1, Ts, &one), SMS_ERR_ORDER);
        c[2].wn = -1.0;
        CHECK_STATUS(sms_chain_config_lag(c, 3, Ts, &one), SMS_ERR_WN);
    }
}

/* Zero lag: a chain padded to A = ceil(D) samples by a delay of A - D, fed A samples early,
 * passes a constant-speed segment unchanged to rounding. */
static void test_centred_constant_speed(void)
{
    sms_stage_config c[2];
    sms_stage stages[2];
    sms_chain ch;
    sms_delay d;
    size_t need, i, A;
    double lag, worst = 0.0;
    const double v = 0.013, x0 = 3.0;
    c[0] = config_of(0);
    c[1] = config_of(6);
    CHECK_STATUS(sms_chain_init(&ch, stages, c, 2, Ts, memory, CELLS), SMS_OK);
    lag = sms_chain_lag(&ch);
    A = (size_t)ceil(lag);
    CHECK_STATUS(sms_delay_buffer_size((double)A - lag, &need), SMS_OK);
    CHECK_STATUS(sms_delay_init(&d, (double)A - lag, ring, CELLS), SMS_OK);
    sms_chain_reset(&ch, (sms_real)x0);
    sms_delay_reset(&d, (sms_real)x0);
    for (i = 0; i < 2000; ++i) {
        /* the input A samples ahead of the output's instant n = i - A */
        const double ahead = i < 300 ? x0 : x0 + v * ((double)i - 300.0);
        sms_real y = (sms_real)ahead;
        sms_chain_step(&ch, &y);
        sms_delay_step(&d, &y);
        if (i >= 900) {   /* the window of both stages inside the segment */
            const double want = x0 + v * ((double)(i - A) - 300.0);
            if (fabs((double)y - want) > worst)
                worst = fabs((double)y - want);
        }
    }
    /* rounding: a few ulps of the position (at most 3 + 0.013 * 1700 = 25) */
    CHECK(worst <= 32.0 * 25.0 * UNIT);
    printf("centred chain (lag %.4f samples, look-ahead %lu): constant speed off by %.3g\n", lag,
           (unsigned long)A, worst);
}

static void test_delay(void)
{
    static sms_real in[500], out1[500], out2[500];
    static double state[CELLS];
    sms_delay d, e;
    size_t need = 0, i;
    CHECK_STATUS(sms_delay_buffer_size(-1.0, &need), SMS_ERR_DURATION);
    CHECK_STATUS(sms_delay_buffer_size(NAN, &need), SMS_ERR_DURATION);
    CHECK_STATUS(sms_delay_buffer_size(2e12, &need), SMS_ERR_DURATION);
    CHECK_STATUS(sms_delay_buffer_size(7.25, &need), SMS_OK);
    CHECK(need == 9);
    CHECK_STATUS(sms_delay_init(&d, 7.25, ring, 8), SMS_ERR_BUFFER_TOO_SMALL);
    CHECK_STATUS(sms_delay_init(&d, 7.25, NULL, 9), SMS_ERR_NULL);
    /* whole samples: the samples themselves, m later */
    CHECK_STATUS(sms_delay_init(&d, 5.0, ring, CELLS), SMS_OK);
    for (i = 0; i < 500; ++i)
        in[i] = (sms_real)(sin(0.37 * (double)i) * 7.1);
    sms_delay_process(&d, in, out1, 500);
    for (i = 5; i < 500; ++i)
        CHECK(out1[i] == in[i - 5]);
    /* fractional: constants exact, ramps delayed by exactly d to rounding */
    CHECK_STATUS(sms_delay_init(&d, 3.3, ring, CELLS), SMS_OK);
    sms_delay_reset(&d, (sms_real)0.1);
    for (i = 0; i < 20; ++i) {
        sms_real x = (sms_real)0.1;
        sms_delay_step(&d, &x);
        CHECK(x == (sms_real)0.1);
    }
    for (i = 0; i < 100; ++i) {
        sms_real x = (sms_real)(0.5 * (double)i);
        sms_delay_step(&d, &x);
        if (i >= 5)
            CHECK_CLOSE(x, 0.5 * ((double)i - 3.3), 4 * UNIT,
                        0.5 * (double)i);
    }
    /* blocks, hold forms and state against steps */
    CHECK_STATUS(sms_delay_init(&d, 11.6, ring, CELLS), SMS_OK);
    CHECK_STATUS(sms_delay_init(&e, 11.6, ring2, CELLS), SMS_OK);
    sms_delay_process(&d, in, out1, 500);
    for (i = 0; i < 500; i += 7)
        sms_delay_process(&e, in + i, out2 + i, i + 7 <= 500 ? 7 : 500 - i);
    CHECK(memcmp(out1, out2, sizeof out1) == 0);
    sms_delay_get_state(&d, state);
    CHECK_STATUS(sms_delay_set_state(&e, state, sms_delay_state_count(&d) - 1), SMS_ERR_STATE);
    state[2] = 99.0;
    CHECK_STATUS(sms_delay_check_state(&e, state, sms_delay_state_count(&d)), SMS_ERR_STATE);
    sms_delay_get_state(&d, state);
    CHECK_STATUS(sms_delay_set_state(&e, state, sms_delay_state_count(&d)), SMS_OK);
    {
        sms_real y1 = 0, y2;
        for (i = 0; i < 1000; ++i) {
            y1 = (sms_real)2.5;
            sms_delay_step(&d, &y1);
        }
        CHECK(sms_delay_settle_length(&e) == 13);
        y2 = sms_delay_settle(&e, (sms_real)2.5, 1000);
        CHECK(y1 == y2 && d.head == e.head);
        CHECK(memcmp(ring, ring2, 13 * sizeof ring[0]) == 0);
        sms_delay_advance(&e, 12345);
        for (i = 0; i < 12345; ++i) {
            y1 = (sms_real)2.5;
            sms_delay_step(&d, &y1);
        }
        CHECK(d.head == e.head);
    }
}

int main(void)
{
    test_lag_is_the_ramps_delay();
    test_centred_constant_speed();
    test_delay();
    return check_summary("test_align");
}
