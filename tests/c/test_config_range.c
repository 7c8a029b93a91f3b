/* SPDX-License-Identifier: Apache-2.0 */
/* The input range and gain bound of a configuration before it is built
 * (sms_stage_config_range, sms_chain_config_input_max) and of a tunable chain through retunes
 * still to come (sms_tunable_chain_retune_input_max): closed forms of user-defined impulses and
 * ZV taps, and bit for bit what the built stage, chain or switching tunable chain reports. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "check.h"

#ifdef SMS_USE_FLOAT
#define REAL_MAX ((double)FLT_MAX)
#else
#define REAL_MAX DBL_MAX
#endif

static const double Ts = 1e-3;

/* Two user-defined impulses a, 1 - a on the sample grid (paper timing: the taps are the
 * amplitudes, exact in float and double for these a). */
static sms_stage_config two_impulses(double a)
{
    sms_stage_config c = sms_stage_config_default(SMS_SHAPER_IMPULSES);
    c.timing = SMS_TIMING_PAPER;
    c.order = 2;
    c.amplitudes[0] = a;
    c.amplitudes[1] = 1.0 - a;
    c.times[0] = 0.0;
    c.times[1] = 10.0 * Ts;
    return c;
}

/* Build config into malloc'd memory; 0 on failure. */
static int build(const sms_stage_config *c, sms_stage *stage, sms_memory_cell **mem)
{
    size_t cells = 0;
    if (sms_stage_memory_size(c, Ts, &cells) != SMS_OK)
        return 0;
    *mem = (sms_memory_cell *)calloc(cells > 0 ? cells : 1, sizeof(sms_memory_cell));
    if (*mem == NULL)
        return 0;
    if (sms_stage_init(stage, c, Ts, *mem, cells) != SMS_OK) {
        free(*mem);
        return 0;
    }
    return 1;
}

/* Impulses a, 1 - a: sum |g| = 2a - 1 for a >= 1, so the range is REAL_MAX / (2 (2a - 1)),
 * below SMS_INPUT_MAX for a = 600.5 (sum 1200) in either precision. */
static void impulses_closed_form(void)
{
    const double as[] = { 600.5, 2.5, 1.0, 0.75 };
    size_t i;
    for (i = 0; i < sizeof as / sizeof as[0]; ++i) {
        const sms_stage_config c = two_impulses(as[i]);
        const double sum = fabs(as[i]) + fabs(1.0 - as[i]);
        const double want = REAL_MAX / (2.0 * sum) < SMS_INPUT_MAX ? REAL_MAX / (2.0 * sum)
                                                                  : SMS_INPUT_MAX;
        double x = -1.0, g = -1.0;
        CHECK_STATUS(sms_stage_config_range(&c, Ts, &x, &g), SMS_OK);
        CHECK(g == sum);
        CHECK(x == want);
    }
    {   /* the narrowing one is below SMS_INPUT_MAX */
        const sms_stage_config c = two_impulses(600.5);
        double x, g;
        CHECK_STATUS(sms_stage_config_range(&c, Ts, &x, &g), SMS_OK);
        CHECK(x < SMS_INPUT_MAX && x == REAL_MAX / 2400.0);
    }
}

/* ZV (paper timing, half damped period 8 samples): taps 1/(1 + K), K/(1 + K),
 * K = exp(-zeta pi / sqrt(1 - zeta^2)); both positive, so sum |g| = 1 up to their rounding. */
static void zv_closed_form(void)
{
    const double zetas[] = { 0.0, 0.05, 0.3, 0.7 };
    size_t i;
    for (i = 0; i < sizeof zetas / sizeof zetas[0]; ++i) {
        sms_stage_config c = sms_stage_config_default(SMS_SHAPER_ZV);
        const double z = zetas[i], K = exp(-z * 3.14159265358979323846 / sqrt(1.0 - z * z));
        double x, g;
        c.timing = SMS_TIMING_PAPER;
        c.zeta = z;
        c.wn = 3.14159265358979323846 / (8.0 * Ts * sqrt(1.0 - z * z));
        CHECK_STATUS(sms_stage_config_range(&c, Ts, &x, &g), SMS_OK);
        CHECK_CLOSE(g, (double)(sms_real)(1.0 / (1.0 + K)) + (double)(sms_real)(K / (1.0 + K)),
                    SMS_TEST_REL_TOL, 1.0);
        CHECK(x == SMS_INPUT_MAX);   /* REAL_MAX / 2 is above it */
    }
}

/* Every kind, a few designs each: the values the built stage reports, bit for bit. */
static void equals_built_stage(void)
{
    const double wns[] = { 40.0, 300.0, 1200.0 }, zetas[] = { 0.0, 0.1, 0.6 };
    const double Ts_over[] = { 7.0, 12.3, 40.5 };
    int kind;
    size_t i, n_compared = 0;
    for (kind = 0; kind < SMS_KIND_COUNT; ++kind)
        for (i = 0; i < 3; ++i) {
            sms_stage_config c = sms_stage_config_default((sms_kind)kind);
            sms_stage stage;
            sms_memory_cell *mem = NULL;
            double x = -1.0, g = -1.0;
            sms_status st;
            if (kind == SMS_SHAPER_IMPULSES)
                c = two_impulses(i == 0 ? 0.5 : i == 1 ? 3.25 : -0.5);
            c.wn = wns[i];
            c.zeta = zetas[i];
            c.T = Ts_over[i] * Ts;
            c.timing = i == 1 ? SMS_TIMING_PAPER : SMS_TIMING_EXACT;
            if (kind == SMS_DAMPED_HARMONIC || kind == SMS_EXPONENTIAL)
                c.sigma = i == 2 ? -1500.0 : -30.0;   /* heavily damped: a narrow range */
            st = sms_stage_config_range(&c, Ts, &x, &g);
            if (!build(&c, &stage, &mem)) {
                CHECK(st != SMS_OK);   /* refused alike */
                CHECK(x == -1.0 && g == -1.0);
                continue;
            }
            CHECK_STATUS(st, SMS_OK);
            CHECK(x == sms_stage_input_max(&stage));
            CHECK(g == sms_stage_gain_bound(&stage));
            free(mem);
            ++n_compared;
        }
    CHECK(n_compared >= 2u * (size_t)SMS_KIND_COUNT);
}

/* The chain's range: R_i = 1 + 2 G_0 ... G_{i-1}; impulses of sum |g| = 1200 behind a
 * rectangular smoother (G = 1 for paper timing): REAL_MAX / 2400 / 3. Bit for bit the built
 * chain's sms_chain_input_max(). The other order: the smoother's own limit, REAL_MAX / 40
 * (32 c S + 8 with c S = 1, smoother_design.c), over 1 + 2 * 1200. */
static void chain_closed_form(void)
{
    sms_stage_config c[2];
    sms_chain chain;
    sms_stage stages[2];
    sms_memory_cell *mem;
    size_t cells = 0;
    double x = -1.0;
    c[0] = sms_stage_config_default(SMS_RECTANGULAR);
    c[0].T = 20.0 * Ts;
    c[0].timing = SMS_TIMING_PAPER;
    c[1] = two_impulses(600.5);
    CHECK_STATUS(sms_chain_config_input_max(c, 2, Ts, &x), SMS_OK);
    CHECK(x == REAL_MAX / (2.0 * 1200.0) / 3.0);
    CHECK_STATUS(sms_chain_memory_size(c, 2, Ts, &cells), SMS_OK);
    mem = (sms_memory_cell *)calloc(cells, sizeof *mem);
    CHECK(mem != NULL);
    if (mem == NULL)
        return;
    CHECK_STATUS(sms_chain_init(&chain, stages, c, 2, Ts, mem, cells), SMS_OK);
    CHECK(x == sms_chain_input_max(&chain));
    free(mem);
    /* the other order: the impulses first, the smoother sees 1 + 2 * 1200 */
    {
        sms_stage_config r[2];
        r[0] = c[1];
        r[1] = c[0];
        CHECK_STATUS(sms_chain_config_input_max(r, 2, Ts, &x), SMS_OK);
        CHECK_CLOSE(x, REAL_MAX / 40.0 / 2401.0, 1e-14, x);
    }
}

/* Refusals: the statuses and nothing written. */
static void refusals(void)
{
    sms_stage_config c = sms_stage_config_default(SMS_SHAPER_ZV), bad = c;
    double x = -1.0, g = -1.0;
    bad.wn = -1.0;
    CHECK_STATUS(sms_stage_config_range(NULL, Ts, &x, &g), SMS_ERR_NULL);
    CHECK_STATUS(sms_stage_config_range(&c, Ts, NULL, &g), SMS_ERR_NULL);
    CHECK_STATUS(sms_stage_config_range(&c, Ts, &x, NULL), SMS_ERR_NULL);
    CHECK_STATUS(sms_stage_config_range(&bad, Ts, &x, &g), SMS_ERR_WN);
    CHECK_STATUS(sms_stage_config_range(&c, -1.0, &x, &g), SMS_ERR_SAMPLE_PERIOD);
    bad = two_impulses(0.5);
    bad.times[1] = -1.0;
    CHECK_STATUS(sms_stage_config_range(&bad, Ts, &x, &g), SMS_ERR_IMPULSE_TIME);
    CHECK(x == -1.0 && g == -1.0);
    CHECK_STATUS(sms_chain_config_input_max(&c, 0, Ts, &x), SMS_ERR_ORDER);
    CHECK_STATUS(sms_chain_config_input_max(&c, SMS_CHAIN_MAX_STAGES + 1u, Ts, &x),
                 SMS_ERR_ORDER);
    CHECK_STATUS(sms_chain_config_input_max(NULL, 1, Ts, &x), SMS_ERR_NULL);
    CHECK_STATUS(sms_chain_config_input_max(&bad, 1, Ts, &x), SMS_ERR_IMPULSE_TIME);
    CHECK(x == -1.0);
}

/* A tunable chain [rectangular, rectangular] whose first stage is to go to a heavily damped
 * harmonic smoother (range L_B below SMS_INPUT_MAX, gain G_B): stage 0's range becomes
 * min(L_A, L_B), stage 1 sees 1 + 2 (1 + 2 G_B + 2 G_A) during the switch (G_A = 1, paper
 * timing); nothing retuned gives L_A / 3; once the switch is made sms_tunable_chain_input_max()
 * equals the bound (the switch has its gains), and after the switch it is at least the bound. */
static double min3(double a, double b, double c)
{
    const double ab = a < b ? a : b;
    return ab < c ? ab : c;
}

static void tunable_retune_range(void)
{
    sms_stage_config c[2], target = sms_stage_config_default(SMS_DAMPED_HARMONIC);
    sms_tunable stages[2];
    sms_tunable_chain chain;
    sms_memory_cell *mem;
    size_t slot_cells[2], cells = 0, i;
    int retuned[2] = { 1, 0 }, none[2] = { 0, 0 };
    double lim[2] = { 0.0, 0.0 }, gain[2] = { 0.0, 0.0 }, x, first_limit, rect_limit, own;
    for (i = 0; i < 2; ++i) {
        c[i] = sms_stage_config_default(SMS_RECTANGULAR);
        c[i].T = 20.0 * Ts;
        c[i].timing = SMS_TIMING_PAPER;
    }
    target.T = 20.0 * Ts;
#ifdef SMS_USE_FLOAT
    target.sigma = -2000.0;    /* sigma T = -40: the range falls by about e^40 */
#else
    target.sigma = -15000.0;   /* sigma T = -300 */
#endif
    target.timing = SMS_TIMING_PAPER;
    CHECK_STATUS(sms_stage_memory_size(&target, Ts, &slot_cells[0]), SMS_OK);
    slot_cells[1] = slot_cells[0];
    {
        size_t rc = 0;
        CHECK_STATUS(sms_stage_memory_size(&c[0], Ts, &rc), SMS_OK);
        if (rc > slot_cells[0])
            slot_cells[0] = slot_cells[1] = rc;
    }
    CHECK_STATUS(sms_tunable_chain_memory_size(slot_cells, 2, &cells), SMS_OK);
    mem = (sms_memory_cell *)calloc(cells, sizeof *mem);
    CHECK(mem != NULL);
    if (mem == NULL)
        return;
    CHECK_STATUS(sms_tunable_chain_init(&chain, stages, c, slot_cells, 2, Ts, mem, cells),
                 SMS_OK);
    CHECK_STATUS(sms_stage_config_range(&target, Ts, &lim[0], &gain[0]), SMS_OK);
    /* the per-stage limits before the cap: the bound caps once, at its end */
    first_limit = sms_tunable_input_limit(&stages[0]);
    rect_limit = sms_tunable_input_limit(&stages[1]);
    own = sms_tunable_chain_input_max(&chain);
    x = sms_tunable_chain_retune_input_max(&chain, none, lim, gain);
    CHECK(x <= own && x == min3(SMS_INPUT_MAX, first_limit, rect_limit / 3.0));
    CHECK(lim[0] < rect_limit && lim[0] < SMS_INPUT_MAX && gain[0] >= 1.0);
    x = sms_tunable_chain_retune_input_max(&chain, retuned, lim, gain);
    {
        const double stage1 = rect_limit / (1.0 + 2.0 * (1.0 + 2.0 * gain[0] + 2.0 * 1.0));
        const double want = min3(SMS_INPUT_MAX, lim[0] < first_limit ? lim[0] : first_limit,
                                 stage1);
        CHECK(x == want && x < own);
    }
    CHECK_STATUS(sms_tunable_chain_retune(&chain, 0, &target), SMS_OK);
    CHECK(sms_tunable_chain_switching(&chain));
    CHECK(sms_tunable_chain_input_max(&chain) == x);   /* the switch has the bound's gains */
    for (i = 0; i < 100 && sms_tunable_chain_switching(&chain); ++i) {
        sms_real v = (sms_real)1.0;
        sms_tunable_chain_step(&chain, &v);
    }
    CHECK(!sms_tunable_chain_switching(&chain));
    CHECK(sms_tunable_chain_input_max(&chain) >= x);   /* after it: within the bound */
    free(mem);
}

int main(void)
{
    impulses_closed_form();
    zv_closed_form();
    equals_built_stage();
    chain_closed_form();
    refusals();
    tunable_retune_range();
    return check_summary("test_config_range");
}
