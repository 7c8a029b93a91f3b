/* SPDX-License-Identifier: Apache-2.0 */
/* Saved states of the generator, the B-spline and the multi-axis generator carry their
 * configuration's identity (trajectory.h, multi_generator.h): a state of another configuration
 * is refused, writing nothing, with the status naming the first field that differs; a state of
 * the same configuration loads into another instance and continues bit for bit (a run split
 * by save/load equals the one-shot run). */
#include <math.h>
#include <string.h>
#include "check.h"
#include "multi_config.h"

#define REALS 8192
#define STEPS 400
#define SPLIT 150
#define WIDTH (4 * SMS_MULTI_MAX_AXES) /* the most values one step writes */
static sms_real buf_a[REALS], buf_b[REALS];
static double state[REALS], bad[REALS];
static const double Ts = 1e-3;

static sms_real target_at(size_t k)
{
    return (sms_real)(k < 60 ? 0.02 : k < 200 ? -0.015 : 0.01 * (double)(k % 3));
}

/* ------------------------------------------------------------------ one test for all */

/* One kind of object: its two instances (a saves, b loads), how to build and step them, its
 * state functions, and the memory a refused load must leave untouched (b and its buffers). */
typedef struct memory_region {
    void *at;
    size_t size;
} memory_region;

typedef struct object_kind {
    void *a, *b;
    size_t identity_count;
    int (*build)(void *g, const void *config, double ts, int is_b); /* 1 when built */
    size_t (*step)(void *g, size_t k, sms_real *out);               /* values written */
    size_t (*count)(const void *g);
    void (*get)(const void *g, double *dst);
    sms_status (*check)(const void *g, const double *src, size_t n);
    sms_status (*set)(void *g, const double *src, size_t n);
    memory_region b_memory[3]; /* the unused ones at NULL */
} object_kind;

/* The state functions of sms_<name> (instances of type) behind void pointers. */
#define STATE_FUNCTIONS(name, type)                                                         \
    static size_t name##_count(const void *g) { return sms_##name##_state_count(g); }       \
    static void name##_get(const void *g, double *dst) { sms_##name##_get_state(g, dst); }  \
    static sms_status name##_check(const void *g, const double *src, size_t n)              \
    {                                                                                       \
        return sms_##name##_check_state((const type *)g, src, n);                           \
    }                                                                                       \
    static sms_status name##_set(void *g, const double *src, size_t n)                      \
    {                                                                                       \
        return sms_##name##_set_state((type *)g, src, n);                                   \
    }

static unsigned char before[3][REALS * 64];

/* Save a state of (a, Ts_a) mid-motion, load it into (b, Ts_b): expect `want`; on an error b
 * (struct and buffers) untouched; on OK the split run equals a's one-shot run bit for bit. */
static void across(const object_kind *o, const void *a, double Ts_a, const void *b,
                   double Ts_b, sms_status want)
{
    static sms_real one_shot[STEPS][WIDTH];
    sms_real out[WIDTH];
    size_t k, n, i, width = 0;
    if (!o->build(o->a, a, Ts_a, 0) || !o->build(o->b, b, Ts_b, 1))
        return;
    for (k = 0; k < STEPS; ++k)
        width = o->step(o->a, k, one_shot[k]);
    CHECK(o->build(o->a, a, Ts_a, 0));
    for (k = 0; k < SPLIT; ++k)
        o->step(o->a, k, out);
    n = o->count(o->a);
    CHECK(n <= REALS && n > o->identity_count);
    o->get(o->a, state);
    for (i = 0; i < 3 && o->b_memory[i].at != NULL; ++i) {
        CHECK(o->b_memory[i].size <= sizeof before[i]);
        if (o->b_memory[i].size <= sizeof before[i])
            memcpy(before[i], o->b_memory[i].at, o->b_memory[i].size);
    }
    CHECK_STATUS(o->check(o->b, state, n), want);
    CHECK_STATUS(o->set(o->b, state, n), want);
    if (want != SMS_OK) {
        for (i = 0; i < 3 && o->b_memory[i].at != NULL; ++i)
            CHECK(memcmp(before[i], o->b_memory[i].at, o->b_memory[i].size) == 0);
        return;
    }
    for (k = SPLIT; k < STEPS; ++k) {
        o->step(o->b, k, out);
        CHECK(memcmp(out, one_shot[k], width * sizeof out[0]) == 0);
    }
}

/* ------------------------------------------------------------------ generator */

static sms_generator gen_a, gen_b;

static int gen_build(void *g, const void *config, double ts, int is_b)
{
    size_t need = 0;
    CHECK_STATUS(sms_generator_buffer_size(config, ts, &need), SMS_OK);
    if (need > REALS) {
        CHECK(0);
        return 0;
    }
    CHECK_STATUS(sms_generator_init(g, config, ts, is_b ? buf_b : buf_a, need), SMS_OK);
    if (is_b)
        sms_generator_reset(g, 3); /* somewhere else: a refused load must leave it there */
    return 1;
}

static size_t gen_step(void *g, size_t k, sms_real *out)
{
    sms_generator_step(g, target_at(k), out);
    return 4;
}

STATE_FUNCTIONS(generator, sms_generator)

static const object_kind generator = {
    &gen_a, &gen_b, SMS_GENERATOR_IDENTITY_COUNT, gen_build, gen_step, generator_count,
    generator_get, generator_check, generator_set,
    {{&gen_b, sizeof gen_b}, {buf_b, sizeof buf_b}, {NULL, 0}}};

static void gen_across(const sms_generator_config *a, double Ts_a, const sms_generator_config *b,
                       double Ts_b, sms_status want)
{
    across(&generator, a, Ts_a, b, Ts_b, want);
}

static void generator_fields(void)
{
    const sms_generator_config a = {1.0, 10.0, 100.0, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    const sms_generator_config m = {1.0, 10.0, 100.0, SMS_PROFILE_POLYNOMIAL, 60.0, 0.1, 0.0, 0.0, 0.0, 0.0};
    sms_generator_config b;
    gen_across(&a, Ts, &a, Ts, SMS_OK);
    gen_across(&m, Ts, &m, Ts, SMS_OK);
    b = a; b.vmax = 2.0; gen_across(&a, Ts, &b, Ts, SMS_ERR_STATE_VMAX);
    b = a; b.amax = 11.0; gen_across(&a, Ts, &b, Ts, SMS_ERR_STATE_AMAX);
    b = a; b.jmax = 100.0 * (1.0 + 2e-16); gen_across(&a, Ts, &b, Ts, SMS_ERR_STATE_JMAX);
    b = a; b.profile = SMS_PROFILE_TRIGONOMETRIC; gen_across(&a, Ts, &b, Ts, SMS_ERR_STATE_PROFILE);
    b = a; gen_across(&a, Ts, &b, 2e-3, SMS_ERR_STATE_TS);
    /* with and without a mode: another length too, still named */
    gen_across(&a, Ts, &m, Ts, SMS_ERR_STATE_WN);
    gen_across(&m, Ts, &a, Ts, SMS_ERR_STATE_WN);
    b = m; b.wn = 61.0; gen_across(&m, Ts, &b, Ts, SMS_ERR_STATE_WN);
    b = m; b.zeta = 0.2; gen_across(&m, Ts, &b, Ts, SMS_ERR_STATE_ZETA);
    b = m; b.profile = SMS_PROFILE_DAMPED; gen_across(&m, Ts, &b, Ts, SMS_ERR_STATE_PROFILE);
    b = m; b.profile = SMS_PROFILE_TRIGONOMETRIC; gen_across(&m, Ts, &b, Ts, SMS_ERR_STATE_PROFILE);
    /* zeta without a mode is part of the configuration as given */
    b = a; b.zeta = 0.3; gen_across(&a, Ts, &b, Ts, SMS_ERR_STATE_ZETA);
}

/* Tag, version, precision and kind: a vector that is not a generator state of this build. */
static void generator_format(void)
{
    const sms_generator_config a = {1.0, 10.0, 100.0, SMS_PROFILE_POLYNOMIAL, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    sms_generator g;
    sms_stage_config sc = sms_stage_config_default(SMS_RECTANGULAR);
    sms_stage s;
    size_t n, cells, i;
    static sms_memory_cell cell[1024];
    if (!gen_build(&g, &a, Ts, 0))
        return;
    n = sms_generator_state_count(&g);
    sms_generator_get_state(&g, state);
    CHECK(state[0] == SMS_STATE_TAG && state[1] == SMS_STATE_VERSION);
    CHECK(state[2] == (double)sizeof(sms_real) && state[3] == SMS_STATE_KIND_GENERATOR);
    CHECK(state[4] == Ts && state[5] == 1.0 && state[6] == 10.0 && state[7] == 100.0);
    for (i = 0; i < 4; ++i) {
        memcpy(bad, state, n * sizeof *state);
        bad[i] = i == 2 ? (sizeof(sms_real) == sizeof(double) ? 4.0 : 8.0) : bad[i] + 1.0;
        CHECK_STATUS(sms_generator_set_state(&g, bad, n),
                     i < 2 ? SMS_ERR_STATE_FORMAT
                           : i == 2 ? SMS_ERR_STATE_PRECISION : SMS_ERR_STATE_KIND);
    }
    memcpy(bad, state, n * sizeof *state);
    bad[5] = NAN; /* NaN never equals */
    CHECK_STATUS(sms_generator_set_state(&g, bad, n), SMS_ERR_STATE_VMAX);
    /* a stage's state is not a generator's, and the other way round */
    sc.T = 0.05;
    CHECK_STATUS(sms_stage_memory_size(&sc, Ts, &cells), SMS_OK);
    CHECK(cells <= 1024);
    CHECK_STATUS(sms_stage_init(&s, &sc, Ts, cell, cells), SMS_OK);
    sms_stage_get_state(&s, bad);
    CHECK_STATUS(sms_generator_set_state(&g, bad, sms_stage_state_count(&s)), SMS_ERR_STATE_KIND);
    CHECK_STATUS(sms_stage_set_state(&s, state, n), SMS_ERR_STATE_KIND);
    CHECK_STATUS(sms_generator_set_state(&g, state, n - 1), SMS_ERR_STATE);
    CHECK_STATUS(sms_generator_set_state(&g, state, 3), SMS_ERR_STATE);
    CHECK_STATUS(sms_generator_set_state(&g, state, n), SMS_OK);
    CHECK(strstr(sms_status_string(SMS_ERR_STATE_VMAX), "vmax") != NULL);
    CHECK(strstr(sms_status_string(SMS_ERR_STATE_PROFILE), "profile") != NULL);
}

/* Seeded random configurations: the same one continues bit for bit from the split; one
 * field moved to its neighbouring double (or the next profile) is refused naming it. */
static unsigned long rng_state = 2463534242ul;

static double uniform(void)
{
    rng_state ^= (rng_state << 13) & 0xFFFFFFFFul;
    rng_state ^= rng_state >> 17;
    rng_state ^= (rng_state << 5) & 0xFFFFFFFFul;
    return (double)(rng_state & 0xFFFFFFul) / 16777216.0;
}

static void generator_random(void)
{
    static const sms_status field_status[7] = {
        SMS_ERR_STATE_VMAX, SMS_ERR_STATE_AMAX, SMS_ERR_STATE_JMAX, SMS_ERR_STATE_PROFILE,
        SMS_ERR_STATE_WN, SMS_ERR_STATE_ZETA, SMS_ERR_STATE_TS
    };
    int trial, tried = 0;
    for (trial = 0; trial < 200; ++trial) {
        sms_generator_config a, b;
        double Ts_b = Ts;
        size_t need, field = (size_t)(uniform() * 7.0);
        a.vmax = pow(10.0, 2.0 * uniform() - 1.0);
        a.amax = a.vmax * pow(10.0, 2.0 * uniform() - 0.5);
        a.jmax = a.amax * pow(10.0, 2.0 * uniform());
        a.profile = (sms_profile)(int)(uniform() * 3.0);
        a.wn = a.profile == SMS_PROFILE_DAMPED || uniform() < 0.3 ? 20.0 + 200.0 * uniform() : 0.0;
        a.zeta = a.wn > 0.0 ? 0.3 * uniform() : 0.0;
        a.vmin = a.amin = 0.0; /* symmetric */
        a.qmin = a.qmax = 0.0; /* no position limits */
        b = a;
        switch (field) {
        case 0: b.vmax = nextafter(a.vmax, 1e300); break;
        case 1: b.amax = nextafter(a.amax, 0.0); break;
        case 2: b.jmax = nextafter(a.jmax, 1e300); break;
        case 3: b.profile = a.profile == SMS_PROFILE_POLYNOMIAL ? SMS_PROFILE_TRIGONOMETRIC
                                                                : SMS_PROFILE_POLYNOMIAL; break;
        case 4: b.wn = a.wn > 0.0 ? nextafter(a.wn, 1e300) : 50.0; break;
        case 5: b.zeta = nextafter(a.zeta, 1.0); break;
        default: Ts_b = nextafter(Ts, 1.0); break;
        }
        if (field == 4 && a.wn == 0.0 && b.profile == SMS_PROFILE_DAMPED)
            continue;
        if (sms_generator_buffer_size(&a, Ts, &need) != SMS_OK || need > REALS
            || sms_generator_buffer_size(&b, Ts_b, &need) != SMS_OK || need > REALS)
            continue; /* limits the generator refuses at init */
        ++tried;
        gen_across(&a, Ts, &a, Ts, SMS_OK);
        gen_across(&a, Ts, &b, Ts_b, field_status[field]);
    }
    CHECK(tried >= 150);
}

/* ------------------------------------------------------------------ B-spline */

/* A B-spline configuration: degree, axes, knot spacing T [s]. */
typedef struct bspline_config {
    unsigned degree;
    size_t axes;
    double T;
} bspline_config;

static sms_bspline bspline_a, bspline_b;

static int bspline_build(void *g, const void *config, double ts, int is_b)
{
    const bspline_config *c = config;
    size_t need = 0;
    CHECK_STATUS(sms_bspline_buffer_size(c->degree, c->axes, c->T, ts, &need), SMS_OK);
    if (need > REALS) {
        CHECK(0);
        return 0;
    }
    CHECK_STATUS(sms_bspline_init(g, c->degree, c->axes, c->T, ts, is_b ? buf_b : buf_a, need),
                 SMS_OK);
    return 1;
}

static size_t bspline_step(void *g, size_t k, sms_real *out)
{
    sms_real x[SMS_BSPLINE_MAX_AXES];
    x[0] = target_at(k);
    x[1] = x[2] = (sms_real)(k % 7);
    sms_bspline_step(g, x, out);
    return ((sms_bspline *)g)->n_axes;
}

STATE_FUNCTIONS(bspline, sms_bspline)

static const object_kind bspline = {
    &bspline_a, &bspline_b, SMS_BSPLINE_IDENTITY_COUNT, bspline_build, bspline_step,
    bspline_count, bspline_get, bspline_check, bspline_set,
    {{&bspline_b, sizeof bspline_b}, {buf_b, sizeof buf_b}, {NULL, 0}}};

static void bspline_across(unsigned pa, size_t axa, double Ta, double Tsa, unsigned pb,
                           size_t axb, double Tb, double Tsb, sms_status want)
{
    const bspline_config a = {pa, axa, Ta}, b = {pb, axb, Tb};
    across(&bspline, &a, Tsa, &b, Tsb, want);
}

static void bspline_fields(void)
{
    bspline_across(3, 2, 0.05, Ts, 3, 2, 0.05, Ts, SMS_OK);
    /* T is the knot spacing as realised, N Ts: 0.0501 s rounds to the same 50 samples */
    bspline_across(3, 2, 0.05, Ts, 3, 2, 0.0501, Ts, SMS_OK);
    bspline_across(3, 2, 0.05, Ts, 3, 2, 0.06, Ts, SMS_ERR_STATE_T);
    bspline_across(3, 2, 0.05, Ts, 2, 2, 0.05, Ts, SMS_ERR_STATE_DEGREE);
    bspline_across(3, 2, 0.05, Ts, 3, 3, 0.05, Ts, SMS_ERR_STATE_AXES);
    bspline_across(3, 2, 0.05, Ts, 3, 2, 0.05, 2.5e-3, SMS_ERR_STATE_TS);
}

/* ------------------------------------------------------------------ multi-axis generator */

static sms_stage mg_structs_a[64], mg_structs_b[64];
static sms_memory_cell mg_cells_a[REALS], mg_cells_b[REALS];
static sms_multi_generator mg_a, mg_b;

static void mg_limits(size_t i, double lim[3])
{
    lim[0] = 1.0 + 0.25 * (double)i;
    lim[1] = 10.0 - (double)i;
    lim[2] = 100.0 + 10.0 * (double)i;
}

static int mg_build(void *g, const void *config, double ts, int is_b)
{
    size_t ns = 0, nc = 0;
    CHECK_STATUS(sms_multi_generator_memory(config, ts, &ns, &nc, NULL), SMS_OK);
    if (ns > 64 || nc > REALS) {
        CHECK(0);
        return 0;
    }
    CHECK_STATUS(sms_multi_generator_init(g, config, ts, is_b ? mg_structs_b : mg_structs_a, ns,
                                          is_b ? mg_cells_b : mg_cells_a, nc, NULL),
                 SMS_OK);
    return 1;
}

static size_t mg_step(void *g, size_t k, sms_real *out)
{
    sms_real t[SMS_MULTI_MAX_AXES];
    size_t i, n_axes = ((sms_multi_generator *)g)->n_axes;
    for (i = 0; i < n_axes; ++i)
        t[i] = (sms_real)((double)target_at(k) * (1.0 + (double)i));
    sms_multi_generator_step(g, t, out);
    return 4 * n_axes;
}

STATE_FUNCTIONS(multi_generator, sms_multi_generator)

static const object_kind multi_generator = {
    &mg_a, &mg_b, SMS_MULTI_IDENTITY_COUNT, mg_build, mg_step, multi_generator_count,
    multi_generator_get, multi_generator_check, multi_generator_set,
    {{&mg_b, sizeof mg_b}, {mg_structs_b, sizeof mg_structs_b}, {mg_cells_b, sizeof mg_cells_b}}};

static void multi_across(const sms_multi_generator_config *a, double Ts_a,
                         const sms_multi_generator_config *b, double Ts_b, sms_status want)
{
    across(&multi_generator, a, Ts_a, b, Ts_b, want);
}

static void multi_fields(void)
{
    sms_multi_generator_config a = multi_config(2, SMS_SYNC_PHASE, mg_limits), b;
    sms_stage_config zv = sms_stage_config_default(SMS_SHAPER_ZV), zv2;
    multi_across(&a, Ts, &a, Ts, SMS_OK);
    b = multi_config(3, SMS_SYNC_PHASE, mg_limits); multi_across(&a, Ts, &b, Ts, SMS_ERR_STATE_AXES);
    b = a; b.sync = SMS_SYNC_INDEPENDENT; multi_across(&a, Ts, &b, Ts, SMS_ERR_STATE_SYNC);
    b = a; b.vmax[1] = 2.0; multi_across(&a, Ts, &b, Ts, SMS_ERR_STATE_VMAX);
    b = a; b.amax[0] = 9.5; multi_across(&a, Ts, &b, Ts, SMS_ERR_STATE_AMAX);
    b = a; b.jmax[1] = 111.0; multi_across(&a, Ts, &b, Ts, SMS_ERR_STATE_JMAX);
    b = a; multi_across(&a, Ts, &b, 2e-3, SMS_ERR_STATE_TS);
    /* stages: their number per axis, then a stage's own field */
    zv.wn = 60.0;
    zv2 = zv;
    zv2.wn = 61.0;
    a.stages[1] = &zv;
    a.n_stages[1] = 1;
    multi_across(&a, Ts, &a, Ts, SMS_OK);
    b = a; b.n_stages[1] = 0; b.stages[1] = NULL;
    multi_across(&a, Ts, &b, Ts, SMS_ERR_STATE_STAGES);
    b = a; b.stages[1] = &zv2; multi_across(&a, Ts, &b, Ts, SMS_ERR_STATE_WN);
    a.sync = SMS_SYNC_INDEPENDENT;
    multi_across(&a, Ts, &a, Ts, SMS_OK);
}

int main(void)
{
    generator_fields();
    generator_format();
    generator_random();
    bspline_fields();
    multi_fields();
    return check_summary("test_trajectory_state");
}
