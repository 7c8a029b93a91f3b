/* SPDX-License-Identifier: Apache-2.0 */
/* The multi-axis generator's alignment (config.align): with different stages per axis a
 * straight move at constant speed leaves the line by about v |D_i - D_j| Ts; aligned, every
 * axis lags by the common lag and the constant-speed segment stays on the line to rounding.
 * The lag reported, the hold against the steps, the saved state, refusals. */
#include <string.h>
#include "check.h"

#ifdef SMS_USE_FLOAT
#define UNIT 5.9604644775390625e-08
#else
#define UNIT 1.1102230246251565e-16
#endif
#define N_SAMPLES 5000
#define CELLS 40000

static const double Ts = 1e-3;
static sms_stage stage_structs[256], stage_structs2[256];
static sms_memory_cell memory[CELLS], memory2[CELLS];
static sms_real out[N_SAMPLES * 4 * 3];

/* Three axes: x a ZVD shaper and a rectangular stage, y an EI shaper at another mode, z none. */
static sms_multi_generator_config config3(sms_stage_config *sx, sms_stage_config *sy, int align)
{
    sms_multi_generator_config c;
    size_t i;
    memset(&c, 0, sizeof c);
    c.n_axes = 3;
    for (i = 0; i < 3; ++i) {
        c.vmax[i] = 0.5;
        c.amax[i] = 5.0;
        c.jmax[i] = 200.0;
    }
    (void)sms_design_for_mode(SMS_SHAPER_ZVD, 2.0 * 3.14159265358979 * 12.0, 0.05, 1, &sx[0]);
    sx[1] = sms_stage_config_default(SMS_RECTANGULAR);
    sx[1].T = 20.5 * Ts;
    (void)sms_design_for_mode(SMS_SHAPER_EI, 2.0 * 3.14159265358979 * 31.0, 0.02, 1, &sy[0]);
    c.stages[0] = sx;
    c.n_stages[0] = 2;
    c.stages[1] = sy;
    c.n_stages[1] = 1;
    c.align = align;
    return c;
}

static void build(sms_multi_generator *g, const sms_multi_generator_config *c,
                  sms_stage *structs, sms_memory_cell *mem)
{
    size_t n_structs = 0, n_cells = 0;
    CHECK_STATUS(sms_multi_generator_memory(c, Ts, &n_structs, &n_cells, NULL), SMS_OK);
    CHECK(n_structs <= 256 && n_cells <= CELLS);
    CHECK_STATUS(sms_multi_generator_init(g, c, Ts, structs, n_structs, mem, n_cells, NULL),
                 SMS_OK);
}

/* Largest distance of the q outputs from the line p0 -> p1 over samples [from, to). */
static double line_deviation(const double *p0, const double *p1, size_t from, size_t to)
{
    double u[3], len = 0.0, worst = 0.0;
    size_t k, i;
    for (i = 0; i < 3; ++i) {
        u[i] = p1[i] - p0[i];
        len += u[i] * u[i];
    }
    len = sqrt(len);
    for (i = 0; i < 3; ++i)
        u[i] /= len;
    for (k = from; k < to; ++k) {
        double r[3], along = 0.0, d = 0.0;
        for (i = 0; i < 3; ++i) {
            r[i] = (double)out[(k * 3 + i) * 4] - p0[i];
            along += r[i] * u[i];
        }
        for (i = 0; i < 3; ++i)
            d += (r[i] - along * u[i]) * (r[i] - along * u[i]);
        if (sqrt(d) > worst)
            worst = sqrt(d);
    }
    return worst;
}

/* A long straight move from rest: its cruise (constant speed) and the whole move. */
static void run_move(int align, double *cruise, double *whole, double *lag)
{
    sms_stage_config sx[2], sy[1];
    const sms_multi_generator_config c = config3(sx, sy, align);
    sms_multi_generator g;
    static const double p0[3] = {0.0, 0.0, 0.0}, p1[3] = {1.2, -0.8, 0.5};
    sms_real target[3];
    size_t k, i;
    build(&g, &c, stage_structs, memory);
    for (i = 0; i < 3; ++i)
        target[i] = (sms_real)p1[i];
    for (k = 0; k < N_SAMPLES; ++k)
        sms_multi_generator_step(&g, target, &out[k * 12]);
    *lag = sms_multi_generator_lag(&g);
    /* the cruise: the profile at vmax of the slowest-scaled axis from about 0.15 s to 2.4 s;
     * the stages' windows (under 0.15 s) inside it */
    *cruise = line_deviation(p0, p1, 600, 2300);
    *whole = line_deviation(p0, p1, 0, N_SAMPLES);
}

static void test_alignment_keeps_the_line(void)
{
    double cruise0, whole0, lag0, cruise1, whole1, lag1;
    run_move(0, &cruise0, &whole0, &lag0);
    run_move(1, &cruise1, &whole1, &lag1);
    printf("straight move, different stages per axis: off the line by %.3g (constant speed) and "
           "%.3g (whole move); aligned (common lag %.4f s): %.3g and %.3g\n", cruise0, whole0,
           lag1, cruise1, whole1);
    CHECK(cruise0 > 1e-3);                       /* v |D_x - D_y| Ts is millimetres here */
    CHECK(cruise1 <= 64.0 * UNIT * 1.5);         /* rounding of positions up to 1.5 */
    CHECK(whole1 < whole0);
    CHECK(lag0 == lag1 && lag1 > 0.0);
}

/* The reported lag is the ramp's delay: the aligned axes' positions all equal the profile
 * delayed by the common lag at constant speed. */
static void test_lag_value(void)
{
    sms_stage_config sx[2], sy[1];
    sms_multi_generator_config c = config3(sx, sy, 1);
    double lx, ly;
    sms_multi_generator g;
    CHECK_STATUS(sms_chain_config_lag(sx, 2, Ts, &lx), SMS_OK);
    CHECK_STATUS(sms_chain_config_lag(sy, 1, Ts, &ly), SMS_OK);
    build(&g, &c, stage_structs, memory);
    CHECK_CLOSE(sms_multi_generator_lag(&g), (lx > ly ? lx : ly) * Ts, 1e-15, lx * Ts);
    CHECK(g.axis_lag[2] == 0.0);
    c.align = 2;
    {
        size_t a = 0, b = 0;
        CHECK_STATUS(sms_multi_generator_memory(&c, Ts, &a, &b, NULL), SMS_ERR_KIND);
    }
}

/* Hold equals steps, bit for bit, aligned; a saved state continues bit for bit; a state of the
 * unaligned generator is refused. */
static void test_hold_and_state(void)
{
    sms_stage_config sx[2], sy[1];
    const sms_multi_generator_config c = config3(sx, sy, 1), c0 = config3(sx, sy, 0);
    sms_multi_generator a, b, u;
    static double state[CELLS];
    sms_real t1[3] = {0.3, 0.2, -0.1}, o1[12], o2[12];
    size_t k, n;
    build(&a, &c, stage_structs, memory);
    build(&b, &c, stage_structs2, memory2);
    for (k = 0; k < 300; ++k) {
        sms_multi_generator_step(&a, t1, o1);
        sms_multi_generator_step(&b, t1, o2);
    }
    CHECK(sms_multi_generator_hold(&a, t1, 20000, o1) == 20000);
    for (k = 0; k < 20000; ++k)
        sms_multi_generator_step(&b, t1, o2);
    CHECK(memcmp(o1, o2, sizeof o1) == 0);
    /* at rest the delays add nothing: the unaligned generator's output (its stages' rest) */
    build(&u, &c0, stage_structs2 + 128, memory2 + CELLS / 2);
    {
        sms_real t0[3] = {0.3, 0.2, -0.1}, o3[12];
        (void)sms_multi_generator_hold(&u, t0, 20300, o3);
        for (k = 0; k < 12; ++k)
            CHECK(o1[k] == o3[k]);
    }
    t1[0] = -0.4;
    for (k = 0; k < 700; ++k)
        sms_multi_generator_step(&a, t1, o1);
    n = sms_multi_generator_state_count(&a);
    CHECK(n <= CELLS);
    sms_multi_generator_get_state(&a, state);
    CHECK_STATUS(sms_multi_generator_set_state(&b, state, n), SMS_OK);
    for (k = 0; k < 900; ++k) {
        sms_multi_generator_step(&a, t1, o1);
        sms_multi_generator_step(&b, t1, o2);
        CHECK(memcmp(o1, o2, sizeof o1) == 0);
    }
    build(&u, &c0, stage_structs2, memory2);
    CHECK(sms_multi_generator_set_state(&u, state, n) != SMS_OK);
    CHECK(sms_multi_generator_check_state(&b, state, n) == SMS_OK);
    {   /* the first delay's head out of range */
        size_t i, m, delays = 0;
        for (i = 0; i < 3; ++i)
            for (m = 0; m < 4; ++m)
                delays += sms_delay_state_count(&b.delay[i][m]);
        state[n - delays + 2] = -1.0;
        CHECK(sms_multi_generator_check_state(&b, state, n) == SMS_ERR_STATE);
    }
}

int main(void)
{
    test_alignment_keeps_the_line();
    test_lag_value();
    test_hold_and_state();
    return check_summary("test_multi_align");
}
