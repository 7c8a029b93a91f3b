/* SPDX-License-Identifier: Apache-2.0 */
/* Bounded work and finite results: sizes of arbitrarily long filters come from closed forms
 * (exact values checked here; tests/bench/refusal_bench.c prints the times), designs and
 * identifications never return SMS_OK with a non-finite value, and one rule for T below Ts. */
#include <float.h>
#include <math.h>
#include <string.h>
#include "check.h"
#include "compensated_sum.h"

static const sms_kind smoothers[] = { SMS_RECTANGULAR, SMS_HARMONIC, SMS_DAMPED_HARMONIC,
                                      SMS_EXPONENTIAL };

static int all_finite(const double *v, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i)
        if (!isfinite(v[i]))
            return 0;
    return 1;
}

/* Sizes of smoothers up to 2^52 samples, on and off the grid: N (or floor(nu) + 1 for exact
 * timing), without any per-tap work. */
static void long_smoother_sizes(void)
{
    const double Ts = 1e-6, nus[] = { 1e6, 1e9 + 0.25, 1e12, 1e15 + 0.5, 4.0e15 };
    size_t i, j, need, len;
    for (i = 0; i < sizeof nus / sizeof nus[0]; ++i)
        for (j = 0; j < 4; ++j) {
            sms_stage_config c = sms_stage_config_default(smoothers[j]);
            double nu;
            c.T = nus[i] * Ts;
            c.sigma = -1e-3;
            nu = c.T / Ts;
            CHECK_STATUS(sms_stage_buffer_size(&c, Ts, &need), SMS_OK);
            CHECK_STATUS(sms_smoother_length(&c, Ts, &len), SMS_OK);
            if (fabs(nu - floor(nu + 0.5)) <= 1e-9 * nu) {
                CHECK(need == (size_t)floor(nu + 0.5) && len == need);
            } else {
                CHECK(need == (size_t)floor(nu) && len == need + 1u);
            }
        }
}

/* A mode with zeta = 0.99999999999: T = k Td is 1.4e7..2.1e7 samples at Ts = 1 ms; the design
 * (closed-form sums) must be finite and the same as the taps the short form gives. */
static void near_critical_mode(void)
{
    size_t j, need;
    for (j = 0; j < 4; ++j) {
        sms_stage_config c;
        CHECK_STATUS(sms_design_for_mode(smoothers[j], 100.0, 0.99999999999, 1u, &c), SMS_OK);
        CHECK_STATUS(sms_stage_buffer_size(&c, 1e-3, &need), SMS_OK);
        CHECK(need > 10000000u && need < 30000000u);
    }
}

/* Closed-form normalisation against a direct compensated sum, where the old per-tap loop
 * was the definition: every family, on and off the grid, light and heavy damping. */
static void closed_form_dc_gain(void)
{
    static double taps[20001];
    const double Ts = 1e-3, Ts_nu[] = { 7.0, 100.0, 1234.5678, 19999.9 };
    const double sigmas[] = { 0.0, -0.37, -80.0 };
    size_t i, j, m, n;
    for (i = 0; i < sizeof Ts_nu / sizeof Ts_nu[0]; ++i)
        for (j = 0; j < 4; ++j)
            for (m = 0; m < 3; ++m) {
                sms_stage_config c = sms_stage_config_default(smoothers[j]);
                compensated_sum sum = { 0.0, 0.0 };
                size_t len;
                c.T = Ts_nu[i] * Ts;
                c.sigma = sigmas[m];
                CHECK_STATUS(sms_smoother_length(&c, Ts, &len), SMS_OK);
                CHECK_STATUS(sms_smoother_taps(&c, Ts, taps, 20001), SMS_OK);
                CHECK(all_finite(taps, len));
                for (n = 0; n < len; ++n)
                    compensated_add_product(&sum, taps[n], 1.0);
                /* each tap carries one rounding of gain * base: |sum - 1| <= a few eps */
                CHECK_CLOSE(compensated_value(&sum), 1.0, 8.0 * DBL_EPSILON, 1.0);
            }
}

/* Two-hump EI with a tolerance near the bottom of (0, 1): finite taps summing to 1. */
static void ei2_tiny_tolerance(void)
{
    const double tolerances[] = { 1e-100, 1e-200, 1e-300, 4.9e-324 };
    double amp[8], times[8], taps[64];
    size_t i, n, m;
    for (i = 0; i < sizeof tolerances / sizeof tolerances[0]; ++i) {
        sms_stage_config c = sms_stage_config_default(SMS_SHAPER_EI2);
        double sum = 0.0;
        c.wn = 2.0 * 3.14159265358979 * 40.0;
        c.zeta = 0.1;
        c.tolerance = tolerances[i];
        CHECK_STATUS(sms_shaper_impulses(&c, amp, times, 8, &n), SMS_OK);
        CHECK(n == 4 && all_finite(amp, n));
        for (m = 0; m < n; ++m)
            sum += amp[m];
        CHECK_CLOSE(sum, 1.0, 4.0 * DBL_EPSILON, 1.0);
        /* V -> 0 is ZVD's cousin: A1 -> 1/8 (X -> 0) */
        CHECK(amp[0] > 0.0 && amp[0] < 0.2);
        CHECK_STATUS(sms_shaper_taps(&c, 1e-3, taps, 64), SMS_OK);
        CHECK(all_finite(taps, 64));
    }
}

/* Two peaks: every input meeting the documented conditions gives a finite mode with wn > 0 and
 * zeta in [0, 1), or SMS_ERR_RECORD when the rates overflow double. */
static void peaks_extremes(void)
{
    const double times[][2] = { { 0.0, 1e-300 }, { 0.0, 1e300 }, { -DBL_MAX, DBL_MAX },
                                { 0.0, 1.0 }, { 1.0, nextafter(1.0, 2.0) }, { 0.0, 4.9e-324 } };
    const double peaks[][2] = { { 1.0, 0.5 }, { DBL_MAX, 4.9e-324 }, { 1.0, nextafter(1.0, 0.0) },
                                { -1.0, -1e-300 }, { 1e-300, 1e-310 } };
    size_t i, j;
    for (i = 0; i < sizeof times / sizeof times[0]; ++i)
        for (j = 0; j < sizeof peaks / sizeof peaks[0]; ++j) {
            sms_mode m;
            sms_status st;
            memset(&m, 0x5A, sizeof m);
            st = sms_identify_from_peaks(times[i][0], peaks[j][0], times[i][1], peaks[j][1], &m);
            if (st == SMS_OK) {
                CHECK(isfinite(m.wn) && m.wn > 0.0 && isfinite(m.wd) && m.wd > 0.0);
                /* sigma may round to -0 (a decay of one ulp over 1e308 s) */
                CHECK(isfinite(m.sigma) && m.sigma <= 0.0);
                CHECK(m.zeta >= 0.0 && m.zeta < 1.0);
            } else {
                CHECK(st == SMS_ERR_RECORD);
            }
        }
    {   /* the cases that used to give wn = Inf, 0 and NaN */
        sms_mode m;
        CHECK_STATUS(sms_identify_from_peaks(0.0, 1.0, 1e-300, 0.5, &m), SMS_OK);
        CHECK_CLOSE(m.wd, 2.0 * 3.14159265358979323846 / 1e-300, 1e-15, m.wd);
        CHECK_STATUS(sms_identify_from_peaks(-DBL_MAX, 1.0, DBL_MAX, 0.5, &m), SMS_OK);
        CHECK(m.wn > 0.0 && isfinite(m.zeta));
        CHECK_STATUS(sms_identify_from_peaks(0.0, 1.0, 4.9e-324, 0.5, &m), SMS_ERR_RECORD);
    }
}

/* Pole-zero matched notch far below the sample rate: the DC normalisation used to be 0/0. */
static void matched_notch_low_mode(void)
{
    const double wn_ts[] = { 1e-6, 1e-10, 1e-200, 1e-306 };
    size_t i;
    for (i = 0; i < sizeof wn_ts / sizeof wn_ts[0]; ++i) {
        sms_stage_config c = sms_stage_config_default(SMS_NOTCH_MATCHED);
        sms_notch f;
        sms_real x = (sms_real)3;
        int n;
        c.wn = wn_ts[i] / 1e-3;
        c.zeta = 0.01;
        CHECK_STATUS(sms_notch_init(&f, &c, 1e-3), SMS_OK);
        CHECK(isfinite((double)f.d0) && isfinite((double)f.d2) && isfinite((double)f.a1)
              && isfinite((double)f.a2));
        sms_notch_reset(&f, (sms_real)3);
        for (n = 0; n < 10; ++n)
            sms_notch_step(&f, &x);
        CHECK(x == (sms_real)3); /* unit DC gain */
    }
    {   /* wn Ts below the normal range of double is refused, naming wn */
        sms_stage_config c = sms_stage_config_default(SMS_NOTCH_MATCHED);
        sms_notch f;
        c.wn = 1e-310 / 1e-3;
        CHECK_STATUS(sms_notch_init(&f, &c, 1e-3), SMS_ERR_WN);
    }
}

/* One rule for T below Ts: refused unless within the grid tolerance of one sample. */
static void tiny_durations(void)
{
    const double Ts = 1e-3, below[] = { 1e-12, 1e-9, 1e-3, 0.5, 1.0 - 2e-9 };
    size_t i, j, need;
    for (i = 0; i < sizeof below / sizeof below[0]; ++i) {
        for (j = 0; j < 4; ++j) {
            sms_stage_config c = sms_stage_config_default(smoothers[j]);
            c.T = below[i] * Ts;
            CHECK_STATUS(sms_stage_buffer_size(&c, Ts, &need), SMS_ERR_DURATION_BELOW_TS);
            c.timing = SMS_TIMING_PAPER;
            CHECK_STATUS(sms_stage_buffer_size(&c, Ts, &need), SMS_ERR_DURATION_BELOW_TS);
        }
        CHECK_STATUS(sms_bspline_buffer_size(3u, 1u, below[i] * Ts, Ts, &need),
                     SMS_ERR_DURATION_BELOW_TS);
    }
    {   /* T within 1e-9 of Ts is one sample for the families that allow one */
        sms_stage_config c = sms_stage_config_default(SMS_RECTANGULAR);
        c.T = (1.0 - 5e-10) * Ts;
        CHECK_STATUS(sms_stage_buffer_size(&c, Ts, &need), SMS_OK);
        CHECK(need == 1u);
        CHECK_STATUS(sms_bspline_buffer_size(3u, 1u, c.T, Ts, &need), SMS_OK);
        c.kind = SMS_HARMONIC;
        CHECK_STATUS(sms_stage_buffer_size(&c, Ts, &need), SMS_ERR_DURATION_BELOW_TS);
    }
}

/* Heavily damped harmonic smoothers (sigma Ts from -6 to -200, first taps ~e^{sigma Ts}) have
 * an internal gain ~e^{-sigma Ts}/sin(pi/N): their finite input range sms_smoother_input_max()
 * is below SMS_INPUT_MAX, and at it (inputs and rest alternating +-bound, the worst swing)
 * every output stays finite and every saved state loads. The FMU fuzz campaign found NaN
 * outputs for inputs below SMS_INPUT_MAX in exactly this class. */
#define DAMPED_MAX_CELLS 4096
static void damped_input_range(void)
{
#ifdef SMS_USE_FLOAT
    const double decays[] = { -3.0, -6.0, -19.0, -40.0, -80.0 };
#else
    const double decays[] = { -6.0, -19.0, -50.0, -200.0, -700.0 };
#endif
    const double Ts = 1e-3, nus[] = { 2.0, 3.0, 10.0, 37.5, 200.0 };
    static sms_memory_cell memory[DAMPED_MAX_CELLS];
    static double state[DAMPED_MAX_CELLS];
    size_t i, j, t, k;
    for (i = 0; i < sizeof decays / sizeof decays[0]; ++i)
        for (j = 0; j < sizeof nus / sizeof nus[0]; ++j)
            for (t = 0; t < 2; ++t) {
                sms_stage_config c[2];
                sms_chain chain;
                sms_stage stages[2];
                size_t cells, n_state;
                double bound, chain_bound;
                int finite = 1;
                c[0] = sms_stage_config_default(SMS_DAMPED_HARMONIC);
                c[0].T = nus[j] * Ts;
                c[0].sigma = decays[i] / Ts;
                c[0].k = 1u;
                c[0].timing = t ? SMS_TIMING_PAPER : SMS_TIMING_EXACT;
                if (nus[j] == 37.5 && !t)
                    c[0].k = 3u;
                c[1] = sms_stage_config_default(SMS_RECTANGULAR);
                c[1].T = 5.0 * Ts;
                CHECK_STATUS(sms_chain_memory_size(c, 2, Ts, &cells), SMS_OK);
                CHECK(cells <= DAMPED_MAX_CELLS);
                if (cells > DAMPED_MAX_CELLS)
                    continue;
                CHECK_STATUS(sms_chain_init(&chain, stages, c, 2, Ts, memory, cells), SMS_OK);
                bound = sms_stage_input_max(&stages[0]);
                chain_bound = sms_chain_input_max(&chain);
                CHECK(bound >= 1.0 && bound <= SMS_INPUT_MAX);
                CHECK(chain_bound <= bound && chain_bound >= bound / 3.0);
                /* the range is a bound, not a guess: it is below SMS_INPUT_MAX exactly when the
                 * internal gain e^{-sigma Ts}/sin(pi/N) is large */
                if (decays[i] <= -19.0)
                    CHECK(bound < SMS_INPUT_MAX);
                sms_chain_reset(&chain, (sms_real)(-chain_bound));
                for (k = 0; k < 4000u && finite; ++k) {
                    sms_real x = (sms_real)((k / 3u) % 2u ? chain_bound : -chain_bound);
                    sms_chain_step(&chain, &x);
                    finite = isfinite((double)x);
                    if (k % 997u == 0u) {
                        n_state = sms_chain_state_count(&chain);
                        CHECK(n_state <= DAMPED_MAX_CELLS);
                        sms_chain_get_state(&chain, state);
                        CHECK_STATUS(sms_chain_set_state(&chain, state, n_state), SMS_OK);
                    }
                }
                CHECK(finite);
                if (!finite)
                    fprintf(stderr, "  sigma Ts = %g, T/Ts = %g, timing %d: NaN at sample %lu "
                            "for inputs of %g\n", decays[i], nus[j], (int)t, (unsigned long)k,
                            chain_bound);
            }
    /* ordinary smoothers keep the whole range */
    for (j = 0; j < 4; ++j) {
        sms_stage_config c = sms_stage_config_default(smoothers[j]);
        sms_stage stage;
        size_t cells;
        c.T = 0.0375;
        c.sigma = -20.0;
        CHECK_STATUS(sms_stage_memory_size(&c, Ts, &cells), SMS_OK);
        CHECK_STATUS(sms_stage_init(&stage, &c, Ts, memory, cells), SMS_OK);
        CHECK(sms_stage_input_max(&stage) == SMS_INPUT_MAX);
    }
    /* a sigma so negative that inputs of order one would overflow is refused at init */
    {
        sms_stage_config c = sms_stage_config_default(SMS_DAMPED_HARMONIC);
        size_t cells;
        c.T = 2.0 * Ts;
#ifdef SMS_USE_FLOAT
        c.sigma = -86.0 / Ts;
#else
        c.sigma = -708.0 / Ts;
#endif
        CHECK_STATUS(sms_stage_memory_size(&c, Ts, &cells), SMS_ERR_SIGMA);
    }
}

int main(void)
{
    long_smoother_sizes();
    near_critical_mode();
    closed_form_dc_gain();
    ei2_tiny_tolerance();
    peaks_extremes();
    matched_notch_low_mode();
    tiny_durations();
    damped_input_range();
    return check_summary("test_bounded");
}
