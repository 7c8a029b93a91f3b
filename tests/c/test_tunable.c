/* SPDX-License-Identifier: Apache-2.0 */
/* Retuning a running stage (tunable.h): over random configurations of every family and random
 * switch instants, the output equals the rule's definition, y[n] = rest + sum_k s_{a(k)}[n-k]
 * dx[k] (each increment through the step response of the filter active when it arrived),
 * computed here directly from the taps; the switch moves the output by at most one sample's
 * motion of the input against the old filter; from max(L_A, L_B) - 2 samples after it the
 * output is the new filter's. Also: split blocks equal one block bit for bit, a state saved
 * during a switch continues bit for bit, refusals change nothing, and many switches leave no
 * drift. */
#include <stdlib.h>
#include <string.h>
#include "check.h"

#define N_IN 700
#define MAX_TAPS 2048
#define SLOT_CELLS 4096
#define CASES 160
#ifdef SMS_USE_FLOAT
#define UNIT_ROUNDOFF 5.9604644775390625e-08   /* 2^-24 */
#else
#define UNIT_ROUNDOFF 1.1102230246251565e-16   /* 2^-53 */
#endif
#define TOL_U 32.0

static const double Ts = 1e-3;

static unsigned long rng_state = 12345u;
static double uniform(void)   /* [0, 1): a fixed LCG, the same on every platform */
{
    rng_state = (rng_state * 1103515245u + 12345u) & 0x7fffffffu;
    return (double)rng_state / 2147483648.0;
}
static size_t below(size_t n)
{
    return (size_t)(uniform() * (double)n);
}

/* A random valid configuration of the given family (0 smoother, 1 shaper, 2 notch) at Ts. */
static sms_stage_config random_config(int family)
{
    static const sms_kind smoothers[4] = {SMS_RECTANGULAR, SMS_HARMONIC, SMS_DAMPED_HARMONIC,
                                          SMS_EXPONENTIAL};
    static const sms_kind shapers[9] = {SMS_SHAPER_ZV, SMS_SHAPER_ZVD, SMS_SHAPER_ZVDD,
                                        SMS_SHAPER_ZVN, SMS_SHAPER_EI, SMS_SHAPER_EI2,
                                        SMS_SHAPER_MZV, SMS_SHAPER_EI3, SMS_SHAPER_GMZV};
    sms_stage_config c;
    for (;;) {
        if (family == 0) {
            c = sms_stage_config_default(smoothers[below(4)]);
            c.T = (2.0 + 58.0 * uniform()) * Ts;
            c.timing = (sms_timing)below(3);
            if (c.kind == SMS_DAMPED_HARMONIC || c.kind == SMS_EXPONENTIAL)
                c.sigma = -uniform() * 80.0;
        } else if (family == 1) {
            c = sms_stage_config_default(shapers[below(9)]);
            c.wn = 150.0 + 600.0 * uniform();
            c.zeta = 0.2 * uniform();
            c.timing = (sms_timing)below(2);
            c.order = c.kind == SMS_SHAPER_ZVN ? 1u + (unsigned)below(4) : c.order;
        } else {
            c = sms_stage_config_default(below(2) ? SMS_NOTCH_TUSTIN : SMS_NOTCH_MATCHED);
            c.wn = 100.0 + 900.0 * uniform();
            c.zeta = 0.1 * uniform();
            c.notch_pole_zeta = 0.3 + 1.5 * uniform();
        }
        if (sms_stage_config_validate(&c, Ts) == SMS_OK)
            return c;
    }
}

/* Step response s[0 .. n) of a config, in double from its realised taps (FIR) or from its
 * realised coefficients (notch: the biquad H = 1 + D/A of notch.h). */
static void step_response(const sms_stage_config *c, double *s, size_t n)
{
    static double taps[MAX_TAPS];
    size_t i, L = 0;
    if (c->kind == SMS_NOTCH_TUSTIN || c->kind == SMS_NOTCH_MATCHED) {
        sms_notch f;
        double w1 = 0.0, w2 = 0.0, x1 = 0.0, x2 = 0.0;
        CHECK_STATUS(sms_notch_init(&f, c, Ts), SMS_OK);
        for (i = 0; i < n; ++i) {
            const double w = (double)f.d0 * (1.0 - x1) + (double)f.d2 * (x2 - x1)
                             - (double)f.a1 * w1 - (double)f.a2 * w2;
            s[i] = 1.0 + w;
            w2 = w1;
            w1 = w;
            x2 = x1;
            x1 = 1.0;
        }
        return;
    }
    if (c->kind <= SMS_EXPONENTIAL) {
        CHECK_STATUS(sms_smoother_length(c, Ts, &L), SMS_OK);
        CHECK_STATUS(sms_smoother_taps(c, Ts, taps, MAX_TAPS), SMS_OK);
    } else {
        CHECK_STATUS(sms_shaper_buffer_size(c, Ts, &L), SMS_OK);
        CHECK_STATUS(sms_shaper_taps(c, Ts, taps, MAX_TAPS), SMS_OK);
    }
    for (i = 0; i < n; ++i)
        s[i] = (i > 0 ? s[i - 1] : 0.0) + (i < L ? taps[i] : 0.0);
}

static size_t config_length(const sms_stage_config *c)
{
    size_t L = 0;
    if (c->kind <= SMS_EXPONENTIAL)
        (void)sms_smoother_length(c, Ts, &L);
    else if (c->kind != SMS_NOTCH_TUSTIN && c->kind != SMS_NOTCH_MATCHED)
        (void)sms_shaper_buffer_size(c, Ts, &L);
    return L;
}

/* A move: piecewise-constant velocity (random slopes, some pauses) from rest, plus noise. */
static void random_move(double *x, size_t n, double rest)
{
    double v = 0.0, pos = rest;
    size_t i;
    for (i = 0; i < n; ++i) {
        if (i % 37 == 0)
            v = uniform() < 0.25 ? 0.0 : (2.0 * uniform() - 1.0) * 0.05;
        pos += v;
        x[i] = pos + (uniform() < 0.02 ? 0.01 * (2.0 * uniform() - 1.0) : 0.0);
    }
}

/* The rule's definition: y[n] = rest + sum_k s_{a(k)}[n-k] dx[k], a(k) = A before n0, B from
 * it; summed with Neumaier's compensation, so that its own error (about 2 u |y|) stays far
 * below the realisation's. */
static void definition(const double *x, size_t n, double rest, size_t n0, const double *sA,
                       const double *sB, double *y)
{
    size_t i, k;
    for (i = 0; i < n; ++i) {
        double acc = rest, lost = 0.0;
        for (k = 0; k <= i; ++k) {
            const double dx = x[k] - (k > 0 ? x[k - 1] : rest);
            const double term = (k < n0 ? sA[i - k] : sB[i - k]) * dx, sum = acc + term;
            lost += fabs(acc) >= fabs(term) ? (acc - sum) + term : (term - sum) + acc;
            acc = sum;
        }
        y[i] = acc + lost;
    }
}

static sms_memory_cell mem_a[2 * SLOT_CELLS], mem_b[2 * SLOT_CELLS], mem_c[2 * SLOT_CELLS];
static sms_memory_cell fixed_mem[SLOT_CELLS];

/* Run a fixed stage of config c on x from rest. */
static void run_fixed(const sms_stage_config *c, const double *x, size_t n, double rest,
                      double *y)
{
    sms_stage s;
    size_t i;
    CHECK_STATUS(sms_stage_init(&s, c, Ts, fixed_mem, SLOT_CELLS), SMS_OK);
    sms_stage_reset(&s, (sms_real)rest);
    for (i = 0; i < n; ++i) {
        sms_real v = (sms_real)x[i];
        sms_stage_step(&s, &v);
        y[i] = (double)v;
    }
}

/* The largest |a - b| over [from, n) in units of tol (1: at the tolerance). */
static double worst_seen[3];
static double err_in_tol(const double *a, const double *b, size_t from, size_t n, double tol,
                         int which)
{
    double worst = 0.0;
    size_t i;
    for (i = from; i < n; ++i)
        if (!(fabs(a[i] - b[i]) <= worst * tol))
            worst = fabs(a[i] - b[i]) / tol;
    if (worst > worst_seen[which])
        worst_seen[which] = worst;
    return worst;
}

/* One random switch of one family pair: definition, jump, new filter, blocks, saved state. */
static void switch_case(int fam_a, int fam_b, double *worst_jump_ratio)
{
    static double x[N_IN], y[N_IN], yd[N_IN], yA[N_IN], yB[N_IN], sA[N_IN], sB[N_IN];
    static sms_real blk[N_IN], saved_out[N_IN];
    static double state[2 * SLOT_CELLS + 256];
    const sms_stage_config a = random_config(fam_a), b = random_config(fam_b);
    const double rest = 10.0 * (2.0 * uniform() - 1.0);
    const size_t n0 = 50 + below(300), LA = config_length(&a), LB = config_length(&b);
    const size_t settled = n0 + (LA > LB ? LA : LB);
    sms_tunable t, u;
    size_t i, jump_at;
    double scale = 0.0, tol;
    random_move(x, N_IN, rest);
    for (i = 0; i < N_IN; ++i)
        scale = fabs(x[i]) > scale ? fabs(x[i]) : scale;
    /* Tolerance: a few roundings of the signal's magnitude, TOL_U units u (u the unit roundoff
     * of sms_real): the input's own rounding to sms_real, the realisation's sums (the
     * drift-free recursions err by the rounding of one window, docs/numerics.md; a shaper's
     * sum of at most 45 taps of sum 1), the definition's sums in double. */
    tol = TOL_U * UNIT_ROUNDOFF * scale;
    CHECK_STATUS(sms_tunable_init(&t, &a, Ts, SLOT_CELLS, mem_a, 2 * SLOT_CELLS), SMS_OK);
    sms_tunable_reset(&t, (sms_real)rest);
    for (i = 0; i < N_IN; ++i) {
        sms_real v = (sms_real)x[i];
        if (i == n0)
            CHECK_STATUS(sms_tunable_retune(&t, &b), SMS_OK);
        sms_tunable_step(&t, &v);
        y[i] = (double)v;
        blk[i] = (sms_real)x[i];
    }
    step_response(&a, sA, N_IN);
    step_response(&b, sB, N_IN);
    definition(x, N_IN, rest, n0, sA, sB, yd);
    CHECK(err_in_tol(y, yd, 0, N_IN, tol, 0) <= 1.0);
    /* the jump: against the old filter kept, at most (h_B[0] - h_A[0]) dx[n0] */
    run_fixed(&a, x, N_IN, rest, yA);
    run_fixed(&b, x, N_IN, rest, yB);
    CHECK(err_in_tol(y, yA, 0, n0, tol, 1) <= 1.0);
    jump_at = n0;
    {
        const double motion = fabs(x[jump_at] - x[jump_at - 1]);
        const double jump = fabs(y[jump_at] - yA[jump_at]);
        CHECK(jump <= fabs(sB[0] - sA[0]) * motion + tol);
        if (motion > 0.0 && jump / motion > *worst_jump_ratio)
            *worst_jump_ratio = jump / motion;
    }
    /* the new filter exactly, for FIR stages: from n0 + max(L_A, L_B) - 2 on */
    if (LA > 0 && LB > 0 && settled < N_IN)
        CHECK(err_in_tol(y, yB, settled - 2u, N_IN, tol, 2) <= 1.0);
    /* split into random blocks: the same bits */
    CHECK_STATUS(sms_tunable_init(&u, &a, Ts, SLOT_CELLS, mem_b, 2 * SLOT_CELLS), SMS_OK);
    sms_tunable_reset(&u, (sms_real)rest);
    i = 0;
    while (i < N_IN) {
        size_t m = 1 + below(90);
        if (i < n0 && i + m > n0)
            m = n0 - i;
        if (i + m > N_IN)
            m = N_IN - i;
        if (i == n0)
            CHECK_STATUS(sms_tunable_retune(&u, &b), SMS_OK);
        sms_tunable_process(&u, &blk[i], &blk[i], m);
        i += m;
    }
    for (i = 0; i < N_IN; ++i)
        CHECK((double)blk[i] == y[i]);
    /* save during the switch, restore into a tunable brought to the same configuration */
    {
        sms_tunable w;
        const size_t at = n0 + 1 + below(4);
        sms_stage_config ca, cb;
        int switching = 0;
        CHECK_STATUS(sms_tunable_init(&u, &a, Ts, SLOT_CELLS, mem_b, 2 * SLOT_CELLS), SMS_OK);
        sms_tunable_reset(&u, (sms_real)rest);
        for (i = 0; i < at; ++i) {
            sms_real v = (sms_real)x[i];
            if (i == n0)
                CHECK_STATUS(sms_tunable_retune(&u, &b), SMS_OK);
            sms_tunable_step(&u, &v);
        }
        CHECK(sms_tunable_state_count(&u) <= sizeof state / sizeof state[0]);
        sms_tunable_get_state(&u, state);
        CHECK_STATUS(sms_tunable_state_configs(state, sms_tunable_state_count(&u), &cb, &ca,
                                               &switching), SMS_OK);
        CHECK(switching == sms_tunable_switching(&u));
        CHECK_STATUS(sms_tunable_init(&w, switching ? &ca : &cb, Ts, SLOT_CELLS, mem_c,
                                      2 * SLOT_CELLS), SMS_OK);
        if (switching)
            CHECK_STATUS(sms_tunable_retune(&w, &cb), SMS_OK);
        CHECK_STATUS(sms_tunable_set_state(&w, state, sms_tunable_state_count(&u)), SMS_OK);
        for (i = at; i < N_IN; ++i) {
            sms_real v = (sms_real)x[i];
            sms_tunable_step(&w, &v);
            saved_out[i] = v;
        }
        for (i = at; i < N_IN; ++i)
            CHECK((double)saved_out[i] == y[i]);
    }
}

static void test_switches(void)
{
    int fa, fb, c;
    double worst = 0.0;
    for (c = 0; c < CASES; ++c)
        for (fa = 0; fa < 3; ++fa)
            for (fb = 0; fb < 3; ++fb)
                if (c % 9 == fa * 3 + fb || c < 18)
                    switch_case(fa, fb, &worst);
    /* the jump is a fraction |h_B[0] - h_A[0]| < 1 of one sample's motion */
    CHECK(worst <= 1.0);
    printf("largest errors in units of u times the signal's magnitude: against the definition "
           "%.3g, before the switch against the old filter %.3g, after both lengths against the "
           "new filter %.3g\n", worst_seen[0] * TOL_U, worst_seen[1] * TOL_U, worst_seen[2] * TOL_U);
    printf("largest jump at a switch: %.3g of one sample's input motion\n", worst);
}

/* Refusals change nothing: busy, too large, invalid, NULL. */
static void test_refusals(void)
{
    static double before[2 * SLOT_CELLS + 256], after[2 * SLOT_CELLS + 256];
    sms_stage_config a = sms_stage_config_default(SMS_RECTANGULAR), big, bad, zv;
    sms_tunable t;
    size_t cells = 0, i;
    a.T = 20 * Ts;
    big = a;
    big.T = 200 * Ts;
    bad = a;
    bad.T = -1.0;
    zv = sms_stage_config_default(SMS_SHAPER_ZV);
    zv.wn = 300.0;
    CHECK_STATUS(sms_tunable_slot_cells(&a, 1, Ts, &cells), SMS_OK);
    CHECK_STATUS(sms_tunable_slot_cells(&a, 0, Ts, &cells), SMS_ERR_ORDER);
    CHECK_STATUS(sms_tunable_slot_cells(&bad, 1, Ts, &cells), SMS_ERR_DURATION);
    CHECK_STATUS(sms_tunable_slot_cells(&a, 1, Ts, &cells), SMS_OK);
    CHECK_STATUS(sms_tunable_init(&t, &big, Ts, cells, mem_a, 2 * cells), SMS_ERR_BUFFER_TOO_SMALL);
    CHECK_STATUS(sms_tunable_init(&t, &a, Ts, cells, mem_a, cells - 1), SMS_ERR_BUFFER_TOO_SMALL);
    CHECK_STATUS(sms_tunable_init(&t, &a, Ts, cells, NULL, 2 * cells), SMS_ERR_NULL);
    /* one slot: a fixed stage, every retune refused and nothing changed */
    CHECK_STATUS(sms_tunable_init(&t, &a, Ts, cells, mem_a, cells), SMS_OK);
    CHECK(t.n_slots == 1u);
    CHECK_STATUS(sms_tunable_retune(&t, &a), SMS_ERR_BUFFER_TOO_SMALL);
    CHECK(!sms_tunable_switching(&t));
    sms_tunable_rebind(&t, mem_a);
    CHECK_STATUS(sms_tunable_init(&t, &a, Ts, cells, mem_a, 2 * cells), SMS_OK);
    CHECK(t.n_slots == 2u);
    for (i = 0; i < 30; ++i) {
        sms_real v = (sms_real)(0.1 * (double)i);
        sms_tunable_step(&t, &v);
    }
    sms_tunable_get_state(&t, before);
    CHECK_STATUS(sms_tunable_retune(&t, &big), SMS_ERR_BUFFER_TOO_SMALL);
    CHECK_STATUS(sms_tunable_retune(&t, &bad), SMS_ERR_DURATION);
    CHECK_STATUS(sms_tunable_retune(NULL, &a), SMS_ERR_NULL);
    CHECK_STATUS(sms_tunable_retune(&t, NULL), SMS_ERR_NULL);
    sms_tunable_get_state(&t, after);
    CHECK(memcmp(before, after, sms_tunable_state_count(&t) * sizeof(double)) == 0);
    CHECK(!sms_tunable_switching(&t));
    CHECK_STATUS(sms_tunable_retune(&t, &zv), SMS_OK);   /* the shaper fits the slot */
    CHECK(sms_tunable_switching(&t));
    CHECK(sms_tunable_switch_left(&t) == (double)(20 - 2));
    sms_tunable_get_state(&t, before);
    CHECK_STATUS(sms_tunable_retune(&t, &a), SMS_ERR_RETUNE_BUSY);
    sms_tunable_get_state(&t, after);
    CHECK(memcmp(before, after, sms_tunable_state_count(&t) * sizeof(double)) == 0);
    for (i = 0; i < 18; ++i) {
        sms_real v = (sms_real)3.0;
        CHECK(sms_tunable_switching(&t));
        sms_tunable_step(&t, &v);
    }
    CHECK(!sms_tunable_switching(&t));
    CHECK_STATUS(sms_tunable_retune(&t, &a), SMS_OK);
    {   /* a state of another slot size, precision or kind is refused */
        sms_tunable w;
        const size_t n = sms_tunable_state_count(&t);
        sms_tunable_get_state(&t, before);
        CHECK_STATUS(sms_tunable_init(&w, &zv, Ts, cells + 1, mem_b, 2 * cells + 2), SMS_OK);
        CHECK_STATUS(sms_tunable_retune(&w, &a), SMS_OK);
        CHECK_STATUS(sms_tunable_set_state(&w, before, n), SMS_ERR_STATE);
        memcpy(after, before, n * sizeof(double));
        after[2] = 3.0;
        CHECK_STATUS(sms_tunable_set_state(&t, after, n), SMS_ERR_STATE_PRECISION);
        after[2] = before[2];
        after[3] = 0.0;
        CHECK_STATUS(sms_tunable_set_state(&t, after, n), SMS_ERR_STATE_KIND);
        CHECK_STATUS(sms_tunable_set_state(&t, before, n - 1), SMS_ERR_STATE);
        CHECK_STATUS(sms_tunable_set_state(&t, before, n), SMS_OK);
    }
}

/* A notch's switch ends by itself, within the bound sms_tunable_switch_left() gave, and
 * long before the exact settling for complex, repeated and distinct real poles. */
static void test_notch_fade_ends(void)
{
    static const double pole_zeta[4] = {0.7, 1.0, 1.0 + 1e-9, 3.0};
    int p;
    for (p = 0; p < 4; ++p) {
        sms_stage_config a = sms_stage_config_default(SMS_NOTCH_TUSTIN), b = a;
        sms_tunable t;
        size_t cells = 0, i;
        double bound, settle;
        a.wn = 200.0;
        a.notch_pole_zeta = pole_zeta[p];
        b.wn = 260.0;
        CHECK_STATUS(sms_tunable_slot_cells(&a, 1, Ts, &cells), SMS_OK);
        CHECK_STATUS(sms_tunable_init(&t, &a, Ts, cells, mem_a, 2 * cells), SMS_OK);
        for (i = 0; i < 200; ++i) {
            sms_real v = (sms_real)(0.01 * (double)i + 5.0);
            sms_tunable_step(&t, &v);
        }
        CHECK_STATUS(sms_tunable_retune(&t, &b), SMS_OK);
        CHECK(sms_tunable_switching(&t));
        {
            sms_real v = (sms_real)7.0;
            sms_tunable_step(&t, &v);
            sms_tunable_step(&t, &v);
        }
        bound = sms_tunable_switch_left(&t);
        settle = sms_notch_settle_bound(t.slot[1u - t.active].u.notch);
        for (i = 0; i < 100000 && sms_tunable_switching(&t); ++i) {
            sms_real v = (sms_real)7.0;
            sms_tunable_step(&t, &v);
        }
        CHECK(!sms_tunable_switching(&t));
        CHECK((double)i <= bound + 1.0);
        CHECK((double)i < settle / 4.0);
        printf("notch switch (wn 200 -> 260 rad/s, pole damping %.9g, Ts 1 ms): ended after %lu "
               "samples (bound %.0f, exact settling bound %.0f)\n", pole_zeta[p],
               (unsigned long)(i + 2), bound + 2.0, settle);
    }
}

/* Many switches leave no drift: after each switch has passed both lengths, the output is the
 * new filter's, computed from scratch on the whole input. */
static void test_no_drift(void)
{
    enum { SEG = 900, N_SEG = 120 };
    static double yfix[SEG * 2];
    static double xw[SEG * 2];
    sms_stage_config c[2];
    sms_tunable t;
    size_t cells = 0, s, i;
    double worst = 0.0;
    c[0] = sms_stage_config_default(SMS_DAMPED_HARMONIC);
    c[0].T = 41.37 * Ts;
    c[0].sigma = -20.0;
    c[1] = sms_stage_config_default(SMS_SHAPER_EI);
    c[1].wn = 210.0;
    c[1].zeta = 0.05;
    CHECK_STATUS(sms_tunable_slot_cells(c, 2, Ts, &cells), SMS_OK);
    CHECK_STATUS(sms_tunable_init(&t, &c[0], Ts, cells, mem_a, 2 * cells), SMS_OK);
    /* segment s: the tunable filters it with c[s % 2] after a switch at its start; a fixed
     * stage of that config run over the previous and this segment (enough history) must agree
     * at the segment's end */
    for (s = 0; s < N_SEG; ++s) {
        const size_t base = s % 2 ? 0 : SEG;
        for (i = 0; i < SEG; ++i) {
            const double ti = (double)(s * SEG + i);
            xw[base + i] = 1000.0 + 5.0 * sin(ti * 0.01) + 2.0 * uniform();
        }
        if (s > 0)
            CHECK_STATUS(sms_tunable_retune(&t, &c[s % 2]), SMS_OK);
        for (i = 0; i < SEG; ++i) {
            sms_real v = (sms_real)xw[base + i];
            sms_tunable_step(&t, &v);
            yfix[base + i] = (double)v;
        }
        if (s > 0) {
            static double whole[SEG * 2], out[SEG * 2];
            const size_t prev = s % 2 ? SEG : 0;
            for (i = 0; i < SEG; ++i) {
                whole[i] = xw[prev + i];
                whole[SEG + i] = xw[base + i];
            }
            run_fixed(&c[s % 2], whole, 2 * SEG, whole[0], out);
            /* the fixed stage starts at rest at whole[0]: its start-up is over after its
             * length, well inside the previous segment */
            for (i = SEG / 2; i < SEG; ++i) {
                const double e = fabs(out[SEG + i] - yfix[base + i]) / 1000.0;
                if (e > worst)
                    worst = e;
            }
        }
    }
    CHECK(worst <= SMS_TEST_REL_TOL);
    printf("%d switches: largest error against the new filter from scratch %.3g (relative)\n",
           N_SEG - 1, worst);
}

/* A chain of tunables: series, hold equals steps, rebind after a copy. */
static void test_chain(void)
{
    static sms_memory_cell mem[8 * SLOT_CELLS], copy[8 * SLOT_CELLS];
    sms_stage_config c[3], z;
    size_t slots[3], need, i;
    sms_tunable st[3], st2[3];
    sms_tunable_chain ch, ch2;
    sms_real y1, y2;
    c[0] = sms_stage_config_default(SMS_RECTANGULAR);
    c[0].T = 30.5 * Ts;
    c[1] = sms_stage_config_default(SMS_SHAPER_ZVD);
    c[1].wn = 300.0;
    c[2] = sms_stage_config_default(SMS_NOTCH_MATCHED);
    c[2].wn = 800.0;
    z = c[1];
    z.wn = 250.0;
    for (i = 0; i < 3; ++i)
        CHECK_STATUS(sms_tunable_slot_cells(&c[i], 1, Ts, &slots[i]), SMS_OK);
    (void)sms_tunable_slot_cells(&z, 1, Ts, &slots[1]);   /* room for the lower wn */
    CHECK_STATUS(sms_tunable_chain_memory_size(slots, 3, &need), SMS_OK);
    CHECK(need <= 8 * SLOT_CELLS);
    CHECK_STATUS(sms_tunable_chain_init(&ch, st, c, slots, 3, Ts, mem, need), SMS_OK);
    CHECK_STATUS(sms_tunable_chain_retune(&ch, 3, &z), SMS_ERR_ORDER);
    sms_tunable_chain_reset(&ch, (sms_real)2.0);
    for (i = 0; i < 100; ++i) {
        sms_real v = (sms_real)(2.0 + 0.02 * (double)i);
        sms_tunable_chain_step(&ch, &v);
    }
    CHECK_STATUS(sms_tunable_chain_retune(&ch, 1, &z), SMS_OK);
    CHECK(sms_tunable_chain_switching(&ch));
    memcpy(copy, mem, need * sizeof mem[0]);
    memcpy(st2, st, sizeof st);
    ch2 = ch;
    sms_tunable_chain_rebind(&ch2, st2, copy);
    sms_tunable_chain_hold(&ch, (sms_real)4.5, 5000, &y1);
    for (i = 0; i < 5000; ++i) {
        y2 = (sms_real)4.5;
        sms_tunable_chain_step(&ch2, &y2);
    }
    CHECK(y1 == y2);
    CHECK(!sms_tunable_chain_switching(&ch));
    {
        static double s1[8 * SLOT_CELLS], s2[8 * SLOT_CELLS];
        CHECK(sms_tunable_chain_state_count(&ch) == sms_tunable_chain_state_count(&ch2));
        sms_tunable_chain_get_state(&ch, s1);
        sms_tunable_chain_get_state(&ch2, s2);
        CHECK(memcmp(s1, s2, sms_tunable_chain_state_count(&ch) * sizeof(double)) == 0);
        CHECK_STATUS(sms_tunable_chain_set_state(&ch2, s1, sms_tunable_chain_state_count(&ch)),
                     SMS_OK);
    }
    CHECK(sms_tunable_chain_input_max(&ch) > 0.0);
    CHECK(sms_tunable_chain_length(&ch) > 0);
}

/* A state saved while an old notch fades, loaded as a saved state's configurations say
 * (sms_tunable_state_configs(): init with the old one, retune to the active one): that retune
 * finds the freshly built old notch at rest and begins no switch, so the loading tunable (and
 * chain) counts fewer values than the state holds. sms_tunable_saved_state_count() is the
 * saving one's count; the tunable and the chain load the state with it and then continue bit
 * for bit as the saving ones do. */
static void test_notch_switch_reload(void)
{
    static sms_memory_cell mem[4 * SLOT_CELLS], mem2[4 * SLOT_CELLS];
    static double s[4 * SLOT_CELLS];
    sms_stage_config c[2], b, active, old;
    size_t slots[2], need, n, i;
    sms_tunable st[2], st2[2];
    sms_tunable_chain ch, ch2;
    int switching = 0;
    c[0] = sms_stage_config_default(SMS_SHAPER_ZV);
    c[0].wn = 300.0;
    c[1] = sms_stage_config_default(SMS_NOTCH_TUSTIN);
    c[1].wn = 200.0;
    c[1].notch_pole_zeta = 0.7;
    b = c[1];
    b.wn = 260.0;
    for (i = 0; i < 2; ++i)
        CHECK_STATUS(sms_tunable_slot_cells(&c[i], 1, Ts, &slots[i]), SMS_OK);
    CHECK_STATUS(sms_tunable_chain_memory_size(slots, 2, &need), SMS_OK);
    CHECK(need <= 4 * SLOT_CELLS);
    CHECK_STATUS(sms_tunable_chain_init(&ch, st, c, slots, 2, Ts, mem, need), SMS_OK);
    for (i = 0; i < 200; ++i) {
        sms_real v = (sms_real)(0.01 * (double)i + 5.0);
        sms_tunable_chain_step(&ch, &v);
    }
    CHECK_STATUS(sms_tunable_chain_retune(&ch, 1, &b), SMS_OK);
    for (i = 0; i < 3; ++i) {
        sms_real v = (sms_real)7.0;
        sms_tunable_chain_step(&ch, &v);
    }
    CHECK(sms_tunable_switching(&st[1]));
    n = sms_tunable_chain_state_count(&ch);
    CHECK(n <= 4 * SLOT_CELLS);
    sms_tunable_chain_get_state(&ch, s);
    /* a second chain brought to the state's configurations */
    CHECK_STATUS(sms_tunable_chain_init(&ch2, st2, c, slots, 2, Ts, mem2, need), SMS_OK);
    CHECK_STATUS(sms_tunable_state_configs(s + sms_tunable_state_count(&st[0]),
                                           n - sms_tunable_state_count(&st[0]), &active, &old,
                                           &switching), SMS_OK);
    CHECK(switching == 1 && active.wn == b.wn && old.wn == c[1].wn);
    CHECK_STATUS(sms_tunable_chain_retune(&ch2, 1, &active), SMS_OK);
    CHECK(!sms_tunable_switching(&st2[1]));   /* the old notch was at rest: nothing to fade */
    CHECK(sms_tunable_chain_state_count(&ch2) < n);
    CHECK(sms_tunable_saved_state_count(&st2[1], s + sms_tunable_state_count(&st[0]),
                                        n - sms_tunable_state_count(&st[0]))
          == sms_tunable_state_count(&st[1]));
    CHECK(sms_tunable_saved_state_count(&st2[1], s, 3) == 0);   /* too short to tell */
    CHECK_STATUS(sms_tunable_chain_set_state(&ch2, s, n - 1), SMS_ERR_STATE);
    CHECK_STATUS(sms_tunable_chain_set_state(&ch2, s, n), SMS_OK);
    CHECK(sms_tunable_switching(&st2[1]));
    for (i = 0; i < 3000; ++i) {
        sms_real v = (sms_real)(7.0 + (i < 50 ? 0.01 * (double)i : 0.5)), w = v;
        sms_tunable_chain_step(&ch, &v);
        sms_tunable_chain_step(&ch2, &w);
        CHECK(v == w);
        if (v != w)
            break;
    }
    CHECK(!sms_tunable_switching(&st[1]) && !sms_tunable_switching(&st2[1]));
}

/* The chain's range during a switch and over a retune to come divides each stage's limit
 * before the cap (sms_tunable_input_limit(), sms_stage_config_limit()) by R_i: two moving
 * averages, whose limit is REAL_MAX / 2 (sum |g| = 1), keep SMS_INPUT_MAX while stage 1
 * switches (REAL_MAX / 2 / (1 + 2 G_0) with G_0 = 1 is REAL_MAX / 6, far above it), where the
 * capped figure gave SMS_INPUT_MAX / 3. A heavily damped harmonic smoother in stage 1 (its
 * limit far below REAL_MAX) gives exactly its limit over R_1 = 3, both ways. */
static void test_switch_range_uncapped(void)
{
    static sms_memory_cell mem[4 * SLOT_CELLS];
    sms_stage_config c[2], b, heavy;
    size_t slots[2], need, i;
    double limit, gain, capped, capped_gain, bound;
    int retuned[2] = {0, 1};
    double lim[2], g[2];
    sms_tunable st[2];
    sms_tunable_chain ch;
    c[0] = sms_stage_config_default(SMS_RECTANGULAR);
    c[0].T = 10 * Ts;
    c[1] = c[0];
    c[1].T = 5 * Ts;
    b = c[1];
    b.T = 20 * Ts;
    for (i = 0; i < 2; ++i)
        CHECK_STATUS(sms_tunable_slot_cells(i == 0 ? &c[0] : &b, 1, Ts, &slots[i]), SMS_OK);
    CHECK_STATUS(sms_tunable_chain_memory_size(slots, 2, &need), SMS_OK);
    CHECK(need <= 4 * SLOT_CELLS);
    CHECK_STATUS(sms_tunable_chain_init(&ch, st, c, slots, 2, Ts, mem, need), SMS_OK);
    CHECK_STATUS(sms_stage_config_limit(&b, Ts, &limit, &gain), SMS_OK);
    CHECK_STATUS(sms_stage_config_range(&b, Ts, &capped, &capped_gain), SMS_OK);
    CHECK(gain == capped_gain && capped == SMS_INPUT_MAX && limit > 6.0 * SMS_INPUT_MAX);
    CHECK(sms_tunable_input_limit(&st[1]) == sms_stage_input_limit(sms_tunable_active(&st[1])));
    lim[1] = limit;
    g[1] = gain;
    lim[0] = g[0] = 0.0;   /* not read */
    CHECK(sms_tunable_chain_retune_input_max(&ch, retuned, lim, g) == SMS_INPUT_MAX);
    lim[1] = capped;       /* a capped range: still a bound, the smaller one */
    CHECK(sms_tunable_chain_retune_input_max(&ch, retuned, lim, g) == SMS_INPUT_MAX / 3.0);
    CHECK_STATUS(sms_tunable_chain_retune(&ch, 1, &b), SMS_OK);
    {
        sms_real v = (sms_real)SMS_INPUT_MAX;
        sms_tunable_chain_step(&ch, &v);
        CHECK(sms_tunable_switching(&st[1]));
        CHECK(sms_tunable_chain_input_max(&ch) == SMS_INPUT_MAX);
        for (i = 0; i < 40; ++i) {
            v = (sms_real)(i % 2 ? SMS_INPUT_MAX : -SMS_INPUT_MAX);
            sms_tunable_chain_step(&ch, &v);
            CHECK(v - v == (sms_real)0);   /* finite */
        }
    }
#ifndef SMS_USE_FLOAT   /* e^(sigma T) = e^300 is beyond float */
    heavy = sms_stage_config_default(SMS_DAMPED_HARMONIC);
    heavy.T = 20 * Ts;
    heavy.sigma = -15000.0;
    CHECK_STATUS(sms_stage_config_limit(&heavy, Ts, &limit, &gain), SMS_OK);
    CHECK(limit < SMS_INPUT_MAX);
    lim[1] = limit;
    g[1] = gain;
    bound = sms_tunable_chain_retune_input_max(&ch, retuned, lim, g);
    CHECK(bound == limit / 3.0);   /* R_1 = 1 + 2 G_0, G_0 = 1 (moving average) */
#else
    (void)heavy;
    (void)bound;
#endif
}

int main(void)
{
    test_switches();
    test_refusals();
    test_notch_fade_ends();
    test_no_drift();
    test_chain();
    test_notch_switch_reload();
    test_switch_range_uncapped();
    return check_summary("test_tunable");
}
