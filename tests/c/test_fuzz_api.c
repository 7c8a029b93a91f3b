/* SPDX-License-Identifier: Apache-2.0 */
/* Seeded random configurations and calls against the public C API (sanitizer build: ASan and
 * UBSan see every call). Assertions for every configuration:
 * - no crash, and no call longer than 100 ms (size queries and refusals are O(1); the only
 *   O(length) work is zeroing a delay line the caller provides, here at most MAX_BUF cells);
 * - a failing init leaves the stage / chain (and the caller's memory) byte for byte unchanged;
 * - SMS_OK never comes with a non-finite design value, tap, mode or output (inputs up to 1e3,
 *   then inputs and rest at and within the chain's finite input range sms_chain_input_max();
 *   inputs beyond it up to SMS_INPUT_MAX and DBL_MAX, NaN and Inf are fed too, checking only
 *   that the state stays loadable);
 * - every state saved (also after NaN/Inf and out-of-range inputs) loads again.
 * Usage: test_fuzz_api_<precision> [configurations [seed]] (default 3000, seed 1). The long
 * campaign: build/sanitize/tests/test_fuzz_api_double 100000 (see tests/README.md). */
#include <float.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "check.h"

#define MAX_BUF 20000
#define N_SAMPLES 64
#define MAX_STATE (MAX_BUF + 64)
#define MAX_STAGES 4
#define CALL_LIMIT_S 0.1

static sms_memory_cell buffer[MAX_BUF], buffer_copy[MAX_BUF];
static double state[MAX_STATE * MAX_STAGES], taps[MAX_BUF + 1];
static unsigned long long rng;
static unsigned long n_ok_init, n_refused, n_chains, n_slow, n_samples, n_range_samples;
static unsigned long n_below_input_max;   /* chains whose range is below SMS_INPUT_MAX */
static unsigned long n_zero_range;        /* chains whose range is 0 */
static double slowest;

static unsigned long long next64(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return rng;
}

static double uniform(void)
{
    return (double)(next64() >> 11) * (1.0 / 9007199254740992.0);
}

static unsigned pick(unsigned n)
{
    return (unsigned)(next64() % n);
}

/* Mostly plausible values on a log scale, sometimes the edges of double. */
static double any_real(double lo_exp, double hi_exp)
{
    static const double edge[] = { 0.0, -0.0, -1.0, 1.0, NAN, INFINITY, -INFINITY, DBL_MAX,
                                   -DBL_MAX, DBL_MIN, 4.9e-324, 1e-300, 1e300, 0.99999999999,
                                   1.0 - 1e-16, 0.5, 2.0 };
    if (pick(6) == 0)
        return edge[pick(sizeof edge / sizeof edge[0])];
    return pow(10.0, lo_exp + (hi_exp - lo_exp) * uniform());
}

static unsigned any_unsigned(void)
{
    static const unsigned pool[] = { 0u, 1u, 1u, 1u, 2u, 3u, 4u, 5u, 8u, 9u, 10u, UINT_MAX };
    return pool[pick(sizeof pool / sizeof pool[0])];
}

static sms_stage_config any_config(void)
{
    sms_stage_config c = sms_stage_config_default((sms_kind)pick(SMS_KIND_COUNT));
    if (pick(40) == 0)
        c.kind = (sms_kind)(SMS_KIND_COUNT + pick(3));
    c.timing = (sms_timing)(pick(20) == 0 ? 2 : pick(2));
    c.T = any_real(-4.5, 0.5);
    c.sigma = pick(3) == 0 ? 0.0 : -any_real(-3.0, 4.0);
    c.k = any_unsigned();
    c.wn = any_real(-1.0, 4.0);
    c.zeta = pick(3) == 0 ? 0.0 : any_real(-4.0, 0.0) * (pick(10) == 0 ? -1.0 : 1.0);
    if (pick(10) == 0)
        c.zeta = 1.0 - pow(10.0, -1.0 - 15.0 * uniform());
    c.order = any_unsigned();
    c.tolerance = any_real(-320.0, 0.0);
    c.notch_pole_zeta = any_real(-3.0, 1.0);
    c.duration = any_real(-1.0, 0.5);
    {   /* user-defined impulses: mostly increasing times and positive amplitudes */
        unsigned m;
        double t = pick(4) == 0 ? 0.0 : any_real(-4.0, -1.0);
        for (m = 0; m < SMS_SHAPER_MAX_IMPULSES; ++m) {
            c.amplitudes[m] = pick(8) == 0 ? -any_real(-3.0, 0.0) : any_real(-3.0, 0.0);
            t += pick(10) == 0 ? -any_real(-4.0, -1.0) : any_real(-4.0, -1.0);
            c.times[m] = t;
        }
    }
    return c;
}

static double any_ts(void)
{
    return pick(12) == 0 ? any_real(-12.0, 3.0) : pow(10.0, -4.0 + 2.0 * uniform());
}

static double seconds(void)
{
    return (double)clock() / CLOCKS_PER_SEC;
}

/* Time a call: at most CALL_LIMIT_S whatever the arguments. */
#define TIMED(expr) do { double t0_ = seconds(), dt_; expr; dt_ = seconds() - t0_; \
    if (dt_ > slowest) slowest = dt_; \
    if (dt_ > CALL_LIMIT_S) { ++n_slow; fprintf(stderr, "%s:%d: %s took %.3f s\n", __FILE__, \
    __LINE__, #expr, dt_); } } while (0)

static int finite_all(const double *v, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i)
        if (!isfinite(v[i]))
            return 0;
    return 1;
}

static sms_real in_range_sample(void)
{
    return (sms_real)((2.0 * uniform() - 1.0) * (pick(2) ? 1e3 : 1.0));
}

/* A sample at or within +-m, often at the ends (the largest swing). */
static sms_real extreme_sample(double m)
{
    return (sms_real)(pick(2) ? (pick(2) ? m : -m) : (2.0 * uniform() - 1.0) * m);
}

static sms_real out_of_range_sample(void)
{
    static const double pool[] = { NAN, INFINITY, -INFINITY };
#ifdef SMS_USE_FLOAT
    static const double big = 3.4e38;
#else
    static const double big = DBL_MAX;
#endif
    return pick(2) ? (sms_real)pool[pick(3)] : (sms_real)(pick(2) ? big : -big);
}

/* Design values of an initialised stage: all finite. */
static void check_design(const sms_stage_config *c, double Ts, const sms_stage *s)
{
    size_t L = sms_stage_length(s);
    sms_status st = SMS_OK;
    if (L > 0 && L <= MAX_BUF) {
        if (c->kind <= SMS_EXPONENTIAL)
            TIMED(st = sms_smoother_taps(c, Ts, taps, MAX_BUF + 1));
        else
            TIMED(st = sms_shaper_taps(c, Ts, taps, MAX_BUF + 1));
        CHECK(st == SMS_OK);
        CHECK(finite_all(taps, L));
    }
    if (c->kind == SMS_NOTCH_TUSTIN || c->kind == SMS_NOTCH_MATCHED)
        CHECK(isfinite((double)s->u.notch->d0) && isfinite((double)s->u.notch->d2)
              && isfinite((double)s->u.notch->a1) && isfinite((double)s->u.notch->a2));
}

/* Run the chain on in-range samples (finite outputs), then on bad ones; every state loads. */
static void exercise(sms_chain *chain)
{
    sms_real x[N_SAMPLES];
    size_t i, n;
    sms_status st;
    TIMED(sms_chain_reset(chain, in_range_sample()));
    for (i = 0; i < N_SAMPLES; ++i)
        x[i] = in_range_sample();
    TIMED(sms_chain_process(chain, x, x, N_SAMPLES));
    n_samples += N_SAMPLES;
    for (i = 0; i < N_SAMPLES; ++i)
        if (!isfinite((double)x[i])) {
            CHECK(!"output finite for ordinary inputs");
            break;
        }
    {   /* inputs and rest at the ends of the chain's finite input range: finite outputs */
        double bound;
        TIMED(bound = sms_chain_input_max(chain));
        /* a stage's own range is >= 1; a chain's is 0 behind a notch whose poles round onto
         * the unit circle (its gain bound is then infinite) */
        CHECK(bound >= 0.0 && bound <= SMS_INPUT_MAX);
        n_zero_range += bound == 0.0;
        n_below_input_max += bound < SMS_INPUT_MAX;
        TIMED(sms_chain_reset(chain, (sms_real)(pick(2) ? bound : -bound)));
        for (i = 0; i < N_SAMPLES; ++i)
            x[i] = extreme_sample(bound);
        TIMED(sms_chain_process(chain, x, x, N_SAMPLES));
        n_range_samples += N_SAMPLES;
        for (i = 0; i < N_SAMPLES; ++i)
            if (!isfinite((double)x[i])) {
                CHECK(!"output finite for inputs within sms_chain_input_max");
                break;
            }
    }
    n = sms_chain_state_count(chain);
    if (n > sizeof state / sizeof state[0])
        return;
    sms_chain_get_state(chain, state);
    TIMED(st = sms_chain_set_state(chain, state, n));
    CHECK(st == SMS_OK);
    for (i = 0; i < N_SAMPLES; ++i)
        x[i] = pick(4) == 0 ? out_of_range_sample() : extreme_sample(SMS_INPUT_MAX);
    sms_chain_process(chain, x, x, N_SAMPLES);
    sms_chain_get_state(chain, state);
    TIMED(st = sms_chain_set_state(chain, state, n));
    if (st != SMS_OK)
        fprintf(stderr, "state after out-of-range inputs refused: %d\n", (int)st);
    CHECK(st == SMS_OK);
    /* a state of the wrong length is refused and changes nothing */
    if (n > 1) {
        static double again[MAX_STATE * MAX_STAGES];
        CHECK(sms_chain_set_state(chain, state, n - 1) == SMS_ERR_STATE);
        sms_chain_get_state(chain, again);
        CHECK(memcmp(again, state, n * sizeof state[0]) == 0);
    }
}

static void one_configuration(void)
{
    sms_stage_config c[MAX_STAGES];
    sms_stage stages[MAX_STAGES], before[MAX_STAGES];
    sms_chain chain, chain_before;
    size_t n = 1 + pick(MAX_STAGES), need = 0, i, one;
    double Ts = any_ts();
    sms_status st;
    for (i = 0; i < n; ++i)
        c[i] = any_config();
    /* the single-stage path: size query, validation, init; an error touches nothing */
    TIMED(st = sms_stage_memory_size(&c[0], Ts, &one));
    CHECK(st == sms_stage_config_validate(&c[0], Ts));
    memset(&stages[0], 0xA5, sizeof stages[0]);
    memcpy(&before[0], &stages[0], sizeof stages[0]);
    memcpy(buffer_copy, buffer, sizeof buffer);
    if (st == SMS_OK && one > MAX_BUF) {
        TIMED(st = sms_stage_init(&stages[0], &c[0], Ts, buffer, MAX_BUF));
        CHECK(st == SMS_ERR_BUFFER_TOO_SMALL);
    } else if (st != SMS_OK) {
        sms_status again;
        TIMED(again = sms_stage_init(&stages[0], &c[0], Ts, buffer, MAX_BUF));
        CHECK(again == st);
        ++n_refused;
    } else {
        TIMED(st = sms_stage_init(&stages[0], &c[0], Ts, buffer, MAX_BUF));
        CHECK(st == SMS_OK);
        if (st == SMS_OK) {
            ++n_ok_init;
            check_design(&c[0], Ts, &stages[0]);
            memcpy(&before[0], &stages[0], sizeof stages[0]);
            memcpy(buffer_copy, buffer, sizeof buffer);
        }
    }
    if (st != SMS_OK) {
        CHECK(memcmp(&before[0], &stages[0], sizeof stages[0]) == 0);
        CHECK(memcmp(buffer_copy, buffer, sizeof buffer) == 0);
    }
    /* the chain: all or nothing */
    TIMED(st = sms_chain_memory_size(c, n, Ts, &need));
    memset(&chain, 0x3C, sizeof chain);
    memset(stages, 0x5A, sizeof stages);
    memcpy(&chain_before, &chain, sizeof chain);
    memcpy(before, stages, sizeof stages);
    memcpy(buffer_copy, buffer, sizeof buffer);
    {
        size_t give = st == SMS_OK && need <= MAX_BUF ? need : (pick(2) ? MAX_BUF : 0);
        sms_status init;
        TIMED(init = sms_chain_init(&chain, stages, c, n, Ts, give ? buffer : NULL, give));
        if (st != SMS_OK)
            CHECK(init == st);
        if (init != SMS_OK) {
            CHECK(memcmp(&chain_before, &chain, sizeof chain) == 0);
            CHECK(memcmp(before, stages, sizeof stages) == 0);
            CHECK(memcmp(buffer_copy, buffer, sizeof buffer) == 0);
            return;
        }
    }
    ++n_chains;
    exercise(&chain);
}

/* Design and identification helpers with arbitrary numbers: OK means finite. */
static void design_helpers(void)
{
    sms_stage_config c = sms_stage_config_default(SMS_RECTANGULAR);
    sms_mode m;
    double amp[SMS_SHAPER_MAX_IMPULSES], t[SMS_SHAPER_MAX_IMPULSES], xi2;
    size_t n, need;
    sms_status st;
    sms_stage_config any = any_config();
    TIMED(st = sms_design_for_mode(any.kind, any.wn, any.zeta, any.k, &c));
    if (st == SMS_OK) {
        CHECK(isfinite(c.T) && isfinite(c.sigma) && isfinite(c.wn) && isfinite(c.zeta));
        TIMED(st = sms_stage_buffer_size(&c, any_ts(), &need));
    }
    TIMED(st = sms_identify_from_peaks(any_real(-3, 3) * (pick(2) ? 1 : -1), any_real(-300, 300),
                                       any_real(-300, 300), any_real(-300, 300), &m));
    if (st == SMS_OK)
        CHECK(isfinite(m.wn) && m.wn > 0.0 && isfinite(m.zeta) && m.zeta >= 0.0 && m.zeta < 1.0
              && isfinite(m.wd) && isfinite(m.sigma));
    TIMED(st = sms_shaper_impulses(&any, amp, t, SMS_SHAPER_MAX_IMPULSES, &n));
    if (st == SMS_OK)
        CHECK(n <= SMS_SHAPER_MAX_IMPULSES && finite_all(amp, n) && finite_all(t, n));
    TIMED(st = sms_notch_pole_zeta_from_bandwidth(any.wn, any.zeta, any_real(-3, 5), &xi2));
    if (st == SMS_OK)
        CHECK(isfinite(xi2) && xi2 > 0.0);
    TIMED(st = sms_bspline_buffer_size(1u + pick(6), 1u + pick(4), any.T, any_ts(), &need));
}

static void null_arguments(void)
{
    sms_stage_config c = sms_stage_config_default(SMS_RECTANGULAR);
    sms_stage s;
    sms_chain chain;
    sms_mode m;
    size_t n;
    c.T = 0.01;
    CHECK(sms_stage_buffer_size(NULL, 1e-3, &n) == SMS_ERR_NULL);
    CHECK(sms_stage_buffer_size(&c, 1e-3, NULL) == SMS_ERR_NULL);
    CHECK(sms_stage_init(NULL, &c, 1e-3, buffer, MAX_BUF) == SMS_ERR_NULL);
    CHECK(sms_stage_init(&s, NULL, 1e-3, buffer, MAX_BUF) == SMS_ERR_NULL);
    CHECK(sms_stage_init(&s, &c, 1e-3, NULL, 10) == SMS_ERR_NULL);
    CHECK(sms_stage_memory_size(NULL, 1e-3, &n) == SMS_ERR_NULL);
    CHECK(sms_stage_memory_size(&c, 1e-3, NULL) == SMS_ERR_NULL);
    CHECK(sms_chain_memory_size(NULL, 1, 1e-3, &n) == SMS_ERR_NULL);
    CHECK(sms_chain_init(&chain, NULL, &c, 1, 1e-3, buffer, MAX_BUF) == SMS_ERR_NULL);
    CHECK(sms_chain_init(NULL, &s, &c, 1, 1e-3, buffer, MAX_BUF) == SMS_ERR_NULL);
    CHECK(sms_chain_set_state(NULL, state, 1) == SMS_ERR_NULL);
    CHECK(sms_stage_set_state(NULL, state, 1) == SMS_ERR_NULL);
    CHECK(sms_identify_from_peaks(0.0, 1.0, 1.0, 0.5, NULL) == SMS_ERR_NULL);
    CHECK(sms_identify_from_record(NULL, 100, 1e-3, &m) == SMS_ERR_NULL);
    CHECK(sms_design_for_mode(SMS_SHAPER_ZV, 10.0, 0.1, 1u, NULL) == SMS_ERR_NULL);
    CHECK(sms_smoother_taps(&c, 1e-3, NULL, 10) == SMS_ERR_NULL);
    CHECK(sms_shaper_taps(&c, 1e-3, NULL, 10) == SMS_ERR_NULL);
    CHECK(sms_status_string((sms_status)12345) != NULL);
    CHECK(sms_kind_name((sms_kind)12345) == NULL);
}

int main(int argc, char **argv)
{
    unsigned long n = argc > 1 ? strtoul(argv[1], NULL, 10) : 3000ul, i;
    rng = 0x9E3779B97F4A7C15ull ^ (argc > 2 ? strtoull(argv[2], NULL, 10) : 1ull);
    null_arguments();
    for (i = 0; i < n; ++i) {
        one_configuration();
        design_helpers();
    }
    CHECK(n_slow == 0);
    /* the generator reached every outcome often enough to mean something */
    CHECK(n < 1000 || (n_ok_init > n / 20 && n_refused > n / 20 && n_chains > n / 50));
    printf("fuzz_api: %lu configurations: %lu stages built, %lu refused, %lu chains run "
           "(%lu ordinary samples, %lu at the input range, %lu chains with a range below "
           "SMS_INPUT_MAX, %lu of them 0), %lu calls over %.0f ms, slowest %.3f ms\n", n,
           n_ok_init, n_refused, n_chains, n_samples, n_range_samples, n_below_input_max,
           n_zero_range, n_slow, 1e3 * CALL_LIMIT_S, 1e3 * slowest);
    return check_summary("test_fuzz_api");
}
