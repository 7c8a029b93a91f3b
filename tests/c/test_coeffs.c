/* SPDX-License-Identifier: Apache-2.0 */
/* The firmware path (coeffs.h): a stage or chain built from precomputed coefficients is the one
 * built from the config they were made from, bit for bit (outputs over a random input, saved
 * states, memory sizes), for random configurations of every kind; the coefficients may go away
 * once the stage is built (a shaper's taps are copied); every malformed coefficient set is
 * refused with its status and writes nothing. */
#include <string.h>
#include "check.h"
#include "xorshift.h"

#define MAX_CELLS 20000
#define CASES 300
#define RUN 3000
/* tap table entries: a shaper's at most SMS_SHAPER_MAX_TAPS, an input smoother's one per
 * sample of its window (MAX_CELLS bounds it) */
#define MAX_TAP_ENTRIES 8192

static sms_memory_cell mem_a[MAX_CELLS], mem_b[MAX_CELLS], before[MAX_CELLS];
static sms_real in[RUN], out_a[RUN], out_b[RUN];
static double state_a[MAX_CELLS * 2], state_b[MAX_CELLS * 2];
static uint64_t rng = 0x9E3779B97F4A7C15ull;

static double uniform(double lo, double hi)
{
    return lo + (hi - lo) * xorshift_uniform(&rng);
}

static sms_stage_config random_config(void)
{
    const double pick = xorshift_uniform(&rng) * SMS_KIND_COUNT;
    sms_stage_config c = sms_stage_config_default((sms_kind)(int)pick);
    const double t = xorshift_uniform(&rng);
    c.timing = t < 0.3 ? SMS_TIMING_PAPER : t < 0.5 ? SMS_TIMING_BOUNDED : SMS_TIMING_EXACT;
    c.T = uniform(1.0, 400.0) * 1e-3;
    c.sigma = -uniform(0.0, 40.0);
    c.k = 1u + 2u * (unsigned)(xorshift_uniform(&rng) * 2.0);
    c.wn = uniform(0.02, 2.0) * 1e3;
    c.zeta = uniform(0.0, 0.4);
    c.order = c.kind == SMS_SHAPER_GMZV ? 3u + (unsigned)(xorshift_uniform(&rng) * 4.0)
                                        : 1u + (unsigned)(xorshift_uniform(&rng) * 5.0);
    c.duration = uniform(0.5, 0.45 * (double)(c.order - 1u) + 0.5);
    c.tolerance = uniform(0.02, 0.2);
    c.notch_pole_zeta = c.zeta + uniform(0.05, 0.8);
    if (c.kind == SMS_SHAPER_SI) {      /* 3, 5, 7 or 9 impulses over [(n-1)/4, (n-1)/2] */
        c.order = 3u + 2u * (unsigned)(xorshift_uniform(&rng) * 4.0);
        c.duration = uniform(0.25, 0.5) * (double)(c.order - 1u);
    }
    if (c.kind == SMS_SHAPER_IMPULSES) {  /* 1 .. 9 impulses, a first time at or after 0 */
        unsigned m;
        double at = xorshift_uniform(&rng) < 0.5 ? 0.0 : uniform(0.0, 5e-3);
        c.order = 1u + (unsigned)(xorshift_uniform(&rng) * 9.0);
        for (m = 0; m < c.order; ++m) {
            c.amplitudes[m] = uniform(-0.2, 1.0);
            c.times[m] = at;
            at += uniform(0.3e-3, 20e-3);
        }
        c.amplitudes[0] = uniform(0.5, 1.0);  /* a positive sum */
    }
    return c;
}

/* A stage from its config and one from its coefficients agree bit for bit. */
static int same_stage(const sms_stage_config *c)
{
    static sms_shaper_tap taps[MAX_TAP_ENTRIES];
    sms_stage_coeffs coeffs;
    sms_stage a, b;
    size_t cells, cells_coeffs, i, n;
    if (sms_stage_memory_size(c, 1e-3, &cells) != SMS_OK || cells > MAX_CELLS)
        return 0;
    CHECK_STATUS(sms_stage_coeffs_make(c, 1e-3, &coeffs, taps, MAX_TAP_ENTRIES), SMS_OK);
    CHECK_STATUS(sms_stage_coeffs_memory_size(&coeffs, &cells_coeffs), SMS_OK);
    CHECK(cells_coeffs == cells);
    CHECK_STATUS(sms_stage_init(&a, c, 1e-3, mem_a, MAX_CELLS), SMS_OK);
    CHECK_STATUS(sms_stage_init_coeffs(&b, &coeffs, mem_b, cells), SMS_OK);
    memset(taps, 0xA5, sizeof taps);   /* the stage keeps its own copy of the taps */
    memset(&coeffs, 0xA5, sizeof coeffs);
    for (i = 0; i < RUN; ++i)
        in[i] = (sms_real)uniform(-10.0, 10.0);
    sms_stage_reset(&a, in[0]);
    sms_stage_reset(&b, in[0]);
    sms_stage_process(&a, in, out_a, RUN);
    for (i = 0; i < RUN; ++i) {
        out_b[i] = in[i];
        sms_stage_step(&b, &out_b[i]);
    }
    CHECK(memcmp(out_a, out_b, sizeof out_a) == 0);
    n = sms_stage_state_count(&a);
    CHECK(n == sms_stage_state_count(&b));
    if (n <= sizeof state_a / sizeof state_a[0]) {
        sms_stage_get_state(&a, state_a);
        sms_stage_get_state(&b, state_b);
        CHECK(memcmp(state_a, state_b, n * sizeof(double)) == 0);
        CHECK_STATUS(sms_stage_set_state(&b, state_a, n), SMS_OK);
    }
    return 1;
}

/* Malformed coefficients: refused with `expected`, stage and memory untouched. */
static void refused(const sms_stage_coeffs *bad, sms_status expected)
{
    sms_stage stage, stage_before;
    size_t cells = 7;
    memset(&stage, 0x5A, sizeof stage);
    stage_before = stage;
    memcpy(before, mem_a, sizeof mem_a);
    CHECK_STATUS(sms_stage_coeffs_memory_size(bad, &cells), expected);
    CHECK(cells == 7);
    CHECK_STATUS(sms_stage_init_coeffs(&stage, bad, mem_a, MAX_CELLS), expected);
    CHECK(memcmp(&stage, &stage_before, sizeof stage) == 0);
    CHECK(memcmp(before, mem_a, sizeof mem_a) == 0);
}

static void test_malformed(void)
{
    sms_shaper_tap taps[SMS_SHAPER_MAX_TAPS], bad_taps[SMS_SHAPER_MAX_TAPS];
    sms_stage_config sm = sms_stage_config_default(SMS_HARMONIC);
    sms_stage_config zv = sms_stage_config_default(SMS_SHAPER_ZV);
    sms_stage_config nt = sms_stage_config_default(SMS_NOTCH_MATCHED);
    sms_stage_coeffs good_sm, good_zv, good_nt, bad;
    sms_stage stage;
    sm.T = 0.0505;
    zv.wn = 100.0;
    zv.zeta = 0.05;
    nt.wn = 300.0;
    CHECK_STATUS(sms_stage_coeffs_make(&sm, 1e-3, &good_sm, NULL, 0), SMS_OK);
    CHECK_STATUS(sms_stage_coeffs_make(&zv, 1e-3, &good_zv, taps, SMS_SHAPER_MAX_TAPS), SMS_OK);
    CHECK_STATUS(sms_stage_coeffs_make(&nt, 1e-3, &good_nt, NULL, 0), SMS_OK);
    CHECK(good_sm.u.smoother.n_corrections == 2u);   /* T/Ts off the grid: direct taps */
    /* host side */
    CHECK_STATUS(sms_stage_coeffs_make(&zv, 1e-3, &bad, NULL, 0), SMS_ERR_NULL);
    CHECK_STATUS(sms_stage_coeffs_make(&zv, 1e-3, &bad, taps, good_zv.u.shaper.n_taps - 1u),
                 SMS_ERR_BUFFER_TOO_SMALL);
    CHECK_STATUS(sms_stage_coeffs_make(NULL, 1e-3, &bad, taps, 3), SMS_ERR_NULL);
    CHECK_STATUS(sms_stage_coeffs_make(&zv, 0.0, &bad, taps, 3), SMS_ERR_SAMPLE_PERIOD);
    zv.kind = (sms_kind)99;
    CHECK_STATUS(sms_stage_coeffs_make(&zv, 1e-3, &bad, taps, 3), SMS_ERR_KIND);
    /* target side: every field a design cannot write */
    bad = good_sm; bad.kind = (sms_kind)-1; refused(&bad, SMS_ERR_KIND);
    bad = good_sm; bad.kind = SMS_SHAPER_ZV; bad.u.shaper.taps = NULL;
    refused(&bad, SMS_ERR_COEFFS);
    bad = good_sm; bad.u.smoother.window = 0; refused(&bad, SMS_ERR_COEFFS);
    bad = good_sm; bad.u.smoother.length = bad.u.smoother.window + 2u;
    refused(&bad, SMS_ERR_COEFFS);
    bad = good_sm; bad.u.smoother.n_corrections = 1; refused(&bad, SMS_ERR_COEFFS);
    bad = good_sm; bad.u.smoother.correction_delay[1] = 5; refused(&bad, SMS_ERR_COEFFS);
    bad = good_sm; bad.u.smoother.correction_delay[0] = 3; refused(&bad, SMS_ERR_COEFFS);
    bad = good_sm; bad.u.smoother.gain = (sms_real)NAN; refused(&bad, SMS_ERR_COEFFS);
    bad = good_sm; bad.u.smoother.pole_im = (sms_real)INFINITY; refused(&bad, SMS_ERR_COEFFS);
    bad = good_sm; bad.u.smoother.correction_gain[1] = (sms_real)NAN;
    refused(&bad, SMS_ERR_COEFFS);
    bad = good_sm; bad.u.smoother.window = (size_t)-1; bad.u.smoother.length = (size_t)-1;
    bad.u.smoother.n_corrections = 0; refused(&bad, SMS_ERR_COEFFS);
    memcpy(bad_taps, taps, sizeof taps);
    bad = good_zv; bad.u.shaper.taps = bad_taps;
    bad_taps[1].delay = bad_taps[0].delay; refused(&bad, SMS_ERR_COEFFS);    /* not increasing */
    memcpy(bad_taps, taps, sizeof taps);
    bad_taps[2].gain = (sms_real)NAN; refused(&bad, SMS_ERR_COEFFS);
    memcpy(bad_taps, taps, sizeof taps);
    bad.u.shaper.length += 1u; refused(&bad, SMS_ERR_COEFFS);                 /* not last + 1 */
    bad = good_zv; bad.u.shaper.n_taps = 0; refused(&bad, SMS_ERR_COEFFS);
    bad = good_zv; bad.u.shaper.n_taps = SMS_SHAPER_MAX_TAPS + 1u;
    refused(&bad, SMS_ERR_COEFFS);
    bad = good_zv; bad.u.shaper.taps = NULL; refused(&bad, SMS_ERR_COEFFS);
    bad = good_nt; bad.u.notch.a2 = (sms_real)INFINITY; refused(&bad, SMS_ERR_COEFFS);
    /* NULLs and a small memory */
    CHECK_STATUS(sms_stage_init_coeffs(NULL, &good_zv, mem_a, MAX_CELLS), SMS_ERR_NULL);
    CHECK_STATUS(sms_stage_init_coeffs(&stage, NULL, mem_a, MAX_CELLS), SMS_ERR_NULL);
    CHECK_STATUS(sms_stage_init_coeffs(&stage, &good_zv, NULL, MAX_CELLS), SMS_ERR_NULL);
    {
        size_t need;
        CHECK_STATUS(sms_stage_coeffs_memory_size(&good_zv, &need), SMS_OK);
        CHECK_STATUS(sms_stage_init_coeffs(&stage, &good_zv, mem_a, need - 1u),
                     SMS_ERR_BUFFER_TOO_SMALL);
        CHECK_STATUS(sms_stage_init_coeffs(&stage, &good_zv, mem_a, need), SMS_OK);
    }
}

/* An input smoother's coefficients: every sample of the window a tap, delays 0 .. L-1. */
static void test_input_smoother_malformed(void)
{
    static sms_shaper_tap taps[MAX_TAP_ENTRIES], bad_taps[MAX_TAP_ENTRIES];
    sms_stage_config c = sms_stage_config_default(SMS_SMOOTH_MZV);
    sms_stage_coeffs good, bad;
    size_t n_taps;
    c.wn = 2.0 * 3.14159265358979323846 * 10.0;     /* T about 85 ms: 80-odd taps at 1 ms */
    c.zeta = 0.1;
    CHECK_STATUS(sms_shaper_tap_count(&c, 1e-3, &n_taps), SMS_OK);
    CHECK(n_taps > SMS_SHAPER_MAX_TAPS && n_taps <= MAX_TAP_ENTRIES);
    CHECK_STATUS(sms_stage_coeffs_make(&c, 1e-3, &good, taps, n_taps - 1u),
                 SMS_ERR_BUFFER_TOO_SMALL);
    CHECK_STATUS(sms_stage_coeffs_make(&c, 1e-3, &good, NULL, n_taps), SMS_ERR_NULL);
    CHECK_STATUS(sms_stage_coeffs_make(&c, 1e-3, &good, taps, n_taps), SMS_OK);
    CHECK(good.u.shaper.n_taps == n_taps && good.u.shaper.length == n_taps);
    memcpy(bad_taps, taps, sizeof taps);
    bad = good; bad.u.shaper.taps = bad_taps;
    bad_taps[3].delay = 4u; refused(&bad, SMS_ERR_COEFFS);            /* a sample skipped */
    memcpy(bad_taps, taps, sizeof taps);
    bad_taps[n_taps - 1u].gain = (sms_real)INFINITY; refused(&bad, SMS_ERR_COEFFS);
    memcpy(bad_taps, taps, sizeof taps);
    bad.u.shaper.length += 1u; refused(&bad, SMS_ERR_COEFFS);         /* length != taps */
    bad = good; bad.u.shaper.n_taps = bad.u.shaper.length = 4u;       /* below 4 samples */
    refused(&bad, SMS_ERR_COEFFS);
    bad = good; bad.u.shaper.n_taps = bad.u.shaper.length = SMS_INPUT_SMOOTHER_MAX_LENGTH + 1u;
    refused(&bad, SMS_ERR_COEFFS);
    bad = good; bad.u.shaper.taps = NULL; refused(&bad, SMS_ERR_COEFFS);
}

/* A chain from coefficients is the chain from the configs. */
static void test_chains(void)
{
    int i;
    for (i = 0; i < 40; ++i) {
        static sms_shaper_tap taps[4][MAX_TAP_ENTRIES];
        sms_stage_config cfg[4];
        sms_stage_coeffs coeffs[4];
        sms_stage sa[4], sb[4];
        sms_chain a, b;
        size_t n = 1u + (size_t)(xorshift_uniform(&rng) * 4.0), k, need, need_coeffs;
        for (k = 0; k < n; ++k) {
            size_t cells;
            do
                cfg[k] = random_config();
            while (sms_stage_memory_size(&cfg[k], 1e-3, &cells) != SMS_OK || cells > MAX_CELLS / 4);
            CHECK_STATUS(sms_stage_coeffs_make(&cfg[k], 1e-3, &coeffs[k], taps[k],
                                               MAX_TAP_ENTRIES), SMS_OK);
        }
        CHECK_STATUS(sms_chain_memory_size(cfg, n, 1e-3, &need), SMS_OK);
        CHECK_STATUS(sms_chain_coeffs_memory_size(coeffs, n, &need_coeffs), SMS_OK);
        CHECK(need == need_coeffs);
        CHECK_STATUS(sms_chain_init(&a, sa, cfg, n, 1e-3, mem_a, MAX_CELLS), SMS_OK);
        CHECK_STATUS(sms_chain_init_coeffs(&b, sb, coeffs, n, mem_b, need - 1u),
                     SMS_ERR_BUFFER_TOO_SMALL);
        CHECK_STATUS(sms_chain_init_coeffs(&b, sb, coeffs, n, mem_b, need), SMS_OK);
        for (k = 0; k < RUN; ++k)
            in[k] = (sms_real)uniform(-5.0, 5.0);
        sms_chain_process(&a, in, out_a, RUN);
        sms_chain_process(&b, in, out_b, RUN);
        CHECK(memcmp(out_a, out_b, sizeof out_a) == 0);
        CHECK(sms_chain_length(&a) == sms_chain_length(&b));
    }
    {
        sms_stage_coeffs none[1];
        sms_stage st[1];
        sms_chain c;
        size_t need;
        CHECK_STATUS(sms_chain_coeffs_memory_size(none, 0, &need), SMS_ERR_ORDER);
        CHECK_STATUS(sms_chain_coeffs_memory_size(none, SMS_CHAIN_MAX_STAGES + 1u, &need),
                     SMS_ERR_ORDER);
        CHECK_STATUS(sms_chain_init_coeffs(&c, st, NULL, 1, mem_a, MAX_CELLS), SMS_ERR_NULL);
    }
}

int main(void)
{
    int i, k, built = 0, per_kind[SMS_KIND_COUNT] = {0};
    for (i = 0; i < CASES; ++i) {
        sms_stage_config c = random_config();
        const int ok = same_stage(&c);
        built += ok;
        per_kind[c.kind] += ok;
    }
    CHECK(built >= CASES / 2);
    for (k = 0; k < SMS_KIND_COUNT; ++k)   /* every kind was built both ways */
        if (per_kind[k] == 0) {
            printf("kind %d: no valid random configuration\n", k);
            CHECK(per_kind[k] > 0);
        }
    test_malformed();
    test_input_smoother_malformed();
    test_chains();
    return check_summary("test_coeffs");
}
